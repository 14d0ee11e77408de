#include "rigid_body_sim/ros/node_recorder.h"

#include <utility>

#include "rigid_body_sim/core/parameters.h"

namespace rigid_body_sim {

NodeRecorder::NodeRecorder(const std::string& path, const WorldConfig& config,
                           const std::vector<Body>& bodies, const BagOptions& options, OnFailure on_failure)
    : on_failure_(std::move(on_failure)) {
  try {
    bag_ = openSink(path, config, bodies, bagOpener(options));
  } catch (const rosbag::BagException& error) {
    throw ConfigError("cannot write the bag '" + path + "': " + error.what());
  }
}

template <class Write>
void NodeRecorder::guarded(double t, Write&& write) {
  if (!bag_) return;
  last_t_ = t;
  try {
    write(*bag_);
  } catch (const rosbag::BagException& error) {
    bag_.reset();
    on_failure_(t, error.what());
  }
}

void NodeRecorder::write(const World& world) {
  guarded(world.time(), [&](SampleSink& bag) { bag.write(world); });
}

void NodeRecorder::applied(const WorldCommand& command, std::size_t index, const World& world) {
  guarded(world.time(), [&](SampleSink& bag) { bag.applied(command, index, world); });
}

void NodeRecorder::happened(const std::vector<BodyEvent>& events, const World& world) {
  guarded(world.time(), [&](SampleSink& bag) { bag.happened(events, world); });
}

void NodeRecorder::commit() {
  guarded(last_t_, [](SampleSink& bag) { bag.commit(); });
}

}  // namespace rigid_body_sim
