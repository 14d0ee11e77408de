#include "rigid_body_sim/core/state_fields.h"

namespace rigid_body_sim {

namespace {

template <std::size_t N>
std::vector<std::string> namesOf(const std::array<StateField, N>& fields) {
  std::vector<std::string> names;
  for (const auto& field : fields) names.emplace_back(field.name);
  return names;
}

}  // namespace

std::array<StateField, 7> stateFields(const Rod& rod) {
  const RodMotion& s = rod.state();
  return {{{"x", s.x},
           {"y", s.y},
           {"theta", s.theta},
           {"vx", s.vx},
           {"vy", s.vy},
           {"omega", s.omega},
           {"energy", rod.energy()}}};
}

std::array<StateField, 8> stateFields(const Roller& roller) {
  const RollerMotion& s = roller.state();
  return {{{"x", s.x},
           {"v", s.v},
           {"theta", s.theta},
           {"omega", s.omega},
           {"mode", 0.0, toString(roller.mode())},
           {"friction", roller.frictionForce()},
           {"normal", roller.normalForce()},
           {"energy", roller.energy()}}};
}

const std::vector<std::string>& stateFieldNames(BodyKind kind) {
  // The names are those of the fields of any body of the kind.
  static const std::vector<std::string> rod = namesOf(stateFields(Rod(RodParams{}, RodMotion{})));
  static const std::vector<std::string> roller =
      namesOf(stateFields(Roller(RollerParams{}, RollerInitial{})));
  return kind == BodyKind::Rod ? rod : roller;
}

const std::vector<std::string>& settableStateFields(BodyKind kind) {
  // The motion's own fields; the rest are derived from them and the parameters.
  static const std::vector<std::string> rod(stateFieldNames(BodyKind::Rod).begin(),
                                            stateFieldNames(BodyKind::Rod).begin() + 6);
  static const std::vector<std::string> roller(stateFieldNames(BodyKind::Roller).begin(),
                                               stateFieldNames(BodyKind::Roller).begin() + 4);
  return kind == BodyKind::Rod ? rod : roller;
}

}  // namespace rigid_body_sim
