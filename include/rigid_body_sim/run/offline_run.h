// The offline run behind `simulate`: runs a Session (run/session.h) without a master, samples it at
// t = j / sample_rate, writes the CSV files (and a bag on request), and summarises what happened.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rigid_body_sim/core/world.h"
#include "rigid_body_sim/io/csv_writer.h"
#include "rigid_body_sim/run/session.h"

namespace rigid_body_sim {

struct OfflineOptions {
  double duration = 10.0;    // s of simulated time (the text's 10 s)
  double sample_rate = 0.0;  // Hz; 0 means the config's publish_rate
  std::string out_dir = ".";
  std::string bag;  // empty: no bag
};

// Energy of one body over the run.
struct EnergyRecord {
  double initial = 0.0;
  double final = 0.0;
  double min = 0.0;
  double max = 0.0;
  // Largest |E - E_start| within a stretch of states that conserve it exactly (the type's conservesEnergy:
  // a rolling roller; 0 for the other types).
  double rolling_drift = 0.0;
};

struct OfflineSummary {
  double end_time = 0.0;
  std::int64_t steps = 0;
  std::int64_t samples = 0;  // per body
  std::vector<std::string> bodies;
  std::vector<std::string> final_states;  // one CSV row per body, at end_time
  std::vector<std::string> final_rows;    // the same rows without their header (csvRow)
  std::vector<EnergyRecord> energy;       // per body
  std::vector<int> bounces;               // per body: contacts with a floor begun (rods; 0 for the others)
  std::vector<BodyEvent> events;
};

// Checks the options against the config; throws ConfigError naming the option.
void validate(const OfflineOptions& options, const WorldConfig& config);

// Steps between samples: rate / options.sample_rate, or rate / publish_rate without one.
std::int64_t stepsPerSample(const OfflineOptions& options, const WorldConfig& config);

// The last sample's index j: the last t = j / sample_rate not after the duration (rounding forgiven).
std::int64_t lastSample(const WorldConfig& config, const OfflineOptions& options);

// Opens the bag of options.bag for a run of `config` whose bodies start as `bodies`. This layer knows only
// the sink interface; the ROS layer implements it (ros/bag_recorder.h), so that a run without a bag loads
// no ROS library.
using SinkOpener = std::function<std::unique_ptr<SampleSink>(
    const std::string& path, const WorldConfig& config, const std::vector<Body>& bodies)>;

// The sink of `path` through `open_bag`; none for an empty path; std::runtime_error without `open_bag`.
std::unique_ptr<SampleSink> openSink(const std::string& path, const WorldConfig& config,
                                     const std::vector<Body>& bodies, const SinkOpener& open_bag);

// The files of a run of `config` whose bodies start as `bodies`: DIR/<body>.csv, DIR/events.csv and, if `bag`
// is set, the bag through `open_bag` (opened in that order). Final only on commit(); throws as CsvWriter and
// openSink.
class RunFiles : public SampleSink {
 public:
  RunFiles(const std::string& out_dir, const std::string& bag, const WorldConfig& config,
           const std::vector<Body>& bodies, const SinkOpener& open_bag);
  void write(const World& world) override;  // a CSV row per body; the bag's messages
  void applied(const WorldCommand& command, std::size_t index, const World& world) override;
  void happened(const std::vector<BodyEvent>& events, const World& world) override;  // events.csv; the bag's
  void commit() override;  // the CSV files, then the bag

 private:
  CsvWriter csv_;
  std::unique_ptr<SampleSink> bag_;
};

// Runs the whole thing; throws ConfigError on bad options, std::runtime_error on an output failure (also
// for options.bag without `open_bag`). Shows a progress bar on stderr when it is a terminal and the run
// lasts.
OfflineSummary runOffline(const WorldConfig& config, const OfflineOptions& options,
                          const SinkOpener& open_bag = nullptr);

// The same run and summary, writing nothing (out_dir and bag are ignored): one variant of a sweep.
OfflineSummary summariseRun(const WorldConfig& config, const OfflineOptions& options);

// A few human lines: final states, slip-to-roll times, energy drift.
std::string formatSummary(const OfflineSummary& summary);

}  // namespace rigid_body_sim
