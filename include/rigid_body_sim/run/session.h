// The run loop shared by everything that steps a world and hands out its states: a Session owns the World,
// steps it, hands the state at every sampling instant to its sinks, and applies every change of the world
// in the one order that makes a run reproducible from its command log:
//
//   the state at a step count is handed out (sampled) at most once, and before the commands at that count
//   apply; a command applied while the count is c applies before the step from c to c + 1.
//
// The offline run (run/offline_run.h) and the replay (run/replay.h) run through it, writing CSV files and
// bags in their sinks. How a node uses it: its publisher is a sink (write publishes the states, TF and
// markers; applied publishes the command on ~commands with the index as its seq); every change, whatever
// its entry point, goes through Session::apply (which publishes a pending instant first; a ConfigError is
// the refusal to report); the stepping thread calls advance() with the NaN guard as the step hook and takes
// the events (handed to every sink too); sampleNow() shows the state at the start and after a ~step that ends
// off the publishing grid. Pausing is the caller's: paused, it does not advance, while commands still apply.
// No ROS here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "rigid_body_sim/core/world.h"

namespace rigid_body_sim {

// Where the states and changes of a run go: CSV files, a bag (ros/bag_recorder.h), a node's topics.
class SampleSink {
 public:
  virtual ~SampleSink() = default;
  virtual void write(const World& world) = 0;  // at every sample, t = 0 included
  // A change of the world (number `index` of its log; 0 is the config the sink was opened with), applied
  // to `world` at world.time(): logged as the node logs it, the scene following.
  virtual void applied(const WorldCommand& command, std::size_t index, const World& world) = 0;
  // What happened in a step or with a change (core/event.h), in time order, each event at or before
  // world.time(); before the state at that count is written.
  virtual void happened(const std::vector<BodyEvent>& events, const World& world) = 0;
  // The run is complete: the output becomes final. The owner of the run calls it, never the Session.
  virtual void commit() {}
};

// Called after every step, before the state is handed out: counts what happens between samples (the
// offline run's bounces) or repairs a body (the node's NaN guard). Changes of the world go through apply.
using StepHook = std::function<void(World& world)>;

// Steps between two samples at `sample_rate` Hz (a divisor of `rate`).
std::int64_t stepsPerSample(double rate, double sample_rate);

class Session {
 public:
  // Validates `config` as World does (throws ConfigError); std::invalid_argument if steps_per_sample < 1.
  // Nothing is handed out yet: call sampleNow() for the state at count 0 once the sinks are added.
  Session(const WorldConfig& config, std::vector<std::string> reserved_names, std::int64_t steps_per_sample);
  Session(const Session&) = delete;  // a copy would hand out to the same sinks
  Session& operator=(const Session&) = delete;

  // Not owned: each must outlive the session's use. Called in the order added.
  void addSink(SampleSink& sink);

  // Takes `steps` steps (std::invalid_argument if negative), `observer` seeing each body after its step and
  // `after_step` called after each step; whenever the count lands on a sampling instant (a multiple of
  // stepsPerSample()), hands the state to the sinks.
  void advance(std::int64_t steps = 1, const StepHook& after_step = {}, BodyStepObserver* observer = nullptr);

  // The one way to change the world. At a sampling instant not yet handed out, hands it out first (the
  // state of the count, whatever the command); then applies `command` at the current count (command.step
  // is set here) and tells the sinks. Returns its index in the log (the config is 0; 1, 2, ... follow). A
  // refusal throws ConfigError from World::apply: the world is unchanged and no sink hears of it.
  std::size_t apply(WorldCommand command);

  // Hands out the current state unless this count already has been (on the grid or off it): the start, the
  // end of a ~step. Returns whether it did.
  bool sampleNow();

  bool sampled() const { return last_sampled_ == world_.stepCount(); }  // this count handed out
  bool atSamplingInstant() const { return world_.stepCount() % steps_per_sample_ == 0; }
  std::int64_t stepsPerSample() const { return steps_per_sample_; }
  std::size_t commandsApplied() const { return commands_applied_; }  // after the config

  const World& world() const { return world_; }
  // The events handed to the sinks since the last call.
  std::vector<BodyEvent> takeEvents();

 private:
  void handOut();
  // The world's new events to the sinks (an event with a non-finite number, from a step the NaN guard
  // undid, is dropped: nothing hands out NaN), and kept for takeEvents().
  void handEvents();

  World world_;
  std::int64_t steps_per_sample_;
  std::int64_t last_sampled_ = -1;  // the count last handed out
  std::size_t commands_applied_ = 0;
  std::vector<SampleSink*> sinks_;
  std::vector<BodyEvent> events_;  // handed out, not yet taken
};

}  // namespace rigid_body_sim
