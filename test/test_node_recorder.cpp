// The node's own recorder (ros/node_recorder.h), a sink of a Session as sim_node runs it, without a master:
// its bag holds what the bag of `simulate --bag` (runOffline through bagOpener) holds for the same config
// and marker options, message for message and byte for byte; with commands, what `simulate --replay --bag`
// writes for them; the node's marker options (rate, trail length, labels) show in it; a write error ends the
// recording once, through the callback, and nothing throws.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/resource.h>

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include <rosbag/view.h>
#include <visualization_msgs/MarkerArray.h>

#include "bag_messages.h"
#include "rigid_body_sim/core/node_interface.h"
#include "rigid_body_sim/io/config_loader.h"
#include "rigid_body_sim/ros/node_recorder.h"
#include "rigid_body_sim/ros/params.h"
#include "rigid_body_sim/run/replay.h"
#include "test_util.h"

using namespace rigid_body_sim;
using test::firstDifference;
using test::FolderTest;
using test::messagesOf;
namespace fs = std::filesystem;

namespace {

constexpr double kDuration = 3.0;  // s

std::vector<visualization_msgs::MarkerArray> markersOf(const fs::path& path) {
  rosbag::Bag bag(path.string());
  std::vector<visualization_msgs::MarkerArray> arrays;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/sim/markers")))
    arrays.push_back(*m.instantiate<visualization_msgs::MarkerArray>());
  return arrays;
}

WorldConfig demo() { return loadWorldConfigFile(test::config("demo.yaml")); }

// The node's run: its Session sampled at publish_rate, its recorder a sink, stepped to `duration` with
// `commands` applied at their steps (as the stepping thread applies what callbacks hand it).
void recordAsTheNode(const fs::path& bag, const WorldConfig& config, const BagOptions& options,
                     const std::vector<WorldCommand>& commands = {},
                     const NodeRecorder::OnFailure& on_failure = nullptr, double duration = kDuration) {
  Session session(config, node_interface::ownNames(), stepsPerSample(config.rate, config.publish_rate));
  NodeRecorder recorder(
      bag.string(), config, session.world().bodies(), options,
      on_failure ? on_failure : [](double, const std::string& what) { FAIL() << what; });
  session.addSink(recorder);
  session.sampleNow();
  const auto end = static_cast<std::int64_t>(std::llround(duration * config.rate));
  for (const WorldCommand& command : commands) {
    session.advance(command.step - session.world().stepCount());
    session.apply(command);
  }
  session.advance(end - session.world().stepCount());
  recorder.commit();
}

// `simulate CONFIG --duration kDuration --bag FILE` with these bag options.
fs::path simulateBag(const fs::path& dir, const WorldConfig& config, const BagOptions& options) {
  OfflineOptions offline;
  offline.duration = kDuration;
  offline.out_dir = (dir / "csv").string();
  fs::create_directories(offline.out_dir);
  offline.bag = (dir / "simulate.bag").string();
  runOffline(config, offline, bagOpener(options));
  return offline.bag;
}

BagOptions nodeMarkers() {
  NodeOptions options;
  options.marker_rate = 25.0;
  options.trail_length = 2.0;
  options.label_critical_angles = true;
  return {"/sim", "", markerOptions(options, demo().publish_rate)};
}

class NodeRecorderTest : public FolderTest {};

TEST_F(NodeRecorderTest, HoldsWhatSimulateBagHoldsForTheSameOptions) {
  for (const BagOptions& options : {BagOptions{}, nodeMarkers()}) {
    const fs::path node_bag = dir_ / "node.bag";
    recordAsTheNode(node_bag, demo(), options);
    const auto recorded = messagesOf(node_bag.string());
    const auto simulated = messagesOf(simulateBag(dir_, demo(), options).string());
    ASSERT_GT(recorded.size(), 600u);
    EXPECT_TRUE(recorded == simulated)
        << "marker rate " << options.markers.pieces_rate << ": " << firstDifference(recorded, simulated);
  }
}

// What ~marker_rate 25, ~trail_length 2 and ~label_critical_angles do to the node's bag: markers 1/25 s
// apart, each body's trail pieces cycling through 50 ids, a roller's label giving its critical angle.
TEST_F(NodeRecorderTest, HonoursTheNodesMarkerOptions) {
  const BagOptions options = nodeMarkers();
  recordAsTheNode(dir_ / "node.bag", demo(), options);
  const auto arrays = markersOf(dir_ / "node.bag");
  ASSERT_EQ(arrays.size(), static_cast<std::size_t>(kDuration * 25.0) + 1);
  std::set<int> trail_ids;
  bool critical_label = false;
  for (std::size_t i = 0; i < arrays.size(); ++i) {
    for (const auto& marker : arrays[i].markers) {
      EXPECT_EQ(marker.header.stamp, simStamp(static_cast<double>(i) / 25.0));
      if (marker.ns == "trail") trail_ids.insert(marker.id);
      if (marker.text.find("critical angle") != std::string::npos) critical_label = true;
    }
  }
  const int ring = 2 * 25;
  const std::size_t bodies = demo().bodies.size();
  EXPECT_EQ(trail_ids.size(), bodies * ring) << "every id of every body's ring, after more than 2 s";
  EXPECT_EQ(*trail_ids.rbegin(), static_cast<int>(bodies) * ring - 1);
  EXPECT_TRUE(critical_label);
}

// Commands applied by the node's Session: its bag is what `simulate --replay --bag` writes for them.
TEST_F(NodeRecorderTest, HoldsEveryChangeAsTheReplaysBag) {
  const WorldConfig config = demo();
  ASSERT_EQ(config.bodies[0].name, "rod");
  std::vector<WorldCommand> commands(1);
  commands[0].kind = WorldCommand::Kind::Config;
  commands[0].world = config;
  const auto add = [&](WorldCommand::Kind kind, std::int64_t step, const std::string& body) -> WorldCommand& {
    WorldCommand& command = commands.emplace_back();
    command.kind = kind;
    command.step = step;
    command.body = body;
    return command;
  };
  add(WorldCommand::Kind::Spawn, 310, "ball").config = parseBodyText("ball", "{type: roller, shape: ring}");
  add(WorldCommand::Kind::SetState, 500, "rod").state = parseStateText("rod", "{y: 3.0, omega: 1.5}");
  WorldCommand& longer = add(WorldCommand::Kind::Reconfigure, 1000, "rod");
  longer.config = config.bodies[0];
  std::get<RodConfig>(longer.config.config).params.length = 1.5;
  add(WorldCommand::Kind::Delete, 1000, "cylinder");
  add(WorldCommand::Kind::Reset, 2025, "");

  const std::vector<WorldCommand> changes(commands.begin() + 1, commands.end());
  recordAsTheNode(dir_ / "node.bag", config, BagOptions{}, changes);
  OfflineOptions offline;
  offline.duration = kDuration;
  offline.out_dir = dir_.string();
  offline.bag = (dir_ / "replay.bag").string();
  replayRun(commands, offline, bagOpener());
  const auto recorded = messagesOf((dir_ / "node.bag").string());
  const auto replayed = messagesOf((dir_ / "replay.bag").string());
  EXPECT_TRUE(recorded == replayed) << firstDifference(recorded, replayed);
  std::size_t logged = 0;
  for (const auto& message : recorded) logged += message.topic == "/sim/commands";
  EXPECT_EQ(logged, commands.size());
}

// A file-size limit (as record_write_error.sh sets it, SIGXFSZ ignored): a write fails as on a full disk.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &before_);
    old_handler_ = signal(SIGXFSZ, SIG_IGN);
    rlimit limit = before_;
    limit.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &before_);
    signal(SIGXFSZ, old_handler_);
  }

 private:
  rlimit before_{};
  sighandler_t old_handler_;
};

// The bag's LZ4 chunks reach the file whole, each once it holds 768 kB of messages (some 8 s of the demo):
// a run of 20 s writes a first chunk of about 300 kB, past the 100 kB limit, during the run.
TEST_F(NodeRecorderTest, AWriteErrorEndsTheRecordingOnceWithoutAThrow) {
  constexpr double kPastAChunk = 20.0;  // s
  std::vector<std::string> failures;
  std::vector<double> times;
  {
    const FileSizeLimit limit(100 * 1024);
    recordAsTheNode(
        dir_ / "node.bag", demo(), BagOptions{}, {},
        [&](double t, const std::string& what) {
          times.push_back(t);
          failures.push_back(what);
        },
        kPastAChunk);
  }
  ASSERT_EQ(failures.size(), 1u) << "one report, whatever came after it (the commit too)";
  EXPECT_NE(failures[0].find("node.bag.active' failed"), std::string::npos) << failures[0];
  EXPECT_GT(times[0], 0.0);
  EXPECT_LT(times[0], kPastAChunk);
  EXPECT_TRUE(fs::exists(dir_ / "node.bag.active"));
  EXPECT_FALSE(fs::exists(dir_ / "node.bag")) << "an unfinished recording is never renamed as if complete";
}

TEST_F(NodeRecorderTest, AFileThatCannotBeOpenedIsRefusedInOneLine) {
  const std::string refusal = test::refusalOf([&] {
    NodeRecorder(dir_.string() + "/no/such/folder/run.bag", demo(), World(demo()).bodies(), BagOptions{},
                 [](double, const std::string&) {});
  });
  EXPECT_EQ(refusal.rfind("cannot write the bag '" + dir_.string() + "/no/such/folder/run.bag': ", 0), 0u)
      << refusal;
}

}  // namespace
