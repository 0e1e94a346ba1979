#pragma once
// A raw TCP connection to 127.0.0.1:PORT, for the studio server's tests that send what no HTTP
// client sends: nothing at all, a request's head one byte at a time, a chunked body of any
// length. Test code only.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace owsim::test {

class LoopbackSocket {
 public:
  explicit LoopbackSocket(int port) : socket_(::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0)) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (socket_ < 0 ||
        ::connect(socket_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
      if (socket_ >= 0) ::close(socket_);
      throw std::runtime_error("cannot connect to 127.0.0.1:" + std::to_string(port));
    }
  }
  LoopbackSocket(LoopbackSocket&& other) noexcept : socket_(std::exchange(other.socket_, -1)) {}
  LoopbackSocket& operator=(LoopbackSocket&&) = delete;
  LoopbackSocket(const LoopbackSocket&) = delete;
  LoopbackSocket& operator=(const LoopbackSocket&) = delete;
  ~LoopbackSocket() {
    if (socket_ >= 0) ::close(socket_);
  }

  // All of `bytes`; false once the server has closed the connection.
  bool send(std::string_view bytes) {
    while (!bytes.empty()) {
      const ssize_t sent = ::send(socket_, bytes.data(), bytes.size(), MSG_NOSIGNAL);
      if (sent <= 0) return false;
      bytes.remove_prefix(static_cast<std::size_t>(sent));
    }
    return true;
  }

  // Whether something (bytes, or the end of the stream) can be read within `wait`.
  [[nodiscard]] bool readable(std::chrono::milliseconds wait) const {
    pollfd watched{socket_, POLLIN, 0};
    return ::poll(&watched, 1, static_cast<int>(std::max<std::int64_t>(0, wait.count()))) > 0;
  }

  // Everything the server sends until it closes the connection or `wait` passes.
  std::string read_all(std::chrono::milliseconds wait) {
    std::string received;
    const auto deadline = std::chrono::steady_clock::now() + wait;
    char buffer[65536];
    while (readable(std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now()))) {
      const ssize_t n = ::recv(socket_, buffer, sizeof buffer, 0);
      if (n <= 0) {
        closed_ = true;
        break;
      }
      received.append(buffer, static_cast<std::size_t>(n));
    }
    return received;
  }

  // Whether the server has closed the connection (what it sent before is read and dropped),
  // waiting at most `wait`.
  bool closed_by_server(std::chrono::milliseconds wait) {
    (void)read_all(wait);
    return closed_;
  }

 private:
  int socket_;
  bool closed_ = false;
};

}  // namespace owsim::test
