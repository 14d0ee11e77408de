// The block on an incline against its closed forms, regime by regime: sticking, sliding from rest, launched
// downhill and uphill (stopping and sticking, or sliding back), the stop located inside the step, friction's
// work, hysteresis, and its race with the rollers; then every state a race publishes against the invariants
// of its mode, for generated races of rollers and blocks.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <optional>
#include <random>
#include <string>

#include "rigid_body_sim/core/state_fields.h"
#include "rigid_body_sim/core/world.h"

using namespace rigid_body_sim;

namespace {

constexpr double kDt = 1e-3;
constexpr double kG = kDefaultGravity;

BlockParams slope(double angle, double mu_s, double mu_d, double length = 5.0) {
  BlockParams p;
  p.incline_angle = angle;
  p.mu_s = mu_s;
  p.mu_d = mu_d;
  p.incline_length = length;
  return p;
}

// a = g (sin phi - sign(v) mu_d cos phi): downhill (+1) or uphill (-1) motion.
double sliding(const BlockParams& p, double direction) {
  return kG * (std::sin(p.incline_angle) - direction * p.mu_d * std::cos(p.incline_angle));
}

// Rounding of n closed-form steps against one closed form: x and v to a few ulps of their size per step.
double tolerance(double scale, int steps) { return 8.0 * steps * 2.2e-16 * std::max(1.0, scale); }

// Steps a block n times, returning the first offset at which it came to rest (absolute time).
std::optional<double> stepUntil(Block& block, int n) {
  std::optional<double> stopped;
  for (int i = 0; i < n; ++i) {
    const InclineStepEvents events = block.step(kDt);
    if (events.stuck_at && !stopped) stopped = i * kDt + *events.stuck_at;
  }
  return stopped;
}

}  // namespace

TEST(Block, StaysWhereStaticFrictionHoldsIt) {
  const BlockParams p = slope(0.25, 0.3, 0.2);  // tan 0.25 = 0.255 <= 0.3
  Block block(p, {1.0, 0.0});
  EXPECT_EQ(block.mode(), BlockMode::Sticking);
  stepUntil(block, 2000);
  EXPECT_EQ(block.state().x, 1.0);
  EXPECT_EQ(block.state().v, 0.0);
  EXPECT_EQ(block.mode(), BlockMode::Sticking);
  // Static friction is what holds it: it balances gravity along the slope exactly.
  EXPECT_DOUBLE_EQ(block.frictionForce(), -p.mass * kG * std::sin(p.incline_angle));
  EXPECT_DOUBLE_EQ(block.normalForce(), p.mass * kG * std::cos(p.incline_angle));
}

TEST(Block, SlidesFromRestAtTheKineticAcceleration) {
  const BlockParams p = slope(0.5, 0.3, 0.2);  // tan 0.5 = 0.546 > 0.3
  Block block(p, {0.0, 0.0});
  EXPECT_EQ(block.mode(), BlockMode::Sliding);
  const double a = sliding(p, 1.0);
  for (int n = 1; n <= 1000; ++n) {
    block.step(kDt);
    const double t = n * kDt;
    ASSERT_NEAR(block.state().v, a * t, tolerance(a * t, n)) << t;
    ASSERT_NEAR(block.state().x, 0.5 * a * t * t, tolerance(a * t * t, n)) << t;
  }
  EXPECT_DOUBLE_EQ(block.frictionForce(), -p.mu_d * p.mass * kG * std::cos(p.incline_angle));
}

TEST(Block, LaunchedDownhillOnAGentleSlopeStopsAndSticks) {
  const BlockParams p = slope(0.1, 0.5, 0.4);  // tan 0.1 = 0.1 < mu_d: friction wins
  const double v0 = 3.0;
  const double a = sliding(p, 1.0);  // < 0
  const double t_stop = -v0 / a;
  const double x_stop = 0.5 + v0 * t_stop + 0.5 * a * t_stop * t_stop;
  Block block(p, {0.5, v0});
  const auto stopped = stepUntil(block, 3000);
  ASSERT_TRUE(stopped);
  EXPECT_NEAR(*stopped, t_stop, 1e-12);
  EXPECT_NEAR(block.state().x, x_stop, 1e-12);
  EXPECT_EQ(block.state().v, 0.0);
  EXPECT_EQ(block.mode(), BlockMode::Sticking);
  EXPECT_EQ(closedFormRun(p, {0.5, v0}).stops, t_stop);
}

TEST(Block, LaunchedUphillStopsThenSticksOrSlidesBack) {
  for (const double angle : {0.2, 0.6}) {  // tan 0.2 = 0.2 <= mu_s = 0.3: sticks; tan 0.6 = 0.68: slides back
    SCOPED_TRACE(angle);
    const BlockParams p = slope(angle, 0.3, 0.2);
    const double v0 = -4.0;
    const double up = sliding(p, -1.0);  // > 0: decelerates the uphill motion
    const double t_stop = -v0 / up;
    const double x_stop = 4.0 + v0 * t_stop + 0.5 * up * t_stop * t_stop;
    Block block(p, {4.0, v0});
    const int steps = static_cast<int>(std::floor(t_stop / kDt)) + 300;
    const auto stopped = stepUntil(block, steps);
    const double after = steps * kDt - t_stop;
    if (Block::canStick(p)) {
      ASSERT_TRUE(stopped);
      EXPECT_NEAR(*stopped, t_stop, 1e-12);
      EXPECT_NEAR(block.state().x, x_stop, 1e-12);
      EXPECT_EQ(block.mode(), BlockMode::Sticking);
    } else {
      EXPECT_FALSE(stopped) << "a stop on too steep a slope is no grip";
      const double down = sliding(p, 1.0);
      EXPECT_NEAR(block.state().v, down * after, 1e-11);
      EXPECT_NEAR(block.state().x, x_stop + 0.5 * down * after * after, 1e-11);
      EXPECT_EQ(block.mode(), BlockMode::Sliding);
    }
  }
}

// Between mu_d and mu_s: a block at rest stays; one already sliding downhill speeds up and never stops.
TEST(Block, HysteresisBetweenKineticAndStaticFriction) {
  const BlockParams p = slope(std::atan(0.25), 0.3, 0.2);
  Block resting(p, {0.0, 0.0});
  Block moving(p, {0.0, 0.1});
  stepUntil(resting, 1000);
  EXPECT_FALSE(stepUntil(moving, 1000));
  EXPECT_EQ(resting.state().x, 0.0);
  EXPECT_GT(moving.state().v, 0.1);
  EXPECT_EQ(moving.mode(), BlockMode::Sliding);
}

// Friction's work: while it slides, the energy falls by mu_d N times the path it slid.
TEST(Block, EnergyFallsByTheWorkOfKineticFriction) {
  const BlockParams p = slope(0.4, 0.5, 0.3);
  Block block(p, {3.0, -3.0});
  const double e0 = block.energy();
  double path = 0.0;
  double x = block.state().x;
  for (int i = 0; i < 1500; ++i) {
    block.step(kDt);
    path += std::abs(block.state().x - x);  // the velocity changes sign only at a stop, where the step splits
    x = block.state().x;
  }
  EXPECT_NEAR(block.energy() - e0, -p.mu_d * block.normalForce() * path, 1e-9);
}

TEST(Block, ALostGripIsReportedWhenTheSlopeSteepens) {
  Block block(slope(0.2, 0.3, 0.2), {1.0, 0.0});
  block.setParams(slope(0.5, 0.3, 0.2));
  EXPECT_EQ(block.mode(), BlockMode::Sliding);
  EXPECT_TRUE(block.step(kDt).started_slipping);
  EXPECT_FALSE(block.step(kDt).started_slipping);
}

// Random launches: the stepped stop and finish against the closed forms, and a block that leaves the slope
// restarts from its initial conditions.
TEST(Block, RandomLaunchesMatchTheClosedForms) {
  std::mt19937_64 random(20261128);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int stops = 0, finishes = 0;
  for (int run = 0; run < 300; ++run) {
    const double mu_s = unit(random);
    const BlockParams p = slope(1.4 * unit(random), mu_s, mu_s * unit(random), 1.0 + 4.0 * unit(random));
    const BlockInitial initial{p.incline_length * unit(random), 8.0 * unit(random) - 4.0};
    const BlockRun closed = closedFormRun(p, initial);
    Block block(p, initial);
    block.setHoldAtEnd(true);
    std::optional<double> stopped, finished;
    for (int i = 0; i < 10000 && !finished; ++i) {
      const InclineStepEvents events = block.step(kDt);
      if (events.stuck_at && !stopped) stopped = i * kDt + *events.stuck_at;
      if (events.left_at) finished = i * kDt + *events.left_at;
    }
    SCOPED_TRACE("run " + std::to_string(run));
    ASSERT_EQ(stopped.has_value(), closed.stops.has_value() && Block::canStick(p));
    if (stopped) {
      EXPECT_NEAR(*stopped, *closed.stops, 1e-9);
      ++stops;
    }
    if (closed.finish && *closed.finish < 9.0) {
      ASSERT_TRUE(finished);
      EXPECT_NEAR(*finished, *closed.finish, 1e-9);
      EXPECT_EQ(block.mode(), BlockMode::Finished);
      EXPECT_EQ(block.state().v, 0.0);
      ++finishes;
    }
  }
  EXPECT_GT(stops, 30);
  EXPECT_GT(finishes, 100);
}

// The lesson: on one slope a frictionless block beats every round body, since none of its energy turns.
TEST(Block, AFrictionlessBlockWinsTheRace) {
  WorldConfig config;
  config.race = true;
  BlockConfig block;
  block.params = slope(0.349, 0.0, 0.0);
  config.bodies.push_back({"block", block});
  for (const Shape shape : namedShapes()) {
    RollerConfig roller;
    roller.params.shape = shape;
    roller.params.inertia_factor = inertiaFactorOf(shape);
    config.bodies.push_back({toString(shape), roller});
  }
  World world(config);
  const auto all_over = [&] {
    for (const auto& body : world.bodies()) {
      if (!body.finish) return false;
    }
    return true;
  };
  for (int i = 0; i < 5000 && !all_over(); ++i) world.step();
  ASSERT_TRUE(all_over());
  EXPECT_EQ(world.bodies()[0].finish->place, 1);
  // Its time from x = L = g sin(phi) t^2 / 2, a roller's from g sin(phi) / (1 + c).
  const double t_block = std::sqrt(2.0 * 5.0 / (kG * std::sin(0.349)));
  EXPECT_NEAR(world.bodies()[0].finish->time, t_block, 1e-9);
  EXPECT_NEAR(*world.bodies()[0].finish->closed_form, t_block, 1e-12);
  for (std::size_t i = 1; i < world.bodies().size(); ++i) EXPECT_GT(world.bodies()[i].finish->place, 1);
}

// Racers over the line within kTieTime of each other share a place; the next place counts them all.
TEST(Race, TiesShareAPlace) {
  WorldConfig config;
  config.race = true;
  RollerConfig roller;  // a sphere below its critical angle
  for (const char* name : {"a", "b"}) config.bodies.push_back({name, roller});
  roller.params.shape = Shape::Ring;
  roller.params.inertia_factor = 1.0;
  config.bodies.push_back({"ring", roller});
  World world(config);
  for (int i = 0; i < 5000 && !world.bodies()[2].finish; ++i) world.step();
  ASSERT_TRUE(world.bodies()[0].finish && world.bodies()[1].finish && world.bodies()[2].finish);
  EXPECT_EQ(world.bodies()[0].finish->place, 1);
  EXPECT_EQ(world.bodies()[1].finish->place, 1);
  EXPECT_EQ(world.bodies()[2].finish->place, 3);
}

// Every state of generated races of rollers and blocks, step by step, against the invariants of its mode:
// x changes at the rate v (the mean of the step's two speeds, the acceleration being constant between
// events), a rolling body has v = -omega R, a body that stands still (sticking, finished) has v = 0 and omega
// = 0.
TEST(Race, EveryStateIsTrueOfItsMode) {
  std::mt19937_64 random(20261129);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int run = 0; run < 20; ++run) {
    WorldConfig config;
    config.race = true;
    for (int i = 0; i < 3; ++i) {
      RollerConfig roller;
      roller.params.incline_angle = 1.2 * unit(random);
      roller.params.mu_s = unit(random);
      roller.params.mu_d = roller.params.mu_s * unit(random);
      roller.initial.v0 = 4.0 * unit(random) - 1.0;
      roller.initial.omega0 = 20.0 * unit(random) - 10.0;
      config.bodies.push_back({"roller" + std::to_string(i), roller});
      BlockConfig block;
      block.params = slope(1.2 * unit(random), unit(random), 0.0);
      block.params.mu_d = block.params.mu_s * unit(random);
      block.initial.v0 = 4.0 * unit(random) - 2.0;
      config.bodies.push_back({"block" + std::to_string(i), block});
    }
    World world(config);
    for (int n = 0; n < 6000; ++n) {
      std::vector<std::array<double, 3>> before;  // x, v, dv/dt
      for (const auto& body : world.bodies()) {
        std::visit(
            [&](const auto& model) {
              if constexpr (TypeOfModel<decltype(model)>::kRaces) {  // the racers on slopes: all here
                before.push_back({model.state().x, model.state().v, model.acceleration()});
              }
            },
            body.model);
      }
      world.step();
      const auto events = world.takeEvents();
      for (std::size_t b = 0; b < world.bodies().size(); ++b) {
        const Body& body = world.bodies()[b];
        bool eventful = false;
        for (const auto& event : events) eventful = eventful || event.body == body.name;
        std::visit(
            [&](const auto& model) {
              if constexpr (TypeOfModel<decltype(model)>::kRaces) {  // the racers on slopes: all here
                std::string mode;
                for (const auto& field : stateFields(model)) mode += field.text;
                const double x = model.state().x, v = model.state().v;
                SCOPED_TRACE(body.name + " at step " + std::to_string(n) + ", mode " + mode);
                if (mode == "finished" || mode == "sticking") {
                  ASSERT_EQ(v, 0.0);
                  for (const auto& field : stateFields(model)) {
                    if (std::string(field.name) == "omega") ASSERT_EQ(field.number, 0.0);
                  }
                }
                if (mode == "rolling") {
                  double omega = 0.0, radius = 0.0;
                  for (const auto& field : stateFields(model)) {
                    if (std::string(field.name) == "omega") omega = field.number;
                  }
                  if constexpr (std::is_same_v<std::decay_t<decltype(model)>, Roller>)
                    radius = model.params().radius;
                  ASSERT_NEAR(v, -omega * radius, 1e-9 * std::max(1.0, std::abs(v)));
                }
                // Within a step of one constant acceleration (no event, no turn of the friction).
                if (!eventful && model.acceleration() == before[b][2]) {
                  const double rate = (x - before[b][0]) / kDt;
                  ASSERT_NEAR(rate, 0.5 * (before[b][1] + v), 1e-9 * std::max(1.0, std::abs(v)));
                }
              }
            },
            body.model);
      }
    }
  }
}
