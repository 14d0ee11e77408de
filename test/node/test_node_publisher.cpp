// The node's topics as a sink of its Session (ros/node_publisher.h), under rostest's master (publisher.test)
// and with no sim_node: this test drives a Session of demo.yaml as the node's stepping thread does, with the
// publisher and, beside it, the bag of `simulate --bag` (bagOpener, the same marker options), stamps in
// simulated time. Every state message, /tf, ~commands, ~events and ~scene arrive byte for byte as that bag
// holds them, ~markers too until a reset, which sends a DELETEALL and starts the trails afresh; a spawned
// body's state topic comes and a deleted one's goes; /clock only goes forward, to the end of the run.
#include <mutex>
#include <type_traits>

#include <rosgraph_msgs/Clock.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include "bag_messages.h"
#include "node_test_util.h"
#include "rigid_body_sim/Command.h"
#include "rigid_body_sim/Event.h"
#include "rigid_body_sim/core/node_interface.h"
#include "rigid_body_sim/ros/bag_recorder.h"
#include "rigid_body_sim/ros/node_publisher.h"
#include "test_util.h"

using namespace rigid_body_sim;
using test::BagMessage;
using visualization_msgs::Marker;
using visualization_msgs::MarkerArray;

namespace {

constexpr double kTimeout = 20.0;  // wall seconds for any wait

// Every message of the topics subscribed, as bytes, in arrival order per topic.
class TopicLog {
 public:
  template <class Message>
  void subscribe(ros::NodeHandle& nh, const std::string& topic) {
    subscribers_[topic] =
        nh.subscribe<Message>(topic, 100000, [this, topic](const typename Message::ConstPtr& m) {
          Message message = *m;
          // roscpp numbers the states and events it publishes (header.seq); a bag's are as written.
          // ~commands' seq is the command's index (roscpp's count here too): compared as it is.
          if constexpr (std::is_same_v<Message, RodState> || std::is_same_v<Message, RollerState> ||
                        std::is_same_v<Message, rigid_body_sim::Event>)
            message.header.seq = 0;
          std::lock_guard<std::mutex> lock(mutex_);
          received_[topic].push_back(test::bytesOf(message));
          arrived_.notify_all();
        });
  }
  bool connected(const std::string& topic) { return subscribers_.at(topic).getNumPublishers() > 0; }
  // Waits until `topic` has at least `count` messages.
  bool waitCount(const std::string& topic, std::size_t count) {
    std::unique_lock<std::mutex> lock(mutex_);
    return arrived_.wait_for(lock, std::chrono::duration<double>(kTimeout),
                             [&] { return received_[topic].size() >= count; });
  }
  std::vector<std::vector<std::uint8_t>> of(const std::string& topic) {
    std::lock_guard<std::mutex> lock(mutex_);
    return received_[topic];
  }

 private:
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::map<std::string, std::vector<std::vector<std::uint8_t>>> received_;
  // Last, and so destroyed first: unsubscribing waits for a callback under way (the publisher still sends
  // as the test ends), which still finds the log.
  std::map<std::string, ros::Subscriber> subscribers_;
};

bool waitUntil(const std::function<bool()>& holds) { return test::waitUntil(holds, kTimeout); }

template <class Message>
Message fromBytes(std::vector<std::uint8_t> bytes) {
  Message message;
  ros::serialization::IStream stream(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  ros::serialization::deserialize(stream, message);
  return message;
}

std::vector<std::vector<std::uint8_t>> bytesOf(const std::vector<BagMessage>& messages) {
  std::vector<std::vector<std::uint8_t>> bytes;
  for (const auto& message : messages) bytes.push_back(message.bytes);
  return bytes;
}

WorldCommand commandOf(WorldCommand::Kind kind, const std::string& body) {
  WorldCommand command;
  command.kind = kind;
  command.body = body;
  return command;
}

TEST(NodePublisher, PublishesWhatSimulatesBagHolds) {
  ros::NodeHandle nh;
  ros::NodeHandle private_node("/sim");
  const WorldConfig config = loadWorldConfigFile(test::config("demo.yaml"));
  NodeOptions options;
  options.publish_clock = true;
  options.marker_rate = 25.0;
  options.trail_length = 2.0;
  TaskQueue stepper;  // this thread: the scene resent for a late viewer is never run here
  stepper.becomeOwner();
  Session session(config, node_interface::ownNames(), stepsPerSample(config.rate, config.publish_rate));
  const World& world = session.world();
  NodePublisher publisher(nh, private_node, options, world, true, stepper);
  publisher.publishConfig(world);
  const test::PrivateDir dir("node_publisher");
  const std::string bag_path = (dir.path() / "simulate.bag").string();
  const BagOptions bag_options{"/sim", "", markerOptions(options, config.publish_rate)};
  const auto bag = bagOpener(bag_options)(bag_path, config, world.bodies());
  session.addSink(publisher);
  session.addSink(*bag);

  TopicLog log;
  std::vector<std::string> topics;
  const auto add = [&](auto message, const std::string& topic) {
    log.subscribe<decltype(message)>(nh, topic);
    topics.push_back(topic);
  };
  for (const auto& body : world.bodies()) {
    std::visit([&](const auto& model) { add(toStateMsg(0.0, model), "/sim/" + body.name + "/state"); },
               body.model);
  }
  add(RollerState(), "/sim/ball/state");  // spawned below
  add(tf2_msgs::TFMessage(), "/tf");
  add(MarkerArray(), "/sim/markers");
  add(MarkerArray(), "/sim/scene");
  add(rigid_body_sim::Command(), "/sim/commands");
  add(rigid_body_sim::Event(), "/sim/events");
  add(rosgraph_msgs::Clock(), "/clock");
  ASSERT_TRUE(waitUntil([&] { return publisher.subscribed() && publisher.markersSubscribed(); }));
  ASSERT_TRUE(log.waitCount("/sim/commands", 1)) << "the config, latched";

  // Stepping starts: the scene, the first state; then changes at their steps, as callbacks hand them over.
  publisher.publishScene(world);
  session.sampleNow();
  session.advance(310);
  WorldCommand spawn = commandOf(WorldCommand::Kind::Spawn, "ball");
  spawn.config = parseBodyText("ball", "{type: roller, shape: ring}");
  session.apply(spawn);
  ASSERT_TRUE(waitUntil([&] { return log.connected("/sim/ball/state") && publisher.subscribed(); }))
      << "the spawned body's state topic";
  session.advance(190);
  WorldCommand set_state = commandOf(WorldCommand::Kind::SetState, "rod");
  set_state.state = parseStateText("rod", "{y: 3.0, omega: 1.5}");
  session.apply(set_state);
  session.advance(500);
  WorldCommand longer = commandOf(WorldCommand::Kind::Reconfigure, "rod");
  longer.config = config.bodies[0];
  std::get<RodConfig>(longer.config.config).params.length = 1.5;
  session.apply(longer);
  // A deleted body's publisher goes at once, and with it what it has not yet delivered.
  ASSERT_TRUE(log.waitCount("/sim/cylinder/state", 51)) << "the cylinder's states to t = 1 s";
  session.apply(commandOf(WorldCommand::Kind::Delete, "cylinder"));
  session.advance(1025);
  const double reset_t = world.time();
  session.apply(commandOf(WorldCommand::Kind::Reset, ""));
  session.advance(3000 - world.stepCount());
  bag->commit();
  EXPECT_TRUE(waitUntil([&] { return !log.connected("/sim/cylinder/state"); }))
      << "a deleted body's topic goes";

  const auto recorded = test::messagesOf(bag_path);
  for (const std::string& topic : topics) {
    if (topic == "/sim/markers" || topic == "/clock") continue;
    std::vector<BagMessage> expected;
    for (const auto& message : recorded)
      if (message.topic == topic) expected.push_back(message);
    ASSERT_FALSE(expected.empty()) << topic;
    ASSERT_TRUE(log.waitCount(topic, expected.size()))
        << topic << ": " << log.of(topic).size() << " of " << expected.size();
    const auto got = log.of(topic);
    const auto want = bytesOf(expected);
    std::size_t same = 0;
    while (same < std::min(got.size(), want.size()) && got[same] == want[same]) ++same;
    EXPECT_TRUE(got == want) << topic << ": " << got.size() << " messages, " << want.size() << " in the bag, "
                             << same << " equal before the first difference";
  }

  // ~get_events: the run's events since the reset, the bag's from its restarts on.
  std::vector<std::vector<std::uint8_t>> since_reset;
  for (const auto& message : recorded)
    if (message.topic == "/sim/events" && message.time >= simStamp(reset_t))
      since_reset.push_back(message.bytes);
  std::vector<std::vector<std::uint8_t>> kept;
  for (const auto& event : publisher.runEvents())
    kept.push_back(test::bytesOf(toEventMsg(event, simStamp(event.t))));
  EXPECT_EQ(kept.size(), since_reset.size());
  EXPECT_TRUE(kept == since_reset) << "the run's events since the reset";
  ASSERT_FALSE(publisher.runEvents().empty());
  EXPECT_EQ(findValue(publisher.runEvents().front().values, "cause")->text, "reset");

  // ~markers: as the bag until the reset; then a DELETEALL and trails from the reset on.
  std::vector<BagMessage> before_reset;
  for (const auto& message : recorded)
    if (message.topic == "/sim/markers" && message.time <= simStamp(reset_t)) before_reset.push_back(message);
  ASSERT_TRUE(log.waitCount("/sim/markers", before_reset.size() + 1 + 24));
  const auto markers = log.of("/sim/markers");
  EXPECT_TRUE(std::vector<std::vector<std::uint8_t>>(
                  markers.begin(), markers.begin() + before_reset.size()) == bytesOf(before_reset));
  const auto clear = fromBytes<MarkerArray>(markers[before_reset.size()]);
  ASSERT_EQ(clear.markers.size(), 1u);
  EXPECT_EQ(clear.markers[0].action, Marker::DELETEALL) << "the reset's";
  EXPECT_EQ(clear.markers[0].header.stamp, simStamp(reset_t));
  // The trails start afresh at the first sample after it (t = 2.04 s): one point, no piece yet, and so no
  // line from where the bodies were before the reset.
  for (const auto& marker : fromBytes<MarkerArray>(markers[before_reset.size() + 1]).markers)
    EXPECT_NE(marker.ns, "trail") << "a trail piece drawn across the reset";

  // /clock: simulated time, strictly increasing, to the end of the run.
  ASSERT_TRUE(waitUntil([&] {
    const auto clocks = log.of("/clock");
    return !clocks.empty() && clocks.back() == test::bytesOf([] {
                                rosgraph_msgs::Clock end;
                                end.clock = simStamp(3.0);
                                return end;
                              }());
  })) << "the last /clock is the end of the run";
  EXPECT_EQ(log.of("/clock").size(), 151u) << "t = 0 to 3 s at 50 Hz, each once";
}

}  // namespace

RBS_ROSTEST_MAIN("test_node_publisher")
