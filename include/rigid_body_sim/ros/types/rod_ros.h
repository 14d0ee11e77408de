// The rod's ROS side (ros/body_look.h): its messages; its state, look and handles in rod_ros.cpp.
#pragma once

#include "rigid_body_sim/RodReconfigureConfig.h"
#include "rigid_body_sim/RodState.h"
#include "rigid_body_sim/core/types/rod_type.h"
#include "rigid_body_sim/ros/body_look.h"

namespace rigid_body_sim {

RBS_ROS_BODY_TYPE(RodType, RodState, RodReconfigureConfig);

}  // namespace rigid_body_sim
