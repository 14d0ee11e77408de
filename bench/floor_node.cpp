// The floor under sim_node's CPU figure in make bench: a roscpp node that does only what any node
// publishing at a fixed rate does, with sim_node's threads (an AsyncSpinner, a publishing thread that
// sleeps until each publication is due, a main thread that joins it) and no physics, scene or guard. It
// publishes one RodState on ~state at ~rate (Hz), to the same subscriber that measures sim_node.
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include <ros/ros.h>

#include "rigid_body_sim/RodState.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "floor");
  ros::NodeHandle private_node("~");
  const double rate = private_node.param("rate", 50.0);
  ros::Publisher publisher = private_node.advertise<rigid_body_sim::RodState>("state", 10);
  ros::AsyncSpinner spinner(1);
  spinner.start();
  std::thread publishing([&] {
    const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(1.0 / rate));
    std::mutex mutex;
    std::condition_variable wake;  // the same wait as sim_node's stepper: nothing notifies it
    std::unique_lock<std::mutex> lock(mutex);
    rigid_body_sim::RodState state;
    for (auto due = std::chrono::steady_clock::now(); ros::ok(); due += period) {
      wake.wait_until(lock, due);
      state.header.stamp = ros::Time::now();
      state.t += 1.0 / rate;
      publisher.publish(state);
    }
  });
  publishing.join();
  return 0;
}
