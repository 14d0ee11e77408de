// Work handed to the one thread that owns something (sim_node's stepping thread owns its Session): any other
// thread calls call() and waits for the answer, or post() and goes on; the owner runs what was handed over
// between its own steps (runPending) and sleeps in waitFor until work comes, a deadline passes or stop() is
// called. Once the owner has ended (finish), work runs at once on the caller's thread, one at a time. So the
// owned thing needs no lock of its own, and no lock order exists: the queue's mutex guards only the queue.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <thread>

namespace rigid_body_sim {

class TaskQueue {
 public:
  // Runs `work` on the owner and returns its result, or rethrows what it threw. On the owner itself, or
  // after finish(), runs it at once.
  template <class Work>
  auto call(Work work) -> decltype(work());
  // Hands `work` over without waiting for it (after finish(): runs it at once).
  void post(std::function<void()> work);

  // --- The owner's side
  void becomeOwner();  // the calling thread is the owner: its own call()s run at once
  void runPending();   // what was handed over until now, in the order it came
  // Returns once work is waiting, at `until`, or once stop() has been called.
  void waitFor(std::chrono::steady_clock::time_point until);
  void stop();  // every waitFor returns at once from now on
  bool stopped() const { return stopped_; }
  void finish();  // the owner has ended: what is left runs now, later work at once

 private:
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> tasks_;
  bool finished_ = false;  // under mutex_
  std::atomic<bool> stopped_{false};
  std::atomic<std::thread::id> owner_{};
};

template <class Work>
auto TaskQueue::call(Work work) -> decltype(work()) {
  if (std::this_thread::get_id() == owner_.load()) return work();
  std::unique_lock<std::mutex> lock(mutex_);
  if (finished_) return work();  // under the lock: one at a time
  std::packaged_task<decltype(work())()> task(std::move(work));
  auto answer = task.get_future();
  tasks_.emplace_back([&task] { task(); });  // `task` outlives its run: this thread waits for it below
  lock.unlock();
  wake_.notify_all();
  return answer.get();
}

}  // namespace rigid_body_sim
