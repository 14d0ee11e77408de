// The log of a world's changes as rigid_body_sim/Command messages (~commands, and the bags that record it):
// a WorldCommand to its message and a bag's messages back to the run they describe.
#pragma once

#include <cstdint>
#include <string>

#include <ros/time.h>

#include "rigid_body_sim/Command.h"
#include "rigid_body_sim/core/world.h"
#include "rigid_body_sim/run/replay.h"

namespace rigid_body_sim {

// The message of command number `index` (header.seq; 0 is the config) applied at `t` = step / rate.
rigid_body_sim::Command toMessage(const WorldCommand& command, std::uint32_t index, double t,
                                  const ros::Time& stamp, const std::string& world_frame);

// The commands of a bag: its topic /sim/commands, or else its one topic of type rigid_body_sim/Command, and
// the latest simulated time of its messages (states and commands). Refused with one line (ConfigError): no
// such topic, a first message that is not the config at seq 0, a gap in seq, a payload that does not parse.
RecordedRun readRecordedRun(const std::string& bag_path);

}  // namespace rigid_body_sim
