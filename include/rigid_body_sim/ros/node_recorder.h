// The node's own recording (~bag): a sink of its Session opened by the code that opens the bag of
// `simulate --bag` (bagOpener), with the node's namespace, frame_prefix and marker options, so that it holds
// what that bag holds for the same options. A write error (a full disk, a file-size limit) ends the
// recording, never the process: the sink says so once through its callback and writes nothing more.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rigid_body_sim/ros/bag_recorder.h"
#include "rigid_body_sim/run/session.h"

namespace rigid_body_sim {

class NodeRecorder : public SampleSink {
 public:
  // Called once, with the simulated time and the one line of the error.
  using OnFailure = std::function<void(double t, const std::string& what)>;

  // Opens `path` (throws ConfigError naming it if that fails) for a run of `config` whose bodies start as
  // `bodies`.
  NodeRecorder(const std::string& path, const WorldConfig& config, const std::vector<Body>& bodies,
               const BagOptions& options, OnFailure on_failure);

  void write(const World& world) override;
  void applied(const WorldCommand& command, std::size_t index, const World& world) override;
  void happened(const std::vector<BodyEvent>& events, const World& world) override;
  void commit() override;  // the end of the run: FILE.active becomes FILE
  bool recording() const { return bag_ != nullptr; }

 private:
  template <class Write>
  void guarded(double t, Write&& write);

  std::unique_ptr<SampleSink> bag_;  // null once a write failed
  double last_t_ = 0.0;              // s: the simulated time of the last write
  OnFailure on_failure_;
};

}  // namespace rigid_body_sim
