// dynamic_reconfigure configs <-> core body configs. Pure functions: the node validates what they return.
#pragma once

#include "rigid_body_sim/RodReconfigureConfig.h"
#include "rigid_body_sim/RollerReconfigureConfig.h"
#include "rigid_body_sim/core/parameters.h"

namespace rigid_body_sim {

RodReconfigureConfig toReconfigure(const RodConfig& config);
RollerReconfigureConfig toReconfigure(const RollerConfig& config);

// The body config a reconfigure request asks for, starting from the current one (gravity is kept).
// A named shape brings its own c; changing c without shape custom is left for validation to refuse.
// Throws ConfigError for a name that no enum allows.
RodConfig fromReconfigure(const std::string& body, const RodReconfigureConfig& request,
                          const RodConfig& current);
RollerConfig fromReconfigure(const std::string& body, const RollerReconfigureConfig& request,
                             const RollerConfig& current);

}  // namespace rigid_body_sim
