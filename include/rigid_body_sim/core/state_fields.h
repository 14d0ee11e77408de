// What a body reports at every sample, field by field, in the order of its CSV columns (after t) and of
// its state message (after header and t). The tables below are the one list: the CSV header and rows, the
// sweep's columns, the fields ~set_state sets, the NaN guard's check and the state messages
// (ros/messages.h) follow from them; tests check the .msg files and scripts/ against them.
#pragma once

#include <array>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "rigid_body_sim/core/world.h"

namespace rigid_body_sim {

// One field of a body of type Model (Rod or Roller): a field of its motion (settable: ~set_state writes
// it there), or a number or text that follows from the state and the parameters.
template <class Model>
struct StateFieldDef {
  using Motion = std::decay_t<decltype(std::declval<const Model&>().state())>;
  using MotionMember = double Motion::*;  // named: clang-format 14 and 19 disagree on `T::* name`
  const char* name;
  const char* unit;                             // as the .msg comments give it; "" for a text
  MotionMember motion = nullptr;                // settable
  double (Model::*number)() const = nullptr;    // derived number
  std::string (*text)(const Model&) = nullptr;  // derived text

  constexpr bool settable() const { return motion != nullptr; }
};

using RodField = StateFieldDef<Rod>;
using RollerField = StateFieldDef<Roller>;

std::string modeText(const Roller& roller);  // rolling | slipping

inline constexpr std::array kRodStateFields{
    RodField{"x", "m", &RodMotion::x},
    RodField{"y", "m", &RodMotion::y},
    RodField{"theta", "rad", &RodMotion::theta},
    RodField{"vx", "m/s", &RodMotion::vx},
    RodField{"vy", "m/s", &RodMotion::vy},
    RodField{"omega", "rad/s", &RodMotion::omega},
    RodField{"energy", "J", nullptr, &Rod::energy},  // kinetic + gravitational + elastic
};

// friction and normal: the forces on the body along the slope's +x and +y.
inline constexpr std::array kRollerStateFields{
    RollerField{"x", "m", &RollerMotion::x},
    RollerField{"v", "m/s", &RollerMotion::v},
    RollerField{"theta", "rad", &RollerMotion::theta},
    RollerField{"omega", "rad/s", &RollerMotion::omega},
    RollerField{"mode", "", nullptr, nullptr, &modeText},
    RollerField{"friction", "N", nullptr, &Roller::frictionForce},
    RollerField{"normal", "N", nullptr, &Roller::normalForce},
    RollerField{"energy", "J", nullptr, &Roller::energy},
};

constexpr const auto& stateFieldTable(const Rod&) { return kRodStateFields; }
constexpr const auto& stateFieldTable(const Roller&) { return kRollerStateFields; }

// One reported field: a number, or (a roller's mode) a text.
struct StateField {
  const char* name;
  double number = 0.0;
  std::string text = {};  // not empty for a field that is text
};

std::array<StateField, kRodStateFields.size()> stateFields(const Rod& rod);
std::array<StateField, kRollerStateFields.size()> stateFields(const Roller& roller);

// The field names of a kind of body, in the table's order.
const std::vector<std::string>& stateFieldNames(BodyKind kind);

// The settable fields of a kind of body (what ~set_state may set), in the table's order.
const std::vector<std::string>& settableStateFields(BodyKind kind);

// The motion's field named `name` among the settable ones of the model's table, or null.
template <class Model>
auto settableMember(const Model& model, const std::string& name) {
  decltype(StateFieldDef<Model>::motion) member = nullptr;
  for (const auto& field : stateFieldTable(model)) {
    if (field.settable() && name == field.name) member = field.motion;
  }
  return member;
}

}  // namespace rigid_body_sim
