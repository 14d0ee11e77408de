// Blocking ROS calls (services, the master) off rviz's GUI thread: a worker runs them in order, and each
// hands its result back to the GUI thread through Qt's event queue (dropped if its receiver is gone).
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>

#include <QObject>

#include "rigid_body_sim/ros/service_calls.h"

namespace rigid_body_sim {

class CallQueue {
 public:
  CallQueue();
  ~CallQueue();  // waits for the call under way; drops the others

  // The worker's service clients: for the calls `post` runs (service_calls.h says why a kept connection).
  static ServiceCalls& services();

  // Runs `call` on the worker, then `done` on the GUI thread (if `receiver` still exists).
  template <class Result>
  void post(QObject* receiver, std::function<Result()> call, std::function<void(const Result&)> done) {
    push([receiver, call, done] {
      Result result = call();
      const auto deliver = [done, result] { done(result); };
      QMetaObject::invokeMethod(receiver, deliver, Qt::QueuedConnection);
    });
  }

 private:
  void push(std::function<void()> job);
  void work();

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> jobs_;
  bool stopping_ = false;
  std::thread worker_;
};

}  // namespace rigid_body_sim
