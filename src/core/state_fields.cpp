#include "rigid_body_sim/core/state_fields.h"

namespace rigid_body_sim {

namespace {

template <class Model, std::size_t N>
std::array<StateField, N> read(const Model& model, const std::array<StateFieldDef<Model>, N>& table) {
  std::array<StateField, N> fields;
  for (std::size_t i = 0; i < N; ++i) {
    const StateFieldDef<Model>& def = table[i];
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

template <class Table>
std::vector<std::string> namesOf(const Table& table, bool settable_only) {
  std::vector<std::string> names;
  for (const auto& field : table) {
    if (!settable_only || field.settable()) names.emplace_back(field.name);
  }
  return names;
}

template <class Table>
constexpr std::size_t settableCount(const Table& table) {
  std::size_t count = 0;
  for (const auto& field : table) count += field.settable() ? 1 : 0;
  return count;
}

// The settable fields are the whole motion (a set_state can set any of it, the NaN guard checks all of it).
static_assert(settableCount(kRodStateFields) * sizeof(double) == sizeof(RodMotion));
static_assert(settableCount(kRollerStateFields) * sizeof(double) == sizeof(RollerMotion));

}  // namespace

std::string modeText(const Roller& roller) { return toString(roller.mode()); }

std::array<StateField, kRodStateFields.size()> stateFields(const Rod& rod) {
  return read(rod, kRodStateFields);
}

std::array<StateField, kRollerStateFields.size()> stateFields(const Roller& roller) {
  return read(roller, kRollerStateFields);
}

const std::vector<std::string>& stateFieldNames(BodyKind kind) {
  static const std::vector<std::string> rod = namesOf(kRodStateFields, false);
  static const std::vector<std::string> roller = namesOf(kRollerStateFields, false);
  return kind == BodyKind::Rod ? rod : roller;
}

const std::vector<std::string>& settableStateFields(BodyKind kind) {
  static const std::vector<std::string> rod = namesOf(kRodStateFields, true);
  static const std::vector<std::string> roller = namesOf(kRollerStateFields, true);
  return kind == BodyKind::Rod ? rod : roller;
}

}  // namespace rigid_body_sim
