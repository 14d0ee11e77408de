#include "rigid_body_sim/run/finite_guard.h"

#include <array>
#include <cmath>
#include <sstream>
#include <type_traits>
#include <utility>

#include "rigid_body_sim/core/parameters.h"
#include "rigid_body_sim/core/state_fields.h"

namespace rigid_body_sim {

namespace {

// Every key the body's type writes, as key=value, then what no key holds.
template <class Config>
void describeKeys(std::ostream& out, const Config& config) {
  for (const auto& key : bodyType<Config>().keys) {
    if (key.written()) out << key.name << '=' << key.text(config) << ' ';
  }
  out << "gravity=" << formatNumber(config.params.gravity);
}

// Its keys, then its texts (a mode).
template <class Model>
void describeModel(std::ostream& out, const Model& model) {
  describeKeys(out, typename TypeOfModel<Model>::Config{model.params(), model.initial()});
  for (const auto& field : stateFields(model)) {
    if (!field.text.empty()) out << ' ' << field.name << '=' << field.text;
  }
}

}  // namespace

std::optional<std::string> nonFiniteField(const Body& body) {
  return std::visit(
      [](const auto& model) -> std::optional<std::string> {
        for (const auto& field : stateFields(model)) {
          if (field.text.empty() && !std::isfinite(field.number)) return std::string(field.name);
        }
        return std::nullopt;
      },
      body.model);
}

std::string describeBody(const Body& body) {
  std::ostringstream out;
  std::visit(
      [&](const auto& model) {
        describeModel(out, model);
        out << " | state";
        for (const auto& field : stateFields(model)) {
          if (field.text.empty()) out << ' ' << field.name << '=' << formatNumber(field.number);
        }
      },
      body.model);
  return out.str();
}

FiniteGuard::Progress FiniteGuard::progressOf(const Body& body) {
  return std::visit([](const auto& model) -> Progress { return model.progress(); }, body.model);
}

FiniteGuard::FiniteGuard(const std::vector<Body>& bodies, double dt)
    : dt_(dt), kept_at_(bodies.size(), 0), held_(bodies.size(), 0) {
  for (const auto& body : bodies) kept_.push_back(progressOf(body));
}

namespace {
// The model's last finite state: `kept` stepped again `steps` times, as it went on since.
template <class Model>
void stepAgain(Model& model, const typename Model::Progress& kept, std::uint64_t steps, double dt) {
  model.restore(kept);
  for (std::uint64_t n = 0; n < steps; ++n) model.step(dt);
}
}  // namespace

void FiniteGuard::afterUnsureStep(std::size_t i, Body& body) {
  if (held_[i]) return;  // afterBodiesStep undoes whatever the step did to it
  const std::optional<std::string> field = nonFiniteField(body);
  if (!field) return;  // finite, only larger than surelyFiniteModel's bound
  newly_held_.push_back({i, *field});
  held_[i] = 1;
  ++held_count_;
  std::visit(
      [&](auto& model) {
        using Progress = typename std::decay_t<decltype(model)>::Progress;
        // A body keeps its type: its progress is of it. The last finite state is the one before this step.
        stepAgain(model, std::get<Progress>(kept_[i]), steps_ - kept_at_[i], dt_);
      },
      body.model);
  keep(i, body);
}

void FiniteGuard::afterBodiesStep(std::vector<Body>& bodies) {
  ++steps_;
  if (held_count_ != 0) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (!held_[i]) continue;
      std::visit(
          [&](auto& model) {
            using Progress = typename std::decay_t<decltype(model)>::Progress;
            model.restore(std::get<Progress>(kept_[i]));
          },
          bodies[i].model);
      kept_at_[i] = steps_;  // held at it: a release that fails again steps nothing again
    }
  }
  if (steps_ % kStepsPerKeep != 0) return;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!held_[i]) keep(i, bodies[i]);
  }
}

void FiniteGuard::movedByWorld(std::size_t i, Body& body) {
  if (!held_[i]) keep(i, body);
}

void FiniteGuard::keep(std::size_t i, const Body& body) {
  kept_[i] = progressOf(body);
  kept_at_[i] = steps_;
}

std::vector<NonFinite> FiniteGuard::takeNewlyHeld() {
  std::vector<NonFinite> taken;
  taken.swap(newly_held_);
  return taken;
}

std::vector<NonFinite> FiniteGuard::afterStep(std::vector<Body>& bodies) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!surelyFinite(bodies[i])) afterUnsureStep(i, bodies[i]);
  }
  afterBodiesStep(bodies);
  return takeNewlyHeld();
}

void FiniteGuard::release(std::size_t index, const Body& body) {
  if (held_[index]) --held_count_;
  held_[index] = 0;
  if (finiteState(body)) keep(index, body);
}

void FiniteGuard::releaseAll(const std::vector<Body>& bodies) {
  for (std::size_t i = 0; i < bodies.size(); ++i) release(i, bodies[i]);
}

void FiniteGuard::keepCurrent(const std::vector<Body>& bodies) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!held_[i] && finiteState(bodies[i])) keep(i, bodies[i]);
  }
}

void FiniteGuard::add(const Body& body) {
  kept_.push_back(progressOf(body));
  kept_at_.push_back(steps_);
  held_.push_back(0);
}

void FiniteGuard::remove(std::size_t index) {
  const auto at = static_cast<std::ptrdiff_t>(index);
  if (held_[index]) --held_count_;
  kept_.erase(kept_.begin() + at);
  kept_at_.erase(kept_at_.begin() + at);
  held_.erase(held_.begin() + at);
}

}  // namespace rigid_body_sim
