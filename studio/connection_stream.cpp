#include "studio/connection_stream.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <utility>

namespace owsim::studio {
namespace {

// How often a wait looks whether the server stops.
constexpr auto kSlice = std::chrono::milliseconds(100);

void describe(const sockaddr_storage& address, std::string& ip, int& port) {
  char text[INET6_ADDRSTRLEN] = {};
  if (address.ss_family == AF_INET) {
    const auto& v4 = reinterpret_cast<const sockaddr_in&>(address);
    ::inet_ntop(AF_INET, &v4.sin_addr, text, sizeof text);
    port = ntohs(v4.sin_port);
  } else if (address.ss_family == AF_INET6) {
    const auto& v6 = reinterpret_cast<const sockaddr_in6&>(address);
    ::inet_ntop(AF_INET6, &v6.sin6_addr, text, sizeof text);
    port = ntohs(v6.sin6_port);
  }
  ip = text;
}

}  // namespace

ConnectionStream::ConnectionStream(int socket, Clock::duration io_timeout,
                                   std::function<bool()> stopping)
    : socket_(socket), io_timeout_(io_timeout), stopping_(std::move(stopping)) {}

bool ConnectionStream::await_head(Clock::time_point first_byte_by, Clock::time_point head_by,
                                  std::size_t head_bytes) {
  if (begin_ == end_ && !wait(POLLIN, first_byte_by)) return false;
  in_head_ = true;
  head_by_ = head_by;
  head_left_ = head_bytes;
  return true;
}

void ConnectionStream::start_body() { in_head_ = false; }

void ConnectionStream::drain(Clock::time_point by, std::size_t max_bytes) {
  in_head_ = false;
  std::size_t drained = end_ - begin_;
  begin_ = end_ = 0;
  while (drained < max_bytes) {
    const ssize_t n = fill(by);
    if (n <= 0) return;
    drained += static_cast<std::size_t>(n);
    begin_ = end_ = 0;
  }
}

bool ConnectionStream::wait(short events, Clock::time_point deadline) const {
  for (;;) {
    if (stopping_ && stopping_()) return false;
    const Clock::duration left = deadline - Clock::now();
    if (left <= Clock::duration::zero()) return false;
    const auto slice = std::chrono::ceil<std::chrono::milliseconds>(
        std::min<Clock::duration>(left, std::chrono::duration_cast<Clock::duration>(kSlice)));
    pollfd watched{socket_, events, 0};
    const int ready = ::poll(&watched, 1, static_cast<int>(slice.count()));
    if (ready > 0) return true;
    if (ready < 0 && errno != EINTR) return false;
  }
}

ssize_t ConnectionStream::fill(Clock::time_point deadline) {
  for (;;) {
    if (!wait(POLLIN, deadline)) return -1;
    const ssize_t n = ::recv(socket_, buffer_.data(), buffer_.size(), MSG_DONTWAIT);
    if (n >= 0) {
      begin_ = 0;
      end_ = static_cast<std::size_t>(n);
      return n;
    }
    if (errno != EINTR && errno != EAGAIN && errno != EWOULDBLOCK) return -1;
  }
}

bool ConnectionStream::is_readable() const {
  return begin_ < end_ || wait(POLLIN, Clock::now() + io_timeout_);
}

bool ConnectionStream::is_writable() const { return wait(POLLOUT, Clock::now() + io_timeout_); }

ssize_t ConnectionStream::read(char* data, size_t size) {
  if (size == 0) return 0;
  if (in_head_ && head_left_ == 0) return -1;  // a head longer than its budget
  if (begin_ == end_) {
    const ssize_t n = fill(in_head_ ? head_by_ : Clock::now() + io_timeout_);
    if (n <= 0) return n;
  }
  std::size_t count = std::min(size, end_ - begin_);
  if (in_head_) {
    count = std::min(count, head_left_);
    head_left_ -= count;
  }
  std::memcpy(data, buffer_.data() + begin_, count);
  begin_ += count;
  return static_cast<ssize_t>(count);
}

ssize_t ConnectionStream::write(const char* data, size_t size) {
  const Clock::time_point deadline = Clock::now() + io_timeout_;
  for (;;) {
    if (!wait(POLLOUT, deadline)) return -1;
    const ssize_t n = ::send(socket_, data, size, MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n >= 0) return n;
    if (errno != EINTR && errno != EAGAIN && errno != EWOULDBLOCK) return -1;
  }
}

void ConnectionStream::get_remote_ip_and_port(std::string& ip, int& port) const {
  sockaddr_storage address{};
  socklen_t length = sizeof address;
  if (::getpeername(socket_, reinterpret_cast<sockaddr*>(&address), &length) == 0) {
    describe(address, ip, port);
  }
}

void ConnectionStream::get_local_ip_and_port(std::string& ip, int& port) const {
  sockaddr_storage address{};
  socklen_t length = sizeof address;
  if (::getsockname(socket_, reinterpret_cast<sockaddr*>(&address), &length) == 0) {
    describe(address, ip, port);
  }
}

}  // namespace owsim::studio
