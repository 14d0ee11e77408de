// The roller's ROS side (ros/body_look.h): its messages; its state, look and handles in roller_ros.cpp.
#pragma once

#include "rigid_body_sim/RollerReconfigureConfig.h"
#include "rigid_body_sim/RollerState.h"
#include "rigid_body_sim/core/types/roller_type.h"
#include "rigid_body_sim/ros/body_look.h"

namespace rigid_body_sim {

RBS_ROS_BODY_TYPE(RollerType, RollerState, RollerReconfigureConfig);

}  // namespace rigid_body_sim
