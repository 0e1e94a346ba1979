#pragma once
// One connection to the studio server as cpp-httplib's Stream, with deadlines httplib lacks: a
// request's head (request line and headers) must arrive whole by a deadline and within a byte
// budget, not merely some byte every few seconds, so a client sending one byte at a time cannot
// hold its connection (bounded_http_server.hpp). Reads are buffered for the connection's whole
// life, so bytes of a next request read early are kept for it. Every wait ends when the server
// stops.
#include <array>
#include <chrono>
#include <cstddef>
#include <functional>
#include <string>

// After every header that includes Eigen (httplib.h's <resolv.h> defines `_res`).
#include <httplib.h>

namespace owsim::studio {

class ConnectionStream final : public httplib::Stream {
 public:
  using Clock = std::chrono::steady_clock;

  // `io_timeout`: the longest a read of a body or a write waits; `stopping`: true once the
  // server stops.
  ConnectionStream(int socket, Clock::duration io_timeout, std::function<bool()> stopping);

  // Waits until `first_byte_by` for the next request to begin; its head must then be read whole
  // by `head_by` and be at most `head_bytes` long (a read past either fails). False: nothing came
  // in time, or the server stops.
  bool await_head(Clock::time_point first_byte_by, Clock::time_point head_by,
                  std::size_t head_bytes);
  // The head has been read: from now on each read waits at most the io timeout.
  void start_body();
  [[nodiscard]] bool in_body() const { return !in_head_; }
  // Reads and drops what the peer still sends, until it closes, `by`, or `max_bytes`.
  void drain(Clock::time_point by, std::size_t max_bytes);

  bool is_readable() const override;
  bool is_writable() const override;
  ssize_t read(char* data, size_t size) override;
  ssize_t write(const char* data, size_t size) override;
  void get_remote_ip_and_port(std::string& ip, int& port) const override;
  void get_local_ip_and_port(std::string& ip, int& port) const override;
  int socket() const override { return socket_; }

 private:
  // Waits for `events` (poll) until `deadline`, in short slices so that a stopping server is
  // noticed; true when the socket is ready (or in error: the read or write then says so).
  bool wait(short events, Clock::time_point deadline) const;
  // Refills the empty buffer: the bytes read, 0 at the end of the stream, −1 on an error or at
  // `deadline`.
  ssize_t fill(Clock::time_point deadline);

  int socket_;
  Clock::duration io_timeout_;
  std::function<bool()> stopping_;
  bool in_head_ = false;
  Clock::time_point head_by_{};
  std::size_t head_left_ = 0;
  std::array<char, 4096> buffer_{};
  std::size_t begin_ = 0;
  std::size_t end_ = 0;
};

}  // namespace owsim::studio
