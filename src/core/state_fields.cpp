#include "rigid_body_sim/core/state_fields.h"

namespace rigid_body_sim {

namespace {

// The settable fields are the whole motion (a set_state can set any of it, the NaN guard checks all of it).
template <class... Types>
constexpr bool motionsSettable(BodyTypeList<Types...>) {
  return ((settableCount<Types>() * sizeof(double) ==
           sizeof(typename StateFieldDef<typename Types::Model>::Motion)) &&
          ...);
}
static_assert(motionsSettable(BodyTypes{}));

}  // namespace

const std::vector<std::string>& stateFieldNames(const Body& body) {
  return std::visit(
      [](const auto& model) -> const auto& { return stateFieldNames<TypeOfModel<decltype(model)>>(); },
      body.model);
}

const std::vector<std::string>& stateFieldNames(const BodyConfig& body) {
  return std::visit(
      [](const auto& config) -> const auto& { return stateFieldNames<TypeOfConfig<decltype(config)>>(); },
      body.config);
}

const std::vector<std::string>& settableStateFields(const Body& body) {
  return std::visit(
      [](const auto& model) -> const auto& { return stateFieldNames<TypeOfModel<decltype(model)>>(true); },
      body.model);
}

}  // namespace rigid_body_sim
