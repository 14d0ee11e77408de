// Helpers shared by the compiled tests: files and their lines, the one line of a refusal, and a folder
// of each run's own in which a tool runs as a user runs it. No ROS header.
#pragma once

#include <gtest/gtest.h>

#include <stdlib.h>  // mkdtemp
#include <sys/wait.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
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

// A new, empty folder of this run's own (mkdtemp), removed with the object. Never a fixed path: the same
// test runs at the same time in other working copies on the machine, and a shared folder lets one run
// remove or truncate what another is writing.
class PrivateDir {
 public:
  explicit PrivateDir(const std::string& prefix) {
    std::string pattern = (fs::path(::testing::TempDir()) / (prefix + ".XXXXXX")).string();
    if (!mkdtemp(pattern.data()))
      throw std::runtime_error("mkdtemp " + pattern + ": " + std::strerror(errno));
    path_ = pattern;
  }
  ~PrivateDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  PrivateDir(const PrivateDir&) = delete;
  PrivateDir& operator=(const PrivateDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// A fixture with a private, empty folder named after the test.
class FolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    folder_ = std::make_unique<PrivateDir>(std::string(test->test_suite_name()) + "_" + test->name());
    dir_ = folder_->path();
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

  std::unique_ptr<PrivateDir> folder_;
  fs::path dir_;
};

}  // namespace rigid_body_sim::test
