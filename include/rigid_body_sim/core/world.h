// Any number of named bodies stepped on one clock. Time is an integer step count: t = n / rate.
#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "rigid_body_sim/core/parameters.h"
#include "rigid_body_sim/core/rod.h"
#include "rigid_body_sim/core/roller.h"

namespace rigid_body_sim {

struct Body {
  std::string name;
  std::variant<Rod, Roller> model;
};

// Something worth telling that happened to a body at simulated time t.
struct WorldEvent {
  enum class Kind { StartedRolling, StartedSlipping, Restarted };
  double t;
  std::string body;
  Kind kind;
};
std::string toString(WorldEvent::Kind kind);

class World {
 public:
  explicit World(const WorldConfig& config);  // validates; throws ConfigError

  void step();   // one step of dt = 1 / rate for every body
  void reset();  // every body back to its initial conditions; time goes on

  std::int64_t stepCount() const { return steps_; }
  double time() const;  // stepCount() / rate
  double rate() const { return rate_; }
  double dt() const { return dt_; }

  std::vector<Body>& bodies() { return bodies_; }
  const std::vector<Body>& bodies() const { return bodies_; }
  Body* find(const std::string& name);

  // Events since the last takeEvents().
  std::vector<WorldEvent> takeEvents();

 private:
  double rate_;
  double dt_;
  std::int64_t steps_ = 0;
  std::vector<Body> bodies_;
  std::vector<WorldEvent> events_;
};

// Total energy of a body (J), whatever its kind.
double energyOf(const Body& body);

BodyKind kindOf(const Body& body);
std::string fixedFrameOf(const Body& body);  // <name>_floor or <name>_slope

}  // namespace rigid_body_sim
