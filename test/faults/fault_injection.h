// A fault where the node's NaN guard looks, for sim_node_faults only: test/CMakeLists.txt builds the node's
// sources once more with RBS_FAULT_INJECTION and this header included, and SimNode::afterStep then calls
// injectFault before the guard after every step. The installed sim_node has neither. At the first step to a
// time at or after $RBS_FAULT_TIME (s), body $RBS_FAULT_BODY's x becomes NaN, as a step gone wrong would
// leave it; without RBS_FAULT_BODY nothing happens. (Environment variables: the node refuses a private
// parameter that is not one of its keys.)
#pragma once

#include <cstdlib>
#include <limits>
#include <string>
#include <variant>

#include "rigid_body_sim/core/world.h"

namespace rigid_body_sim {

inline void injectFault(World& world) {
  struct Fault {
    std::string body;
    double time = 0.0;
    bool done = false;
  };
  static Fault fault = [] {
    Fault planned;
    const char* body = std::getenv("RBS_FAULT_BODY");
    const char* time = std::getenv("RBS_FAULT_TIME");
    planned.body = body ? body : "";
    planned.time = time ? std::atof(time) : 0.0;
    planned.done = planned.body.empty();
    return planned;
  }();
  if (fault.done || world.time() < fault.time) return;
  const auto poison = [](auto& model) {
    auto state = model.state();
    state.x = std::numeric_limits<double>::quiet_NaN();
    model.setState(state);
  };
  for (Body& body : world.bodies()) {
    if (body.name == fault.body) std::visit(poison, body.model);
  }
  fault.done = true;
}

}  // namespace rigid_body_sim
