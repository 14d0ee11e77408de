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

bool surelyFinite(const Body& body) {
  // The settable fields are the motion; the rest follow from it. std::abs(NaN) <= bound is false: a NaN is
  // never surely finite.
  return std::visit(
      [](const auto& model) {
        for (const auto& field : stateFieldTable(model)) {
          if (field.settable() && !(std::abs(model.state().*field.motion) <= kSurelyFiniteMotion))
            return false;
        }
        return true;
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

void FiniteGuard::restore(Body& body, const Progress& progress) {
  std::visit(
      [&](auto& model) {
        using Model = std::decay_t<decltype(model)>;
        model.restore(std::get<typename Model::Progress>(progress));
      },
      body.model);
}

FiniteGuard::FiniteGuard(const std::vector<Body>& bodies) : held_(bodies.size(), false) {
  for (const auto& body : bodies) last_finite_.push_back(progressOf(body));
}

std::vector<NonFinite> FiniteGuard::afterStep(std::vector<Body>& bodies) {
  std::vector<NonFinite> newly_held;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!held_[i]) {
      const std::optional<std::string> field =
          surelyFinite(bodies[i]) ? std::nullopt : nonFiniteField(bodies[i]);
      if (!field) {
        last_finite_[i] = progressOf(bodies[i]);
        continue;
      }
      newly_held.push_back({i, *field});
      held_[i] = true;
    }
    restore(bodies[i], last_finite_[i]);  // held: whatever the step did to it is undone
  }
  return newly_held;
}

void FiniteGuard::release(std::size_t index, const Body& body) {
  held_[index] = false;
  if (finiteState(body)) last_finite_[index] = progressOf(body);
}

void FiniteGuard::releaseAll(const std::vector<Body>& bodies) {
  for (std::size_t i = 0; i < bodies.size(); ++i) release(i, bodies[i]);
}

void FiniteGuard::add(const Body& body) {
  last_finite_.push_back(progressOf(body));
  held_.push_back(false);
}

void FiniteGuard::remove(std::size_t index) {
  last_finite_.erase(last_finite_.begin() + static_cast<std::ptrdiff_t>(index));
  held_.erase(held_.begin() + static_cast<std::ptrdiff_t>(index));
}

}  // namespace rigid_body_sim
