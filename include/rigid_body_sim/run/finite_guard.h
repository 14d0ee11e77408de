// The node's last line of defence against NaN: validation refuses every value known to produce a
// non-finite state, but should a body's state still become non-finite, that body is held at its last
// finite state (the others go on) and nothing non-finite reaches a message. No ROS header: pure logic.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "rigid_body_sim/core/state_fields.h"
#include "rigid_body_sim/core/world.h"

namespace rigid_body_sim {

// The first non-finite quantity that a body's messages carry (its state, energy, and a roller's
// friction and normal force), e.g. "theta"; nullopt when all are finite.
std::optional<std::string> nonFiniteField(const Body& body);
inline bool finiteState(const Body& body) { return !nonFiniteField(body).has_value(); }

inline bool surelyFinite(const Body& body) {
  return std::visit([](const auto& model) { return surelyFiniteModel(model); }, body.model);
}

// "k=1000 mass=0.5 ... integrator=euler_cromer gravity=9.8 | state x=0 y=4 ...": what led to a state.
std::string describeBody(const Body& body);

// A body that has just become non-finite, and the first quantity that did.
struct NonFinite {
  std::size_t index;
  std::string field;
};

// Holds every body whose state became non-finite at its last finite state. It keeps what a step changes
// (Model::Progress), not whole bodies: a step changes nothing else; and it keeps it every kStepsPerKeep
// steps only, with the step it kept it at: a step is deterministic, so the last finite state is the kept one
// stepped again as many times as the world stepped since (a copy after every step was most of the guard's
// cost). World::step names it only the bodies not surely finite; the others cost it nothing.
class FiniteGuard : public BodyStepObserver {
 public:
  static constexpr std::uint64_t kStepsPerKeep = 64;

  // The current states are the last finite ones; `dt` is the world's step.
  FiniteGuard(const std::vector<Body>& bodies, double dt);

  // A body not surely finite after its step: one that became non-finite is put back to its last finite
  // state and held there (afterBodiesStep puts it back after every later step); takeNewlyHeld() gives it
  // once.
  void afterUnsureStep(std::size_t index, Body& body) override;
  // Every held body back to its last finite state; every kStepsPerKeep steps, every other body kept.
  void afterBodiesStep(std::vector<Body>& bodies) override;
  void movedByWorld(std::size_t index, Body& body) override;  // kept as it is now
  // The bodies that became non-finite since the last call.
  std::vector<NonFinite> takeNewlyHeld();
  // What World::step tells the guard as its observer, then takeNewlyHeld(): after a step taken without it.
  std::vector<NonFinite> afterStep(std::vector<Body>& bodies);

  bool held(std::size_t index) const { return held_[index] != 0; }
  // The body runs again from its current model (after a reconfigure of it, or a reset); a model that is
  // not finite itself is held again at the next afterStep.
  void release(std::size_t index, const Body& body);
  void releaseAll(const std::vector<Body>& bodies);
  // After any other change to the world (a command): every body not held is kept as it is now, since a
  // change may move more bodies than the one it names (a racer's restarts every racer).
  void keepCurrent(const std::vector<Body>& bodies);
  // The world's list of bodies changed: one spawned (appended), one deleted.
  void add(const Body& body);
  void remove(std::size_t index);

 private:
  using Progress = BodyTypes::Progresses;
  static Progress progressOf(const Body& body);
  void keep(std::size_t index, const Body& body);  // its progress now, at the current step

  double dt_;
  std::uint64_t steps_ = 0;             // the steps observed (afterBodiesStep calls)
  std::vector<Progress> kept_;          // a finite progress of each body (a held one's last finite)
  std::vector<std::uint64_t> kept_at_;  // steps_ when it was kept
  std::size_t held_count_ = 0;          // how many are held (most steps: none)
  std::vector<NonFinite> newly_held_;
  std::vector<char> held_;  // not vector<bool>: its bit arithmetic was a sixth of the guard's time
};

}  // namespace rigid_body_sim
