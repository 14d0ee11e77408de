// The names a world gives out. A body's name is its TF frame and the namespace of its topics, services and
// reconfigure server; its fixed frame (and a rod's ground frame) are named from it.
#pragma once

#include <cstddef>
#include <string>

#include "rigid_body_sim/core/parameters.h"

namespace rigid_body_sim {

// The longest name of a body or of world_frame: it names topics, services and frames, and lines of text.
inline constexpr std::size_t kMaxNameLength = 64;

// True for a name usable as a ROS graph name component and as a TF frame: [A-Za-z][A-Za-z0-9_]*, at most
// kMaxNameLength characters.
bool isValidName(const std::string& name);

// The fixed frame in which a body's coordinates are measured: <name> and its type's suffix (a rod's
// <name>_floor, a body on an incline's <name>_slope).
template <class Type>
std::string fixedFrameOf(const std::string& name) {
  return name + Type::kFixedFrameSuffix;
}
std::string fixedFrameOf(const BodyConfig& body);
// The frame under a body on an unbounded floor (a rod's): <name>_ground.
std::string groundFrameOf(const std::string& name);

}  // namespace rigid_body_sim
