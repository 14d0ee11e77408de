// Writes what the node publishes into a bag with the rosbag C++ API: no master needed. Topic names are
// the node's (launch files name it `sim`): /tf, /tf_static, /sim/scene (latched, once), /sim/markers (trail
// pieces and labels at the default marker rate), /sim/<body>/state, and /sim/commands with the config (so
// that `simulate --replay` takes the bag). A SampleSink (run/session.h): the bag of `simulate --bag` and
// `--replay --bag`, and the node's own recorder, stamped in simulated time.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <rosbag/bag.h>

#include "rigid_body_sim/Command.h"
#include "rigid_body_sim/ros/snapshot.h"
#include "rigid_body_sim/run/session.h"

namespace rigid_body_sim {

class BagRecorder : public SampleSink {
 public:
  // Writes to `path`.active, renamed to `path` by commit(), as `rosbag record` does; starts with the
  // config command of `config`, the fixed frames and the scene of `bodies` (at t = 0). A failed write (a
  // full disk, a file-size limit) throws rosbag::BagIOException naming the file; the recording ends there,
  // `path`.active left unindexed (`rosbag reindex` recovers what reached the disk), and every later call
  // throws too.
  BagRecorder(const std::string& path, const WorldConfig& config, const std::vector<Body>& bodies,
              std::string node_namespace = "/sim", std::string frame_prefix = "");
  ~BagRecorder() override;
  BagRecorder(const BagRecorder&) = delete;
  BagRecorder& operator=(const BagRecorder&) = delete;

  void write(
      const World& world) override;  // TF, every state and (at marker instants) markers at world.time()
  void applied(const WorldCommand& command, std::size_t index, const World& world) override;
  void commit() override;
  // The node's own recorder: a change of the world (written as the node publishes it) and the scene and
  // fixed frames of the bodies there are now, at simulated time t.
  void writeCommand(const rigid_body_sim::Command& command);
  void rebuild(const std::vector<Body>& bodies, double t);

 private:
  std::string path_;
  std::string node_namespace_;
  SnapshotBuilder snapshots_;
  double marker_rate_;                  // Hz
  long long last_marker_instant_ = -1;  // floor(t * marker_rate_) of the last markers written
  std::unique_ptr<rosbag::Bag> bag_;    // null once committed or failed
  bool failed_ = false;

  template <class Write>
  void guarded(Write&& write);
};

// A new rosbag::Bag. Its constructor loads rosbag's encryption plugin, whose class_loader metadata Debian
// 11's class_loader never frees (616 bytes, in a plugin unloaded before LeakSanitizer looks): under the
// sanitizer that allocation is not counted, every other one is. Every Bag of the package is made here.
std::unique_ptr<rosbag::Bag> newBag();

// Whether a bag failed to write and was kept unclosed (BagRecorder): such a bag still holds its encryptor
// plugin, and class_loader (Debian 13) warns on stderr when the process' static destructors unload it.
bool anyBagKeptUnclosed();

// The SinkOpener of `simulate --bag`.
std::unique_ptr<SampleSink> openBag(const std::string& path, const WorldConfig& config,
                                    const std::vector<Body>& bodies);

}  // namespace rigid_body_sim
