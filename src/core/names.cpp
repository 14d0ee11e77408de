#include "rigid_body_sim/core/names.h"

#include <cctype>
#include <variant>

namespace rigid_body_sim {

bool isValidName(const std::string& name) {
  if (name.empty() || name.size() > kMaxNameLength || !std::isalpha(static_cast<unsigned char>(name[0])))
    return false;
  for (const char ch : name) {
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_') return false;
  }
  return true;
}

std::string fixedFrameOf(const BodyConfig& body) {
  return std::visit(
      [&](const auto& config) { return fixedFrameOf<TypeOfConfig<decltype(config)>>(body.name); },
      body.config);
}

std::string groundFrameOf(const std::string& name) { return name + "_ground"; }

}  // namespace rigid_body_sim
