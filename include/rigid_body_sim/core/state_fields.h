// What a body reports at every sample, field by field, in the order of its CSV columns (after t) and of
// its state message (after header and t): the one list behind the CSV header and rows, the sweep's columns,
// the fields ~set_state sets and the NaN guard. The state messages are filled field by field
// (ros/messages.h); a test checks their definitions against this list.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "rigid_body_sim/core/world.h"

namespace rigid_body_sim {

// One reported field: a number, or (a roller's mode) a text.
struct StateField {
  const char* name;
  double number = 0.0;
  std::string text = {};  // not empty for a field that is text
};

// rod: x, y, theta, vx, vy, omega, energy
std::array<StateField, 7> stateFields(const Rod& rod);
// roller: x, v, theta, omega, mode, friction, normal, energy (friction and normal along the slope's +x, +y)
std::array<StateField, 8> stateFields(const Roller& roller);

// The field names of a kind of body, in the same order.
const std::vector<std::string>& stateFieldNames(BodyKind kind);

// The fields that make up a body's state (what ~set_state may set): the first ones of stateFieldNames,
// before what follows from them (a roller's mode, friction and normal force, the energy). Rod x, y, theta,
// vx, vy, omega; roller x, v, theta, omega.
const std::vector<std::string>& settableStateFields(BodyKind kind);

}  // namespace rigid_body_sim
