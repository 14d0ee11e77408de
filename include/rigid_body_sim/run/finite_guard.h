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

// Every field of the body's motion finite and at most kSurelyFiniteMotion in size: then, with parameters
// in their validated ranges, every quantity its messages carry is finite (the energies stay below 1e230,
// the forces follow from the parameters). The guard's check after every step, far cheaper than
// nonFiniteField, which it calls only when this fails.
inline constexpr double kSurelyFiniteMotion = 1e100;
// The settable fields are the motion; the rest follow from it. std::abs(NaN) <= bound is false: a NaN is
// never surely finite. The members are picked at compile time: the check after every step runs over these
// alone, unrolled, inline in the step's loop.
template <class Model>
bool surelyFiniteModel(const Model& model) {
  static constexpr auto kMembers = settableMembers<TypeOfModel<Model>>();
  bool finite = true;
  for (const auto member : kMembers) finite &= std::abs(model.state().*member) <= kSurelyFiniteMotion;
  return finite;
}
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
// steps only, with the count of finite steps since: a step is deterministic, so the last finite state is
// the kept one stepped again that many times (a copy after every step was most of the guard's cost).
class FiniteGuard : public BodyStepObserver {
 public:
  static constexpr std::uint32_t kStepsPerKeep = 64;

  // The current states are the last finite ones; `dt` is the world's step.
  FiniteGuard(const std::vector<Body>& bodies, double dt);

  // Call on each body after its step (World::step's observer). A body that became non-finite is put back
  // to its last finite state and held there at every later call; takeNewlyHeld() gives it once.
  void afterBodyStep(std::size_t index, Body& body) override {
    // Most calls: a body not held, surely finite. Its kept progress is not even looked at (the kept array
    // through the cache at every step was most of what the guard cost).
    if (!held_[index] && surelyFinite(body)) {
      if (++steps_since_[index] == kStepsPerKeep) keep(index, body);
      return;
    }
    afterUnsureStep(index, body);
  }
  void movedByWorld(std::size_t index, Body& body) override;  // kept as it is now
  // The bodies that became non-finite since the last call.
  std::vector<NonFinite> takeNewlyHeld();
  // afterBodyStep on every body, then takeNewlyHeld(): after a step taken without the guard as observer.
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
  void keep(std::size_t index, const Body& body);       // its progress now, the count of steps since 0
  void afterUnsureStep(std::size_t index, Body& body);  // afterBodyStep of a body held or not surely finite

  double dt_;
  std::vector<Progress> kept_;              // a finite progress of each body (a held one's last finite)
  std::vector<std::uint32_t> steps_since_;  // the finite steps since it was kept
  std::vector<NonFinite> newly_held_;
  std::vector<char> held_;  // not vector<bool>: its bit arithmetic was a sixth of the guard's time
};

}  // namespace rigid_body_sim
