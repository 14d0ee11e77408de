// A round body (sphere, cylinder, ring, shell) on an incline with Coulomb friction.
//
// Slope frame: x along the slope, positive downhill; y normal to the slope, away from it; z = x × y.
// State: centre position x along the slope, velocity v, rotation theta about +z, omega = dtheta/dt.
// Rolling without slipping means v = -omega * R (omega < 0 while rolling downhill).
//
// Between events every acceleration is constant, so a step is integrated in closed form; a slip-to-roll
// transition inside a step splits the step at that instant. See DESIGN.md for the physics.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "rigid_body_sim/core/incline.h"
#include "rigid_body_sim/core/incline_body.h"

namespace rigid_body_sim {

enum class Shape { Sphere, Cylinder, Ring, SphericalShell, Custom };

// c = I / (M R^2) for the named shapes; Custom has no fixed value (returns NaN).
double inertiaFactorOf(Shape shape);
std::string toString(Shape shape);
// The shapes with an inertia factor of their own (every one but Custom), in the order the docs list them.
const std::array<Shape, 4>& namedShapes();
// Parses the name of a named shape ("sphere", "cylinder", "ring", "spherical_shell"); nullopt for anything
// else.
std::optional<Shape> shapeFromString(const std::string& name);

// The steepest slope on which static friction holds a rolling body with inertia factor c: tan(phi_c) =
// mu_s (1 + c) / c (DESIGN.md). criticalTangent is the right-hand side, criticalAngle its arctangent (rad).
double criticalTangent(double mu_s, double inertia_factor);
double criticalAngle(double mu_s, double inertia_factor);

// Finished: a racer waiting at rest at the end of its slope (setHoldAtEnd) until its next lap.
enum class RollMode { Rolling, Slipping, Finished };
std::string toString(RollMode mode);

struct RollerParams : InclineParams {
  Shape shape = Shape::Sphere;
  double inertia_factor = 0.4;  // c; must equal inertiaFactorOf(shape) unless shape is Custom
  double radius = 0.1;          // m
};

struct RollerInitial {
  double x0 = 0.0;
  double v0 = 0.0;
  double theta0 = 0.0;
  double omega0 = 0.0;
};

struct RollerMotion {
  double x = 0.0;
  double v = 0.0;
  double theta = 0.0;
  double omega = 0.0;
};

// The motion from the initial conditions in closed form (section 16.3.2, DESIGN.md): the instant at which
// slipping turns into rolling, if it does, and the instant the centre passes an end of the slope, if it does.
struct RollerRun {
  std::optional<double> slip_to_roll;  // s after the start
  std::optional<double> finish;        // s after the start
};
RollerRun closedFormRun(const RollerParams& params, const RollerInitial& initial);

// Its lap and restart lifecycle (setInitial, reset, restartLap, setState, setHoldAtEnd, finished, the
// accessors): incline_body.h.
class Roller : public InclineBody<Roller, RollerParams, RollerInitial, RollerMotion, RollMode> {
 public:
  Roller(const RollerParams& params, const RollerInitial& initial);

  // Everything a step changes (the motion, the mode, the laps): kept and put back exactly, a few bytes
  // instead of the whole body (what the node's guard keeps).
  struct Progress {
    RollerMotion state;
    RollMode mode;
    int slip_sign;
    int laps;
    bool pending_started_slipping;
  };
  using StepEvents = InclineStepEvents<Progress>;

  // Advances by dt seconds in closed form, splitting at a slip-to-roll instant. When the centre leaves
  // the slope (x > incline_length or x < 0) at the end of the step, the body restarts from its initial
  // conditions (a new "lap"); the restart is reported in the returned events.
  StepEvents step(double dt);

  // New parameters apply from the next step; a rolling body whose static friction no longer holds
  // starts slipping forward. The state is kept.
  void setParams(const RollerParams& params);

  Progress progress() const { return {state_, mode_, slip_sign_, laps_, pending_started_slipping_}; }
  void restore(const Progress& progress);

  double slipSpeed() const;      // u = v + omega R
  double frictionForce() const;  // on the body, along slope +x (N)
  double normalForce() const;    // on the body, along slope +y (N)
  double kineticEnergy() const;  // 1/2 M v^2 + 1/2 I omega^2 (J)
  double energy() const;         // kinetic - M g x sin(phi)  (J)
  double acceleration() const;   // dv/dt in the current mode
  double angularAcceleration() const;

  // True when static friction can hold a rolling body: tan(phi) <= mu_s (1 + c) / c.
  static bool canRoll(const RollerParams& params);

 private:
  friend InclineBody;
  static RollerMotion startingMotion(const RollerInitial& initial) {
    return {initial.x0, initial.v0, initial.theta0, initial.omega0};
  }
  static void stop(RollerMotion& motion) {
    motion.v = 0.0;
    motion.omega = 0.0;
  }
  // +1 when the contact point slides downhill (u > 0), -1 for topspin (u < 0); unused while rolling.
  int slipDirection() const;
  void enterModeFromState();
  // Advances by h at the constant accelerations a and alpha of the current mode.
  void advance(double h, double a, double alpha);

  // sin and cos of params_.incline_angle, and the constant accelerations of each mode (0: rolling,
  // 1: slipping with u > 0, 2: with u < 0, 3: finished, at rest), computed when the parameters change rather
  // than several times a step (the same expressions, so results are unchanged; see bench/bench_core.cpp).
  struct ModeAccelerations {
    double a = 0.0;
    double alpha = 0.0;
  };
  void cacheAccelerations();
  const ModeAccelerations& current() const {
    if (mode_ == RollMode::Finished) return accelerations_[3];
    return accelerations_[mode_ == RollMode::Rolling ? 0 : (slip_sign_ > 0 ? 1 : 2)];
  }
  double sin_angle_ = 0.0;
  double cos_angle_ = 1.0;
  ModeAccelerations accelerations_[4];
  int slip_sign_ = 1;
};

using RollerStepEvents = Roller::StepEvents;

}  // namespace rigid_body_sim
