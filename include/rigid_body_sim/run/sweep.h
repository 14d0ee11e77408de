// Parameter sweeps behind `simulate CONFIG --sweep BODY.KEY=START:STOP:N ... [--jobs J] [--shard i/n]`:
// the variants are the Cartesian product of the swept values, each a validated config run on a thread
// pool; one CSV row per variant summarises it.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "rigid_body_sim/core/parameters.h"
#include "rigid_body_sim/run/offline_run.h"

namespace rigid_body_sim {

// One swept key: N values evenly spaced from start to stop, both included (numpy.linspace); N = 1 is start.
struct SweepAxis {
  std::string body;
  std::string key;
  double start = 0.0;
  double stop = 0.0;
  std::int64_t count = 1;

  double value(std::int64_t i) const;
  std::string column() const { return body + "." + key; }
};

// Parses "BODY.KEY=START:STOP:N" against the config (the body exists, KEY is one of its numeric keys);
// throws ConfigError naming what is wrong.
SweepAxis parseSweepAxis(const std::string& spec, const WorldConfig& config);

// Slice i of n (1 <= i <= n): variants [floor(total (i-1) / n), floor(total i / n)).
struct Shard {
  std::int64_t index = 1;
  std::int64_t count = 1;
};
Shard parseShard(const std::string& spec);  // "i/n"; throws ConfigError
std::pair<std::int64_t, std::int64_t> shardRange(std::int64_t total, const Shard& shard);

// Number of variants (the product of the counts); throws ConfigError beyond kMaxVariants or when a
// key is swept twice.
constexpr std::int64_t kMaxVariants = 1000000000;
std::int64_t variantCount(const std::vector<SweepAxis>& axes);

// The swept values of variant v: the last axis varies fastest.
std::vector<double> variantValues(const std::vector<SweepAxis>& axes, std::int64_t variant);

// The base config with variant v's values set, validated like a loaded file (throws ConfigError).
WorldConfig variantConfig(const WorldConfig& base, const std::vector<SweepAxis>& axes, std::int64_t variant);

// The summary CSV: variant, the swept values, t, then per body its final state (CSV columns, prefixed
// "<body>."), energy drift (final - initial, J), and bounces (rods) or slip-to-roll time (rollers;
// empty when the body never went from slipping to rolling).
std::string sweepHeader(const WorldConfig& base, const std::vector<SweepAxis>& axes);
std::string sweepRow(const WorldConfig& base, std::int64_t variant, const std::vector<double>& values,
                     const OfflineSummary& summary);

struct SweepOptions {
  std::vector<SweepAxis> axes;
  Shard shard;
  unsigned jobs = 0;  // threads; 0 = every core
};

struct SweepResult {
  std::int64_t total = 0;  // variants of the whole sweep
  std::int64_t first = 0;  // this shard's [first, end)
  std::int64_t end = 0;
  unsigned jobs = 1;
  std::string path;  // the CSV written
};

// "sweep.csv", or "sweep.<i>-of-<n>.csv" for a shard (i zero-padded, so the files sort in order).
std::string sweepFileName(const Shard& shard);

// Validates every variant of the shard first (nothing is written on a refusal), then runs them on the
// pool and writes out_dir/sweepFileName(shard). Only shard 1 writes the header line, so that the shards'
// files concatenated in order are byte for byte the whole sweep's file.
SweepResult runSweep(const WorldConfig& base, const SweepOptions& sweep, const OfflineOptions& options);

}  // namespace rigid_body_sim
