// Writes what the node publishes into a bag with the rosbag C++ API: no master needed. Topic names are
// the node's (launch files name it `sim`): /tf, /tf_static, /sim/markers, /sim/<body>/state, and
// /sim/commands with the config (so that `simulate --replay` takes the bag). This is the
// sink of `simulate --bag` (io/offline_run.h), stamped in simulated time.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <rosbag/bag.h>

#include "rigid_body_sim/io/offline_run.h"
#include "rigid_body_sim/ros/snapshot.h"

namespace rigid_body_sim {

class BagRecorder : public SampleSink {
 public:
  // Writes to `path`.active, renamed to `path` by commit(), as `rosbag record` does; starts with the
  // config command of `config` and the fixed frames and markers of `bodies` (at t = 0).
  BagRecorder(const std::string& path, const WorldConfig& config, const std::vector<Body>& bodies,
              std::string node_namespace = "/sim");
  ~BagRecorder() override;
  BagRecorder(const BagRecorder&) = delete;
  BagRecorder& operator=(const BagRecorder&) = delete;

  void write(const World& world) override;  // TF, markers and every state at world.time()
  void commit() override;

 private:
  std::string path_;
  std::string node_namespace_;
  SnapshotBuilder snapshots_;
  rosbag::Bag bag_;
  bool open_ = false;
};

// The SinkOpener of `simulate --bag`.
std::unique_ptr<SampleSink> openBag(const std::string& path, const WorldConfig& config,
                                    const std::vector<Body>& bodies);

}  // namespace rigid_body_sim
