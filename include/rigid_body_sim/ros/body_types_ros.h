// Each body type's ROS side: its state message and its reconfigure server's config. A type registered in
// core/body_types.h without its specialization here does not compile.
#pragma once

#include <variant>

#include "rigid_body_sim/BlockReconfigureConfig.h"
#include "rigid_body_sim/BlockState.h"
#include "rigid_body_sim/RodReconfigureConfig.h"
#include "rigid_body_sim/RodState.h"
#include "rigid_body_sim/RollerReconfigureConfig.h"
#include "rigid_body_sim/RollerState.h"
#include "rigid_body_sim/core/body_types.h"

namespace rigid_body_sim {

template <class Type>
struct RosBodyType;

template <>
struct RosBodyType<RodType> {
  using StateMsg = RodState;
  using Reconfigure = RodReconfigureConfig;
};

template <>
struct RosBodyType<RollerType> {
  using StateMsg = RollerState;
  using Reconfigure = RollerReconfigureConfig;
};

template <>
struct RosBodyType<BlockType> {
  using StateMsg = BlockState;
  using Reconfigure = BlockReconfigureConfig;
};

template <class List>
struct RosVariants;
template <class... Types>
struct RosVariants<BodyTypeList<Types...>> {
  using StateMsgs = std::variant<typename RosBodyType<Types>::StateMsg...>;
};

// The state message of any body type.
using StateMsg = RosVariants<BodyTypes>::StateMsgs;

}  // namespace rigid_body_sim
