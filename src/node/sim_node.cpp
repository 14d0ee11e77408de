#include "rigid_body_sim/node/sim_node.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>

#include "rigid_body_sim/core/node_interface.h"
#include "rigid_body_sim/io/config_loader.h"
#include "rigid_body_sim/io/config_writer.h"
#include "rigid_body_sim/ros/launch_end.h"
#include "rigid_body_sim/ros/master_watch.h"
#include "rigid_body_sim/ros/messages.h"
#include "rigid_body_sim/ros/subscriber_backlog.h"
#include "rigid_body_sim/run/session.h"

namespace rigid_body_sim {

namespace {

constexpr double kMaxStepSeconds = 600.0;  // a ~step request may advance at most this much simulated time
constexpr auto kPausedWait = std::chrono::milliseconds(50);  // paused: how often ros::ok() is looked at
// After the last step of a `duration`, subscribers (a recorder, a slow listener at real_time_factor 0) are
// still handed what is queued for them: the node waits while any takes messages, until none has taken one
// for kEndQuiet, or for kEndDeadline at most (docs/performance.md: what a subscriber that stalls loses).
constexpr auto kEndQuiet = std::chrono::milliseconds(500);
constexpr auto kEndDeadline = std::chrono::seconds(30);

double wallNow() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The place of body `name` in `config`, or the number of bodies if it has none.
std::size_t indexIn(const WorldConfig& config, const std::string& name) {
  std::size_t index = 0;
  while (index < config.bodies.size() && config.bodies[index].name != name) ++index;
  return index;
}

std::optional<BodyConfig> findBody(const WorldConfig& config, const std::string& name) {
  const std::size_t index = indexIn(config, name);
  return index < config.bodies.size() ? std::optional(config.bodies[index]) : std::nullopt;
}

// The node's run: sampled (published) at publish_rate.
Session sessionOf(const WorldConfig& config) {
  return Session(config, node_interface::ownNames(), stepsPerSample(config.rate, config.publish_rate));
}

}  // namespace

SimNode::SimNode(ros::NodeHandle node, ros::NodeHandle private_node)
    : node_(node),
      private_node_(private_node),
      start_params_(privateParams(private_node)),
      options_(parseNodeOptions(start_params_)),
      session_(sessionOf(parseNodeConfig(start_params_))),
      after_step_([this](World& world) { afterStep(world); }),
      guard_(world().bodies(), world().dt()),
      pacer_(world().rate(), options_.real_time_factor),
      use_sim_time_(ros::param::param("/use_sim_time", false)),
      publisher_(node_, private_node_, options_, world(), use_sim_time_, stepper_tasks_),
      servers_(
          private_node_,
          [this](const std::string& name, const ReconfigureServers::Reconfigured& reconfigured) {
            return findBody(reconfigure(name, reconfigured, true).config, name);
          },
          [this](const std::string& name) {
            return onStepper([&] { return findBody(world().config(), name); });
          }),
      watch_(
          {private_node_.getNamespace(), start_params_, use_sim_time_, options_.publish_clock},
          kMasterForgotStatus, [this] { return stopping_.load(); },
          [this] {
            exit_status_ = kMasterForgotStatus;
            ros::requestShutdown();
          }),
      services_(private_node_, {[this](const std::string& kind, const std::string& body,
                                       const BuildCommand& build) { return change(kind, body, build); },
                                [this] { return onStepper([this] { return world().config(); }); },
                                [this](bool paused) { onStepper([&] { setPaused(paused); }); },
                                [this](std::uint64_t steps, Step::Response& response) {
                                  onStepper([&] { stepPaused(steps, response); });
                                },
                                [this] { return onStepper([this] { return runEventMessages(); }); }}) {
  paused_ = options_.start_paused;
  for (const auto& note : autoSubstepNotes(world().config())) ROS_INFO_STREAM(note);
  for (const auto& warning : slowRunWarnings(world().config())) ROS_WARN_STREAM(warning);
  if (!options_.bag.empty()) {
    const BagOptions bag{private_node_.getNamespace(), options_.frame_prefix,
                         markerOptions(options_, world().config().publish_rate)};
    recorder_ =
        std::make_unique<NodeRecorder>(options_.bag, world().config(), world().bodies(), bag,
                                       [this](double t, const std::string& what) { stopRecording(t, what); });
  }
  publisher_.publishPaused(paused_);
  publisher_.publishConfig(world());  // before the stepping thread starts
  session_.addSink(publisher_);
  if (recorder_) session_.addSink(*recorder_);
  interactive_ = std::make_unique<InteractiveControls>(
      private_node_.resolveName(node_interface::kInteractive), options_.frame_prefix,
      [this](const std::string& body, const std::map<std::string, double>& initial, std::string* why) {
        return onDrop(body, initial, why);
      });
  interactive_->show(world().config());
}

SimNode::~SimNode() { stopThreads(); }

ChangeAnswer SimNode::change(const std::string& kind, const std::string& body, const BuildCommand& build) {
  ChangeAnswer answer = onStepper([&] { return applyHere(kind, body, build); });
  if (!answer.accepted) ROS_WARN_STREAM(answer.why);
  if (!answer.command) return answer;
  servers_.follow(*answer.command);
  if (interactive_) interactive_->show(answer.config);  // the handles where the bodies now start
  return answer;
}

ChangeAnswer SimNode::applyHere(const std::string& kind, const std::string& body, const BuildCommand& build) {
  ChangeAnswer answer;
  std::size_t index = 0;  // the command's body's, before it
  try {
    answer.command = build(world());
    if (answer.command) {
      index = indexIn(world().config(), answer.command->body);
      // The pending publishing instant, the command, then the sinks' applied.
      session_.apply(*answer.command);
    }
  } catch (const ConfigError& error) {
    answer.command.reset();
    answer.why = refusalLine(kind, body, error.what());
  }
  answer.accepted = answer.why.empty();
  if (answer.accepted) answer.why = "ok";
  if (answer.command) followWorld(*answer.command, index);
  answer.t = world().time();
  answer.config = world().config();
  return answer;
}

void SimNode::followWorld(const WorldCommand& command, std::size_t index) {
  switch (command.kind) {
    case WorldCommand::Kind::Spawn: guard_.add(world().bodies().back()); break;
    case WorldCommand::Kind::Delete: guard_.remove(index); break;
    case WorldCommand::Kind::Reconfigure:
    case WorldCommand::Kind::SetState:
      if (guard_.held(index)) ROS_INFO_STREAM("body '" << command.body << "' runs again");
      guard_.release(index, world().bodies()[index]);
      break;
    case WorldCommand::Kind::Reset: guard_.releaseAll(world().bodies()); break;
    case WorldCommand::Kind::Config: break;  // the node applies none after its start
  }
  guard_.keepCurrent(world().bodies());  // a racer's change restarts every racer
}

// A request to a body's server that changes nothing (the server's first call, a dynparam set of the same
// values) is no command; a drop in rviz always is one.
ChangeAnswer SimNode::reconfigure(const std::string& name,
                                  const ReconfigureServers::Reconfigured& reconfigured,
                                  bool unchanged_is_none) {
  return change(toString(WorldCommand::Kind::Reconfigure), name,
                [&](const World& world) -> std::optional<WorldCommand> {
                  const auto before = findBody(world.config(), name);
                  if (!before) throw ConfigError(name, "name", "'" + name + "'", "a body of the world");
                  WorldCommand command;
                  command.kind = WorldCommand::Kind::Reconfigure;
                  command.body = name;
                  command.config = reconfigured(*before);
                  if (unchanged_is_none && toYaml(command.config) == toYaml(*before)) return std::nullopt;
                  return command;
                });
}

// A drop in rviz is a reconfigure of the body's initial keys: the same validation, the same one line when
// refused, the same log, and the server then shows what runs (as dynparam and the panel see it).
bool SimNode::onDrop(const std::string& body, const std::map<std::string, double>& initial,
                     std::string* why) {
  const auto dropped = [&](const BodyConfig& running) {
    return ReconfigureServers::withKeys(running, initial);
  };
  const ChangeAnswer answer = reconfigure(body, dropped, false);
  if (why) *why = answer.why;
  return answer.accepted;
}

void SimNode::setPaused(bool paused) {
  paused_ = paused;
  publisher_.publishPaused(paused);
  if (!paused) anchor();
}

void SimNode::stepPaused(std::uint64_t steps, Step::Response& response) {
  const auto max_steps = static_cast<std::uint64_t>(kMaxStepSeconds * world().rate());
  if (!paused_) {
    response.message = "refused: call ~pause first (the simulation is running)";
  } else if (steps == 0 || steps > max_steps) {
    response.message = "refused: steps " + std::to_string(steps) + " is not in [1, " +
                       std::to_string(max_steps) + "] (at most " + formatNumber(kMaxStepSeconds) + " s)";
  } else {
    session_.advance(static_cast<std::int64_t>(steps), after_step_, this);
    session_.sampleNow();  // show where the steps ended
    publisher_.publishMarkersNow(world());
    response.success = true;
    response.message = "ok";
  }
  response.t = world().time();
}

void SimNode::serveTasksFor(std::chrono::milliseconds wait) {
  const auto until = std::chrono::steady_clock::now() + wait;
  while (std::chrono::steady_clock::now() < until) {
    stepper_tasks_.runPending();
    stepper_tasks_.waitFor(until);
  }
  stepper_tasks_.runPending();
}

void SimNode::serveTasksWhileSubscribersTake() {
  const auto deadline = std::chrono::steady_clock::now() + kEndDeadline;
  std::uint64_t before = 0;
  std::uint64_t after = messagesHandedToSubscribers();
  do {
    before = after;
    serveTasksFor(kEndQuiet);
    after = messagesHandedToSubscribers();
  } while (after != before && std::chrono::steady_clock::now() < deadline);
}

// The pace and the stamps start from now and the current step: stepping starts or resumes.
void SimNode::anchor() {
  pacer_.restart(wallNow(), world().stepCount());
  publisher_.anchor(world().time());
}

void SimNode::movedByWorld(std::size_t index, Body& body) { guard_.movedByWorld(index, body); }

void SimNode::afterUnsureStep(std::size_t index, Body& body) { guard_.afterUnsureStep(index, body); }

void SimNode::afterBodiesStep(std::vector<Body>& bodies) {
#ifdef RBS_FAULT_INJECTION  // sim_node_faults, a test's build only: test/faults/fault_injection.h
  const double t = static_cast<double>(world().stepCount() + 1) / world().rate();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (injectFault(bodies[i], t)) guard_.afterUnsureStep(i, bodies[i]);
  }
#endif
  guard_.afterBodiesStep(bodies);
}

void SimNode::afterStep(World& world) {
  for (const NonFinite& fault : guard_.takeNewlyHeld()) {
    const Body& held = world.bodies()[fault.index];  // already back at its last finite state
    ROS_ERROR_STREAM("body '" << held.name << "': " << fault.field
                              << " became non-finite in the step to t = " << formatNumber(world.time())
                              << " s; the body is paused at its last finite state, the "
                              << "others go on (a reconfigure of it or ~reset restarts it). It ran with: "
                              << describeBody(held));
  }
  for (const auto& event : session_.takeEvents()) {
    ROS_DEBUG_STREAM(event.body << " " << event.kind << " at t = " << formatNumber(event.t) << " s");
  }
}

std::vector<Event> SimNode::runEventMessages() const {
  std::vector<Event> messages;
  for (const auto& event : publisher_.runEvents())
    messages.push_back(toEventMsg(event, publisher_.stampOf(event.t)));
  return messages;
}

void SimNode::stopRecording(double t, const std::string& what) {
  ROS_ERROR("recording stopped at t = %s s: %s; exiting with status %d", formatNumber(t).c_str(),
            what.c_str(), kRecordingFailedStatus);
  exit_status_ = kRecordingFailedStatus;
  stopping_ = true;
  if (options_.end_launch) endParentRoslaunch();
  ros::requestShutdown();
}

// start_delay wall seconds; with start_on_subscribers only until every state topic, ~events and the
// transforms
// (/tf, or the namespace's tf) have a subscriber (a recorder that found them), start_delay the most it waits.
// Changes handed over meanwhile apply at once.
void SimNode::waitForStart() {
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                             std::chrono::duration<double>(options_.start_delay));
  while (!stopping_ && std::chrono::steady_clock::now() < deadline) {
    stepper_tasks_.runPending();
    if (options_.start_on_subscribers && publisher_.subscribed()) return;
    // Subscriptions arrive on the spinner's thread, which does not wake this one: look again soon.
    stepper_tasks_.waitFor(
        std::min(deadline, std::chrono::steady_clock::now() + std::chrono::milliseconds(20)));
  }
  if (options_.start_on_subscribers && !stopping_ && !publisher_.subscribed()) {
    ROS_WARN(
        "stepping starts after start_delay (%s s) although not every state topic and /tf has a subscriber: "
        "a recorder misses the first states",
        formatNumber(options_.start_delay).c_str());
  }
}

void SimNode::stepLoop() {
  stepper_tasks_.becomeOwner();
  // A valid time before stepping starts (the clock is latched): rosbag record, for one, waits for one before
  // it subscribes to anything, and so would miss the start of a run on simulated time.
  publisher_.publishClock(world());
  waitForStart();
  anchor();
  publisher_.publishScene(world());
  session_.sampleNow();  // unless a command published this count
  const auto duration_steps = static_cast<std::int64_t>(std::llround(options_.duration * world().rate()));
  while (!stopping_ && ros::ok()) {
    stepper_tasks_.runPending();
    if (paused_) {
      stepper_tasks_.waitFor(std::chrono::steady_clock::now() + kPausedWait);
      continue;
    }
    // Step up to what is due, one publishing interval at a time, the work handed over between them.
    const std::int64_t steps_per_publish = session_.stepsPerSample();
    const std::int64_t next_publish = (world().stepCount() / steps_per_publish + 1) * steps_per_publish;
    const std::int64_t target = std::min(pacer_.dueSteps(wallNow()), next_publish);
    while (world().stepCount() < target) {
      session_.advance(1, after_step_, this);  // one at a time: the duration ends a run at its step
      if (duration_steps > 0 && world().stepCount() >= duration_steps) {
        ROS_INFO("simulated %.3f s: the requested duration; shutting down", world().time());
        serveTasksWhileSubscribersTake();
        if (options_.end_launch) endParentRoslaunch();  // its recorder and rviz with it
        ros::requestShutdown();
        return;
      }
    }
    if (pacer_.asFastAsPossible()) continue;
    const double wake_at =
        pacer_.wallTimeOf((world().stepCount() / steps_per_publish + 1) * steps_per_publish);
    stepper_tasks_.waitFor(
        std::chrono::steady_clock::time_point(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
            std::chrono::duration<double>(wake_at))));
  }
}

void SimNode::stopThreads() {
  stopping_ = true;
  stepper_tasks_.stop();
  servers_.stop();
  watch_.stop();
  if (stepper_.joinable()) stepper_.join();
}

int SimNode::run() {
  ros::AsyncSpinner spinner(1);  // every callback on one thread: see sim_node.h
  spinner.start();
  stepper_ = std::thread([this] {
    stepLoop();
    stepper_tasks_.finish();
  });
  watch_.start();
  // Once stepping has started: the first states need not wait.
  servers_.startAll([this] { return onStepper([this] { return world().config(); }); });
  // The stepper runs until roscpp shuts down (Ctrl-C, the duration done, a forgetful master): waiting for
  // it wakes nothing, where ros::waitForShutdown would look 20 times a second.
  stepper_.join();
  stopThreads();
  if (recorder_) onStepper([this] { recorder_->commit(); });
  return exit_status_;
}

}  // namespace rigid_body_sim
