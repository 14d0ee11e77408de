// Writes what the node publishes into a bag with the rosbag C++ API: no master needed. Topic names are
// the node's (launch files name it `sim`): /tf, /tf_static, /sim/scene (latched, once), /sim/markers (trail
// pieces and labels at the marker rate), /sim/<body>/state, /sim/events (each stamped with its instant), and
// /sim/commands with the config (so that `simulate --replay` takes the bag). A SampleSink (run/session.h):
// the bag of `simulate --bag` and
// `--replay --bag`, and the node's own recorder (ros/node_recorder.h), stamped in simulated time.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <rosbag/bag.h>

#include "rigid_body_sim/Command.h"
#include "rigid_body_sim/ros/snapshot.h"
#include "rigid_body_sim/run/offline_run.h"
#include "rigid_body_sim/run/session.h"

namespace rigid_body_sim {

// The names and looks of a bag: `simulate --bag` takes the defaults; the node's own recorder its private
// namespace, frame_prefix and marker options (trail length, marker rate, labels).
struct BagOptions {
  std::string node_namespace = "/sim";
  std::string frame_prefix;
  MarkerOptions markers;
};

class BagRecorder : public SampleSink {
 public:
  // Writes to `path`.active, renamed to `path` by commit(), as `rosbag record` does; starts with the
  // config command of `config`, the fixed frames and the scene of `bodies` (at t = 0). A failed write (a
  // full disk, a file-size limit) throws rosbag::BagIOException naming the file; the recording ends there,
  // `path`.active left unindexed (`rosbag reindex` recovers what reached the disk), and every later call
  // throws too.
  BagRecorder(const std::string& path, const WorldConfig& config, const std::vector<Body>& bodies,
              BagOptions options = {});
  ~BagRecorder() override;
  BagRecorder(const BagRecorder&) = delete;
  BagRecorder& operator=(const BagRecorder&) = delete;

  void write(
      const World& world) override;  // TF, every state and (at marker instants) markers at world.time()
  void applied(const WorldCommand& command, std::size_t index, const World& world) override;
  void happened(const std::vector<BodyEvent>& events, const World& world) override;  // on /sim/events
  void commit() override;

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

// Opens a BagRecorder with `options`: `simulate --bag`'s opener is bagOpener(), the node's own recorder's
// the same with the node's options.
SinkOpener bagOpener(BagOptions options = {});

}  // namespace rigid_body_sim
