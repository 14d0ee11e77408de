// A rigid rod bouncing on a floor (y = 0); each end below the floor is pushed up by N = -k y_end.
//
// Rod plane: x horizontal, y up; theta is measured from +x towards +y; u = (cos theta, sin theta).
// End A is at R + (L/2) u, end B at R - (L/2) u. An end below the floor also feels Coulomb friction
// floor_mu N along x (none by default: the text's floor). No damping. See DESIGN.md and physics.md.
//
// The floor is unbounded (the text's), or spans x in [0, floor_length]: a rod whose centre leaves it
// restarts from its initial conditions at the end of that step, as a roller does at a slope's end.
#pragma once

#include <limits>

#include <optional>
#include <string>

#include "rigid_body_sim/core/constants.h"

namespace rigid_body_sim {

enum class Integrator { EulerCromer, VelocityVerlet, Rk4 };
std::string toString(Integrator integrator);
// Parses "euler_cromer", "velocity_verlet", "rk4"; nullopt for anything else.
std::optional<Integrator> integratorFromString(const std::string& name);

// A rod's sub-steps per step: kAutoSubsteps (split only a stiff step, see Rod::autoSubstepsFor) or a
// fixed count in [1, kMaxSubsteps]; 1 is the text's scheme at any k.
constexpr int kAutoSubsteps = 0;
constexpr int kMaxSubsteps = 1000000000;
std::string substepsToString(int substeps);  // "auto" or the count
// Parses "auto" or a whole number in [1, kMaxSubsteps] (digits only); nullopt for anything else.
std::optional<int> substepsFromString(const std::string& text);

struct RodParams {
  double length = 1.0;               // m
  double mass = 0.5;                 // kg
  double k = 1000.0;                 // N/m, floor spring constant per end
  double gravity = kDefaultGravity;  // m/s^2
  Integrator integrator = Integrator::EulerCromer;
  double floor_length = 0.0;     // m of floor from x = 0; 0 = unbounded (the text's floor)
  int substeps = kAutoSubsteps;  // sub-steps per step
  double floor_mu = 0.0;         // Coulomb friction of the floor, in [0, 100]; 0 = frictionless (the text)
};

struct RodMotion {
  double x = 0.0;
  double y = 4.0;
  double theta = 0.3;
  double vx = 2.0;
  double vy = 0.0;
  double omega = 0.0;
};

// What one step of a rod tells: which ends were below the floor before and after it (bit 0: end A, bit 1:
// end B), and whether it left a bounded floor and restarted.
// Packed in one word, so that it comes back in a register (built in memory, its return stalled the step).
class RodStepEvents {
 public:
  RodStepEvents(unsigned contacts_before, unsigned contacts_after, bool restarted)
      : bits_(contacts_before | contacts_after << 2 | (restarted ? 16u : 0u)) {}
  unsigned contactsBefore() const { return bits_ & 3u; }
  unsigned contactsAfter() const { return (bits_ >> 2) & 3u; }
  bool restarted() const { return (bits_ & 16u) != 0; }
  bool any() const { return restarted() || contactsBefore() != contactsAfter(); }  // the common case: none

 private:
  unsigned bits_;
};

class Rod {
 public:
  // Sub-stepping starts where omega_c * dt exceeds this fraction of the stability bound 2
  // (omega_c = sqrt(4 k / M), the stiffest contact mode: one end of a flat rod).
  static constexpr double kSubstepFraction = 0.05;

  Rod(const RodParams& params, const RodMotion& initial);

  // Advances by dt, split into substepsFor(dt) equal sub-steps of the chosen integrator. Tells the ends'
  // contacts before and after, and whether the centre left a bounded floor (x < 0 or x > floor_length) and
  // the rod restarted from its initial conditions at the end of the step.
  RodStepEvents step(double dt);

  void setParams(const RodParams& params);    // applies from the next step; the state is kept
  void setInitial(const RodMotion& initial);  // restarts from it
  void reset();                               // back to the initial state
  void setState(const RodMotion& state);      // moves it there now; the initial state is kept

  // Everything a step changes (for a rod, its motion): kept and put back exactly, a few bytes instead of
  // the whole body (what the node's guard keeps).
  using Progress = RodMotion;
  const Progress& progress() const { return state_; }
  void restore(const Progress& progress) { state_ = progress; }

  const RodParams& params() const { return params_; }
  const RodMotion& initial() const { return initial_; }
  const RodMotion& state() const { return state_; }

  double momentOfInertia() const;   // M L^2 / 12
  double kineticEnergy() const;     // 1/2 M (vx^2 + vy^2) + 1/2 I omega^2 (J)
  double energy() const;            // kinetic + gravitational + elastic (J)
  double endHeightA() const;        // y of end A
  double endHeightB() const;        // y of end B
  unsigned contacts() const;        // the ends below the floor now: bit 0 end A, bit 1 end B
  double contactFrequency() const;  // omega_c = sqrt(4 k / M) (rad/s)
  // The sub-steps of a step of dt: params().substeps, or autoSubstepsFor(dt) under kAutoSubsteps.
  int substepsFor(double dt) const;
  bool onFloor() const;  // the centre is over the floor (always, when it is unbounded)
  // 1 while omega_c dt <= 2 kSubstepFraction, else ceil(omega_c dt / (2 kSubstepFraction)).
  int autoSubstepsFor(double dt) const;

 private:
  RodParams params_;
  RodMotion initial_;
  RodMotion state_;
  // The contacts the last step ended with, and where: the next step's contacts before, unless the rod was
  // moved or its length changed since (a sine saved a step).
  struct Contacts {
    double y = 0.0;
    double theta = 0.0;
    double length = 0.0;  // 0: none yet (a rod's length is positive)
    unsigned ends = 0;
  };
  Contacts last_contacts_;
  // The sub-steps of the last step's dt, until the parameters change (a square root and two divisions a
  // step, otherwise).
  struct Substeps {
    double dt = std::numeric_limits<double>::quiet_NaN();  // none yet: equal to no dt
    int count = 1;
    double h = 0.0;  // dt / count
  };
  Substeps substeps_;
};

}  // namespace rigid_body_sim
