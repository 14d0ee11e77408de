// One field a body reports at every sample: how a body type's table of state fields (core/types/) names
// each one, in the order of its CSV columns (after t) and of its state message (after header and t).
#pragma once

#include <string>
#include <type_traits>
#include <utility>

namespace rigid_body_sim {

// One field of a body of type Model: a field of its motion (settable: ~set_state writes it there), or a
// number or text that follows from the state and the parameters.
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

}  // namespace rigid_body_sim
