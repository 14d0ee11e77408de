#include "rigid_body_sim/run/sweep.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <thread>
#include <tuple>
#include <type_traits>

#include "rigid_body_sim/core/state_fields.h"
#include "rigid_body_sim/run/progress.h"

namespace rigid_body_sim {

namespace {

const std::string kCommandLine = "(command line)";
const std::string kSweepForm = "BODY.KEY=START:STOP:N, N a whole number >= 1";
// Variants handed to the pool at a time: bounds the rows held in memory for a huge sweep.
constexpr std::int64_t kBlock = 4096;

// A number and nothing else (strtod accepts leading spaces and stops at the first bad character).
bool parseNumber(const std::string& text, double& value) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(value);
}

bool parseWhole(const std::string& text, std::int64_t min, std::int64_t max, std::int64_t& value) {
  double number = 0.0;
  if (!parseNumber(text, number) || number != std::floor(number) || number < static_cast<double>(min) ||
      number > static_cast<double>(max)) {
    return false;
  }
  value = static_cast<std::int64_t>(number);
  return true;
}

// The keys a sweep varies: the numbers, and the texts that take whole numbers (a rod's substeps).
template <class Config>
bool sweepable(const BodyKey<Config>& key) {
  return key.isNumber() || key.counts;
}

template <class Config>
std::string sweepableNames() {
  std::string names;
  for (const auto& key : bodyType<Config>().keys) {
    if (sweepable(key)) names += (names.empty() ? "" : ", ") + std::string(key.name);
  }
  return names;
}

template <class Config>
const BodyKey<Config>* sweepableKey(const std::string& name) {
  const BodyKey<Config>* key = findKey(bodyType<Config>().keys, name);
  return key && sweepable(*key) ? key : nullptr;
}

const BodyConfig* findBody(const WorldConfig& config, const std::string& name) {
  for (const auto& body : config.bodies) {
    if (body.name == name) return &body;
  }
  return nullptr;
}

// Sets a swept key of a body config (parseSweepAxis checked it): a number as it is, a text as the number
// written (a rod's substeps: 3), refused unless the key takes it (2.5 sub-steps).
void setKey(BodyConfig& body, const std::string& key, double value) {
  std::visit(
      [&](auto& config) {
        using Config = std::decay_t<decltype(config)>;
        const BodyKey<Config>& found = *sweepableKey<Config>(key);
        if (found.isNumber()) {
          found.field(config) = value;
        } else if (!found.read(config, formatNumber(value))) {
          throw ConfigError(body.name, key, formatNumber(value), found.allowed());
        }
      },
      body.config);
}

SweepColumn sweepColumnOf(const BodyConfig& body) {
  return std::visit([](const auto& config) { return TypeOfConfig<decltype(config)>::kSweepColumn; },
                    body.config);
}

// The body's final state (its CSV columns), its energy drift, and its type's sweep column (a rod's bounces, a
// roller's first slip-to-roll instant, a block's first stop), each prefixed with "<body>.".
std::string bodyColumns(const BodyConfig& body) {
  std::vector<std::string> fields = stateFieldNames(body);
  fields.push_back(kEnergyDriftColumn);
  fields.push_back(sweepColumnOf(body).name);
  std::string columns;
  for (const auto& field : fields) columns += "," + body.name + "." + field;
  return columns;
}

// The instant of the body's first event of that kind, or "" when there was none.
std::string firstEvent(const OfflineSummary& summary, const std::string& body, const std::string& kind) {
  for (const auto& event : summary.events) {
    if (event.body == body && event.kind == kind) return formatNumber(event.t);
  }
  return "";
}

// Runs variants [first, end) on `jobs` threads into rows[v - first]; `done` counts finished variants.
void runBlock(const WorldConfig& base, const SweepOptions& sweep, const OfflineOptions& options,
              std::int64_t first, std::int64_t end, unsigned jobs, std::vector<std::string>& rows,
              std::atomic<std::int64_t>& done, ProgressBar& progress, std::int64_t shard_first) {
  std::atomic<std::int64_t> next{first};
  std::exception_ptr failure;
  std::mutex mutex;
  std::condition_variable finished;
  unsigned running = jobs;
  const auto work = [&] {
    try {
      for (std::int64_t v = next++; v < end; v = next++) {
        const OfflineSummary summary = summariseRun(variantConfig(base, sweep.axes, v), options);
        rows[static_cast<std::size_t>(v - first)] = sweepRow(base, v, variantValues(sweep.axes, v), summary);
        ++done;
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex);
      failure = std::current_exception();
      next = end;  // the others stop at their next variant
    }
    std::lock_guard<std::mutex> lock(mutex);
    if (--running == 0) finished.notify_one();
  };
  std::vector<std::thread> pool;
  for (unsigned j = 0; j < jobs; ++j) pool.emplace_back(work);
  {
    std::unique_lock<std::mutex> lock(mutex);
    while (!finished.wait_for(lock, std::chrono::milliseconds(100), [&] { return running == 0; })) {
      lock.unlock();
      progress.update(done - shard_first);
      lock.lock();
    }
  }
  for (auto& thread : pool) thread.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace

double SweepAxis::value(std::int64_t i) const {
  if (count == 1) return start;
  if (i == count - 1) return stop;  // exactly the end the user typed
  return start + static_cast<double>(i) * ((stop - start) / static_cast<double>(count - 1));
}

SweepAxis parseSweepAxis(const std::string& spec, const WorldConfig& config) {
  const auto refuse = [&](const std::string& allowed) {
    return ConfigError(kCommandLine, "--sweep", "'" + spec + "'", allowed);
  };
  const std::size_t equals = spec.find('=');
  const std::size_t dot = spec.find('.');
  if (equals == std::string::npos || dot == std::string::npos || dot > equals) throw refuse(kSweepForm);
  SweepAxis axis;
  axis.body = spec.substr(0, dot);
  axis.key = spec.substr(dot + 1, equals - dot - 1);
  const std::string range = spec.substr(equals + 1);
  const std::size_t colon1 = range.find(':');
  const std::size_t colon2 = colon1 == std::string::npos ? colon1 : range.find(':', colon1 + 1);
  if (colon2 == std::string::npos || !parseNumber(range.substr(0, colon1), axis.start) ||
      !parseNumber(range.substr(colon1 + 1, colon2 - colon1 - 1), axis.stop) ||
      !parseWhole(range.substr(colon2 + 1), 1, kMaxVariants, axis.count)) {
    throw refuse(kSweepForm);
  }
  const BodyConfig* body = findBody(config, axis.body);
  if (!body) throw refuse("a body of the config, as BODY.KEY");
  std::visit(
      [&](const auto& config) {
        using Config = std::decay_t<decltype(config)>;
        if (!sweepableKey<Config>(axis.key)) {
          throw ConfigError(axis.body, axis.key, "'" + spec + "'",
                            "a numeric key of this body: " + sweepableNames<Config>());
        }
      },
      body->config);
  return axis;
}

Shard parseShard(const std::string& spec) {
  const std::size_t slash = spec.find('/');
  Shard shard;
  if (slash == std::string::npos || !parseWhole(spec.substr(slash + 1), 1, kMaxVariants, shard.count) ||
      !parseWhole(spec.substr(0, slash), 1, shard.count, shard.index)) {
    throw ConfigError(kCommandLine, "--shard", "'" + spec + "'", "i/n with whole numbers 1 <= i <= n");
  }
  return shard;
}

std::pair<std::int64_t, std::int64_t> shardRange(std::int64_t total, const Shard& shard) {
  // total and count are at most 1e9, so the products fit in 64 bits.
  return {total * (shard.index - 1) / shard.count, total * shard.index / shard.count};
}

std::int64_t variantCount(const std::vector<SweepAxis>& axes) {
  std::set<std::string> swept;
  std::int64_t total = 1;
  for (const auto& axis : axes) {
    if (!swept.insert(axis.column()).second) {
      throw ConfigError(kCommandLine, "--sweep", "'" + axis.column() + "'", "each key swept once");
    }
    if (axis.count > kMaxVariants / total) {
      throw ConfigError(kCommandLine, "--sweep", "(" + axis.column() + " and the others)",
                        "at most " + formatNumber(static_cast<double>(kMaxVariants)) + " variants in all");
    }
    total *= axis.count;
  }
  return total;
}

std::vector<double> variantValues(const std::vector<SweepAxis>& axes, std::int64_t variant) {
  std::vector<double> values(axes.size());
  for (std::size_t a = axes.size(); a-- > 0;) {
    values[a] = axes[a].value(variant % axes[a].count);
    variant /= axes[a].count;
  }
  return values;
}

WorldConfig variantConfig(const WorldConfig& base, const std::vector<SweepAxis>& axes, std::int64_t variant) {
  WorldConfig config = base;
  const std::vector<double> values = variantValues(axes, variant);
  for (std::size_t a = 0; a < axes.size(); ++a) {
    for (auto& body : config.bodies) {
      if (body.name == axes[a].body) setKey(body, axes[a].key, values[a]);
    }
  }
  validate(config);
  return config;
}

std::string sweepHeader(const WorldConfig& base, const std::vector<SweepAxis>& axes) {
  std::string header = "variant";
  for (const auto& axis : axes) header += "," + axis.column();
  header += ",t";
  for (const auto& body : base.bodies) header += bodyColumns(body);
  return header;
}

std::string sweepRow(const WorldConfig& base, std::int64_t variant, const std::vector<double>& values,
                     const OfflineSummary& summary) {
  std::string row = std::to_string(variant);
  for (const double value : values) row += "," + formatNumber(value);
  row += "," + formatNumber(summary.end_time);
  for (std::size_t b = 0; b < base.bodies.size(); ++b) {
    const std::string& state = summary.final_rows[b];
    row += state.substr(state.find(','));  // the CSV row without its t
    row += "," + formatNumber(summary.energy[b].final - summary.energy[b].initial);
    const SweepColumn column = sweepColumnOf(base.bodies[b]);
    row +=
        "," + (column.of == SweepColumn::Of::Bounces ? std::to_string(summary.bounces[b])
                                                     : firstEvent(summary, summary.bodies[b], column.event));
  }
  return row;
}

std::string sweepFileName(const Shard& shard) {
  if (shard.count == 1) return "sweep.csv";
  std::string index = std::to_string(shard.index);
  index.insert(0, std::to_string(shard.count).size() - index.size(), '0');
  return "sweep." + index + "-of-" + std::to_string(shard.count) + ".csv";
}

SweepResult runSweep(const WorldConfig& base, const SweepOptions& sweep, const OfflineOptions& options) {
  SweepResult result;
  result.total = variantCount(sweep.axes);
  std::tie(result.first, result.end) = shardRange(result.total, sweep.shard);
  validate(options, base);
  for (std::int64_t v = result.first; v < result.end; ++v)
    variantConfig(base, sweep.axes, v);  // refuse early

  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  result.jobs = static_cast<unsigned>(std::max<std::int64_t>(
      1, std::min<std::int64_t>(sweep.jobs ? sweep.jobs : cores, result.end - result.first)));
  std::filesystem::create_directories(options.out_dir);
  result.path = (std::filesystem::path(options.out_dir) / sweepFileName(sweep.shard)).string();
  const std::string temp_path = result.path + ".tmp";
  std::ofstream out(temp_path);
  if (!out) throw std::runtime_error("cannot write '" + temp_path + "'");
  try {
    if (sweep.shard.index == 1) out << sweepHeader(base, sweep.axes) << '\n';
    ProgressBar progress(result.end - result.first, "variants");
    std::atomic<std::int64_t> done{result.first};
    for (std::int64_t first = result.first; first < result.end; first += kBlock) {
      const std::int64_t end = std::min(result.end, first + kBlock);
      std::vector<std::string> rows(static_cast<std::size_t>(end - first));
      runBlock(base, sweep, options, first, end, result.jobs, rows, done, progress, result.first);
      for (const auto& row : rows) out << row << '\n';
    }
    progress.finish();
    out.close();
    if (out.fail()) throw std::runtime_error("cannot write '" + temp_path + "'");
  } catch (...) {
    out.close();
    std::error_code ignored;
    std::filesystem::remove(temp_path, ignored);
    throw;
  }
  std::filesystem::rename(temp_path, result.path);
  return result;
}

}  // namespace rigid_body_sim
