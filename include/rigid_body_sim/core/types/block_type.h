// The block sliding on an incline as a body type: its config, the description of its keys, its state fields
// and its frames (core/body_types.h registers it).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "rigid_body_sim/core/block.h"
#include "rigid_body_sim/core/body_key.h"
#include "rigid_body_sim/core/state_field_def.h"
#include "rigid_body_sim/core/types/incline_events.h"

namespace rigid_body_sim {

struct BlockConfig {
  BlockParams params;
  BlockInitial initial;
};

std::string modeText(const Block& block);  // sticking | sliding | finished

struct BlockType : InclineEvents<Block> {  // its events' lifecycle: incline_events.h
  using Config = BlockConfig;
  using Model = Block;
  static constexpr const char* kName = "block";
  static constexpr const char* kFixedFrameSuffix = "_slope";
  // Its events: its grip kinds, then the lap's.
  static constexpr std::array kEventKinds = inclineEventKinds(
      {"came_to_rest",
       "it stopped where static friction holds it; value closed_form (its instant in closed form, s since "
       "its "
       "lap started, when the lap ran as configured)"},
      {"started_sliding",
       "at rest, it started to slide: a change made the slope too steep for static friction to hold"});
  static constexpr bool kRaces = true;  // in a race it stops at the end of its slope (World::step)
  static const BodyType<Config>& description();
  static constexpr SweepColumn kSweepColumn{"stops_at", SweepColumn::Of::FirstEvent, "came_to_rest",
                                            "time it came to rest", "s"};
  // friction and normal: the forces on the block along the slope's +x and +y.
  static constexpr std::array kStateFields{
      StateFieldDef<Block>{"x", "m", &BlockMotion::x},
      StateFieldDef<Block>{"v", "m/s", &BlockMotion::v},
      StateFieldDef<Block>{"mode", "", nullptr, nullptr, &modeText},
      StateFieldDef<Block>{"friction", "N", nullptr, &Block::frictionForce},
      StateFieldDef<Block>{"normal", "N", nullptr, &Block::normalForce},
      StateFieldDef<Block>{"energy", "J", nullptr, &Block::energy},
  };
  static std::vector<std::string> extraFrames(const std::string&) { return {}; }
  // A state that leaves the block where it may be (set_state): x on its slope. Throws ConfigError.
  static void checkState(const std::string& body, const Config& config, const BlockMotion& state);
  // The instant of an event of kind `kind` (an index into kEventKinds) in closed form from the initial
  // conditions, s after the lap's start (closedFormRun): came_to_rest's and finished's; none for the other
  // kinds, or when the run has no such instant. The world adds it to an event of a lap that ran as
  // configured.
  static std::optional<double> closedFormInstant(const Config& config, std::size_t kind);
  // The run summary's tallies (simulate): whether energy is conserved exactly in this state (a stretch of
  // such states is followed for drift), and whether the body touches a floor (a contact begun: a bounce).
  static bool conservesEnergy(const Block&) { return false; }  // sliding, friction takes it
  static bool touchesFloor(const Block&) { return false; }
};

// Throws ConfigError on the first refused value: ranges, then relations between keys (mu_d <= mu_s, x0 on
// the slope).
void validate(const std::string& body, const BlockConfig& config);
inline void validateSubsteps(const std::string&, const BlockConfig&, double) {}  // closed form: none
inline std::string slowRunWarning(const std::string&, const BlockConfig&, double) { return ""; }
inline std::string autoSubstepNote(const std::string&, const BlockConfig&, double) { return ""; }

}  // namespace rigid_body_sim
