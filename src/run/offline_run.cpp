#include "rigid_body_sim/run/offline_run.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "rigid_body_sim/core/body_types.h"
#include "rigid_body_sim/io/csv_writer.h"
#include "rigid_body_sim/run/progress.h"

namespace rigid_body_sim {

namespace {

const std::string kCommandLine = "(command line)";
constexpr double kMaxDuration = 1e7;  // s; about four months of simulated time

double effectiveSampleRate(const OfflineOptions& options, const WorldConfig& config) {
  return options.sample_rate > 0.0 ? options.sample_rate : config.publish_rate;
}

// Follows the energy of every body from sample to sample.
class EnergyTracker {
 public:
  explicit EnergyTracker(const std::vector<Body>& bodies)
      : records_(bodies.size()), rolling_start_(bodies.size()) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const double e = energyOf(bodies[i]);
      records_[i] = {e, e, e, e, 0.0};
      rolling_start_[i] = isRolling(bodies[i]) ? e : NAN;
    }
  }

  void sample(const std::vector<Body>& bodies, const std::vector<bool>& interrupted) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const double e = energyOf(bodies[i]);
      EnergyRecord& record = records_[i];
      record.final = e;
      record.min = std::min(record.min, e);
      record.max = std::max(record.max, e);
      if (!isRolling(bodies[i])) {
        rolling_start_[i] = NAN;
      } else if (std::isnan(rolling_start_[i]) || interrupted[i]) {
        rolling_start_[i] = e;  // a new stretch of rolling begins at this sample
      } else {
        record.rolling_drift = std::max(record.rolling_drift, std::abs(e - rolling_start_[i]));
      }
    }
  }

  const std::vector<EnergyRecord>& records() const { return records_; }

 private:
  static bool isRolling(const Body& body) {
    return std::visit([](const auto& model) { return TypeOfModel<decltype(model)>::conservesEnergy(model); },
                      body.model);
  }
  std::vector<EnergyRecord> records_;
  std::vector<double> rolling_start_;
};

// Bodies that restarted or changed mode since the last sample: their rolling stretch starts anew.
std::vector<bool> interruptedBodies(const std::vector<Body>& bodies, const std::vector<BodyEvent>& events) {
  std::vector<bool> interrupted(bodies.size(), false);
  for (const auto& event : events) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (bodies[i].name == event.body) interrupted[i] = true;
    }
  }
  return interrupted;
}

// Counts each rod's bounces: a bounce begins at the step where an end goes below the floor while
// neither was below it at the step before. Checked every step, as a contact lasts only tens of steps.
class BounceCounter {
 public:
  explicit BounceCounter(const std::vector<Body>& bodies)
      : touching_(bodies.size()), bounces_(bodies.size(), 0) {
    for (std::size_t i = 0; i < bodies.size(); ++i) touching_[i] = touchesFloor(bodies[i]);
  }

  void step(const std::vector<Body>& bodies) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const bool touching = touchesFloor(bodies[i]);
      if (touching && !touching_[i]) ++bounces_[i];
      touching_[i] = touching;
    }
  }

  const std::vector<int>& bounces() const { return bounces_; }

 private:
  static bool touchesFloor(const Body& body) {
    return std::visit([](const auto& model) { return TypeOfModel<decltype(model)>::touchesFloor(model); },
                      body.model);
  }
  std::vector<char> touching_;
  std::vector<int> bounces_;
};

// The summary of a run that ended at `world`, with its trackers.
OfflineSummary summaryOf(const World& world, std::int64_t samples, const EnergyTracker& energy,
                         const BounceCounter& bounces) {
  OfflineSummary summary;
  summary.end_time = world.time();
  summary.steps = world.stepCount();
  summary.samples = samples;
  for (const auto& body : world.bodies()) {
    summary.bodies.push_back(body.name);
    summary.final_rows.push_back(csvRow(world.time(), body));
    summary.final_states.push_back(csvHeader(body) + " = " + summary.final_rows.back());
  }
  summary.energy = energy.records();
  summary.bounces = bounces.bounces();
  return summary;
}

// The session of a run of `config`, sampling at the options' rate; throws ConfigError on bad options.
Session sessionOf(const WorldConfig& config, const OfflineOptions& options) {
  validate(options, config);
  return Session(config, {}, stepsPerSample(options, config));
}

// Runs `session` from t = 0 to the last sample, its sinks getting every sample (t = 0 included); tracks
// energies (at samples), bounces (every step: a contact lasts only tens of steps) and events on the way.
OfflineSummary stepAndSample(Session& session, std::int64_t last_sample, ProgressBar* progress) {
  EnergyTracker energy(session.world().bodies());
  BounceCounter bounces(session.world().bodies());
  const StepHook count_bounces = [&bounces](World& world) { bounces.step(world.bodies()); };
  std::vector<BodyEvent> events;
  session.sampleNow();
  if (progress) progress->update(0);
  for (std::int64_t j = 1; j <= last_sample; ++j) {
    session.advance(session.stepsPerSample(), count_bounces);
    if (progress) progress->update(j);
    std::vector<BodyEvent> new_events = session.takeEvents();
    energy.sample(session.world().bodies(), interruptedBodies(session.world().bodies(), new_events));
    events.insert(events.end(), new_events.begin(), new_events.end());
  }
  OfflineSummary summary = summaryOf(session.world(), last_sample + 1, energy, bounces);
  summary.events = std::move(events);
  return summary;
}

}  // namespace

void validate(const OfflineOptions& options, const WorldConfig& config) {
  const Range duration{0.0, kMaxDuration, false, false};
  if (!duration.contains(options.duration)) {
    throw ConfigError(kCommandLine, "--duration", formatNumber(options.duration), duration.describe());
  }
  const double sample_rate = effectiveSampleRate(options, config);
  if (!dividesRate(config.rate, sample_rate)) {
    throw ConfigError(kCommandLine, "--sample-rate", formatNumber(sample_rate),
                      "a divisor of rate = " + formatNumber(config.rate) + " (rate / sample_rate whole)");
  }
}

std::unique_ptr<SampleSink> openSink(const std::string& path, const WorldConfig& config,
                                     const std::vector<Body>& bodies, const SinkOpener& open_bag) {
  if (path.empty()) return nullptr;
  if (!open_bag) throw std::runtime_error("cannot write '" + path + "': no bag writer in this program");
  return open_bag(path, config, bodies);
}

std::int64_t stepsPerSample(const OfflineOptions& options, const WorldConfig& config) {
  return stepsPerSample(config.rate, effectiveSampleRate(options, config));
}

std::int64_t lastSample(const WorldConfig& config, const OfflineOptions& options) {
  return static_cast<std::int64_t>(
      std::floor(options.duration * effectiveSampleRate(options, config) + 1e-9));
}

RunFiles::RunFiles(const std::string& out_dir, const std::string& bag, const WorldConfig& config,
                   const std::vector<Body>& bodies, const SinkOpener& open_bag)
    : csv_(out_dir, bodies), bag_(openSink(bag, config, bodies, open_bag)) {}

void RunFiles::write(const World& world) {
  csv_.write(world.time(), world.bodies());
  if (bag_) bag_->write(world);
}

void RunFiles::applied(const WorldCommand& command, std::size_t index, const World& world) {
  if (bag_) bag_->applied(command, index, world);
}

void RunFiles::happened(const std::vector<BodyEvent>& events, const World& world) {
  csv_.write(events);
  if (bag_) bag_->happened(events, world);
}

void RunFiles::commit() {
  csv_.commit();
  if (bag_) bag_->commit();
}

OfflineSummary runOffline(const WorldConfig& config, const OfflineOptions& options,
                          const SinkOpener& open_bag) {
  Session session = sessionOf(config, options);
  RunFiles files(options.out_dir, options.bag, config, session.world().bodies(), open_bag);
  session.addSink(files);
  const std::int64_t last_sample = lastSample(config, options);
  ProgressBar progress(last_sample, "samples");
  OfflineSummary summary = stepAndSample(session, last_sample, &progress);
  progress.finish();
  files.commit();
  return summary;
}

OfflineSummary summariseRun(const WorldConfig& config, const OfflineOptions& options) {
  Session session = sessionOf(config, options);
  return stepAndSample(session, lastSample(config, options), nullptr);
}

namespace {
// A line per kind of the body's events: every instant of a kind that happened up to three times, else the
// count and the first (a rod's contacts come by the dozen).
std::string eventLines(const std::vector<BodyEvent>& events, const std::string& body) {
  std::vector<std::pair<std::string, std::vector<double>>> kinds;
  for (const auto& event : events) {
    if (event.body != body) continue;
    auto same =
        std::find_if(kinds.begin(), kinds.end(), [&](const auto& kind) { return kind.first == event.kind; });
    if (same == kinds.end()) same = kinds.insert(kinds.end(), {event.kind, {}});
    same->second.push_back(event.t);
  }
  std::ostringstream out;
  for (const auto& [kind, times] : kinds) {
    out << "  " << kind << ": ";
    if (times.size() > 3) {
      out << times.size() << " times, first at t = " << times.front() << " s\n";
      continue;
    }
    out << "t =";
    for (std::size_t k = 0; k < times.size(); ++k) out << (k == 0 ? " " : ", ") << times[k];
    out << " s\n";
  }
  return out.str();
}
}  // namespace

std::string formatSummary(const OfflineSummary& summary) {
  std::ostringstream out;
  out << "simulated " << summary.end_time << " s in " << summary.steps << " steps, " << summary.samples
      << " samples per body\n";
  for (std::size_t i = 0; i < summary.bodies.size(); ++i) {
    const EnergyRecord& e = summary.energy[i];
    out << summary.bodies[i] << ":\n  final " << summary.final_states[i] << "\n  energy " << e.initial
        << " J -> " << e.final << " J (min " << e.min << ", max " << e.max << ")";
    if (e.rolling_drift > 0.0) out << ", largest drift while rolling " << e.rolling_drift << " J";
    out << "\n";
    if (summary.bounces[i] > 0) out << "  " << summary.bounces[i] << " bounces\n";
    out << eventLines(summary.events, summary.bodies[i]);
  }
  return out.str();
}

}  // namespace rigid_body_sim
