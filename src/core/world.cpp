#include "rigid_body_sim/core/world.h"

#include <algorithm>
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

World::World(const WorldConfig& config, std::vector<std::string> reserved_names)
    : config_(config),
      reserved_names_(std::move(reserved_names)),
      rate_(config.rate),
      dt_(1.0 / config.rate) {
  validate(config, reserved_names_);
  bodies_.reserve(config.bodies.size());
  for (auto& body : config_.bodies) {
    body = withGravity(body, config.gravity);
    bodies_.push_back(Body{body.name, makeModel(body, config.gravity, config.race), std::nullopt, 0.0, true});
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
      for (std::size_t i = 0; i < bodies_.size(); ++i) restarted(i, "config");
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
      bool restarts = false;
      std::visit(
          [&](auto& model) {
            using Config = typename TypeOfModel<decltype(model)>::Config;
            const auto& next = std::get<Config>(wanted.config);  // the same type: checked above
            model.setParams(next.params);
            if (initialChanged(next, std::get<Config>(config_.bodies[index].config))) {
              model.setInitial(next.initial);
              bodies_[index].finish.reset();
              restarts = true;
              if (races(model) && restartRace("reconfigure")) restarts = false;  // a racer restarts all
            }
          },
          bodies_[index].model);
      config_.bodies[index] = wanted;
      if (restarts) {
        restarted(index, "reconfigure");
      } else if (!bodies_[index].finish && bodies_[index].lap_start != time()) {
        bodies_[index].lap_as_configured =
            false;  // changed in mid-lap: the lap's closed form no longer holds
      }
      return;
    }
    case WorldCommand::Kind::Spawn: {
      const BodyConfig wanted = bodyOf(command);
      WorldConfig would_be = config_;
      would_be.bodies.push_back(wanted);
      validateWouldBe(would_be);
      bodies_.push_back(
          Body{wanted.name, makeModel(wanted, config_.gravity, config_.race), std::nullopt, time(), true});
      config_.bodies.push_back(wanted);
      // A racer that joins starts with the others.
      const bool racer = std::visit([](const auto& model) { return races(model); }, bodies_.back().model);
      if (!racer || !restartRace("spawn")) restarted(bodies_.size() - 1, "spawn");
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
        bodies_[index].lap_as_configured = false;
      },
      bodies_[index].model);
}

double World::time() const { return static_cast<double>(steps_) / rate_; }

void World::step(BodyStepObserver* observer) {
  const double t0 = time();
  const std::size_t first_event = events_.size();
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    std::visit(
        [&](auto& model) {
          const auto happened = model.step(dt_);
          report(i, t0, model, happened);
          if (observer && !surelyFiniteModel(model)) observer->afterUnsureStep(i, bodies_[i]);
        },
        bodies_[i].model);
  }
  if (observer) observer->afterBodiesStep(bodies_);
  ++steps_;
  if (events_.size() != first_event) {
    // In time order: bodies stepped one after another may have their events in either order within a step
    // (most steps' are in order already: a rod's are all at the step's end; the sort takes a buffer).
    const auto first = events_.begin() + static_cast<std::ptrdiff_t>(first_event);
    const auto earlier = [](const BodyEvent& a, const BodyEvent& b) { return a.t < b.t; };
    if (!std::is_sorted(first, events_.end(), earlier)) std::stable_sort(first, events_.end(), earlier);
    if (config_.race) placeFinishers(first_event);
  }
  if (!config_.race || !raceOver()) return;
  if (!race_over_step_) race_over_step_ = steps_;
  if (static_cast<double>(steps_ - *race_over_step_) < kRaceResultsShown * rate_) return;
  restartRace("race", observer);
}

template <class Model, class Happened>
void World::report(std::size_t index, double t0, const Model& model, const Happened& happened) {
  if (!happened.any()) return;  // most steps: nothing to build
  // At the step's end: the next count's time exactly (t0 + dt may differ from it in the last bit).
  const double t1 = static_cast<double>(steps_ + 1) / rate_;
  TypeOfModel<Model>::forEachEvent(
      model, happened, dt_,
      [&](std::size_t kind, double offset, const Model& at, std::vector<EventValue> values) {
        record(index, offset >= dt_ ? t1 : t0 + offset, kind, at, std::move(values));
      });
}

template <class Model>
void World::record(std::size_t index, double t, std::size_t kind, const Model& at,
                   std::vector<EventValue> values) {
  using Type = TypeOfModel<Model>;
  Body& body = bodies_[index];
  const EventKind& what = Type::kEventKinds[kind];
  BodyEvent event{t, body.name, Type::kName, what.name, {}, std::move(values)};
  const auto fields = stateFields(at);
  event.state.reserve(fields.size());
  for (const auto& field : fields) event.state.push_back(EventValue{field.name, field.number, field.text});
  if (what.role == EventRole::Finish) event.values.push_back(EventValue{"lap_time", t - body.lap_start});
  // The kind's instant in closed form since the lap's start, as its type computes it (none for most kinds):
  // it holds only while the lap runs as configured.
  const auto& config = std::get<typename Type::Config>(config_.bodies[index].config);
  const std::optional<double> closed_form = Type::closedFormInstant(config, kind);
  if (closed_form && body.lap_as_configured) event.values.push_back(EventValue{"closed_form", *closed_form});
  if (what.role == EventRole::Finish) {
    if constexpr (Type::kRaces) {
      const auto& model = std::get<Model>(body.model);
      if (model.finished()) finish(index, t, findValue(event.values, "speed")->number);
    }
  } else if (what.role == EventRole::Restart) {
    body.lap_start = t;
    body.lap_as_configured = true;
  }
  events_.push_back(std::move(event));
}

void World::restarted(std::size_t index, const char* cause) {
  std::visit(
      [&](const auto& model) {
        using Type = TypeOfModel<decltype(model)>;
        for (std::size_t kind = 0; kind < Type::kEventKinds.size(); ++kind) {
          if (Type::kEventKinds[kind].role != EventRole::Restart) continue;
          record(index, time(), kind, model, std::vector<EventValue>{EventValue{"cause", 0.0, cause}});
          return;
        }
      },
      bodies_[index].model);
}

void World::placeFinishers(std::size_t first_event) {
  for (std::size_t e = first_event; e < events_.size(); ++e) {
    BodyEvent& event = events_[e];
    const auto index = indexOf(event.body);
    if (!index || !bodies_[*index].finish || findValue(event.values, "lap_time") == nullptr) continue;
    event.values.push_back(EventValue{"place", static_cast<double>(bodies_[*index].finish->place)});
  }
}

void World::finish(std::size_t index, double t, double speed) {
  Body& body = bodies_[index];
  const double lap_start = static_cast<double>(lap_start_step_) / rate_;
  // The instant of its type's Finish kind in closed form.
  const std::optional<double> closed_form = std::visit(
      [&](const auto& config) {
        using Type = TypeOfConfig<decltype(config)>;
        std::optional<double> instant;
        for (std::size_t kind = 0; kind < Type::kEventKinds.size(); ++kind) {
          if (Type::kEventKinds[kind].role == EventRole::Finish)
            instant = Type::closedFormInstant(config, kind);
        }
        return instant;
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

bool World::restartRace(const char* cause, BodyStepObserver* observer) {
  if (!config_.race) return false;
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    std::visit(
        [&](auto& model) {
          if constexpr (TypeOfModel<decltype(model)>::kRaces) {
            model.restartLap();
            restarted(i, cause);
            if (observer) observer->movedByWorld(i, bodies_[i]);
          }
        },
        bodies_[i].model);
    bodies_[i].finish.reset();
  }
  lap_start_step_ = steps_;
  race_over_step_.reset();
  return true;
}

void World::reset() {
  for (auto& body : bodies_) {
    std::visit([](auto& model) { model.reset(); }, body.model);
    body.finish.reset();
  }
  lap_start_step_ = steps_;
  race_over_step_.reset();
  for (std::size_t i = 0; i < bodies_.size(); ++i) restarted(i, "reset");
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

std::vector<BodyEvent> World::takeEvents() {
  std::vector<BodyEvent> taken;
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

const std::vector<std::pair<std::string, std::vector<EventKindInfo>>>& eventKindsByType() {
  static const auto table = [] {
    std::vector<std::pair<std::string, std::vector<EventKindInfo>>> out;
    BodyTypes::forEach([&](auto type) {
      using Type = decltype(type);
      std::vector<EventKindInfo> kinds;
      for (const auto& kind : Type::kEventKinds) kinds.push_back({kind.name, kind.meaning});
      out.emplace_back(Type::kName, std::move(kinds));
    });
    return out;
  }();
  return table;
}

const EventValue* findValue(const std::vector<EventValue>& values, const std::string& name) {
  for (const auto& value : values) {
    if (value.name == name) return &value;
  }
  return nullptr;
}

std::string fixedFrameOf(const Body& body) {
  return std::visit([&](const auto& model) { return fixedFrameOf<TypeOfModel<decltype(model)>>(body.name); },
                    body.model);
}

}  // namespace rigid_body_sim
