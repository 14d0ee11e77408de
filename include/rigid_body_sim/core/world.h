// Any number of named bodies stepped on one clock. Time is an integer step count: t = n / rate.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "rigid_body_sim/core/command.h"
#include "rigid_body_sim/core/event.h"
#include "rigid_body_sim/core/parameters.h"

namespace rigid_body_sim {

// A racer's result in the current lap of a race (WorldConfig::race).
struct RaceFinish {
  int place;     // 1: the first over the line; racers whose times are within kTieTime share a place
  double time;   // s from the lap's start to the instant it passed the end of its slope
  double speed;  // m/s along the slope at that instant (it then waits at rest)
  std::optional<double> closed_form;  // s: the same from the closed forms (closedFormRun)
};
// Finish times this close are a tie: they differ by the rounding of the steps that located them.
inline constexpr double kTieTime = 1e-9;

struct Body {
  std::string name;
  AnyModel model;
  std::optional<RaceFinish> finish;  // a racer that finished the current lap
  double lap_start = 0.0;            // s: when its current lap started (its start, a restart, a reset)
  bool lap_as_configured = true;     // nothing moved it or changed it since (its lap's closed form holds)
};

// The names of a type's event kinds, and what each means (Type::kEventKinds), in its order.
struct EventKindInfo {
  std::string name;
  std::string meaning;
};

// Looks at the bodies after each step (the node's NaN guard). The world checks each body right after its
// step, while it is at hand in the cache (surelyFiniteModel, core/state_fields.h), and names only those that
// fail it: most steps cost the observer one call, not one a body.
class BodyStepObserver {
 public:
  // A body whose motion is not surely finite right after its step (in the step, before the next body's).
  virtual void afterUnsureStep(std::size_t index, Body& body) = 0;
  // Once every body has stepped, before the world moves any itself (movedByWorld) and its clock advances.
  virtual void afterBodiesStep(std::vector<Body>& bodies) = 0;
  // The world itself moved the body in the step, after afterBodiesStep (a race's next lap).
  virtual void movedByWorld(std::size_t index, Body& body) = 0;

 protected:
  ~BodyStepObserver() = default;
};

class World {
 public:
  // Simulated seconds a race's results stand, every racer at its finish, before the next lap starts.
  static constexpr double kRaceResultsShown = 2.0;

  // Validates (with the names a body may not take beside the world keys); throws ConfigError.
  explicit World(const WorldConfig& config, std::vector<std::string> reserved_names = {});

  // One step of dt = 1 / rate for every body; `observer` sees the bodies after it (BodyStepObserver).
  void step(BodyStepObserver* observer = nullptr);
  void reset();  // every body back to its initial conditions (a race's new lap); time goes on

  // Applies a change made while the world runs (command.step must be stepCount()). The world it would make
  // is validated exactly like a config file (names, reserved names, distinct frames, ranges, relations, at
  // most kMaxBodies bodies), a SetState's fields like the matching initial conditions; a refusal throws
  // ConfigError (one line) and changes nothing.
  //   Config: every body anew from the command's world (same rate and publish_rate); time goes on.
  //   Reconfigure: new parameters; the body restarts only when its initial conditions changed.
  //   Spawn: a new body (last in bodies()) starting from its initial conditions now.
  //   Delete: the body goes (the world keeps at least one).
  //   SetState: the body moves now; its initial conditions stay (a roller's mode follows from v and omega).
  //   Reset: every body back to its initial conditions; time goes on.
  void apply(const WorldCommand& command);

  // The world as it runs now: what a config file of it says (spawned, deleted, reconfigured bodies included).
  const WorldConfig& config() const { return config_; }

  std::int64_t stepCount() const { return steps_; }
  double time() const;  // stepCount() / rate
  double rate() const { return rate_; }
  double dt() const { return dt_; }

  std::vector<Body>& bodies() { return bodies_; }
  const std::vector<Body>& bodies() const { return bodies_; }
  Body* find(const std::string& name);
  std::optional<std::size_t> indexOf(const std::string& name) const;

  // What happened since the last takeEvents() (core/event.h), in time order.
  std::vector<BodyEvent> takeEvents();
  bool hasEvents() const { return !events_.empty(); }

 private:
  std::size_t existingIndex(const WorldCommand& command) const;  // of command.body; throws ConfigError
  // command.config with the world's gravity, checked to be the body the command names.
  BodyConfig bodyOf(const WorldCommand& command) const;
  void validateWouldBe(const WorldConfig& config) const;
  void setState(std::size_t index, const std::vector<StateValue>& state);
  // A race (WorldConfig::race): a racer (a type with kRaces) that passes the end of its slope at t with
  // `speed` finishes; places follow the times (ties share one). Once every racer has, the results stand
  // kRaceResultsShown simulated seconds, then all start a new lap together.
  void finish(std::size_t index, double t, double speed);
  // Collects the events of a step of body `index` that started at t0.
  template <class Model, class Happened>
  void report(std::size_t index, double t0, const Model& model, const Happened& happened);
  // Collects one event of kind Type::kEventKinds[kind] at t, `at` being the model at that instant.
  template <class Model>
  void record(std::size_t index, double t, std::size_t kind, const Model& at, std::vector<EventValue> values);
  // The body started again from its initial conditions now (a reset, a restarting change): its type's
  // restart event, with `cause`.
  void restarted(std::size_t index, const char* cause);
  void placeFinishers(std::size_t first_event);  // a race's places on the finish events from first_event on
  bool raceOver() const;
  // Every racer starts a new lap now (a restart event with `cause` each); false, doing nothing, unless the
  // world races.
  bool restartRace(const char* cause, BodyStepObserver* observer = nullptr);

  WorldConfig config_;
  std::vector<std::string> reserved_names_;
  double rate_;
  double dt_;
  std::int64_t steps_ = 0;
  std::int64_t lap_start_step_ = 0;             // of the race's current lap
  std::optional<std::int64_t> race_over_step_;  // when its last racer finished
  std::vector<Body> bodies_;
  std::vector<BodyEvent> events_;
};

// Total energy of a body (J), whatever its kind.
double energyOf(const Body& body);

std::string typeName(const Body& body);  // its type's kName
// Each type's event kinds, by type name, in the list's order.
const std::vector<std::pair<std::string, std::vector<EventKindInfo>>>& eventKindsByType();
std::string fixedFrameOf(const Body& body);  // <name>_floor or <name>_slope

}  // namespace rigid_body_sim
