// A fault where the node's NaN guard looks, for sim_node_faults only: test/CMakeLists.txt builds the node's
// sources once more with RBS_FAULT_INJECTION and this header included, and SimNode::afterBodiesStep then
// calls injectFault on each body after the step, before the guard looks at it. The installed sim_node has
// neither. At the first step to a time at or after $RBS_FAULT_TIME (s), body $RBS_FAULT_BODY's x becomes NaN,
// as a step gone wrong would leave it; without RBS_FAULT_BODY nothing happens. (Environment variables: the
// node refuses a private parameter that is not one of its keys.)
#pragma once

#include <cstdlib>
#include <limits>
#include <string>
#include <variant>

#include "rigid_body_sim/core/world.h"

namespace rigid_body_sim {

// `body` has just stepped to time `t`. True when it made the body's x NaN.
inline bool injectFault(Body& body, double t) {
  struct Fault {
    std::string body;
    double time = 0.0;
    bool done = false;
  };
  static Fault fault = [] {
    Fault planned;
    const char* name = std::getenv("RBS_FAULT_BODY");
    const char* time = std::getenv("RBS_FAULT_TIME");
    planned.body = name ? name : "";
    planned.time = time ? std::atof(time) : 0.0;
    planned.done = planned.body.empty();
    return planned;
  }();
  if (fault.done || t < fault.time || body.name != fault.body) return false;
  std::visit(
      [](auto& model) {
        auto state = model.state();
        state.x = std::numeric_limits<double>::quiet_NaN();
        model.setState(state);
      },
      body.model);
  fault.done = true;
  return true;
}

}  // namespace rigid_body_sim
