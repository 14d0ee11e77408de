// Parameter sweeps: variant generation, sharding, refusals, and `simulate --sweep` end to end against
// single runs of the same variants and the core stepped directly.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "rigid_body_sim/core/world.h"
#include "rigid_body_sim/io/config_loader.h"
#include "rigid_body_sim/run/sweep.h"
#include "test_util.h"

namespace fs = std::filesystem;
using namespace rigid_body_sim;
using namespace rigid_body_sim::test;

namespace {

// A CSV file as rows of column name -> text.
std::vector<std::map<std::string, std::string>> readCsv(const fs::path& path) {
  const auto lines = split(slurp(path), '\n');
  std::vector<std::map<std::string, std::string>> rows;
  if (lines.empty()) return rows;
  const auto header = split(lines[0], ',');
  for (std::size_t i = 1; i < lines.size(); ++i) {
    if (lines[i].empty()) continue;
    const auto cells = split(lines[i], ',');
    std::map<std::string, std::string> row;
    for (std::size_t c = 0; c < header.size(); ++c) row[header[c]] = c < cells.size() ? cells[c] : "?";
    rows.push_back(row);
  }
  return rows;
}

using SweepTest = FolderTest;

TEST(SweepAxis, ValuesAreEvenlySpacedWithBothEndsIncluded) {
  const WorldConfig base = loadWorldConfigFile(config("demo.yaml"));
  const SweepAxis axis = parseSweepAxis("sphere.mu_s=0.1:0.3:5", base);
  EXPECT_EQ(axis.body, "sphere");
  EXPECT_EQ(axis.key, "mu_s");
  ASSERT_EQ(axis.count, 5);
  EXPECT_EQ(axis.value(0), 0.1);
  EXPECT_EQ(axis.value(4), 0.3);
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(axis.value(i), 0.1 + 0.05 * i, 1e-15);
  EXPECT_EQ(parseSweepAxis("rod.theta0=2:9:1", base).value(0), 2.0);
  EXPECT_EQ(parseSweepAxis("rod.k=-3e2:1e3:2", base).value(0), -300.0);  // parsed; refused when run
}

TEST(SweepAxis, VariantsAreTheCartesianProductOnceEach) {
  const WorldConfig base = loadWorldConfigFile(config("demo.yaml"));
  const std::vector<SweepAxis> axes = {parseSweepAxis("rod.theta0=0:3:4", base),
                                       parseSweepAxis("sphere.mu_s=0.2:0.4:3", base)};
  ASSERT_EQ(variantCount(axes), 12);
  std::set<std::vector<double>> seen;
  for (std::int64_t v = 0; v < 12; ++v) seen.insert(variantValues(axes, v));
  EXPECT_EQ(seen.size(), 12u);
  for (double theta : {0.0, 1.0, 2.0, 3.0}) {
    for (double mu : {0.2, axes[1].value(1), 0.4})
      EXPECT_EQ(seen.count({theta, mu}), 1u) << theta << " " << mu;
  }
  // The last axis varies fastest, and the variant's config carries its values into the world.
  EXPECT_EQ(variantValues(axes, 5), (std::vector<double>{1.0, 0.4}));
  World world(variantConfig(base, axes, 5));
  EXPECT_EQ(std::get<Rod>(world.find("rod")->model).state().theta, 1.0);
  EXPECT_EQ(std::get<Roller>(world.find("sphere")->model).params().mu_s, 0.4);
  EXPECT_EQ(std::get<Roller>(world.find("cylinder")->model).params().mu_s, 0.2);  // the others untouched
}

TEST(SweepAxis, BadSpecificationsAreRefusedWithOneLine) {
  const WorldConfig base = loadWorldConfigFile(config("demo.yaml"));
  for (const char* spec :
       {"rod.theta0", "rod.theta0=0:1", "rod.theta0=0:1:0", "rod.theta0=0:1:2.5", "rod.theta0=a:1:3",
        "rod.theta0=0:1:3:4", "theta0=0:1:3", "rod.theta0=0:nan:3", "rod.theta0= 0:1:3", "nobody.k=1:2:3",
        "rod.mu_s=0:1:3", "sphere.k=1:2:3", "rod.integrator=0:1:2", "sphere.shape=0:1:2"}) {
    try {
      parseSweepAxis(spec, base);
      ADD_FAILURE() << spec << " was accepted";
    } catch (const ConfigError& error) {
      const std::string line = error.what();
      EXPECT_EQ(line.find('\n'), std::string::npos) << line;
      EXPECT_NE(line.find(spec), std::string::npos) << line;
      EXPECT_NE(line.find("allowed"), std::string::npos) << line;
    }
  }
  EXPECT_THROW(variantCount({parseSweepAxis("rod.k=1:2:3", base), parseSweepAxis("rod.k=5:6:3", base)}),
               ConfigError);
  EXPECT_THROW(
      variantCount({parseSweepAxis("rod.k=1:2:100000", base), parseSweepAxis("rod.mass=1:2:100000", base)}),
      ConfigError);
}

TEST(SweepAxis, SubstepsAreSweptAsWholeNumbers) {
  const WorldConfig base = loadWorldConfigFile(config("demo.yaml"));
  const std::vector<SweepAxis> axes = {parseSweepAxis("rod.substeps=1:4:4", base)};
  for (std::int64_t v = 0; v < 4; ++v) {
    const WorldConfig variant = variantConfig(base, axes, v);
    EXPECT_EQ(std::get<RodConfig>(variant.bodies[0].config).params.substeps, v + 1);
  }
  const std::vector<SweepAxis> halves = {parseSweepAxis("rod.substeps=1:2:3", base)};  // 1, 1.5, 2
  try {
    variantConfig(base, halves, 1);
    ADD_FAILURE() << "substeps 1.5 was accepted";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("'substeps': value 1.5"), std::string::npos) << error.what();
  }
  EXPECT_THROW(parseSweepAxis("sphere.substeps=1:2:2", base), ConfigError);
}

TEST(SweepShard, ShardsCoverEveryVariantExactlyOnceInOrder) {
  for (std::int64_t total : {1, 2, 7, 10, 1000, 1001}) {
    for (std::int64_t n = 1; n <= 13; ++n) {
      std::int64_t expected_first = 0;
      for (std::int64_t i = 1; i <= n; ++i) {
        const auto [first, end] = shardRange(total, Shard{i, n});
        EXPECT_EQ(first, expected_first) << total << " " << i << "/" << n;
        EXPECT_LE(first, end);
        EXPECT_LE(end - first, total / n + 1);  // balanced
        expected_first = end;
      }
      EXPECT_EQ(expected_first, total) << total << " " << n;
    }
  }
  EXPECT_EQ(parseShard("2/5").index, 2);
  EXPECT_EQ(parseShard("2/5").count, 5);
  for (const char* bad : {"0/3", "4/3", "1", "1/0", "a/b", "1.5/3", "-1/3", "/3"}) {
    EXPECT_THROW(parseShard(bad), ConfigError) << bad;
  }
  EXPECT_EQ(sweepFileName(Shard{1, 1}), "sweep.csv");
  EXPECT_EQ(sweepFileName(Shard{3, 12}), "sweep.03-of-12.csv");
}

// A rod's contacts counted straight from the core: steps at which an end goes below the floor while
// neither was below it at the step before.
int bouncesOf(const WorldConfig& config, const std::string& body, std::int64_t steps) {
  World world(config);
  const auto touching = [&] {
    const Rod& rod = std::get<Rod>(world.find(body)->model);
    return rod.endHeightA() < 0.0 || rod.endHeightB() < 0.0;
  };
  int bounces = 0;
  bool before = touching();
  for (std::int64_t s = 0; s < steps; ++s) {
    world.step();
    const bool now = touching();
    bounces += now && !before;
    before = now;
  }
  return bounces;
}

TEST_F(SweepTest, ARowEqualsASingleRunOfThatVariant) {
  const auto run =
      simulate(config("demo.yaml") + " --duration 3 --sweep rod.theta0=0:3:3 --sweep bowler.omega0=5:15:2" +
               " --jobs 2 --out-dir " + dir_.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto rows = readCsv(dir_ / "sweep.csv");
  ASSERT_EQ(rows.size(), 6u);
  const WorldConfig base = loadWorldConfigFile(config("demo.yaml"));
  for (std::size_t v = 0; v < rows.size(); ++v) {
    const auto& row = rows[v];
    EXPECT_EQ(row.at("variant"), std::to_string(v));
    // The variant as a config file of its own, run by simulate alone.
    YAML::Node yaml = YAML::LoadFile(config("demo.yaml"));
    yaml["bodies"]["rod"]["theta0"] = std::stod(row.at("rod.theta0"));
    yaml["bodies"]["bowler"]["omega0"] = std::stod(row.at("bowler.omega0"));
    const fs::path variant_dir = dir_ / ("variant" + std::to_string(v));
    fs::create_directories(variant_dir);
    std::ofstream(variant_dir / "variant.yaml") << yaml;
    const auto single =
        simulate((variant_dir / "variant.yaml").string() + " --duration 3 --out-dir " + variant_dir.string());
    ASSERT_EQ(single.exit_code, 0) << single.err;
    for (const auto& body : base.bodies) {
      const auto samples = readCsv(variant_dir / (body.name + ".csv"));
      ASSERT_FALSE(samples.empty());
      EXPECT_EQ(row.at("t"), samples.back().at("t"));
      for (const auto& [column, text] : samples.back()) {
        if (column != "t") EXPECT_EQ(row.at(body.name + "." + column), text) << body.name << "." << column;
      }
      const double drift = std::stod(samples.back().at("energy")) - std::stod(samples.front().at("energy"));
      EXPECT_NEAR(std::stod(row.at(body.name + ".energy_drift")), drift, 1e-12 * (1.0 + std::abs(drift)));
    }
    WorldConfig variant = base;
    YAML::Node parsed = YAML::LoadFile((variant_dir / "variant.yaml").string());
    variant = parseWorldConfig(parsed);
    EXPECT_EQ(std::stoi(row.at("rod.bounces")), bouncesOf(variant, "rod", 3000));
    EXPECT_GT(std::stoi(row.at("rod.bounces")), 0);
    // The bowler launched sliding: its slip-to-roll instant is the core's event.
    World world(variant);
    std::string first_roll;
    for (int s = 0; s < 3000 && first_roll.empty(); ++s) {
      world.step();
      for (const auto& event : world.takeEvents()) {
        if (event.body == "bowler" && event.kind == "slip_to_roll") first_roll = formatNumber(event.t);
      }
    }
    ASSERT_FALSE(first_roll.empty());
    EXPECT_EQ(row.at("bowler.slip_to_roll"), first_roll);
    EXPECT_EQ(row.at("sphere.slip_to_roll"), "");  // released rolling: it never had to stop slipping
  }
}

TEST_F(SweepTest, ResultsDoNotDependOnTheNumberOfThreads) {
  const std::string sweep =
      config("demo.yaml") + " --duration 1 --sweep rod.theta0=0:6:7 --sweep sphere.mu_s=0.15:0.6:3";
  const auto single = simulate(sweep + " --jobs 1 --out-dir " + (dir_ / "one").string());
  ASSERT_EQ(single.exit_code, 0) << single.err;
  EXPECT_NE(single.out.find(" on 1 thread in "), std::string::npos) << single.out;
  const auto three = simulate(sweep + " --jobs 3 --out-dir " + (dir_ / "three").string());
  ASSERT_EQ(three.exit_code, 0) << three.err;
  EXPECT_NE(three.out.find("on 3 threads"), std::string::npos) << three.out;
  const std::string one = slurp(dir_ / "one" / "sweep.csv");
  EXPECT_EQ(std::count(one.begin(), one.end(), '\n'), 1 + 21);
  EXPECT_EQ(one, slurp(dir_ / "three" / "sweep.csv"));
}

TEST_F(SweepTest, ShardsConcatenateToTheWholeSweep) {
  const std::string sweep =
      config("rod.yaml") + " --duration 0.5 --sweep rod.theta0=0:6.283:10 --out-dir " + dir_.string();
  ASSERT_EQ(simulate(sweep).exit_code, 0);
  std::string joined;
  for (int i = 1; i <= 4; ++i) {
    const auto shard = simulate(sweep + " --shard " + std::to_string(i) + "/4");
    ASSERT_EQ(shard.exit_code, 0) << shard.err;
    joined += slurp(dir_ / ("sweep." + std::to_string(i) + "-of-4.csv"));
  }
  EXPECT_EQ(joined, slurp(dir_ / "sweep.csv"));
}

TEST_F(SweepTest, AnEmptyShardSaysSo) {
  // 2 variants in 4 shards: shard 1 holds [0, 0).
  const auto run = simulate(
      config("rod.yaml") + " --duration 0.1 --sweep rod.theta0=0:1:2 --shard 1/4 --out-dir " + dir_.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out.rfind("swept none of 2 variants: this shard is empty -> ", 0), 0u) << run.out;
  EXPECT_EQ(run.out.find("-1"), std::string::npos) << run.out;
}

TEST_F(SweepTest, ABadSweptValueIsRefusedWithOneLineAndNoOutput) {
  const auto run = simulate(config("rod.yaml") + " --sweep rod.k=-1000:1000:3 --out-dir " + dir_.string());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("body 'rod', key 'k': value -1000 is not allowed (allowed:"), std::string::npos)
      << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_FALSE(fs::exists(dir_ / "sweep.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "sweep.csv.tmp"));
  // A relation between keys is checked per variant too: mu_d above a swept mu_s.
  const auto relation =
      simulate(config("incline.yaml") + " --sweep sphere.mu_s=0:0.3:4 --out-dir " + dir_.string());
  EXPECT_EQ(relation.exit_code, 1);
  EXPECT_NE(relation.err.find("body 'sphere', key 'mu_d'"), std::string::npos) << relation.err;
  EXPECT_FALSE(fs::exists(dir_ / "sweep.csv"));
}

TEST_F(SweepTest, OptionsThatNeedASweepOrExcludeOneAreRefused) {
  for (const std::string args : {" --jobs 2", " --shard 1/2", " --sweep rod.k=1:2:2 --bag x.bag",
                                 " --sweep rod.k=1:2:2 --jobs -1", " --sweep rod.k=1:2:2 --shard 3/2"}) {
    const auto run = simulate(config("rod.yaml") + args + " --out-dir " + dir_.string());
    EXPECT_EQ(run.exit_code, 1) << args;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << args << ": " << run.err;
  }
  EXPECT_FALSE(fs::exists(dir_ / "sweep.csv"));
}

TEST_F(SweepTest, NoProgressBarWhenStderrIsNotATerminal) {
  const auto run =
      simulate(config("rod.yaml") + " --sweep rod.theta0=0:1:4000 --duration 10 --out-dir " + dir_.string());
  ASSERT_EQ(run.exit_code, 0);
  EXPECT_EQ(run.err, "");
}

}  // namespace
