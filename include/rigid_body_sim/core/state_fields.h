// What a body reports at every sample, field by field, in the order of its CSV columns (after t) and of its
// state message (after header and t). Each body type's table (Type::kStateFields, core/types/) is the one
// list: the CSV header and rows, the sweep's columns, the fields ~set_state sets, the NaN guard's check and
// the state messages (ros/messages.h) follow from it; tests check the .msg files and scripts/ against it.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "rigid_body_sim/core/world.h"

namespace rigid_body_sim {

template <class Model>
constexpr const auto& stateFieldTable(const Model&) {
  return TypeOfModel<Model>::kStateFields;
}

// One reported field: a number, or (a mode) a text.
struct StateField {
  const char* name;
  double number = 0.0;
  std::string text = {};  // not empty for a field that is text
};

// The fields of a model now, in its table's order.
template <class Model>
auto stateFields(const Model& model) {
  const auto& table = stateFieldTable(model);
  std::array<StateField, std::tuple_size_v<std::decay_t<decltype(table)>>> fields;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const auto& def = table[i];
    fields[i].name = def.name;
    if (def.settable()) {
      fields[i].number = model.state().*def.motion;
    } else if (def.number != nullptr) {
      fields[i].number = (model.*def.number)();
    } else {
      fields[i].text = def.text(model);
    }
  }
  return fields;
}

// The field names of a type (all, or the settable ones: what ~set_state may set), in its table's order.
template <class Type>
const std::vector<std::string>& stateFieldNames(bool settable_only = false) {
  static const auto names = [](bool settable) {
    std::vector<std::string> out;
    for (const auto& field : Type::kStateFields) {
      if (!settable || field.settable()) out.emplace_back(field.name);
    }
    return out;
  };
  static const std::vector<std::string> all = names(false);
  static const std::vector<std::string> settable = names(true);
  return settable_only ? settable : all;
}
const std::vector<std::string>& stateFieldNames(const Body& body);
const std::vector<std::string>& stateFieldNames(const BodyConfig& body);
const std::vector<std::string>& settableStateFields(const Body& body);

// How many of a type's fields are settable, and their members of the motion, in the table's order: picked
// at compile time (the NaN guard's check after every step runs over these alone).
template <class Type>
constexpr std::size_t settableCount() {
  std::size_t count = 0;
  for (const auto& field : Type::kStateFields) count += field.settable() ? 1 : 0;
  return count;
}
template <class Type>
constexpr auto settableMembers() {
  std::array<typename StateFieldDef<typename Type::Model>::MotionMember, settableCount<Type>()> members{};
  std::size_t i = 0;
  for (const auto& field : Type::kStateFields) {
    if (field.settable()) members[i++] = field.motion;
  }
  return members;
}

// Every field of the motion finite and at most kSurelyFiniteMotion in size: then, with parameters in their
// validated ranges, every quantity a body's messages carry is finite (the energies stay below 1e230, the
// forces follow from the parameters). World::step checks this on each body right after its step, while it
// is at hand in the cache, and names to its observer (the node's NaN guard) only the bodies that fail it.
inline constexpr double kSurelyFiniteMotion = 1e100;
// The settable fields are the motion; the rest follow from it. std::abs(NaN) <= bound is false: a NaN is
// never surely finite. The members are picked at compile time: the check runs over these alone, unrolled.
template <class Model>
bool surelyFiniteModel(const Model& model) {
  static constexpr auto kMembers = settableMembers<TypeOfModel<Model>>();
  bool finite = true;
  for (const auto member : kMembers) finite &= std::abs(model.state().*member) <= kSurelyFiniteMotion;
  return finite;
}

// The motion's field named `name` among the settable ones of the model's table, or null.
template <class Model>
auto settableMember(const Model& model, const std::string& name) {
  typename StateFieldDef<Model>::MotionMember member = nullptr;
  for (const auto& field : stateFieldTable(model)) {
    if (field.settable() && name == field.name) member = field.motion;
  }
  return member;
}

}  // namespace rigid_body_sim
