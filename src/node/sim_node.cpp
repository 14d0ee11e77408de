#include "rigid_body_sim/node/sim_node.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <rosgraph_msgs/Clock.h>

#include "rigid_body_sim/io/node_interface.h"
#include "rigid_body_sim/ros/master_watch.h"
#include "rigid_body_sim/ros/reconfigure.h"

namespace rigid_body_sim {

namespace {

// Room for the samples of a run as fast as possible to wait for a slow subscriber instead of being dropped.
constexpr std::uint32_t kStateQueue = 10000;
constexpr double kMaxStepSeconds = 600.0;  // a ~step request may advance at most this much simulated time
constexpr auto kWatchTick = std::chrono::milliseconds(100);  // the master is asked every 10 ticks

template <class Config>
Config& configOf(WorldConfig& world, std::size_t index) {
  return std::get<Config>(world.bodies[index].config);
}

// Whether a change moves the body's fixed frame or changes its look (static TF and markers anew).
bool placementChanged(const RodConfig& a, const RodConfig& b) {
  return a.params.floor_length != b.params.floor_length;
}
bool placementChanged(const RollerConfig& a, const RollerConfig& b) {
  return a.params.incline_angle != b.params.incline_angle ||
         a.params.incline_length != b.params.incline_length || a.params.shape != b.params.shape ||
         a.params.radius != b.params.radius;
}

}  // namespace

SimNode::SimNode(ros::NodeHandle node, ros::NodeHandle private_node)
    : node_(node),
      private_node_(private_node),
      start_params_(privateParams(private_node)),
      options_(parseNodeOptions(start_params_)),
      config_(parseNodeConfig(start_params_)),
      world_(config_),
      guard_(world_.bodies()),
      steps_per_publish_(std::llround(config_.rate / config_.publish_rate)),
      steps_per_markers_(steps_per_publish_ *
                         std::max<std::int64_t>(1, std::llround(config_.publish_rate /
                                                                markerRate(options_, config_.publish_rate)))),
      pacer_(config_.rate, options_.real_time_factor) {
  checkFrames(options_, config_);
  use_sim_time_ = ros::param::param("/use_sim_time", false);
  anchorLocked();  // for anything published before stepping starts (a ~reset during start_delay)
  const TrailOptions trail{options_.trail_length, markerRate(options_, config_.publish_rate)};
  snapshots_ =
      std::make_unique<SnapshotBuilder>(config_.world_frame, options_.frame_prefix, world_.bodies(), trail);
  if (!options_.bag.empty()) {
    try {
      recorder_ = std::make_unique<BagRecorder>(options_.bag, config_.world_frame, world_.bodies(),
                                                private_node_.getNamespace(), options_.frame_prefix);
    } catch (const rosbag::BagException& error) {
      throw ConfigError("cannot write the bag '" + options_.bag + "': " + error.what());
    }
  }
  advertise();
}

SimNode::~SimNode() {
  stopping_ = true;
  wake_.notify_all();
  if (stepper_.joinable()) stepper_.join();
  if (watcher_.joinable()) watcher_.join();
}

void SimNode::advertise() {
  namespace names = node_interface;
  marker_publisher_ = private_node_.advertise<visualization_msgs::MarkerArray>(names::kMarkers, 10);
  scene_publisher_ = private_node_.advertise<visualization_msgs::MarkerArray>(names::kScene, 1, true);
  if (options_.publish_clock) clock_publisher_ = node_.advertise<rosgraph_msgs::Clock>("/clock", 10, true);
  if (node_.getNamespace() != "/") {
    namespace_tf_ = node_.advertise<tf2_msgs::TFMessage>(names::kNamespaceTf, 100);
    namespace_tf_static_ = node_.advertise<tf2_msgs::TFMessage>(names::kNamespaceTfStatic, 1, true);
  }
  // Subscribers counted as they come and go: Publisher::getNumSubscribers looks the topic up among all of
  // the node's publications, and once per body per publication that was most of the node's work with a
  // thousand bodies.
  state_subscribers_ = std::make_unique<std::atomic<int>[]>(world_.bodies().size());
  for (std::size_t i = 0; i < world_.bodies().size(); ++i) {
    const Body& body = world_.bodies()[i];
    std::atomic<int>& count = state_subscribers_[i];
    count = 0;
    const auto connected = [&count](const ros::SingleSubscriberPublisher&) { ++count; };
    const auto disconnected = [&count](const ros::SingleSubscriberPublisher&) { --count; };
    if (std::holds_alternative<Rod>(body.model)) {
      state_publishers_.push_back(private_node_.advertise<RodState>(names::stateTopic(body.name), kStateQueue,
                                                                    connected, disconnected));
    } else {
      state_publishers_.push_back(private_node_.advertise<RollerState>(names::stateTopic(body.name),
                                                                       kStateQueue, connected, disconnected));
    }
  }
  services_.push_back(private_node_.advertiseService(names::kReset, &SimNode::onReset, this));
  services_.push_back(private_node_.advertiseService(names::kPause, &SimNode::onPause, this));
  services_.push_back(private_node_.advertiseService(names::kUnpause, &SimNode::onUnpause, this));
  services_.push_back(private_node_.advertiseService(names::kStep, &SimNode::onStep, this));
}

// The YAML's values go to each server before its callback is set, so that they win over the .cfg
// defaults; the first callback then finds nothing to change. Called once stepping has started: each server
// takes some 40 calls to the master, and the first states need not wait for a thousand bodies' servers.
// A body's config changes only through its own server's callback, so reading it before that server exists
// needs no lock.
void SimNode::startReconfigureServers() {
  for (std::size_t i = 0; i < config_.bodies.size() && ros::ok() && !stopping_; ++i) {
    const ros::NodeHandle body_node(private_node_, config_.bodies[i].name);
    if (std::holds_alternative<RodConfig>(config_.bodies[i].config)) {
      auto server = std::make_unique<RodServer>(reconfigure_mutex_, body_node);
      server->updateConfig(toReconfigure(configOf<RodConfig>(config_, i)));
      server->setCallback(
          [this, i](RodReconfigureConfig& request, uint32_t) { reconfigure<Rod, RodConfig>(i, request); });
      rod_servers_.push_back(std::move(server));
    } else {
      auto server = std::make_unique<RollerServer>(reconfigure_mutex_, body_node);
      server->updateConfig(toReconfigure(configOf<RollerConfig>(config_, i)));
      server->setCallback([this, i](RollerReconfigureConfig& request, uint32_t) {
        reconfigure<Roller, RollerConfig>(i, request);
      });
      roller_servers_.push_back(std::move(server));
    }
  }
}

// Applies a reconfigure request to one body if it validates; otherwise logs one line and changes
// nothing. The request is rewritten to what runs, so that the server shows the truth.
template <class Model, class Config, class Request>
void SimNode::reconfigure(std::size_t index, Request& request) {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::string& name = config_.bodies[index].name;
  Config& current = configOf<Config>(config_, index);
  try {
    const Config wanted = fromReconfigure(name, request, current);
    validate(name, wanted);
    Model& model = std::get<Model>(world_.bodies()[index].model);
    model.setParams(wanted.params);
    if (initialChanged(wanted, current)) model.setInitial(wanted.initial);
    if (guard_.held(index)) ROS_INFO_STREAM("body '" << name << "' reconfigured: it runs again");
    guard_.release(index, world_.bodies()[index]);
    const bool moved = placementChanged(wanted, current);
    current = wanted;
    if (moved) rebuildSceneLocked();  // the slope's place or the body's look changed
  } catch (const ConfigError& error) {
    ROS_WARN_STREAM("refused reconfigure, simulation unchanged: " << error.what());
  }
  request = toReconfigure(current);
}

bool SimNode::onReset(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  std::lock_guard<std::mutex> lock(mutex_);
  world_.reset();
  world_.takeEvents();
  guard_.releaseAll(world_.bodies());
  // Trails start anew: the viewer drops the old ones.
  snapshots_->scene().clearTrails();
  if (markers_watched_) marker_publisher_.publish(snapshots_->scene().clearMarkers(stampOf(world_.time())));
  publishLocked();
  ROS_INFO("reset: every body back to its initial conditions at t = %.6f s", world_.time());
  return true;
}

bool SimNode::onPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  std::lock_guard<std::mutex> lock(mutex_);
  paused_ = true;
  return true;
}

bool SimNode::onUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    paused_ = false;
    anchorLocked();
  }
  wake_.notify_all();
  return true;
}

bool SimNode::onStep(Step::Request& request, Step::Response& response) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto max_steps = static_cast<std::uint64_t>(kMaxStepSeconds * world_.rate());
  if (!paused_) {
    response.message = "refused: call ~pause first (the simulation is running)";
  } else if (request.steps == 0 || request.steps > max_steps) {
    response.message = "refused: steps " + std::to_string(request.steps) + " is not in [1, " +
                       std::to_string(max_steps) + "] (at most " + formatNumber(kMaxStepSeconds) + " s)";
  } else {
    for (std::uint32_t i = 0; i < request.steps; ++i) stepOnceLocked();
    if (last_published_step_ != world_.stepCount()) publishLocked();  // show where the steps ended
    response.success = true;
    response.message = "ok";
  }
  if (!response.success) ROS_WARN_STREAM("~step " << response.message);
  response.t = world_.time();
  return true;
}

double SimNode::wallNow() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

ros::Time SimNode::stampOf(double t) const {
  return use_sim_time_ ? simStamp(t) : stamp_anchor_ + ros::Duration(t - time_anchor_);
}

// The pace and the wall-clock stamps start from now and the current step: stepping starts (after any
// start_delay) or resumes at wall-clock pace, and so the stamps of what follows are current. Never earlier
// than a stamp already published (faster than wall-clock pace, or after ~step calls, stamps can be ahead of
// the clock): stamps stay strictly increasing.
void SimNode::anchorLocked() {
  pacer_.restart(wallNow(), world_.stepCount());
  const ros::WallTime wall = ros::WallTime::now();
  stamp_anchor_ = std::max(ros::Time(wall.sec, wall.nsec), last_tf_stamp_ + ros::Duration(0, 1));
  time_anchor_ = world_.time();
}

void SimNode::stepOnceLocked() {
  world_.step();
  guardLocked();
  for (const auto& event : world_.takeEvents()) {
    ROS_DEBUG_STREAM(event.body << " " << toString(event.kind) << " at t = " << event.t << " s");
  }
  if (world_.stepCount() % steps_per_publish_ == 0) publishLocked();
}

void SimNode::guardLocked() {
  for (const NonFinite& fault : guard_.afterStep(world_.bodies())) {
    const Body held{world_.bodies()[fault.index].name, guard_.lastFinite(fault.index)};
    ROS_ERROR_STREAM("body '" << held.name << "': " << fault.field
                              << " became non-finite in the step to t = " << formatNumber(world_.time())
                              << " s; the body is paused at its last finite state, the "
                              << "others go on (a reconfigure of it or ~reset restarts it). It ran with: "
                              << describeBody(held));
  }
}

// Only forward: /clock never repeats a time (a reset or a ~step publishes the current time once more).
void SimNode::publishClockLocked() {
  const ros::Time now = simStamp(world_.time());
  if (!options_.publish_clock || now <= last_clock_) return;
  rosgraph_msgs::Clock clock;
  clock.clock = now;
  clock_publisher_.publish(clock);
  last_clock_ = now;
}

void SimNode::publishLocked() {
  const double t = world_.time();
  const ros::Time stamp = stampOf(t);
  publishClockLocked();
  const auto& bodies = world_.bodies();
  // The transforms always (a viewer that joins finds every frame at once); a state message only for a topic
  // with a subscriber. A transform is never sent twice at one stamp (listeners warn TF_REPEATED_DATA and
  // drop it): after a reset at a publishing instant the frames move with the next one.
  if (stamp > last_tf_stamp_) {
    tf2_msgs::TFMessage tf;
    for (std::size_t i = 0; i < bodies.size(); ++i)
      tf.transforms.push_back(snapshots_->transform(i, stamp, bodies[i]));
    tf_broadcaster_.sendTransform(tf.transforms);
    if (namespace_tf_) namespace_tf_.publish(tf);
    last_tf_stamp_ = stamp;
  }
  publishMarkersLocked(stamp);
  if (recorder_) recorder_->write(world_);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (state_subscribers_[i] <= 0) continue;
    std::visit([&](const auto& msg) { state_publishers_[i].publish(msg); },
               snapshots_->state(i, t, stamp, bodies[i]));
  }
  last_published_step_ = world_.stepCount();
}

void SimNode::publishMarkersLocked(const ros::Time& stamp) {
  Scene& scene = snapshots_->scene();
  const bool watched = marker_publisher_.getNumSubscribers() > 0;
  if (!watched) {
    if (markers_watched_) scene.clearTrails();  // a viewer that comes sees trails from then on
    markers_watched_ = false;
    return;
  }
  markers_watched_ = true;
  scene.sample(world_.bodies());
  if (world_.stepCount() % steps_per_markers_ == 0) {
    marker_publisher_.publish(scene.changes(stamp, world_.bodies()));
  }
}

void SimNode::publishStaticTransformsLocked() {
  tf2_msgs::TFMessage fixed;
  fixed.transforms = snapshots_->staticTransforms(stampOf(world_.time()));
  static_broadcaster_.sendTransform(fixed.transforms);
  if (namespace_tf_static_) namespace_tf_static_.publish(fixed);
}

void SimNode::publishSceneLocked() {
  publishStaticTransformsLocked();
  scene_publisher_.publish(snapshots_->scene().sceneMarkers());
}

void SimNode::rebuildSceneLocked() {
  if (snapshots_->scene().rebuild(world_.bodies())) {
    scene_publisher_.publish(snapshots_->scene().sceneMarkers());
  }
  publishStaticTransformsLocked();
}

void SimNode::stepLoop() {
  std::unique_lock<std::mutex> lock(mutex_);
  // A valid time before stepping starts (the clock is latched): rosbag record, for one, waits for one before
  // it subscribes to anything, and so would miss the start of a run on simulated time.
  publishClockLocked();
  wake_.wait_for(lock, std::chrono::duration<double>(options_.start_delay),
                 [this] { return stopping_.load(); });
  anchorLocked();
  publishSceneLocked();
  publishLocked();
  const auto duration_steps = static_cast<std::int64_t>(std::llround(options_.duration * world_.rate()));
  while (!stopping_ && ros::ok()) {
    if (paused_) {
      wake_.wait_for(lock, std::chrono::milliseconds(50));
      continue;
    }
    // Step up to what is due, one publishing interval at a time so that callbacks get the lock.
    const std::int64_t next_publish = (world_.stepCount() / steps_per_publish_ + 1) * steps_per_publish_;
    const std::int64_t target = std::min(pacer_.dueSteps(wallNow()), next_publish);
    while (world_.stepCount() < target) {
      stepOnceLocked();
      if (duration_steps > 0 && world_.stepCount() >= duration_steps) {
        ROS_INFO("simulated %.3f s: the requested duration; shutting down", world_.time());
        // A moment for subscribers (a recorder) to receive the last messages before the launch ends.
        lock.unlock();
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
        ros::requestShutdown();
        return;
      }
    }
    if (pacer_.asFastAsPossible()) {
      lock.unlock();
      std::this_thread::yield();
      lock.lock();
      continue;
    }
    const double wake_at =
        pacer_.wallTimeOf((world_.stepCount() / steps_per_publish_ + 1) * steps_per_publish_);
    const auto wait = std::chrono::duration<double>(wake_at - wallNow());
    if (wait.count() > 0) wake_.wait_for(lock, wait);
  }
}

void SimNode::watchMaster() {
  while (!stopping_ && ros::ok()) {
    if (askMaster() == MasterView::Forgot) {
      restoreParameters();
      ROS_ERROR(
          "the ROS master at %s restarted and no longer knows this node, which cannot register again: "
          "exiting with status %d (sim.launch respawn:=true starts it afresh)",
          ros::master::getURI().c_str(), kMasterForgotStatus);
      exit_status_ = kMasterForgotStatus;
      ros::requestShutdown();
      return;
    }
    for (int tenth = 0; tenth < 10 && !stopping_; ++tenth) std::this_thread::sleep_for(kWatchTick);
  }
}

// A restarted master holds none of the parameters roslaunch set: put back the ones this node started from,
// so that a respawned node starts on the same config (unless something has set them meanwhile).
void SimNode::restoreParameters() {
  if (ros::param::has(private_node_.getNamespace())) return;
  ros::param::set(private_node_.getNamespace(), start_params_);
  if (use_sim_time_ && !ros::param::has("/use_sim_time")) ros::param::set("/use_sim_time", true);
}

int SimNode::run() {
  ros::AsyncSpinner spinner(1);
  spinner.start();
  stepper_ = std::thread([this] { stepLoop(); });
  watcher_ = std::thread([this] { watchMaster(); });
  startReconfigureServers();
  ros::waitForShutdown();
  stopping_ = true;
  wake_.notify_all();
  stepper_.join();
  watcher_.join();
  if (recorder_) recorder_->commit();
  return exit_status_;
}

}  // namespace rigid_body_sim
