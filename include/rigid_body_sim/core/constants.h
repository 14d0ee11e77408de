// π and the default gravity, once for the whole package (C++17 has no std::numbers).
#pragma once

namespace rigid_body_sim {

inline constexpr double kPi = 3.14159265358979323846;
// m/s^2, the text's g: the world's default, which every body takes.
inline constexpr double kDefaultGravity = 9.8;

}  // namespace rigid_body_sim
