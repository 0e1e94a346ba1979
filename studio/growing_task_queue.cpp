#include "studio/growing_task_queue.hpp"

#include <system_error>
#include <utility>

namespace owsim::studio {

GrowingTaskQueue::GrowingTaskQueue(std::size_t max_threads, std::chrono::milliseconds idle_exit)
    : max_threads_(max_threads), idle_exit_(idle_exit) {}

GrowingTaskQueue::~GrowingTaskQueue() { shutdown(); }

void GrowingTaskQueue::enqueue(std::function<void()> task) {
  const std::lock_guard lock(mutex_);
  join_ended();
  tasks_.push_back(std::move(task));
  if (idle_ >= tasks_.size() || threads_.size() >= max_threads_) {
    wake_.notify_one();
    return;
  }
  try {
    std::thread thread([this] { work(); });
    const std::thread::id id = thread.get_id();
    threads_.emplace(id, std::move(thread));
  } catch (const std::system_error&) {
    wake_.notify_one();  // no thread to spare: the task waits for one of those running
  }
}

void GrowingTaskQueue::work() {
  std::unique_lock lock(mutex_);
  for (;;) {
    ++idle_;
    const bool woken =
        wake_.wait_for(lock, idle_exit_, [this] { return shutting_down_ || !tasks_.empty(); });
    --idle_;
    if (tasks_.empty()) {
      if (shutting_down_ || !woken) break;
      continue;
    }
    std::function<void()> task = std::move(tasks_.front());
    tasks_.pop_front();
    lock.unlock();
    task();
    task = nullptr;  // what it holds goes before the lock is taken again
    lock.lock();
  }
  ended_.push_back(std::this_thread::get_id());
}

void GrowingTaskQueue::join_ended() {
  for (const std::thread::id id : ended_) {
    const auto thread = threads_.find(id);
    if (thread == threads_.end()) continue;
    thread->second.join();  // it has returned from work(): at once
    threads_.erase(thread);
  }
  ended_.clear();
}

void GrowingTaskQueue::shutdown() {
  std::map<std::thread::id, std::thread> running;
  {
    const std::lock_guard lock(mutex_);
    shutting_down_ = true;
    running.swap(threads_);
    ended_.clear();
  }
  wake_.notify_all();
  for (auto& entry : running) entry.second.join();
}

std::size_t GrowingTaskQueue::threads() {
  const std::lock_guard lock(mutex_);
  join_ended();
  return threads_.size();
}

}  // namespace owsim::studio
