// Core cost per step (Google Benchmark): the rod with each integrator, a roller rolling and slipping,
// and worlds of 1 to 1000 bodies, the 1000 also stepped as the node steps them. `make bench` runs it with
// repetitions and tabulates the JSON.
#include <benchmark/benchmark.h>

#include <chrono>
#include <string>
#include <thread>

#include "rigid_body_sim/core/world.h"

namespace rigid_body_sim {
namespace {

constexpr double kDt = 0.001;  // the text's step (rate 1000)

// The text's rod: it falls, bounces and keeps bouncing (no damping), so a long run mixes flight and
// contact the way the text's 10 s do.
void rodStep(benchmark::State& state, Integrator integrator) {
  RodParams params;
  params.integrator = integrator;
  Rod rod(params, RodMotion{});
  for (auto _ : state) {
    rod.step(kDt);
    benchmark::DoNotOptimize(rod.state());
  }
}
BENCHMARK_CAPTURE(rodStep, euler_cromer, Integrator::EulerCromer);
BENCHMARK_CAPTURE(rodStep, velocity_verlet, Integrator::VelocityVerlet);
BENCHMARK_CAPTURE(rodStep, rk4, Integrator::Rk4);

// A sphere below its critical angle rolls; a ring above its own slips (config/incline.yaml's slope).
// Both restart at the bottom now and then, as in the node.
void rollerStep(benchmark::State& state, Shape shape, RollMode expected) {
  RollerParams params;
  params.shape = shape;
  params.inertia_factor = inertiaFactorOf(shape);
  params.incline_angle = 0.576;
  params.mu_s = 0.2;
  params.mu_d = 0.15;
  Roller roller(params, RollerInitial{});
  if (roller.mode() != expected) state.SkipWithError("the roller is not in the mode this case measures");
  for (auto _ : state) {
    benchmark::DoNotOptimize(roller.step(kDt));
    benchmark::DoNotOptimize(roller.state());
  }
}
BENCHMARK_CAPTURE(rollerStep, rolling, Shape::Sphere, RollMode::Rolling);
BENCHMARK_CAPTURE(rollerStep, slipping, Shape::Ring, RollMode::Slipping);

// A world of n bodies, half rods (each its own theta0) and half rollers of the three shapes: one
// iteration is one world step, so ns per body-step is the time divided by n.
WorldConfig mixedWorld(int n) {
  WorldConfig config;
  const Shape shapes[] = {Shape::Sphere, Shape::Cylinder, Shape::Ring};
  for (int i = 0; i < n; ++i) {
    if (i % 2 == 0) {
      RodConfig rod;
      rod.initial.theta = 0.3 + 0.01 * i;
      config.bodies.push_back({"rod" + std::to_string(i), rod});
    } else {
      RollerConfig roller;
      roller.params.shape = shapes[(i / 2) % 3];
      roller.params.inertia_factor = inertiaFactorOf(roller.params.shape);
      roller.params.incline_angle = 0.576;
      roller.params.mu_s = 0.2;
      roller.params.mu_d = 0.15;
      config.bodies.push_back({"roller" + std::to_string(i), roller});
    }
  }
  return config;
}

void worldStep(benchmark::State& state) {
  const auto n = static_cast<int>(state.range(0));
  World world(mixedWorld(n));
  for (auto _ : state) {
    world.step();
    benchmark::DoNotOptimize(world.bodies().data());
  }
  state.counters["body_steps"] = n;  // per iteration
  state.SetItemsProcessed(state.iterations() * n);
}
BENCHMARK(worldStep)->Arg(1)->Arg(10)->Arg(100)->Arg(1000);

// The same world of 1000 bodies stepped as the node steps it: a sample's 20 steps (rate 1000, 50 Hz) after
// 20 ms asleep (not timed). A core woken from idle runs slower for a millisecond or two, so a step costs
// more here than in worldStep's unbroken loop: the node's CPU share follows this row, not that one.
void worldStepAfterSleep(benchmark::State& state) {
  constexpr int kBodies = 1000;
  constexpr int kStepsPerSample = 20;
  World world(mixedWorld(kBodies));
  for (auto _ : state) {
    state.PauseTiming();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    state.ResumeTiming();
    for (int i = 0; i < kStepsPerSample; ++i) world.step();
    benchmark::DoNotOptimize(world.bodies().data());
  }
  state.counters["body_steps"] = kBodies * kStepsPerSample;  // per iteration
  state.SetItemsProcessed(state.iterations() * kBodies * kStepsPerSample);
}
BENCHMARK(worldStepAfterSleep)->Iterations(100);

}  // namespace
}  // namespace rigid_body_sim

BENCHMARK_MAIN();
