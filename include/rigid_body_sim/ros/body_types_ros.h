// Every body type's ROS side, each in its own files (ros/types/<type>_ros.h: its state message, reconfigure
// config, look and handles). A type registered in core/body_types.h without its specialization does not
// compile.
#pragma once

#include <variant>

#include "rigid_body_sim/core/body_types.h"
#include "rigid_body_sim/ros/body_look.h"
#include "rigid_body_sim/ros/types/block_ros.h"
#include "rigid_body_sim/ros/types/rod_ros.h"
#include "rigid_body_sim/ros/types/roller_ros.h"

namespace rigid_body_sim {

template <class List>
struct RosVariants;
template <class... Types>
struct RosVariants<BodyTypeList<Types...>> {
  using StateMsgs = std::variant<typename RosBodyType<Types>::StateMsg...>;
};

// The state message of any body type.
using StateMsg = RosVariants<BodyTypes>::StateMsgs;

}  // namespace rigid_body_sim
