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

#include "rigid_body_sim/core/constants.h"
#include "rigid_body_sim/core/incline.h"

namespace rigid_body_sim {

enum class BlockMode { Sticking, Sliding, Finished };
std::string toString(BlockMode mode);  // sticking | sliding | finished

struct BlockParams {
  double size = 0.2;                 // m, the edge of the cube drawn (the physics is a point's)
  double mass = 1.0;                 // kg
  double incline_angle = 0.349;      // rad, 0 <= phi < pi/2
  double incline_length = 5.0;       // m of slope; the centre runs over x in [0, incline_length]
  double mu_s = 0.3;                 // static friction coefficient
  double mu_d = 0.2;                 // kinetic friction coefficient, mu_d <= mu_s
  double gravity = kDefaultGravity;  // m/s^2
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

class Block {
 public:
  Block(const BlockParams& params, const BlockInitial& initial);

  // Everything a step changes, kept and put back exactly (the node's guard keeps one after every step).
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
  void setInitial(const BlockInitial& initial);  // restarts from it
  void reset();                                  // back to the initial conditions
  // Moves it to `state` now (at rest: sticking or sliding as at a start); initial conditions and laps kept.
  void setState(const BlockMotion& state);

  // In a race: a centre that passes an end of the slope stops there, at rest (mode finished), until
  // restartLap().
  void setHoldAtEnd(bool hold) { hold_at_end_ = hold; }
  bool finished() const { return mode_ == BlockMode::Finished; }
  void restartLap();

  Progress progress() const { return {state_, mode_, laps_, pending_started_slipping_}; }
  void restore(const Progress& progress);

  const BlockParams& params() const { return params_; }
  const BlockInitial& initial() const { return initial_; }
  const BlockMotion& state() const { return state_; }
  BlockMode mode() const { return mode_; }
  int laps() const { return laps_; }

  double frictionForce() const;  // on the block, along slope +x (N)
  double normalForce() const;    // on the block, along slope +y (N)
  double kineticEnergy() const;  // 1/2 M v^2 (J)
  double energy() const;         // kinetic - M g x sin(phi) (J)
  double acceleration() const;   // dv/dt in the current mode

  // True when static friction holds a block at rest: tan(phi) <= mu_s.
  static bool canStick(const BlockParams& params);

 private:
  void enterModeFromState();
  void advance(double h, double a);

  BlockParams params_;
  double sin_angle_ = 0.0;
  double cos_angle_ = 1.0;
  BlockInitial initial_;
  BlockMotion state_;
  BlockMode mode_ = BlockMode::Sticking;
  int laps_ = 0;
  bool pending_started_slipping_ = false;  // set by setParams, reported by the next step
  bool hold_at_end_ = false;
};

}  // namespace rigid_body_sim
