#pragma once
// The studio server's threads (cpp-httplib's TaskQueue; one connection is one task, from its
// accept to its close): a thread is started whenever a task would otherwise wait, up to
// `max_threads`, and a thread idle for `idle_exit` ends. So connections that hold a thread doing
// nothing (idle or slow sockets, until bounded_http_server.hpp's deadlines close them) cannot
// keep the user's requests waiting, as they could in httplib's fixed pool of 8 threads, and a
// burst leaves no threads behind.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

// After every header that includes Eigen (httplib.h's <resolv.h> defines `_res`).
#include <httplib.h>

namespace owsim::studio {

class GrowingTaskQueue final : public httplib::TaskQueue {
 public:
  GrowingTaskQueue(std::size_t max_threads, std::chrono::milliseconds idle_exit);
  GrowingTaskQueue(const GrowingTaskQueue&) = delete;
  GrowingTaskQueue& operator=(const GrowingTaskQueue&) = delete;
  ~GrowingTaskQueue() override;  // shutdown()

  void enqueue(std::function<void()> task) override;
  // Runs the tasks queued, then joins every thread.
  void shutdown() override;
  // Threads started and not yet ended.
  [[nodiscard]] std::size_t threads();

 private:
  void work();
  void join_ended();  // with mutex_ held

  const std::size_t max_threads_;
  const std::chrono::milliseconds idle_exit_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> tasks_;
  std::map<std::thread::id, std::thread> threads_;
  std::vector<std::thread::id> ended_;  // threads that returned, to join
  std::size_t idle_ = 0;                // threads waiting for a task
  bool shutting_down_ = false;
};

}  // namespace owsim::studio
