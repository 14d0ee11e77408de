// `simulate` end to end, as a user runs it: command line, CSV header and sample times, exit codes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "rigid_body_sim/core/world.h"
#include "rigid_body_sim/io/config_loader.h"
#include "rigid_body_sim/io/csv_writer.h"
#include "test_util.h"

namespace fs = std::filesystem;
using namespace rigid_body_sim;
using namespace rigid_body_sim::test;

namespace {

using SimulateTest = FolderTest;

std::vector<std::string> fileLines(const fs::path& path) { return lines(slurp(path)); }

}  // namespace

TEST_F(SimulateTest, WritesOneCsvPerBodyWithTheContractsColumns) {
  const auto run = simulate(config("demo.yaml") + " --duration 2 --out-dir " + dir_.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(fileLines(dir_ / "rod.csv").at(0), "t,x,y,theta,vx,vy,omega,energy");
  for (const char* roller : {"sphere", "cylinder", "ring", "bowler"}) {
    const auto rows = fileLines(dir_ / (std::string(roller) + ".csv"));
    ASSERT_FALSE(rows.empty()) << roller;
    EXPECT_EQ(rows.at(0), "t,x,v,theta,omega,mode,friction,normal,energy");
  }
  EXPECT_FALSE(fs::exists(dir_ / "rod.csv.tmp"));
}

TEST_F(SimulateTest, SamplesAtWholeMultiplesOfTheSamplePeriodFromZero) {
  const auto run =
      simulate(config("rod.yaml") + " --duration 1.5 --sample-rate 20 --out-dir " + dir_.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto rows = fileLines(dir_ / "rod.csv");
  ASSERT_EQ(rows.size(), 1u + 31u);  // header, t = 0, 0.05, ..., 1.5
  for (std::size_t j = 1; j < rows.size(); ++j) {
    const double t = std::stod(rows[j].substr(0, rows[j].find(',')));
    EXPECT_EQ(t, static_cast<double>((j - 1) * 50) / 1000.0) << rows[j];
  }
}

TEST_F(SimulateTest, CsvRowsAreTheCoresStatesAtThoseTimes) {
  const auto run =
      simulate(config("demo.yaml") + " --duration 3 --sample-rate 100 --out-dir " + dir_.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  World world(loadWorldConfigFile(config("demo.yaml")));
  std::vector<std::vector<std::string>> files;
  for (const auto& body : world.bodies()) files.push_back(fileLines(dir_ / (body.name + ".csv")));
  for (int j = 0; j <= 300; ++j) {
    for (std::size_t b = 0; b < world.bodies().size(); ++b) {
      ASSERT_EQ(files[b].at(1 + j), csvRow(world.time(), world.bodies()[b])) << world.bodies()[b].name;
    }
    for (int s = 0; s < 10; ++s) world.step();
  }
}

// The bowler (demo.yaml) is launched sliding with spin, u0 = v0 + omega0 R > 0: kinetic friction brings the
// slip speed to 0 at t* = u0 / (g cos(phi) mu_d (1 + 1/c) - g sin(phi)), where it starts rolling. The summary
// prints that instant (to 6 digits).
TEST_F(SimulateTest, PrintsASummaryWithTheSlipToRollTime) {
  const auto run = simulate(config("demo.yaml") + " --duration 2 --out-dir " + dir_.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const WorldConfig demo = loadWorldConfigFile(config("demo.yaml"));
  const auto& bowler = std::get<RollerConfig>(demo.bodies.at(*World(demo).indexOf("bowler")).config);
  const RollerParams& p = bowler.params;
  const double u0 = bowler.initial.v0 + bowler.initial.omega0 * p.radius;
  const double g = demo.gravity;
  const double t_roll = u0 / (g * std::cos(p.incline_angle) * p.mu_d * (1.0 + 1.0 / p.inertia_factor) -
                              g * std::sin(p.incline_angle));
  const std::size_t section = run.out.find("bowler:");
  ASSERT_NE(section, std::string::npos) << run.out;
  const std::size_t at = run.out.find("slip_to_roll: t = ", section) + std::string("slip_to_roll: ").size();
  const std::size_t end = run.out.find(" s\n", at);
  ASSERT_TRUE(at != std::string::npos && end != std::string::npos && at < end) << run.out.substr(section);
  EXPECT_NEAR(std::stod(run.out.substr(at + 4, end - at - 4)), t_roll, 5e-6 * t_roll)
      << run.out.substr(section);
}

TEST_F(SimulateTest, SaysOncePerRodWhenAutoSplitsItsSteps) {
  const fs::path stiff = write("stiff.yaml",
                               "bodies: {soft: {type: rod}, stiff: {type: rod, k: 5000}, "
                               "fixed: {type: rod, k: 5000, substeps: 1}}\n");
  const auto run = simulate(stiff.string() + " --duration 1 --out-dir " + (dir_ / "out").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_NE(run.err.find("simulate: note: body 'stiff': substeps auto splits each step into 2 sub-steps"),
            std::string::npos)
      << run.err;
  EXPECT_EQ(simulate(config("rod.yaml") + " --duration 1 --out-dir " + (dir_ / "text").string()).err, "");
}

// A body whose file cannot be opened: the .tmp files of the bodies before it are removed too.
TEST_F(SimulateTest, CsvWriterThatCannotOpenAFileLeavesNoTemporaryFile) {
  const World world(loadWorldConfigFile(config("demo.yaml")));
  ASSERT_GT(world.bodies().size(), 2u);
  const fs::path out = dir_ / "out";
  fs::create_directories(out /
                         (world.bodies()[2].name + ".csv.tmp"));  // a folder: cannot be opened as a file
  EXPECT_THROW(CsvWriter(out.string(), world.bodies()), std::runtime_error);
  for (const auto& entry : fs::directory_iterator(out)) {
    EXPECT_TRUE(fs::is_directory(entry.path())) << entry.path() << " left behind";
  }
}

// simulate never writes a non-finite number: a body that became one (no path through valid input is known;
// the writer catches any) stops the run with one line, and no CSV file stays.
TEST_F(SimulateTest, CsvWriterRefusesANonFiniteStateAndLeavesNoFile) {
  World world(loadWorldConfigFile(config("rod.yaml")));
  auto& rod = std::get<Rod>(world.bodies().at(0).model);
  RodMotion broken = rod.state();
  broken.omega = std::nan("");
  const fs::path out = dir_ / "out";
  {
    CsvWriter csv(out.string(), world.bodies());
    csv.write(world.time(), world.bodies());
    rod.restore(broken);
    try {
      csv.write(world.time(), world.bodies());
      ADD_FAILURE() << "a non-finite state was written";
    } catch (const std::runtime_error& error) {
      EXPECT_EQ(std::string(error.what()),
                "body 'rod' became non-finite by t = 0 s (omega = nan): stopped, no file written");
    }
  }
  EXPECT_TRUE(fs::is_empty(out)) << "a file stayed";
}

TEST_F(SimulateTest, WritesABag) {
  const auto run = simulate(config("rod.yaml") + " --duration 1 --out-dir " + dir_.string() + " --bag " +
                            (dir_ / "run.bag").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(fs::exists(dir_ / "run.bag"));
  EXPECT_FALSE(fs::exists(dir_ / "run.bag.active"));
  // What the node publishes in 1 s of rod.yaml: a state and a /tf per publishing period (50 Hz) and one at
  // t = 0, the markers at marker_rate (10 Hz, the default) and at t = 0, the latched ones once.
  const fs::path info_dir = dir_ / "info";
  fs::create_directories(info_dir);
  const auto info = runTool("rosbag info --yaml --key=topics " + (dir_ / "run.bag").string(), info_dir);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  std::map<std::string, int> counts;
  for (const auto& topic : YAML::Load(info.out))
    counts[topic["topic"].as<std::string>()] = topic["messages"].as<int>();
  // And every event of the core's run of that second (its contacts with the floor), in the bag and in
  // events.csv.
  World world(loadWorldConfigFile(config("rod.yaml")));
  std::size_t events = 0;
  while (world.stepCount() < 1000) {
    world.step();
    events += world.takeEvents().size();
  }
  ASSERT_GT(events, 0u);
  const std::map<std::string, int> expected = {{"/sim/rod/state", 51},
                                               {"/tf", 51},
                                               {"/sim/markers", 11},
                                               {"/tf_static", 1},
                                               {"/sim/scene", 1},
                                               {"/sim/commands", 1},
                                               {"/sim/events", static_cast<int>(events)}};
  EXPECT_EQ(counts, expected);
  std::ifstream events_csv(dir_ / "events.csv");
  std::size_t rows = 0;
  for (std::string line; std::getline(events_csv, line);) ++rows;
  EXPECT_EQ(rows, events + 1) << "a header and a row an event";
}

// The text's own scheme (substeps: 1) at a stiff k, and a fixed count: the config on /sim/commands carries
// every key, so `simulate --replay` of the bag is the run it recorded, CSV for CSV, byte for byte.
TEST_F(SimulateTest, ReplayOfItsBagIsTheSameRunForEveryKey) {
  const fs::path config_file = write(
      "stiff.yaml",
      "bodies:\n"
      "  book: {type: rod, k: 50000, substeps: 1, integrator: euler_cromer, theta0: 0.4}\n"
      "  split: {type: rod, k: 20000, substeps: 3, integrator: velocity_verlet, floor_length: 30, vy0: 1}\n"
      "  hoop: {type: roller, shape: custom, inertia_factor: 0.8, incline_angle: 0.6, v0: 1.5, omega0: 4}\n");
  const fs::path run = dir_ / "run";
  const fs::path replay = dir_ / "replay";
  fs::create_directories(run);
  fs::create_directories(replay);
  const auto recorded = simulate(config_file.string() + " --duration 5 --out-dir " + run.string() +
                                 " --bag " + (dir_ / "run.bag").string());
  ASSERT_EQ(recorded.exit_code, 0) << recorded.err;
  const auto replayed =
      simulate("--replay " + (dir_ / "run.bag").string() + " --duration 5 --out-dir " + replay.string());
  ASSERT_EQ(replayed.exit_code, 0) << replayed.err;
  for (const char* body : {"book", "split", "hoop"}) {
    const std::string csv = std::string(body) + ".csv";
    ASSERT_TRUE(fs::exists(run / csv)) << csv;
    EXPECT_EQ(slurp(run / csv), slurp(replay / csv)) << csv;
  }
}

// Without --duration a replay runs to the bag's last state, whatever the bodies' types: for every type, a
// world of that type alone, recorded for 2 s, replays for 2 s, CSV for CSV.
TEST_F(SimulateTest, ReplayRunsToTheLastStateOfEveryBodyType) {
  for (const auto& type : bodyTypeNames()) {
    SCOPED_TRACE(type);
    const fs::path config_file = write(type + ".yaml", "bodies:\n  only: {type: " + type + "}\n");
    const fs::path run = dir_ / (type + "_run"), replay = dir_ / (type + "_replay");
    const fs::path bag = dir_ / (type + ".bag");
    fs::create_directories(run);
    fs::create_directories(replay);
    const auto recorded =
        simulate(config_file.string() + " --duration 2 --out-dir " + run.string() + " --bag " + bag.string());
    ASSERT_EQ(recorded.exit_code, 0) << recorded.err;
    const auto replayed = simulate("--replay " + bag.string() + " --out-dir " + replay.string());
    ASSERT_EQ(replayed.exit_code, 0) << replayed.err;
    ASSERT_TRUE(fs::exists(replay / "only.csv"));
    EXPECT_EQ(slurp(run / "only.csv"), slurp(replay / "only.csv"));
  }
}

TEST_F(SimulateTest, BadInputExitsNonZeroWithOneLineAndNoOutput) {
  const fs::path bad = write("bad.yaml", "bodies: {rod: {type: rod, k: -1}}\n");
  const auto run = simulate(bad.string() + " --out-dir " + (dir_ / "out").string());
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("body 'rod', key 'k': value -1"), std::string::npos) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_FALSE(fs::exists(dir_ / "out" / "rod.csv"));
}

// --check: what a script runs before a launch (roslaunch exits 0 whatever its node does).
TEST_F(SimulateTest, CheckSaysWhetherTheNodeWouldAcceptAConfigAndRunsNothing) {
  const auto good = simulate(config("demo.yaml") + " --check --out-dir " + (dir_ / "out").string());
  EXPECT_EQ(good.exit_code, 0) << good.err;
  EXPECT_EQ(good.out, config("demo.yaml") + ": accepted, bodies: rod sphere cylinder ring bowler\n");
  EXPECT_EQ(good.err, "");
  const fs::path bad = write("bad.yaml", "bodies: {rod: {type: rod, k: -1}}\n");
  const auto refused = simulate(bad.string() + " --check --out-dir " + (dir_ / "out").string());
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_EQ(refused.out, "");
  EXPECT_EQ(refused.err, "simulate: " + refusalOf([&] { loadWorldConfigFile(bad.string()); }) + "\n");
  EXPECT_FALSE(fs::exists(dir_ / "out")) << "--check writes nothing";
  const auto mixed = simulate(config("demo.yaml") + " --check --sweep rod.k=1:2:2");
  EXPECT_EQ(mixed.exit_code, 1);
  EXPECT_NE(mixed.err.find("key '--check'"), std::string::npos) << mixed.err;
}

TEST_F(SimulateTest, NoArgumentsExitOneWithOneLineThatPointsToHelp) {
  const auto run = simulate("");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_EQ(run.err, "simulate: CONFIG is required (simulate --help lists the options)\n");
  const auto help = simulate("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("Usage: simulate"), std::string::npos) << help.out;
}

TEST_F(SimulateTest, BadOptionsAreRefused) {
  EXPECT_NE(simulate(config("rod.yaml") + " --sample-rate 300 --out-dir " + dir_.string()).exit_code, 0);
  EXPECT_NE(simulate(config("rod.yaml") + " --duration -1 --out-dir " + dir_.string()).exit_code, 0);
  EXPECT_NE(simulate(config("rod.yaml") + " --duration abc").exit_code, 0);
  EXPECT_NE(simulate("/nonexistent.yaml").exit_code, 0);
  EXPECT_NE(simulate("").exit_code, 0);
  const auto run = simulate(config("rod.yaml") + " --sample-rate 300 --out-dir " + dir_.string());
  EXPECT_NE(run.err.find("--sample-rate"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir_ / "rod.csv"));
}

TEST_F(SimulateTest, SummaryCountsTheRodsBouncesAsTheCoreDoes) {
  const auto run = simulate(config("rod.yaml") + " --out-dir " + dir_.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // Contacts begun, counted straight from the core's end heights at every step of the 10 s.
  World world(loadWorldConfigFile(config("rod.yaml")));
  const Rod& rod = std::get<Rod>(world.bodies().at(0).model);
  int bounces = 0;
  bool touching = false;
  for (int s = 0; s < 10000; ++s) {
    world.step();
    const bool now = rod.endHeightA() < 0.0 || rod.endHeightB() < 0.0;
    bounces += now && !touching;
    touching = now;
  }
  ASSERT_GT(bounces, 1);
  EXPECT_NE(run.out.find("  " + std::to_string(bounces) + " bounces\n"), std::string::npos) << run.out;
}
