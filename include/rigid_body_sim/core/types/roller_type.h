// The round body on an incline as a body type: its config, the description of its keys, its state fields
// and its frames (core/body_types.h registers it).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "rigid_body_sim/core/body_key.h"
#include "rigid_body_sim/core/roller.h"
#include "rigid_body_sim/core/state_field_def.h"
#include "rigid_body_sim/core/types/incline_events.h"

namespace rigid_body_sim {

struct RollerConfig {
  RollerParams params;
  RollerInitial initial;
};

std::string modeText(const Roller& roller);  // rolling | slipping | finished

struct RollerType : InclineEvents<Roller> {  // its events' lifecycle: incline_events.h
  using Config = RollerConfig;
  using Model = Roller;
  static constexpr const char* kName = "roller";
  static constexpr const char* kFixedFrameSuffix = "_slope";
  // Its events: its grip kinds, then the lap's.
  static constexpr std::array kEventKinds = inclineEventKinds(
      {"slip_to_roll",
       "slipping turned into rolling: the contact point's speed reached 0 where static friction holds; value "
       "closed_form (its instant in closed form, s since its lap started, when the lap ran as configured)"},
      {"roll_to_slip",
       "rolling turned into slipping: a change made the slope too steep for static friction to hold"});
  static constexpr bool kRaces = true;  // in a race it stops at the end of its slope (World::step)
  static const BodyType<Config>& description();
  static constexpr SweepColumn kSweepColumn{"slip_to_roll", SweepColumn::Of::FirstEvent, "slip_to_roll",
                                            "slip-to-roll time", "s"};
  // friction and normal: the forces on the body along the slope's +x and +y.
  static constexpr std::array kStateFields{
      StateFieldDef<Roller>{"x", "m", &RollerMotion::x},
      StateFieldDef<Roller>{"v", "m/s", &RollerMotion::v},
      StateFieldDef<Roller>{"theta", "rad", &RollerMotion::theta},
      StateFieldDef<Roller>{"omega", "rad/s", &RollerMotion::omega},
      StateFieldDef<Roller>{"mode", "", nullptr, nullptr, &modeText},
      StateFieldDef<Roller>{"friction", "N", nullptr, &Roller::frictionForce},
      StateFieldDef<Roller>{"normal", "N", nullptr, &Roller::normalForce},
      StateFieldDef<Roller>{"energy", "J", nullptr, &Roller::energy},
  };
  static std::vector<std::string> extraFrames(const std::string&) { return {}; }
  // A state that leaves the body where it may be (set_state): x on its slope. Throws ConfigError.
  static void checkState(const std::string& body, const Config& config, const RollerMotion& state);
  // The instant of an event of kind `kind` (an index into kEventKinds) in closed form from the initial
  // conditions, s after the lap's start (closedFormRun): slip_to_roll's and finished's; none for the other
  // kinds, or when the run has no such instant. The world adds it to an event of a lap that ran as
  // configured.
  static std::optional<double> closedFormInstant(const Config& config, std::size_t kind);
  // The run summary's tallies (simulate): whether energy is conserved exactly in this state (a stretch of
  // such states is followed for drift), and whether the body touches a floor (a contact begun: a bounce).
  static bool conservesEnergy(const Roller& roller) { return roller.mode() == RollMode::Rolling; }
  static bool touchesFloor(const Roller&) { return false; }
};

// Throws ConfigError on the first refused value: ranges, then relations between keys (mu_d <= mu_s, x0 on
// the slope, inertia_factor matching the shape).
void validate(const std::string& body, const RollerConfig& config);
inline void validateSubsteps(const std::string&, const RollerConfig&, double) {}  // closed form: none
inline std::string slowRunWarning(const std::string&, const RollerConfig&, double) { return ""; }
inline std::string autoSubstepNote(const std::string&, const RollerConfig&, double) { return ""; }

}  // namespace rigid_body_sim
