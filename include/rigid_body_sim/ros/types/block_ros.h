// The block's ROS side (ros/body_look.h): its messages; its state, look and handles in block_ros.cpp.
#pragma once

#include "rigid_body_sim/BlockReconfigureConfig.h"
#include "rigid_body_sim/BlockState.h"
#include "rigid_body_sim/core/types/block_type.h"
#include "rigid_body_sim/ros/body_look.h"

namespace rigid_body_sim {

RBS_ROS_BODY_TYPE(BlockType, BlockState, BlockReconfigureConfig);

}  // namespace rigid_body_sim
