#include "rigid_body_sim/rviz/call_queue.h"

#include <utility>

namespace rigid_body_sim {

CallQueue::CallQueue() : worker_([this] { work(); }) {}

ServiceCalls& CallQueue::services() {
  thread_local ServiceCalls calls;  // one set per thread: the worker's, ended with it
  return calls;
}

CallQueue::~CallQueue() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    jobs_.clear();
  }
  wake_.notify_all();
  worker_.join();
}

void CallQueue::push(std::function<void()> job) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    jobs_.push_back(std::move(job));
  }
  wake_.notify_all();
}

void CallQueue::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stopping_ || !jobs_.empty(); });
    if (stopping_) return;
    auto job = std::move(jobs_.front());
    jobs_.pop_front();
    lock.unlock();
    job();
    lock.lock();
  }
}

}  // namespace rigid_body_sim
