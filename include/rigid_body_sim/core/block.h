// A block sliding on an incline with Coulomb friction and no rotation (DESIGN.md, "Block on an incline").
//
// Slope frame as the roller's: x along the slope, positive downhill; y normal to the slope, away from it.
// State: the centre's position x along the slope and its velocity v.
// At rest it sticks while tan(phi) <= mu_s, else it slides downhill with a = g (sin phi - mu_d cos phi);
// moving, kinetic friction mu_d N opposes the velocity, so a = g (sin phi - sign(v) mu_d cos phi). Between
// events every acceleration is constant: a step is integrated in closed form, split at the instant the
// block stops.
#pragma once

#include <optional>
#include <string>

#include "rigid_body_sim/core/incline.h"
#include "rigid_body_sim/core/incline_body.h"

namespace rigid_body_sim {

enum class BlockMode { Sticking, Sliding, Finished };
std::string toString(BlockMode mode);  // sticking | sliding | finished

struct BlockParams : InclineParams {
  double size = 0.2;  // m, the edge of the cube drawn (the physics is a point's)
};

struct BlockInitial {
  double x0 = 0.0;
  double v0 = 0.0;
};

struct BlockMotion {
  double x = 0.0;
  double v = 0.0;
};

// The motion from the initial conditions in closed form: the instant the centre passes an end of the slope,
// if it does (slip_to_roll stays empty: a block has no such instant; the instant it stops is `stops`).
struct BlockRun {
  std::optional<double> stops;   // s after the start: a moving block comes to rest
  std::optional<double> finish;  // s after the start
};
BlockRun closedFormRun(const BlockParams& params, const BlockInitial& initial);

// Its lap and restart lifecycle (setInitial, reset, restartLap, setState, setHoldAtEnd, finished, the
// accessors): incline_body.h.
class Block : public InclineBody<Block, BlockParams, BlockInitial, BlockMotion, BlockMode> {
 public:
  Block(const BlockParams& params, const BlockInitial& initial);

  // Everything a step changes, kept and put back exactly (what the node's guard keeps).
  struct Progress {
    BlockMotion state;
    BlockMode mode;
    int laps;
    bool pending_started_slipping;
  };
  using StepEvents = InclineStepEvents<Progress>;

  // Advances by dt seconds in closed form, split at the instant the block stops. When the centre leaves the
  // slope at the end of the step, the block restarts from its initial conditions (a new lap).
  StepEvents step(double dt);

  // New parameters apply from the next step; a sticking block that static friction no longer holds starts
  // sliding downhill. The state is kept.
  void setParams(const BlockParams& params);

  Progress progress() const { return {state_, mode_, laps_, pending_started_slipping_}; }
  void restore(const Progress& progress);

  double frictionForce() const;  // on the block, along slope +x (N)
  double normalForce() const;    // on the block, along slope +y (N)
  double kineticEnergy() const;  // 1/2 M v^2 (J)
  double energy() const;         // kinetic - M g x sin(phi) (J)
  double acceleration() const;   // dv/dt in the current mode

  // True when static friction holds a block at rest: tan(phi) <= mu_s.
  static bool canStick(const BlockParams& params);

 private:
  friend InclineBody;
  static BlockMotion startingMotion(const BlockInitial& initial) { return {initial.x0, initial.v0}; }
  static void stop(BlockMotion& motion) { motion.v = 0.0; }
  // At rest: sticking where static friction holds it, else sliding.
  void enterModeFromState();
  void advance(double h, double a);

  double sin_angle_ = 0.0;
  double cos_angle_ = 1.0;
};

}  // namespace rigid_body_sim
