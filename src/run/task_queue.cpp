#include "rigid_body_sim/run/task_queue.h"

#include <utility>

namespace rigid_body_sim {

void TaskQueue::post(std::function<void()> work) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (finished_) return work();
  tasks_.push_back(std::move(work));
  lock.unlock();
  wake_.notify_all();
}

void TaskQueue::becomeOwner() { owner_ = std::this_thread::get_id(); }

void TaskQueue::runPending() {
  std::deque<std::function<void()>> now;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    now.swap(tasks_);
  }
  for (auto& task : now) task();
}

void TaskQueue::waitFor(std::chrono::steady_clock::time_point until) {
  std::unique_lock<std::mutex> lock(mutex_);
  wake_.wait_until(lock, until, [this] { return !tasks_.empty() || stopped_; });
}

void TaskQueue::stop() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);  // a waitFor between its check and its wait sees it
    stopped_ = true;
  }
  wake_.notify_all();
}

void TaskQueue::finish() {
  const std::lock_guard<std::mutex> lock(mutex_);
  finished_ = true;
  for (auto& task : tasks_) task();
  tasks_.clear();
}

}  // namespace rigid_body_sim
