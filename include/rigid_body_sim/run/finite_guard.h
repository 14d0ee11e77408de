// The node's last line of defence against NaN: validation refuses every value known to produce a
// non-finite state, but should a body's state still become non-finite, that body is held at its last
// finite state (the others go on) and nothing non-finite reaches a message. No ROS header: pure logic.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <variant>
#include <vector>

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
bool surelyFinite(const Body& body);

// "k=1000 mass=0.5 ... integrator=euler_cromer gravity=9.8 | state x=0 y=4 ...": what led to a state.
std::string describeBody(const Body& body);

// A body that has just become non-finite, and the first quantity that did.
struct NonFinite {
  std::size_t index;
  std::string field;
};

// Holds every body whose state became non-finite at its last finite state. It keeps what a step changes
// (Model::Progress), not whole bodies: a step changes nothing else.
class FiniteGuard : public BodyStepObserver {
 public:
  explicit FiniteGuard(const std::vector<Body>& bodies);  // the current states are the last finite ones

  // Call on each body after its step (World::step's observer). A body that became non-finite is put back
  // to its last finite state and held there at every later call; takeNewlyHeld() gives it once.
  void afterBodyStep(std::size_t index, Body& body) override;
  // The bodies that became non-finite since the last call.
  std::vector<NonFinite> takeNewlyHeld();
  // afterBodyStep on every body, then takeNewlyHeld(): after a step taken without the guard as observer.
  std::vector<NonFinite> afterStep(std::vector<Body>& bodies);

  bool held(std::size_t index) const { return held_[index] != 0; }
  // The body runs again from its current model (after a reconfigure of it, or a reset); a model that is
  // not finite itself is held again at the next afterStep.
  void release(std::size_t index, const Body& body);
  void releaseAll(const std::vector<Body>& bodies);
  // The world's list of bodies changed: one spawned (appended), one deleted.
  void add(const Body& body);
  void remove(std::size_t index);

 private:
  using Progress = BodyTypes::Progresses;
  static Progress progressOf(const Body& body);

  std::vector<Progress> last_finite_;
  std::vector<NonFinite> newly_held_;
  std::vector<char> held_;  // not vector<bool>: its bit arithmetic was a sixth of the guard's time
};

}  // namespace rigid_body_sim
