#include "rigid_body_sim/core/world.h"

namespace rigid_body_sim {

namespace {

// Builds the model of one body; the world's gravity overrides whatever the body config carried.
std::variant<Rod, Roller> makeModel(const BodyConfig& body, double gravity) {
  if (const auto* rod = std::get_if<RodConfig>(&body.config)) {
    RodParams params = rod->params;
    params.gravity = gravity;
    return Rod(params, rod->initial);
  }
  const auto& roller = std::get<RollerConfig>(body.config);
  RollerParams params = roller.params;
  params.gravity = gravity;
  return Roller(params, roller.initial);
}

}  // namespace

std::string toString(WorldEvent::Kind kind) {
  switch (kind) {
    case WorldEvent::Kind::StartedRolling: return "started rolling";
    case WorldEvent::Kind::StartedSlipping: return "started slipping";
    case WorldEvent::Kind::Restarted: return "left the end of its slope or floor and restarted";
  }
  return "?";
}

World::World(const WorldConfig& config) : rate_(config.rate), dt_(1.0 / config.rate) {
  validate(config);
  bodies_.reserve(config.bodies.size());
  for (const auto& body : config.bodies) {
    bodies_.push_back(Body{body.name, makeModel(body, config.gravity)});
  }
}

double World::time() const { return static_cast<double>(steps_) / rate_; }

void World::step() {
  const double t0 = time();
  for (auto& body : bodies_) {
    if (auto* rod = std::get_if<Rod>(&body.model)) {
      if (rod->step(dt_)) events_.push_back({t0 + dt_, body.name, WorldEvent::Kind::Restarted});
      continue;
    }
    const RollerStepEvents happened = std::get<Roller>(body.model).step(dt_);
    if (happened.started_slipping) {
      events_.push_back({t0, body.name, WorldEvent::Kind::StartedSlipping});
    }
    if (happened.stuck_at) {
      events_.push_back({t0 + *happened.stuck_at, body.name, WorldEvent::Kind::StartedRolling});
    }
    if (happened.restarted) {
      events_.push_back({t0 + dt_, body.name, WorldEvent::Kind::Restarted});
    }
  }
  ++steps_;
}

void World::reset() {
  for (auto& body : bodies_) {
    std::visit([](auto& model) { model.reset(); }, body.model);
  }
}

Body* World::find(const std::string& name) {
  for (auto& body : bodies_) {
    if (body.name == name) return &body;
  }
  return nullptr;
}

std::vector<WorldEvent> World::takeEvents() {
  std::vector<WorldEvent> taken;
  taken.swap(events_);
  return taken;
}

double energyOf(const Body& body) {
  return std::visit([](const auto& model) { return model.energy(); }, body.model);
}

BodyKind kindOf(const Body& body) {
  return std::holds_alternative<Rod>(body.model) ? BodyKind::Rod : BodyKind::Roller;
}

std::string fixedFrameOf(const Body& body) { return fixedFrameOf(body.name, kindOf(body)); }

}  // namespace rigid_body_sim
