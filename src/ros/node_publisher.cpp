#include "rigid_body_sim/ros/node_publisher.h"

#include <algorithm>
#include <cmath>

#include <rosgraph_msgs/Clock.h>
#include <std_msgs/Bool.h>
#include <tf2_msgs/TFMessage.h>

#include "rigid_body_sim/core/node_interface.h"
#include "rigid_body_sim/ros/command_log.h"
#include "rigid_body_sim/ros/messages.h"

namespace rigid_body_sim {

namespace {

// Room for the samples of a run as fast as possible to wait for a slow subscriber instead of being dropped.
constexpr std::uint32_t kStateQueue = 10000;
// ~commands keeps every change for a slow subscriber (a recorder): none may be dropped.
constexpr std::uint32_t kCommandQueue = 100000;

}  // namespace

template <class Message>
NodePublisher::CountedPublisher NodePublisher::advertiseCounted(ros::NodeHandle& node,
                                                                const std::string& topic, std::uint32_t queue,
                                                                std::shared_ptr<std::atomic<int>> total) {
  auto count = std::make_shared<std::atomic<int>>(0);
  const auto connected = [count, total](const ros::SingleSubscriberPublisher&) {
    ++*count;
    if (total) ++*total;
  };
  const auto disconnected = [count, total](const ros::SingleSubscriberPublisher&) {
    --*count;
    if (total) --*total;
  };
  return {node.advertise<Message>(topic, queue, connected, disconnected), std::move(count)};
}

NodePublisher::NodePublisher(ros::NodeHandle node, ros::NodeHandle private_node, const NodeOptions& options,
                             const World& world, bool use_sim_time, TaskQueue& stepper)
    : node_(node),
      private_node_(private_node),
      publish_clock_(options.publish_clock),
      use_sim_time_(use_sim_time),
      snapshots_(world.config().world_frame, options.frame_prefix, world.bodies(),
                 markerOptions(options, world.config().publish_rate)),
      steps_per_markers_(
          stepsPerSample(world.rate(), world.config().publish_rate) *
          std::max<std::int64_t>(1, std::llround(world.config().publish_rate /
                                                 markerRate(options, world.config().publish_rate)))) {
  namespace names = node_interface;
  anchor(world.time());  // for anything published before stepping starts (a ~reset during start_delay)
  markers_ = advertiseCounted<visualization_msgs::MarkerArray>(private_node_, names::kMarkers, 10);
  tf_ = advertiseCounted<tf2_msgs::TFMessage>(node_, "/tf", 100);
  // A viewer gets the latched scene as it subscribes, and the scene once more a second or two later: rviz
  // drops for good a marker of stamp 0 whose frame's first transform comes in the instant it looks for it
  // (tf2's transformable request sees "the transform is older than the cache" for stamp 0). By then it
  // has the transforms, and the second copy is drawn whatever happened to the first.
  scene_ = private_node_.advertise<visualization_msgs::MarkerArray>(
      names::kScene, 1, [this](const ros::SingleSubscriberPublisher&) { scene_viewer_joined_ = true; },
      ros::SubscriberStatusCallback(), ros::VoidConstPtr(), true);
  scene_resend_timer_ =
      private_node_.createWallTimer(ros::WallDuration(1.0), [this, &stepper](const ros::WallTimerEvent&) {
        const bool due = scene_resend_due_.exchange(false);
        if (scene_viewer_joined_.exchange(false)) scene_resend_due_ = true;
        if (due) stepper.post([this] { scene_.publish(snapshots_.scene().sceneMarkers()); });
      });
  if (publish_clock_) clock_ = node_.advertise<rosgraph_msgs::Clock>("/clock", 10, true);
  if (node_.getNamespace() != "/") {
    namespace_tf_ = advertiseCounted<tf2_msgs::TFMessage>(node_, names::kNamespaceTf, 100);
    namespace_tf_static_ = node_.advertise<tf2_msgs::TFMessage>(names::kNamespaceTfStatic, 1, true);
  }
  commands_ = private_node_.advertise<rigid_body_sim::Command>(names::kCommands, kCommandQueue, true);
  events_ = advertiseCounted<rigid_body_sim::Event>(private_node_, names::kEvents, kCommandQueue);
  paused_ = private_node_.advertise<std_msgs::Bool>(names::kPaused, 1, true);
  for (const auto& body : world.bodies()) advertiseState(body);
}

void NodePublisher::advertiseState(const Body& body) {
  const std::string topic = node_interface::stateTopic(body.name);
  states_.push_back(std::visit(
      [&](const auto& model) {
        using Msg = typename RosBodyType<TypeOfModel<decltype(model)>>::StateMsg;
        return advertiseCounted<Msg>(private_node_, topic, kStateQueue, state_subscribers_);
      },
      body.model));
  state_bodies_.push_back(body.name);
}

bool NodePublisher::subscribed() const {
  return (tf_.watched() || namespace_tf_.watched()) && events_.watched() &&
         std::all_of(states_.begin(), states_.end(), [](const CountedPublisher& p) { return p.watched(); });
}

ros::Time NodePublisher::stampOf(double t) const {
  return use_sim_time_ ? simStamp(t) : stamp_anchor_ + ros::Duration(t - time_anchor_);
}

// Stepping starts (after any start_delay) or resumes at wall-clock pace, and so the stamps of what follows
// are current. Never earlier than a stamp already published (faster than wall-clock pace, or after ~step
// calls, stamps can be ahead of the clock): stamps stay strictly increasing.
void NodePublisher::anchor(double t) {
  const ros::WallTime wall = ros::WallTime::now();
  stamp_anchor_ = std::max(ros::Time(wall.sec, wall.nsec), last_tf_stamp_ + ros::Duration(0, 1));
  time_anchor_ = t;
}

void NodePublisher::publishConfig(const World& world) {
  WorldCommand start;
  start.kind = WorldCommand::Kind::Config;
  start.world = world.config();
  commands_.publish(toMessage(start, 0, world.time(), stampOf(world.time()), world.config().world_frame));
}

void NodePublisher::publishPaused(bool paused) {
  std_msgs::Bool message;
  message.data = paused;
  paused_.publish(message);
}

// A reset or a ~step publishes the current time once more: not on /clock.
void NodePublisher::publishClock(const World& world) {
  const ros::Time now = simStamp(world.time());
  if (!publish_clock_ || now <= last_clock_) return;
  rosgraph_msgs::Clock clock;
  clock.clock = now;
  clock_.publish(clock);
  last_clock_ = now;
}

void NodePublisher::write(const World& world) {
  const double t = world.time();
  const ros::Time stamp = stampOf(t);
  publishClock(world);
  const auto& bodies = world.bodies();
  // Every body's transform in one message and a state message per body, built only for a topic with a
  // subscriber (a viewer that joins finds every frame at the next publication). A transform is never sent
  // twice at one stamp (listeners warn TF_REPEATED_DATA and drop it): after a reset at a publishing instant
  // the frames move with the next one.
  if (stamp > last_tf_stamp_ && (tf_.watched() || namespace_tf_.watched())) {
    tf2_msgs::TFMessage tf;
    tf.transforms.reserve(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) snapshots_.appendTransforms(i, stamp, bodies[i], tf);
    tf_.publisher.publish(tf);
    if (namespace_tf_.publisher) namespace_tf_.publisher.publish(tf);
    last_tf_stamp_ = stamp;
  }
  publishMarkers(world, stamp);
  if (*state_subscribers_ == 0) return;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!states_[i].watched()) continue;
    std::visit([&](const auto& msg) { states_[i].publisher.publish(msg); },
               snapshots_.state(i, t, stamp, bodies[i]));
  }
}

void NodePublisher::happened(const std::vector<BodyEvent>& events, const World&) {
  const bool watched = events_.watched();
  for (const auto& event : events) {
    if (watched) events_.publisher.publish(toEventMsg(event, stampOf(event.t)));
    run_events_.push_back(event);
  }
}

void NodePublisher::applied(const WorldCommand& command, std::size_t index, const World& world) {
  if (command.kind == WorldCommand::Kind::Reset || command.kind == WorldCommand::Kind::Config) {
    run_events_.clear();  // a new run: its restart events follow
  }
  ROS_INFO_STREAM(toString(command.kind)
                  << (command.body.empty() ? "" : " '" + command.body + "'") << " at step " << command.step
                  << " (t = " << formatNumber(world.time()) << " s)");
  commands_.publish(toMessage(command, static_cast<std::uint32_t>(index), world.time(), stampOf(world.time()),
                              world.config().world_frame));
  switch (command.kind) {
    case WorldCommand::Kind::Spawn:
      advertiseState(world.bodies().back());
      rebuildScene(world);
      return;
    case WorldCommand::Kind::Delete: {
      const auto gone = std::find(state_bodies_.begin(), state_bodies_.end(), command.body);
      states_.erase(states_.begin() + (gone - state_bodies_.begin()));
      state_bodies_.erase(gone);
      rebuildScene(world);
      return;
    }
    case WorldCommand::Kind::Reconfigure:
      // Any key may change the look (a rod's length, a slope, a radius): the scene knows which do, and
      // sends only what changed, as the recorder of simulate --bag does.
      rebuildScene(world);
      return;
    case WorldCommand::Kind::Reset:
      // Trails start anew: the viewer drops the old ones.
      snapshots_.scene().clearTrails();
      if (markers_watched_)
        markers_.publisher.publish(snapshots_.scene().clearMarkers(stampOf(world.time())));
      return;
    case WorldCommand::Kind::SetState:
    case WorldCommand::Kind::Config: return;
  }
}

// Trail pieces and labels at marker instants, built only while someone subscribes.
void NodePublisher::publishMarkers(const World& world, const ros::Time& stamp) {
  Scene& scene = snapshots_.scene();
  if (!markers_.watched()) {
    if (markers_watched_) scene.clearTrails();  // a viewer that comes sees trails from then on
    markers_watched_ = false;
    return;
  }
  markers_watched_ = true;
  scene.sample(world.bodies());
  if (world.stepCount() % steps_per_markers_ == 0)
    markers_.publisher.publish(scene.changes(stamp, world.bodies()));
}

// A ~step ends anywhere between marker periods: its labels (and the trail up to there) go out at once, so
// that a paused picture shows them where the bodies are, not where the last period left them.
void NodePublisher::publishMarkersNow(const World& world) {
  if (!markers_watched_) return;
  markers_.publisher.publish(snapshots_.scene().changes(stampOf(world.time()), world.bodies()));
}

// The fixed frames on /tf_static (and <ns>/tf_static).
void NodePublisher::publishStaticTransforms(double t) {
  tf2_msgs::TFMessage fixed;
  fixed.transforms = snapshots_.staticTransforms(stampOf(t));
  static_broadcaster_.sendTransform(fixed.transforms);
  if (namespace_tf_static_) namespace_tf_static_.publish(fixed);
}

void NodePublisher::publishScene(const World& world) {
  publishStaticTransforms(world.time());
  scene_.publish(snapshots_.scene().sceneMarkers());
}

void NodePublisher::rebuildScene(const World& world) {
  const bool changed = snapshots_.scene().rebuild(world.bodies());
  publishStaticTransforms(world.time());  // the new placements' frames first, then the markers drawn in them
  if (changed) scene_.publish(snapshots_.scene().sceneMarkers());
}

}  // namespace rigid_body_sim
