#include "rigid_body_sim/core/world.h"

#include <type_traits>

#include "rigid_body_sim/core/state_fields.h"

namespace rigid_body_sim {

namespace {

// Builds the model of one body; the world's gravity overrides whatever the body config carried.
// A race's rollers stop at the end of their slopes until every one has finished.
std::variant<Rod, Roller> makeModel(const BodyConfig& body, double gravity, bool race) {
  if (const auto* rod = std::get_if<RodConfig>(&body.config)) {
    RodParams params = rod->params;
    params.gravity = gravity;
    return Rod(params, rod->initial);
  }
  const auto& roller = std::get<RollerConfig>(body.config);
  RollerParams params = roller.params;
  params.gravity = gravity;
  Roller model(params, roller.initial);
  model.setHoldAtEnd(race);
  return model;
}

BodyConfig withGravity(BodyConfig body, double gravity) {
  std::visit([&](auto& config) { config.params.gravity = gravity; }, body.config);
  return body;
}

std::string kindName(BodyKind kind) { return kind == BodyKind::Rod ? "rod" : "roller"; }

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

// Where SetState puts a state field: the settable field of that name in the body's table. Any other name
// throws ConfigError naming the body, the field, the value and the settable fields.
template <class Model>
auto fieldOf(const Model& model, const std::string& body, const StateValue& value) {
  const auto member = settableMember(model, value.field);
  if (member == nullptr) {
    const BodyKind kind = std::is_same_v<Model, Rod> ? BodyKind::Rod : BodyKind::Roller;
    throw ConfigError(
        body, value.field, formatNumber(value.value),
        "no such state field of a " + kindName(kind) + "; its fields: " + joined(settableStateFields(kind)));
  }
  return member;
}

// A state field takes the range of its initial condition (x: x0, omega: omega0, ...); a roller's x must also
// be on its slope. Throws ConfigError naming the body, the field and the value.
template <class Config>
void checkStateValue(const std::string& body, const StateValue& value, const Config& config) {
  const BodyKey<Config>* key = keyOfStateField<Config>(value.field);
  if (!key->range.contains(value.value)) {
    throw ConfigError(body, value.field, formatNumber(value.value), key->range.describe());
  }
  if constexpr (std::is_same_v<Config, RollerConfig>) {
    if (value.field == "x" && value.value > config.params.incline_length) {
      throw ConfigError(body, "x", formatNumber(value.value),
                        "a position on the slope, in [0, incline_length = " +
                            formatNumber(config.params.incline_length) + "]");
    }
  }
}

}  // namespace

std::string toString(WorldCommand::Kind kind) {
  switch (kind) {
    case WorldCommand::Kind::Config: return "config";
    case WorldCommand::Kind::Reconfigure: return "reconfigure";
    case WorldCommand::Kind::Spawn: return "spawn";
    case WorldCommand::Kind::Delete: return "delete";
    case WorldCommand::Kind::SetState: return "set_state";
    case WorldCommand::Kind::Reset: return "reset";
  }
  return "?";
}

std::optional<WorldCommand::Kind> commandKindFromString(const std::string& name) {
  for (const auto kind :
       {WorldCommand::Kind::Config, WorldCommand::Kind::Reconfigure, WorldCommand::Kind::Spawn,
        WorldCommand::Kind::Delete, WorldCommand::Kind::SetState, WorldCommand::Kind::Reset}) {
    if (toString(kind) == name) return kind;
  }
  return std::nullopt;
}

std::string refusalLine(const std::string& kind, const std::string& body, const std::string& why) {
  return "refused " + kind + (body.empty() ? "" : " of '" + body + "'") + ", simulation unchanged: " + why;
}

std::string toString(WorldEvent::Kind kind) {
  switch (kind) {
    case WorldEvent::Kind::StartedRolling: return "started rolling";
    case WorldEvent::Kind::StartedSlipping: return "started slipping";
    case WorldEvent::Kind::Restarted: return "restarted (the end of its slope or floor, or a race's new lap)";
    case WorldEvent::Kind::Finished: return "finished the race's lap";
  }
  return "?";
}

World::World(const WorldConfig& config, std::vector<std::string> reserved_names)
    : config_(config),
      reserved_names_(std::move(reserved_names)),
      rate_(config.rate),
      dt_(1.0 / config.rate) {
  validate(config, reserved_names_);
  bodies_.reserve(config.bodies.size());
  for (auto& body : config_.bodies) {
    body = withGravity(body, config.gravity);
    bodies_.push_back(Body{body.name, makeModel(body, config.gravity, config.race), std::nullopt});
  }
}

void World::apply(const WorldCommand& command) {
  if (command.step != steps_) {
    throw ConfigError("command " + toString(command.kind) + " for step " + std::to_string(command.step) +
                      " refused: the world is at step " + std::to_string(steps_));
  }
  switch (command.kind) {
    case WorldCommand::Kind::Config: {
      if (command.world.rate != rate_ || command.world.publish_rate != config_.publish_rate) {
        throw ConfigError("(world)", "rate", formatNumber(command.world.rate),
                          "the running rate " + formatNumber(rate_) + " and publish_rate " +
                              formatNumber(config_.publish_rate));
      }
      World fresh(command.world, reserved_names_);
      config_ = fresh.config_;
      bodies_ = std::move(fresh.bodies_);
      lap_start_step_ = steps_;
      race_over_step_.reset();
      return;
    }
    case WorldCommand::Kind::Reconfigure: {
      const std::size_t index = existingIndex(command);
      const BodyConfig wanted = bodyOf(command);
      if (kindOf(wanted) != kindOf(config_.bodies[index])) {
        throw ConfigError(command.body, "type", kindName(kindOf(wanted)),
                          "the body's own type, " + kindName(kindOf(config_.bodies[index])));
      }
      WorldConfig would_be = config_;
      would_be.bodies[index] = wanted;
      validateWouldBe(would_be);
      std::visit(
          [&](auto& model) {
            using Config = std::conditional_t<std::is_same_v<std::decay_t<decltype(model)>, Rod>, RodConfig,
                                              RollerConfig>;
            const auto& next = std::get<Config>(wanted.config);
            model.setParams(next.params);
            if (initialChanged(next, std::get<Config>(config_.bodies[index].config))) {
              model.setInitial(next.initial);
              bodies_[index].finish.reset();
              if (std::is_same_v<Config, RollerConfig>) restartRace();  // a racer that restarts restarts all
            }
          },
          bodies_[index].model);
      config_.bodies[index] = wanted;
      return;
    }
    case WorldCommand::Kind::Spawn: {
      const BodyConfig wanted = bodyOf(command);
      WorldConfig would_be = config_;
      would_be.bodies.push_back(wanted);
      validateWouldBe(would_be);
      bodies_.push_back(Body{wanted.name, makeModel(wanted, config_.gravity, config_.race), std::nullopt});
      config_.bodies.push_back(wanted);
      if (kindOf(wanted) == BodyKind::Roller) restartRace();  // the newcomer starts with the others
      return;
    }
    case WorldCommand::Kind::Delete: {
      const std::size_t index = existingIndex(command);
      WorldConfig would_be = config_;
      would_be.bodies.erase(would_be.bodies.begin() + static_cast<std::ptrdiff_t>(index));
      validateWouldBe(would_be);
      bodies_.erase(bodies_.begin() + static_cast<std::ptrdiff_t>(index));
      config_.bodies.erase(config_.bodies.begin() + static_cast<std::ptrdiff_t>(index));
      return;
    }
    case WorldCommand::Kind::SetState: setState(existingIndex(command), command.state); return;
    case WorldCommand::Kind::Reset: reset(); return;
  }
}

std::size_t World::existingIndex(const WorldCommand& command) const {
  const auto index = indexOf(command.body);
  if (!index) {
    std::vector<std::string> names;
    for (const auto& body : bodies_) names.push_back(body.name);
    throw ConfigError(command.body, "(body)", "'" + command.body + "'",
                      "the name of a body of the world: " + joined(names));
  }
  return *index;
}

BodyConfig World::bodyOf(const WorldCommand& command) const {
  if (command.config.name != command.body) {
    throw ConfigError(command.body, "(name)", "'" + command.config.name + "'", "the body's own name");
  }
  return withGravity(command.config, config_.gravity);
}

void World::validateWouldBe(const WorldConfig& config) const { validate(config, reserved_names_); }

void World::setState(std::size_t index, const std::vector<StateValue>& state) {
  const std::string& name = bodies_[index].name;
  if (state.empty()) {
    throw ConfigError(name, "(state)", "(no field)",
                      "at least one of " + joined(settableStateFields(kindOf(bodies_[index]))));
  }
  const auto& config = config_.bodies[index].config;
  std::visit(
      [&](auto& model) {
        auto motion = model.state();
        for (std::size_t i = 0; i < state.size(); ++i) {
          const StateValue& value = state[i];
          const auto field = fieldOf(model, name, value);
          for (std::size_t j = 0; j < i; ++j) {
            if (state[j].field == value.field) {
              throw ConfigError(name, value.field, formatNumber(value.value), "each field once");
            }
          }
          std::visit([&](const auto& body_config) { checkStateValue(name, value, body_config); }, config);
          motion.*field = value.value;
        }
        model.setState(motion);  // only once every value passed: a refusal changes nothing
      },
      bodies_[index].model);
}

double World::time() const { return static_cast<double>(steps_) / rate_; }

void World::step() {
  const double t0 = time();
  for (auto& body : bodies_) {
    if (auto* rod = std::get_if<Rod>(&body.model)) {
      if (rod->step(dt_)) events_.push_back({t0 + dt_, body.name, WorldEvent::Kind::Restarted});
      continue;
    }
    auto& roller = std::get<Roller>(body.model);
    const RollerStepEvents happened = roller.step(dt_);
    if (happened.started_slipping) {
      events_.push_back({t0, body.name, WorldEvent::Kind::StartedSlipping});
    }
    if (happened.stuck_at) {
      events_.push_back({t0 + *happened.stuck_at, body.name, WorldEvent::Kind::StartedRolling});
    }
    if (happened.left_at && roller.finished()) finish(body, t0 + *happened.left_at);
    if (happened.restarted) {
      events_.push_back({t0 + dt_, body.name, WorldEvent::Kind::Restarted});
    }
  }
  ++steps_;
  if (!config_.race || !raceOver()) return;
  if (!race_over_step_) race_over_step_ = steps_;
  if (static_cast<double>(steps_ - *race_over_step_) < kRaceResultsShown * rate_) return;
  restartRace();
  for (const auto& body : bodies_) {
    if (kindOf(body) == BodyKind::Roller) events_.push_back({time(), body.name, WorldEvent::Kind::Restarted});
  }
}

void World::finish(Body& body, double t) {
  int place = 1;
  for (const auto& other : bodies_) place += other.finish ? 1 : 0;
  const auto& roller = std::get<Roller>(body.model);
  const double lap_start = static_cast<double>(lap_start_step_) / rate_;
  body.finish = RaceFinish{place, t - lap_start, closedFormRun(roller.params(), roller.initial()).finish};
  events_.push_back({t, body.name, WorldEvent::Kind::Finished});
}

bool World::raceOver() const {
  bool any = false;
  for (const auto& body : bodies_) {
    const auto* roller = std::get_if<Roller>(&body.model);
    if (roller && !roller->finished()) return false;
    any = any || roller;
  }
  return any;
}

void World::restartRace() {
  if (!config_.race) return;
  for (auto& body : bodies_) {
    if (auto* roller = std::get_if<Roller>(&body.model)) roller->restartLap();
    body.finish.reset();
  }
  lap_start_step_ = steps_;
  race_over_step_.reset();
}

void World::reset() {
  for (auto& body : bodies_) {
    std::visit([](auto& model) { model.reset(); }, body.model);
    body.finish.reset();
  }
  lap_start_step_ = steps_;
  race_over_step_.reset();
}

std::optional<std::size_t> World::indexOf(const std::string& name) const {
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_[i].name == name) return i;
  }
  return std::nullopt;
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
