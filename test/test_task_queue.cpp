// The node's one-owner rule: work handed to the owning thread runs there, in order, and is answered.
#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <stdexcept>
#include <thread>
#include <vector>

#include "rigid_body_sim/run/task_queue.h"

using namespace rigid_body_sim;
using std::chrono::steady_clock;

namespace {

constexpr auto kDeadline = std::chrono::seconds(10);  // for what should happen at once
constexpr auto kFar = std::chrono::hours(1);          // a wait that only work or stop() may end

// An owner that serves the queue until it is stopped, as the node's stepping thread does between steps.
std::future<void> serve(TaskQueue& queue) {
  return std::async(std::launch::async, [&queue] {
    queue.becomeOwner();
    while (!queue.stopped()) {
      queue.runPending();
      queue.waitFor(steady_clock::now() + kFar);
    }
    queue.finish();
  });
}

}  // namespace

TEST(TaskQueue, CallRunsOnTheOwnerAndReturnsItsAnswer) {
  TaskQueue queue;
  std::thread::id owner;
  auto served = std::async(std::launch::async, [&] {
    owner = std::this_thread::get_id();
    queue.becomeOwner();
    while (!queue.stopped()) {
      queue.runPending();
      queue.waitFor(steady_clock::now() + kFar);
    }
  });
  const std::thread::id ran_on = queue.call([] { return std::this_thread::get_id(); });
  EXPECT_EQ(42, queue.call([] { return 42; }));
  EXPECT_EQ(owner, ran_on);
  EXPECT_NE(std::this_thread::get_id(), ran_on);
  queue.stop();
  EXPECT_EQ(std::future_status::ready, served.wait_for(kDeadline)) << "stop() did not end the owner's wait";
}

TEST(TaskQueue, CallRethrowsWhatTheWorkThrew) {
  TaskQueue queue;
  auto served = serve(queue);
  EXPECT_THROW(queue.call([]() -> int { throw std::runtime_error("refused"); }), std::runtime_error);
  EXPECT_EQ(1, queue.call([] { return 1; })) << "the owner went on after the exception";
  queue.stop();
  EXPECT_EQ(std::future_status::ready, served.wait_for(kDeadline));
}

TEST(TaskQueue, WorkRunsInTheOrderItCameAndACallOnTheOwnerRunsAtOnce) {
  TaskQueue queue;
  auto served = serve(queue);
  std::vector<int> order;  // touched by the owner only, read here after a call that came last
  for (int i = 0; i < 100; ++i) queue.post([&order, i] { order.push_back(i); });
  // A call made by the owner itself (from work it runs) cannot wait for itself: it runs at once.
  const int nested = queue.call([&queue] { return queue.call([] { return 5; }); });
  EXPECT_EQ(5, nested);
  std::vector<int> expected;
  for (int i = 0; i < 100; ++i) expected.push_back(i);
  EXPECT_EQ(expected, queue.call([&order] { return order; }));
  queue.stop();
  EXPECT_EQ(std::future_status::ready, served.wait_for(kDeadline));
}

TEST(TaskQueue, WaitForEndsWhenWorkComesOrAtItsDeadline) {
  TaskQueue queue;
  const auto start = steady_clock::now();
  queue.waitFor(start + std::chrono::milliseconds(50));  // nothing comes
  EXPECT_GE(steady_clock::now() - start, std::chrono::milliseconds(50));

  int ran = 0;
  auto owner = std::async(std::launch::async, [&queue, &ran] {
    queue.becomeOwner();
    queue.waitFor(steady_clock::now() + kFar);
    queue.runPending();
    return ran;
  });
  queue.post([&ran] { ++ran; });
  ASSERT_EQ(std::future_status::ready, owner.wait_for(kDeadline)) << "work came and the wait went on";
  EXPECT_EQ(1, owner.get()) << "the owner ran what came";
}

TEST(TaskQueue, StopEndsEveryWaitFromThenOn) {
  TaskQueue queue;
  auto waited = std::async(std::launch::async, [&queue] { queue.waitFor(steady_clock::now() + kFar); });
  queue.stop();
  EXPECT_EQ(std::future_status::ready, waited.wait_for(kDeadline));
  auto later = std::async(std::launch::async, [&queue] { queue.waitFor(steady_clock::now() + kFar); });
  EXPECT_EQ(std::future_status::ready, later.wait_for(kDeadline)) << "a wait after stop() went on";
}

TEST(TaskQueue, FinishRunsWhatIsLeftAndLaterWorkAtOnceOnTheCaller) {
  TaskQueue queue;
  int ran = 0;
  queue.post([&ran] { ++ran; });
  queue.post([&ran] { ++ran; });
  EXPECT_EQ(0, ran) << "posted work ran before its owner took it";
  queue.finish();
  EXPECT_EQ(2, ran);
  EXPECT_EQ(std::this_thread::get_id(), queue.call([] { return std::this_thread::get_id(); }));
  queue.post([&ran] { ++ran; });
  EXPECT_EQ(3, ran);
}
