// π, once for the whole package (C++17 has no std::numbers).
#pragma once

namespace rigid_body_sim {

inline constexpr double kPi = 3.14159265358979323846;

}  // namespace rigid_body_sim
