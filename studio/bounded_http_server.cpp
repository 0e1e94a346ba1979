#include "studio/bounded_http_server.hpp"

#include <sys/socket.h>
#include <unistd.h>

#include <exception>

#include "studio/connection_stream.hpp"
#include "studio/growing_task_queue.hpp"

namespace owsim::studio {
namespace {

constexpr std::chrono::seconds kIdleThreadExit{10};
constexpr std::size_t kMaxLingerBytes = 16u << 20;

// Set by close_after while this thread serves a request.
thread_local bool close_requested = false;

}  // namespace

BoundedHttpServer::BoundedHttpServer() {
  new_task_queue = [] {
    return new GrowingTaskQueue(
        kMaxThreads, std::chrono::duration_cast<std::chrono::milliseconds>(kIdleThreadExit));
  };
  // What the Keep-Alive header of an answer says.
  set_keep_alive_timeout(kFirstByteWithin.count());
  set_keep_alive_max_count(kRequestsPerConnection);
}

void BoundedHttpServer::widen_listen_queue() {
  if (svr_sock_ != INVALID_SOCKET) ::listen(svr_sock_, SOMAXCONN);
}

void BoundedHttpServer::close_after(httplib::Response& response) {
  close_requested = true;
  response.set_header("Connection", "close");
}

bool BoundedHttpServer::process_and_close_socket(int socket) {
  if (const auto open = admit(socket)) {
    try {
      serve(socket, *open);
    } catch (const std::exception&) {
      // Only this connection ends (httplib lets nothing else escape a request).
    }
    release(*open);
  }
  ::shutdown(socket, SHUT_RDWR);
  ::close(socket);
  return true;
}

void BoundedHttpServer::serve(int socket, OpenList::iterator open) {
  ConnectionStream stream(socket, kIoTimeout, [this] { return svr_sock_ == INVALID_SOCKET; });
  close_requested = false;
  for (std::size_t served = 0; served < kRequestsPerConnection; ++served) {
    const Clock::time_point now = Clock::now();
    if (!stream.await_head(now + kFirstByteWithin, now + kHeadWithin, kMaxHeadBytes)) return;
    bool closed_by_client = false;
    const bool answered =
        process_request(stream, served + 1 == kRequestsPerConnection, closed_by_client,
                        [this, &stream, open](httplib::Request&) {
                          stream.start_body();
                          set_waiting(open, false);
                        });
    // A head that did not arrive whole in time (or was malformed) ends the connection too.
    if (!answered || closed_by_client || close_requested || !stream.in_body()) break;
    set_waiting(open, true);
  }
  if (close_requested) {
    // The answer is sent; what the client still sends of its body is read and dropped for a
    // moment, so that closing does not reset the connection before the client reads the answer.
    ::shutdown(socket, SHUT_WR);
    stream.drain(Clock::now() + kLinger, kMaxLingerBytes);
  }
}

std::optional<BoundedHttpServer::OpenList::iterator> BoundedHttpServer::admit(int socket) {
  const std::lock_guard lock(open_mutex_);
  if (admitted_ >= kMaxConnections) {
    auto oldest = open_.end();
    for (auto open = open_.begin(); open != open_.end(); ++open) {
      if (open->waiting && !open->evicted &&
          (oldest == open_.end() || open->waiting_since < oldest->waiting_since)) {
        oldest = open;
      }
    }
    if (oldest == open_.end()) return std::nullopt;
    ::shutdown(oldest->socket, SHUT_RDWR);  // its thread sees the end of the stream and closes it
    oldest->evicted = true;
    --admitted_;
  }
  ++admitted_;
  return open_.insert(open_.end(), Open{socket, Clock::now(), true, false});
}

void BoundedHttpServer::set_waiting(OpenList::iterator open, bool waiting) {
  const std::lock_guard lock(open_mutex_);
  open->waiting = waiting;
  if (waiting) open->waiting_since = Clock::now();
}

void BoundedHttpServer::release(OpenList::iterator open) {
  const std::lock_guard lock(open_mutex_);
  if (!open->evicted) --admitted_;
  open_.erase(open);  // before the socket closes: no one shuts down a number reused meanwhile
}

}  // namespace owsim::studio
