#include "rigid_body_sim/run/session.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <utility>

namespace rigid_body_sim {

std::int64_t stepsPerSample(double rate, double sample_rate) {
  return static_cast<std::int64_t>(std::llround(rate / sample_rate));
}

Session::Session(const WorldConfig& config, std::vector<std::string> reserved_names,
                 std::int64_t steps_per_sample)
    : world_(config, std::move(reserved_names)), steps_per_sample_(steps_per_sample) {
  if (steps_per_sample_ < 1) {
    throw std::invalid_argument("steps per sample " + std::to_string(steps_per_sample_) + " is not >= 1");
  }
}

void Session::addSink(SampleSink& sink) { sinks_.push_back(&sink); }

void Session::advance(std::int64_t steps, const StepHook& after_step, BodyStepObserver* observer) {
  if (steps < 0) throw std::invalid_argument("cannot advance " + std::to_string(steps) + " steps");
  for (std::int64_t i = 0; i < steps; ++i) {
    world_.step(observer);
    if (after_step) after_step(world_);
    if (world_.hasEvents()) handEvents();
    if (atSamplingInstant()) handOut();
  }
}

std::size_t Session::apply(WorldCommand command) {
  if (atSamplingInstant() && !sampled()) handOut();
  command.step = world_.stepCount();
  world_.apply(command);  // a refusal throws here, before anything below
  const std::size_t index = ++commands_applied_;
  for (SampleSink* sink : sinks_) sink->applied(command, index, world_);
  if (world_.hasEvents()) handEvents();
  return index;
}

namespace {
bool finite(const std::vector<EventValue>& values) {
  for (const auto& value : values) {
    if (!std::isfinite(value.number)) return false;
  }
  return true;
}
}  // namespace

void Session::handEvents() {
  std::vector<BodyEvent> events = world_.takeEvents();
  events.erase(std::remove_if(events.begin(), events.end(),
                              [](const BodyEvent& event) {
                                return !std::isfinite(event.t) || !finite(event.state) ||
                                       !finite(event.values);
                              }),
               events.end());
  if (events.empty()) return;
  for (SampleSink* sink : sinks_) sink->happened(events, world_);
  events_.insert(events_.end(), std::make_move_iterator(events.begin()),
                 std::make_move_iterator(events.end()));
}

std::vector<BodyEvent> Session::takeEvents() {
  std::vector<BodyEvent> taken;
  taken.swap(events_);
  return taken;
}

bool Session::sampleNow() {
  if (sampled()) return false;
  handOut();
  return true;
}

void Session::handOut() {
  last_sampled_ = world_.stepCount();
  for (SampleSink* sink : sinks_) sink->write(world_);
}

}  // namespace rigid_body_sim
