// `simulate` on every row of test/bad_input/configs.yaml: exit code 1, exactly one line on stderr that
// names what was refused (for a config error: the loader's own message, word for word), nothing on the
// way to the out dir (not even a half-written or temporary file).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "rigid_body_sim/io/config_loader.h"
#include "test_util.h"

namespace fs = std::filesystem;
using namespace rigid_body_sim;
using namespace rigid_body_sim::test;

namespace {

struct Row {
  std::string what;
  std::string config;  // YAML text; unused when file is set
  std::string file;    // "", "missing" or "directory"
  std::string args;
  std::vector<std::string> expect;
};

std::vector<Row> table() {
  std::vector<Row> rows;
  for (const auto& entry : YAML::LoadFile(std::string(RBS_BAD_INPUT_DIR) + "/configs.yaml")) {
    Row row{entry["what"].as<std::string>(), entry["config"].as<std::string>(""),
            entry["file"].as<std::string>(""), entry["args"].as<std::string>(""),
            entry["expect"].as<std::vector<std::string>>()};
    rows.push_back(row);
  }
  return rows;
}

// What the loader says about the same text (the line simulate must print after "simulate: "), or ""
// when the loader accepts it (a command-line error).
std::string loaderMessage(const std::string& text, const std::string& source) {
  return refusalOf([&] { parseWorldConfigText(text, source); });
}

}  // namespace

TEST(BadInputSimulate, TableHasEnoughDistinctRows) {
  const auto rows = table();
  std::set<std::string> names;
  for (const auto& row : rows) names.insert(row.what);
  EXPECT_EQ(names.size(), rows.size()) << "duplicate row names";
  EXPECT_GE(rows.size(), 30u);
}

// docs/reliability.md counts the rows of the tables: its figures are these files' (rows the node runs: those
// of configs.yaml without `node: false`, and every row of node_startup.yaml).
TEST(BadInputSimulate, TheDocsCountTheRowsThereAre) {
  const std::string dir = RBS_BAD_INPUT_DIR;
  std::size_t node_rows = YAML::LoadFile(dir + "/node_startup.yaml").size();
  const YAML::Node configs = YAML::LoadFile(dir + "/configs.yaml");
  for (const auto& row : configs) node_rows += row["node"].as<bool>(true) ? 1 : 0;
  const std::string docs = slurp(fs::path(RBS_README).parent_path() / "docs" / "reliability.md");
  const std::string simulate_count =
      "`test/bad_input/configs.yaml` (" + std::to_string(configs.size()) + " rows:";
  const std::string node_count = "`bad_input_startup.test` (" + std::to_string(node_rows) + " rows ";
  EXPECT_NE(docs.find(simulate_count), std::string::npos)
      << "docs/reliability.md should say " << simulate_count;
  EXPECT_NE(docs.find(node_count), std::string::npos) << "docs/reliability.md should say " << node_count;
}

TEST(BadInputSimulate, EveryRowIsRefusedWithOneLineAndNoOutput) {
  const PrivateDir private_root("bad_input_simulate");
  const fs::path& root = private_root.path();
  int index = 0;
  for (const Row& row : table()) {
    SCOPED_TRACE(row.what);
    const fs::path dir = root / std::to_string(index++);
    const fs::path out = dir / "out";
    fs::create_directories(out);
    fs::path config = dir / "config.yaml";
    if (row.file == "missing") {
      config = dir / "no_such_config.yaml";
    } else if (row.file == "directory") {
      config = dir;
    } else {
      std::ofstream(config) << row.config;
    }
    // A bag too, so that nothing is written in any mode; but --check takes no --bag and would refuse that.
    const bool check = row.args.find("--check") != std::string::npos;
    const std::string bag = check ? "" : " --bag " + (out / "run.bag").string();
    const ToolRun run = runTool(std::string(RBS_SIMULATE_EXE) + " " + config.string() + " " + row.args +
                                    " --out-dir " + out.string() + bag,
                                dir);
    ASSERT_NE(run.exit_code, -1) << "simulate did not exit normally (a crash?)";
    EXPECT_EQ(run.exit_code, 1);
    const auto err = lines(run.err);
    ASSERT_EQ(err.size(), 1u) << "stderr:\n" << run.err;
    for (const auto& fragment : row.expect) {
      EXPECT_NE(err[0].find(fragment), std::string::npos) << "missing '" << fragment << "' in: " << err[0];
    }
    if (row.file.empty()) {
      const std::string message = loaderMessage(row.config, config.string());
      if (!message.empty()) EXPECT_EQ(err[0], "simulate: " + message);
    }
    EXPECT_TRUE(fs::is_empty(out)) << "something was written to the out dir";
  }
}

// A valid but slow config runs, with the core's note on its sub-steps and its warning on stderr
// (--duration 0: no step is taken).
using SlowConfig = FolderTest;
TEST_F(SlowConfig, RunsWithOneNoteAndOneWarning) {
  const std::string yaml = "bodies: {rod: {type: rod, k: 1e9, mass: 1e-6}}";
  const ToolRun run =
      simulate(write("stiff.yaml", yaml).string() + " --duration 0 --out-dir " + dir_.string());
  EXPECT_EQ(run.exit_code, 0);
  const WorldConfig config = parseWorldConfigText(yaml, "stiff");
  const auto notes = autoSubstepNotes(config);
  const auto warnings = slowRunWarnings(config);
  ASSERT_EQ(notes.size(), 1u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(lines(run.err),
            (std::vector<std::string>{"simulate: note: " + notes[0], "simulate: warning: " + warnings[0]}));
  EXPECT_TRUE(fs::exists(dir_ / "rod.csv"));
}
