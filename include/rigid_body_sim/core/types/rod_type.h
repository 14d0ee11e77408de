// The rod as a body type: its config, the description of its keys, its state fields and its frames
// (core/body_types.h registers it).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "rigid_body_sim/core/body_key.h"
#include "rigid_body_sim/core/event.h"
#include "rigid_body_sim/core/rod.h"
#include "rigid_body_sim/core/state_field_def.h"

namespace rigid_body_sim {

struct RodConfig {
  RodParams params;
  RodMotion initial;
};

struct RodType {
  using Config = RodConfig;
  using Model = Rod;
  static constexpr const char* kName = "rod";
  // Its coordinates are measured in <name>_floor; on an unbounded floor it also has <name>_ground.
  static constexpr const char* kFixedFrameSuffix = "_floor";
  static constexpr bool kRaces = false;
  // Its events: an end's contact with the floor, seen in the step in which it began or ended (at the
  // step's end), and a restart.
  static constexpr std::array kEventKinds{
      EventKind{"contact_began",
                "an end went below the floor in this step, its spring pushing it up; value end: A or B"},
      EventKind{"contact_ended", "an end came back above the floor in this step; value end: A or B"},
      EventKind{
          "restarted",
          "it started again from its initial conditions; value cause: lap (off the end of a bounded floor), "
          "reset, reconfigure, spawn or config",
          EventRole::Restart},
  };
  template <class Report>
  static void forEachEvent(const Rod& rod, const RodStepEvents& happened, double dt, Report&& report) {
    if (happened.restarted()) {
      report(2, dt, rod, std::vector<EventValue>{EventValue{"cause", 0.0, "lap"}});
      return;
    }
    const unsigned changed = happened.contactsBefore() ^ happened.contactsAfter();
    for (const unsigned end : {1u, 2u}) {
      if ((changed & end) == 0) continue;
      const bool began = (happened.contactsAfter() & end) != 0;
      report(began ? 0 : 1, dt, rod, std::vector<EventValue>{EventValue{"end", 0.0, end == 1u ? "A" : "B"}});
    }
  }
  // Its events' instants in closed form: none (the text's scheme locates a contact only to its step).
  static std::optional<double> closedFormInstant(const Config&, std::size_t) { return std::nullopt; }
  static const BodyType<Config>& description();
  static constexpr SweepColumn kSweepColumn{"bounces", SweepColumn::Of::Bounces, "", "bounces", ""};
  static constexpr std::array kStateFields{
      StateFieldDef<Rod>{"x", "m", &RodMotion::x},
      StateFieldDef<Rod>{"y", "m", &RodMotion::y},
      StateFieldDef<Rod>{"theta", "rad", &RodMotion::theta},
      StateFieldDef<Rod>{"vx", "m/s", &RodMotion::vx},
      StateFieldDef<Rod>{"vy", "m/s", &RodMotion::vy},
      StateFieldDef<Rod>{"omega", "rad/s", &RodMotion::omega},
      StateFieldDef<Rod>{"energy", "J", nullptr, &Rod::energy},  // kinetic + gravitational + elastic
  };
  // Frames beside <name> and its fixed frame: <name>_ground.
  static std::vector<std::string> extraFrames(const std::string& name);
  // A state that leaves the body where it may be (set_state): x on a bounded floor. Throws ConfigError.
  static void checkState(const std::string& body, const Config& config, const RodMotion& state);
  // The run summary's tallies (simulate): whether energy is conserved exactly in this state (a stretch of
  // such states is followed for drift), and whether the body touches a floor (a contact begun: a bounce).
  static bool conservesEnergy(const Rod&) { return false; }  // the springs' scheme only nearly does
  static bool touchesFloor(const Rod& rod);                  // an end below it
};

// The theta0 drawn for a rod from `seed` when theta0 is not given: 2 pi u, u uniform in [0, 1) from
// the first output of std::mt19937_64(seed) (portable, unlike std::uniform_real_distribution).
double theta0FromSeed(unsigned long long seed);

// Throws ConfigError on the first refused value: ranges, then relations between keys (x0 on a bounded floor,
// a contact frequency sqrt(4 k / mass) <= maxContactFrequency(): its sub-stepping costs about 10 sub-steps
// per rad/s and simulated second, and the step count per step must stay an int).
void validate(const std::string& body, const RodConfig& config);
double maxContactFrequency();  // rad/s
// What `substeps` allows, for messages: "auto or a whole number in [1, 1e+09]".
std::string substepsAllowed();
// A fixed sub-step count must keep each sub-step stable at the world's rate: omega_c dt / N < 2
// (validate(WorldConfig) checks it; the node again for a reconfigured rod).
void validateSubsteps(const std::string& body, const RodConfig& config, double rate);

// At the world's rate: a line when the rod makes the run slow (more than kSlowSubstepsPerSecond sub-steps
// per simulated second), and one when `substeps: auto` splits its steps; "" when not.
std::string slowRunWarning(const std::string& body, const RodConfig& config, double rate);
std::string autoSubstepNote(const std::string& body, const RodConfig& config, double rate);

}  // namespace rigid_body_sim
