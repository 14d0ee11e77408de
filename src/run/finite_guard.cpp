#include "rigid_body_sim/run/finite_guard.h"

#include <array>
#include <cmath>
#include <new>
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

namespace {
// The settable fields are the motion; the rest follow from it. std::abs(NaN) <= bound is false: a NaN is
// never surely finite. The members are picked at compile time: the check after every step runs over these
// alone, unrolled, instead of over the table asking each field whether it is settable.
template <class Model>
bool surelyFiniteModel(const Model& model) {
  static constexpr auto kMembers = settableMembers<TypeOfModel<Model>>();
  bool finite = true;
  for (const auto member : kMembers) finite &= std::abs(model.state().*member) <= kSurelyFiniteMotion;
  return finite;
}
}  // namespace

bool surelyFinite(const Body& body) {
  return std::visit([](const auto& model) { return surelyFiniteModel(model); }, body.model);
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

FiniteGuard::FiniteGuard(const std::vector<Body>& bodies) : held_(bodies.size(), 0) {
  for (const auto& body : bodies) last_finite_.push_back(progressOf(body));
}

namespace {
// The model's progress built in its slot, not assigned from a temporary: a Progress just built on the stack
// and copied in wider moves stalled on store forwarding, most of the guard's cost.
template <class Model>
void keepProgress(typename Model::Progress& slot, const Model& model) {
  using Progress = typename Model::Progress;
  static_assert(std::is_trivially_destructible_v<Progress>);
  ::new (static_cast<void*>(&slot)) Progress(model.progress());
}
}  // namespace

void FiniteGuard::afterBodyStep(std::size_t i, Body& body) {
  // One visit a body, its progress kept in place: a body keeps its type, so its last finite progress is of
  // its own type (three visits and a variant's construction a body-step were a third of the node's CPU).
  std::visit(
      [&](auto& model) {
        using Progress = typename std::decay_t<decltype(model)>::Progress;
        Progress& last = std::get<Progress>(last_finite_[i]);
        if (!held_[i]) {
          if (surelyFiniteModel(model)) {
            keepProgress(last, model);
            return;
          }
          const std::optional<std::string> field = nonFiniteField(body);
          if (!field) {
            keepProgress(last, model);
            return;
          }
          newly_held_.push_back({i, *field});
          held_[i] = 1;
        }
        model.restore(last);  // held: whatever the step did to it is undone
      },
      body.model);
}

std::vector<NonFinite> FiniteGuard::takeNewlyHeld() {
  std::vector<NonFinite> taken;
  taken.swap(newly_held_);
  return taken;
}

std::vector<NonFinite> FiniteGuard::afterStep(std::vector<Body>& bodies) {
  for (std::size_t i = 0; i < bodies.size(); ++i) afterBodyStep(i, bodies[i]);
  return takeNewlyHeld();
}

void FiniteGuard::release(std::size_t index, const Body& body) {
  held_[index] = 0;
  if (finiteState(body)) last_finite_[index] = progressOf(body);
}

void FiniteGuard::releaseAll(const std::vector<Body>& bodies) {
  for (std::size_t i = 0; i < bodies.size(); ++i) release(i, bodies[i]);
}

void FiniteGuard::add(const Body& body) {
  last_finite_.push_back(progressOf(body));
  held_.push_back(0);
}

void FiniteGuard::remove(std::size_t index) {
  last_finite_.erase(last_finite_.begin() + static_cast<std::ptrdiff_t>(index));
  held_.erase(held_.begin() + static_cast<std::ptrdiff_t>(index));
}

}  // namespace rigid_body_sim
