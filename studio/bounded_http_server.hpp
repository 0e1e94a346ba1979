#pragma once
// cpp-httplib's server with bounds on what a connection may hold before it has said who it is,
// so that any local process opening sockets cannot starve the studio (issue 45): httplib 0.11
// serves a connection on one of 8 threads for as long as it sends a byte every 5 s, so ten
// connections trickling their headers, or a few hundred idle ones, kept the user's requests
// waiting for minutes. Here:
// - a thread per connection, started on demand (growing_task_queue.hpp), so connections that
//   wait do not keep others waiting;
// - a request's first byte must come within kFirstByteWithin of the connection opening or of
//   the previous answer, and its whole head (request line and headers, at most kMaxHeadBytes)
//   within kHeadWithin of the same moment (connection_stream.hpp), not merely a byte every few
//   seconds;
// - at most kMaxConnections at once: one more closes the connection that has waited longest for
//   its request to arrive (a request being served is never closed for it);
// - a refused request, or one whose body is not read whole, ends its connection after the
//   answer (close_after), with the rest of its body drained for at most kLinger so the client
//   reads the answer rather than a reset.
#include <chrono>
#include <cstddef>
#include <list>
#include <mutex>
#include <optional>

// After every header that includes Eigen (httplib.h's <resolv.h> defines `_res`).
#include <httplib.h>

namespace owsim::studio {

inline constexpr std::size_t kMaxConnections = 256;
inline constexpr std::size_t kMaxThreads = kMaxConnections + 64;  // closed ones end in ≤ 0.1 s
inline constexpr std::chrono::seconds kFirstByteWithin{5};
inline constexpr std::chrono::seconds kHeadWithin{10};
inline constexpr std::size_t kMaxHeadBytes = 64u << 10;
inline constexpr std::chrono::seconds kIoTimeout{5};  // a body's read, an answer's write
inline constexpr std::chrono::seconds kLinger{2};
inline constexpr std::size_t kRequestsPerConnection = 100;

class BoundedHttpServer : public httplib::Server {
 public:
  BoundedHttpServer();

  // After bind_to_port or bind_to_any_port: a listen queue as long as the system allows
  // (httplib's is 5 connections, too few for a burst).
  void widen_listen_queue();

  // From a handler (or the pre-routing handler), on the thread serving the request: its
  // connection closes once `response` is sent, which says so ("Connection: close").
  static void close_after(httplib::Response& response);

 private:
  using Clock = std::chrono::steady_clock;
  struct Open {
    int socket;
    Clock::time_point waiting_since;
    bool waiting;  // for a request to arrive (its head), not serving one
    bool evicted;
  };
  using OpenList = std::list<Open>;

  bool process_and_close_socket(int socket) override;
  // Serves the requests of a connection admitted as `open` until one of the bounds ends it.
  void serve(int socket, OpenList::iterator open);
  // Counts `socket` in, closing the longest-waiting connection if there are kMaxConnections
  // already; nullopt (refused) when none of them is waiting.
  std::optional<OpenList::iterator> admit(int socket);
  void set_waiting(OpenList::iterator open, bool waiting);
  void release(OpenList::iterator open);

  std::mutex open_mutex_;
  OpenList open_;             // guarded by open_mutex_
  std::size_t admitted_ = 0;  // not evicted; guarded by open_mutex_
};

}  // namespace owsim::studio
