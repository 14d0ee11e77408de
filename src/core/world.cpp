#include "rigid_body_sim/core/world.h"

#include <type_traits>

#include "rigid_body_sim/core/names.h"
#include "rigid_body_sim/core/state_fields.h"

namespace rigid_body_sim {

namespace {

// Builds the model of one body; the world's gravity overrides whatever the body config carried.
// A race's racers stop at the end of their slopes until every one has finished.
AnyModel makeModel(const BodyConfig& body, double gravity, bool race) {
  return std::visit(
      [&](const auto& config) -> AnyModel {
        using Type = TypeOfConfig<decltype(config)>;
        auto params = config.params;
        params.gravity = gravity;
        typename Type::Model model(params, config.initial);
        if constexpr (Type::kRaces) model.setHoldAtEnd(race);
        return model;
      },
      body.config);
}

template <class Model>
constexpr bool races(const Model&) {
  return TypeOfModel<Model>::kRaces;
}

BodyConfig withGravity(BodyConfig body, double gravity) {
  std::visit([&](auto& config) { config.params.gravity = gravity; }, body.config);
  return body;
}

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
    using Type = TypeOfModel<Model>;
    throw ConfigError(body, value.field, formatNumber(value.value),
                      std::string("no such state field of a ") + Type::kName +
                          "; its fields: " + joined(stateFieldNames<Type>(true)));
  }
  return member;
}

// A state field takes the range of its initial condition (x: x0, omega: omega0, ...). Throws ConfigError
// naming the body, the field and the value.
template <class Config>
void checkStateValue(const std::string& body, const StateValue& value) {
  const BodyKey<Config>* key = keyOfStateField<Config>(value.field);
  if (!key->range.contains(value.value)) {
    throw ConfigError(body, value.field, formatNumber(value.value), key->range.describe());
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
    case WorldEvent::Kind::Gripped: return "gripped (started rolling, or came to rest)";
    case WorldEvent::Kind::LostGrip: return "lost its grip (started slipping or sliding)";
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
      if (wanted.config.index() != config_.bodies[index].config.index()) {
        throw ConfigError(command.body, "type", typeName(wanted),
                          "the body's own type, " + typeName(config_.bodies[index]));
      }
      WorldConfig would_be = config_;
      would_be.bodies[index] = wanted;
      validateWouldBe(would_be);
      std::visit(
          [&](auto& model) {
            using Config = typename TypeOfModel<decltype(model)>::Config;
            const auto& next = std::get<Config>(wanted.config);  // the same type: checked above
            model.setParams(next.params);
            if (initialChanged(next, std::get<Config>(config_.bodies[index].config))) {
              model.setInitial(next.initial);
              bodies_[index].finish.reset();
              if (races(model)) restartRace();  // a racer that restarts restarts all
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
      // A racer that joins starts with the others.
      if (std::visit([](const auto& model) { return races(model); }, bodies_.back().model)) restartRace();
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
                      "at least one of " + joined(settableStateFields(bodies_[index])));
  }
  std::visit(
      [&](auto& model) {
        using Type = TypeOfModel<decltype(model)>;
        const auto& config = std::get<typename Type::Config>(config_.bodies[index].config);
        auto motion = model.state();
        for (std::size_t i = 0; i < state.size(); ++i) {
          const StateValue& value = state[i];
          const auto field = fieldOf(model, name, value);
          for (std::size_t j = 0; j < i; ++j) {
            if (state[j].field == value.field) {
              throw ConfigError(name, value.field, formatNumber(value.value), "each field once");
            }
          }
          checkStateValue<typename Type::Config>(name, value);
          motion.*field = value.value;
        }
        Type::checkState(name, config, motion);  // where it may be: on its floor or slope
        model.setState(motion);                  // only once every value passed: a refusal changes nothing
        bodies_[index].finish.reset();           // a racer moved on leaves the lap's results
      },
      bodies_[index].model);
}

double World::time() const { return static_cast<double>(steps_) / rate_; }

void World::step() {
  const double t0 = time();
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    std::visit(
        [&](auto& model) {
          const auto happened = model.step(dt_);
          report(i, t0, model, happened);
        },
        bodies_[i].model);
  }
  ++steps_;
  if (!config_.race || !raceOver()) return;
  if (!race_over_step_) race_over_step_ = steps_;
  if (static_cast<double>(steps_ - *race_over_step_) < kRaceResultsShown * rate_) return;
  restartRace();
  for (const auto& body : bodies_) {
    if (std::visit([](const auto& model) { return races(model); }, body.model)) {
      events_.push_back({time(), body.name, WorldEvent::Kind::Restarted, "started the race's next lap"});
    }
  }
}

void World::event(double t, std::size_t index, WorldEvent::Kind kind, std::string what) {
  if (what.empty()) what = toString(kind);
  events_.push_back({t, bodies_[index].name, kind, std::move(what)});
}

void World::report(std::size_t index, double t0, const Rod&, bool restarted) {
  if (restarted) event(t0 + dt_, index, WorldEvent::Kind::Restarted, "restarted (off the end of its floor)");
}

template <class Model>
void World::report(std::size_t index, double t0, const Model& model, const InclineStepEvents& happened) {
  using Type = TypeOfModel<Model>;
  if (happened.started_slipping) event(t0, index, WorldEvent::Kind::LostGrip, Type::kLostGripText);
  if (happened.stuck_at) event(t0 + *happened.stuck_at, index, WorldEvent::Kind::Gripped, Type::kGrippedText);
  if (happened.left_at && model.finished()) finish(index, t0 + *happened.left_at, happened.arrival_speed);
  if (happened.restarted)
    event(t0 + dt_, index, WorldEvent::Kind::Restarted, "restarted (off an end of its slope)");
}

void World::finish(std::size_t index, double t, double speed) {
  Body& body = bodies_[index];
  const double lap_start = static_cast<double>(lap_start_step_) / rate_;
  const std::optional<double> closed_form = std::visit(
      [&](const auto& config) -> std::optional<double> {
        using Type = TypeOfConfig<decltype(config)>;
        if constexpr (Type::kRaces) return Type::closedFormFinish(config);
        return std::nullopt;
      },
      config_.bodies[index].config);
  body.finish = RaceFinish{1, t - lap_start, speed, closed_form};
  // Places from the times, not from the order of the bodies: two finishing in one step may be in either
  // order, and a tie shares its place.
  for (auto& racer : bodies_) {
    if (!racer.finish) continue;
    racer.finish->place = 1;
    for (const auto& other : bodies_) {
      if (other.finish && other.finish->time < racer.finish->time - kTieTime) ++racer.finish->place;
    }
  }
  event(t, index, WorldEvent::Kind::Finished, "finished the race's lap");
}

bool World::raceOver() const {
  bool any = false;
  for (const auto& body : bodies_) {
    const bool waiting = std::visit(
        [&](const auto& model) {
          if constexpr (TypeOfModel<decltype(model)>::kRaces) {
            any = true;
            return model.finished();
          }
          return true;
        },
        body.model);
    if (!waiting) return false;
  }
  return any;
}

void World::restartRace() {
  if (!config_.race) return;
  for (auto& body : bodies_) {
    std::visit(
        [](auto& model) {
          if constexpr (TypeOfModel<decltype(model)>::kRaces) model.restartLap();
        },
        body.model);
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

std::string typeName(const Body& body) {
  return std::visit([](const auto& model) -> std::string { return TypeOfModel<decltype(model)>::kName; },
                    body.model);
}

std::string fixedFrameOf(const Body& body) {
  return std::visit([&](const auto& model) { return fixedFrameOf<TypeOfModel<decltype(model)>>(body.name); },
                    body.model);
}

}  // namespace rigid_body_sim
