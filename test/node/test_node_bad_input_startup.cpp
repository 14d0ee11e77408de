// sim_node at start-up on bad parameters: every row of test/bad_input/configs.yaml that the parameter
// server can hold, and the node's own options (test/bad_input/node_startup.yaml). Each row is loaded into
// a private namespace of its own and sim_node is started on it: it must exit 1 and print exactly one line
// on stderr, which holds the loader's message for those parameters and the row's fragments.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "node_test_util.h"
#include "rigid_body_sim/ros/params.h"
#include "test_util.h"

namespace fs = std::filesystem;
using namespace rigid_body_sim;
using test::nonEmptyLines;
using test::PrivateDir;
using test::slurp;

namespace {

struct Row {
  std::string what;
  std::string params;  // YAML map; empty: load nothing
  std::vector<std::string> expect;
};

// The rows of configs.yaml the parameter server can hold, then the node's own.
std::vector<Row> table() {
  std::vector<Row> rows;
  const std::string dir = RBS_BAD_INPUT_DIR;
  for (const auto& entry : YAML::LoadFile(dir + "/configs.yaml")) {
    if (!entry["node"].as<bool>(true) || entry["file"]) continue;
    rows.push_back({entry["what"].as<std::string>(), entry["config"].as<std::string>(),
                    entry["expect"].as<std::vector<std::string>>()});
  }
  for (const auto& entry : YAML::LoadFile(dir + "/node_startup.yaml")) {
    rows.push_back({entry["what"].as<std::string>(), entry["params"].as<std::string>(""),
                    entry["expect"].as<std::vector<std::string>>()});
  }
  return rows;
}

// YAML -> parameter-server value, typed as rosparam types a YAML file: quoted text stays a string.
XmlRpc::XmlRpcValue toXmlRpc(const YAML::Node& node) {
  XmlRpc::XmlRpcValue value;
  if (node.IsMap()) {
    value.begin();  // an empty struct, even when the map is empty
    for (const auto& entry : node) value[entry.first.as<std::string>()] = toXmlRpc(entry.second);
    return value;
  }
  if (node.IsSequence()) {
    value.setSize(static_cast<int>(node.size()));
    for (std::size_t i = 0; i < node.size(); ++i) value[static_cast<int>(i)] = toXmlRpc(node[i]);
    return value;
  }
  const std::string text = node.Scalar();
  if (node.Tag() == "!") return XmlRpc::XmlRpcValue(text);
  if (text == "true" || text == "false") return XmlRpc::XmlRpcValue(text == "true");
  char* end = nullptr;
  const long long integer = std::strtoll(text.c_str(), &end, 10);
  if (!text.empty() && *end == '\0' && integer >= INT32_MIN && integer <= INT32_MAX) {
    return XmlRpc::XmlRpcValue(static_cast<int>(integer));
  }
  try {
    return XmlRpc::XmlRpcValue(node.as<double>());
  } catch (const YAML::Exception&) {
    return XmlRpc::XmlRpcValue(text);
  }
}

// What the loader says about the parameters as the server gives them back (the node's own view, its
// options left out); "" when the config part is fine.
std::string loaderMessage(const std::string& ns) {
  XmlRpc::XmlRpcValue params;
  if (!ros::param::get(ns, params)) return "";
  try {
    parseNodeConfig(params);
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "";
}

// The sim_node built beside this test; RBS_SIM_NODE_EXE in the environment overrides it (to try a fix).
std::string simNodeExe() {
  const char* exe = std::getenv("RBS_SIM_NODE_EXE");
  return exe ? exe : RBS_SIM_NODE_EXE;
}

}  // namespace

TEST(SimNodeBadInputStartup, EveryRowIsRefusedWithTheLoadersLine) {
  const PrivateDir private_dir("bad_input_startup");
  const fs::path& dir = private_dir.path();
  int index = 0;
  int refused = 0;
  for (const Row& row : table()) {
    SCOPED_TRACE(row.what);
    const std::string name = "bad" + std::to_string(index++);
    const std::string ns = "/" + name;
    if (!row.params.empty()) ros::param::set(ns, toXmlRpc(YAML::Load(row.params)));
    const fs::path err = dir / (name + ".err");
    // `timeout`: a node that accepted the input would run for ever; 124 then tells it apart.
    const std::string command = "timeout 30 " + simNodeExe() + " __name:=" + name + " >" +
                                (dir / (name + ".out")).string() + " 2>" + err.string();
    const int status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 1) << "(124: the node accepted the input and ran)";
    const auto lines = nonEmptyLines(slurp(err));
    ASSERT_EQ(lines.size(), 1u) << "stderr:\n" << slurp(err) << "stdout:\n" << slurp(dir / (name + ".out"));
    for (const auto& fragment : row.expect) {
      EXPECT_NE(lines[0].find(fragment), std::string::npos)
          << "missing '" << fragment << "' in: " << lines[0];
    }
    const std::string message = loaderMessage(ns);
    if (!message.empty()) {
      EXPECT_NE(lines[0].find("refused config: " + message), std::string::npos) << lines[0];
    }
    refused += WEXITSTATUS(status) == 1;
  }
  std::printf("sim_node refused %d bad inputs at start-up\n", refused);
  EXPECT_GE(index, 30);
}

RBS_ROSTEST_MAIN("test_node_bad_input_startup")
