// Helpers shared by the compiled tests: files and their lines, the one line of a refusal, and a fresh
// folder per test in which a tool runs as a user runs it. No ROS header.
#pragma once

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "rigid_body_sim/core/parameters.h"

namespace rigid_body_sim::test {

namespace fs = std::filesystem;

// A rod and a ball launched sliding on a long gentle slope (it slips, then rolls): a small world of both
// kinds.
inline WorldConfig rodAndBall() {
  WorldConfig config;
  RollerConfig ball;
  ball.params.incline_angle = 0.1;
  ball.params.incline_length = 1e6;
  ball.initial.v0 = 3.0;
  config.bodies.push_back({"rod", RodConfig{}});
  config.bodies.push_back({"ball", ball});
  return config;
}

inline std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// Every part, a trailing separator ending with an empty one (an empty last cell of a CSV row).
inline std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::istringstream in(text);
  for (std::string part; std::getline(in, part, separator);) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.push_back("");
  return parts;
}

// Every line; a final newline ends the last one.
inline std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> result;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) result.push_back(line);
  return result;
}

inline std::vector<std::string> nonEmptyLines(const std::string& text) {
  std::vector<std::string> result;
  for (auto& line : lines(text)) {
    if (!line.empty()) result.push_back(std::move(line));
  }
  return result;
}

// The one line of the ConfigError that `action` throws, or "" when it throws none.
template <class Action>
std::string refusalOf(Action&& action) {
  try {
    action();
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "";
}

// A config file shipped with the package.
inline std::string config(const std::string& name) { return std::string(RBS_CONFIG_DIR) + "/" + name; }

struct ToolRun {
  int exit_code;  // -1: did not exit normally (a crash?)
  std::string out;
  std::string err;
};

// Runs a shell command line with stdout and stderr into files of `dir`.
inline ToolRun runTool(const std::string& command, const fs::path& dir) {
  const std::string line = command + " >" + (dir / "stdout").string() + " 2>" + (dir / "stderr").string();
  const int status = std::system(line.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir / "stdout"), slurp(dir / "stderr")};
}

// A fixture with a fresh, empty folder named after the test.
class FolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / (std::string(test->test_suite_name()) + "_" + test->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }

#ifdef RBS_SIMULATE_EXE  // a test that runs simulate (TOOLS simulate in test/CMakeLists.txt)
  ToolRun simulate(const std::string& args) const {
    return runTool(std::string(RBS_SIMULATE_EXE) + " " + args, dir_);
  }
#endif

  // Writes a file into the folder.
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }

  fs::path dir_;
};

}  // namespace rigid_body_sim::test
