// The docs' tables of configuration keys against the core: each body type's table is generated from its
// description and must stand in docs/configuration.md as it is, and the world's numbers stand in their table
// with the core's default and range, so that the one place where a user reads them cannot drift from the
// code. Likewise the docs' lists of state fields (CSV columns, what ~set_state sets) against
// core/state_fields.h, and DESIGN.md's example config against the core's defaults.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "rigid_body_sim/core/parameters.h"
#include "rigid_body_sim/core/state_fields.h"
#include "test_util.h"

using namespace rigid_body_sim;
using namespace rigid_body_sim::test;

namespace {

struct Cell {
  std::string default_value;
  std::string allowed;
};

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(' ');
  const auto last = text.find_last_not_of(' ');
  return first == std::string::npos ? "" : text.substr(first, last - first + 1);
}

fs::path packageFile(const std::string& path) { return fs::path(RBS_README).parent_path() / path; }

const char* const kConfigurationDoc = "docs/configuration.md";

// The rows of the first table after the line that starts with `heading` in `file`: key -> (default, allowed).
std::map<std::string, Cell> tableAfter(const std::string& file, const std::string& heading) {
  std::map<std::string, Cell> rows;
  std::istringstream doc(slurp(packageFile(file)));
  std::string line;
  while (std::getline(doc, line) && line.rfind(heading, 0) != 0) {
  }
  while (std::getline(doc, line) && line.rfind("|", 0) != 0) {
  }
  for (; !line.empty() && line[0] == '|'; std::getline(doc, line)) {
    const auto cells = split(line, '|');  // "", key, default, allowed, ""
    if (cells.size() < 4 || cells[1].find('`') == std::string::npos) continue;
    const std::string key = trimmed(cells[1]);
    rows[key.substr(1, key.size() - 2)] = {trimmed(cells[2]), cells[3]};
  }
  return rows;
}

// "(0, 1e+12]" of "a finite number in (0, 1e+12]".
std::string interval(const Range& range) {
  const std::string text = range.describe();
  return text.substr(text.find_first_of("[("));
}

// A body type's table of keys, as the docs must show it: every key of its description in order, with its
// default, what it allows (a number's interval and unit) and what it is.
template <class Config>
std::string keyTable() {
  const Config defaults;
  std::string table = "| key | default | allowed | what |\n|---|---|---|---|\n";
  for (const auto& key : bodyType<Config>().keys) {
    const std::string unit = *key.unit ? std::string(" ") + key.unit : "";
    table += "| `" + std::string(key.name) + "` | " + (key.written() ? key.text(defaults) : "(none)") +
             " | " + (key.isNumber() ? interval(key.range) + unit : key.allowed()) + " | " + key.meaning +
             " |\n";
  }
  return table;
}

template <class Config>
void expectKeyTableDocumented() {
  const std::string table = keyTable<Config>();
  EXPECT_NE(slurp(packageFile(kConfigurationDoc)).find(table), std::string::npos)
      << kConfigurationDoc << " lacks the table of " << bodyType<Config>().type << " keys; it is:\n"
      << table;
}

}  // namespace

TEST(Docs, EveryBodyTypesKeysAreTheDescriptions) {
  BodyTypes::forEach([](auto type) { expectKeyTableDocumented<typename decltype(type)::Config>(); });
}

TEST(Docs, WorldNumbersAreTheCores) {
  const auto rows = tableAfter(kConfigurationDoc, "## The world");
  const WorldConfig defaults;
  const std::map<std::string, std::pair<double, Range>> world = {
      {"rate", {defaults.rate, rateRange()}},
      {"publish_rate", {defaults.publish_rate, publishRateRange()}},
      {"gravity", {defaults.gravity, gravityRange()}}};
  for (const auto& [name, expected] : world) {
    SCOPED_TRACE(name);
    ASSERT_EQ(rows.count(name), 1u);
    EXPECT_EQ(rows.at(name).default_value, formatNumber(expected.first));
    EXPECT_NE(rows.at(name).allowed.find(interval(expected.second)), std::string::npos);
  }
  EXPECT_EQ(rows.at("world_frame").default_value, "`" + defaults.world_frame + "`");
  for (const auto& key : worldKeys()) EXPECT_EQ(rows.count(key), 1u) << key;
}

namespace {

std::string joined(const std::vector<std::string>& names, const std::string& separator) {
  std::string out;
  for (const auto& name : names) out += (out.empty() ? "" : separator) + name;
  return out;
}

}  // namespace

// "  - rod: `t,x,...`": the CSV header simulate writes, t and the table's fields.
TEST(Docs, CsvColumnsAreTheCoreFields) {
  for (const char* file : {"README.md", "docs/DESIGN.md"}) {
    BodyTypes::forEach([&](auto type) {
      using Type = decltype(type);
      const std::string start = std::string("  - ") + Type::kName + ": `";
      const std::string expected = start + "t," + joined(stateFieldNames<Type>(), ",") + "`";
      int found = 0;
      for (const auto& line : lines(slurp(packageFile(file)))) {
        if (line.rfind(start, 0) != 0) continue;
        ++found;
        EXPECT_EQ(line.substr(0, expected.size()), expected) << file;
      }
      EXPECT_EQ(found, 1) << file << ": " << expected;
    });
  }
}

TEST(Docs, SetStateFieldsAreTheSettableOnes) {
  const std::string rod = joined(stateFieldNames<RodType>(true), ", ");
  const std::string roller = joined(stateFieldNames<RollerType>(true), ", ");
  const std::string commands = slurp(packageFile("docs/commands.md"));
  EXPECT_NE(commands.find("(rod `" + rod + "`; roller `" + roller + "`)"), std::string::npos);
  const std::string srv = slurp(packageFile("srv/SetState.srv"));
  EXPECT_NE(srv.find("rod " + rod + "; roller " + roller + "\n"), std::string::npos);
}

// DESIGN.md's example config gives every key it lists the core's default.
TEST(Docs, DesignsExampleConfigIsTheDefaults) {
  const WorldConfig world;
  const RodConfig rod;
  const RollerConfig roller;
  const std::map<std::string, double> world_numbers = {
      {"rate", world.rate}, {"publish_rate", world.publish_rate}, {"gravity", world.gravity}};
  std::string type;  // of the body whose keys follow
  int checked = 0;
  const auto design = lines(slurp(packageFile("docs/DESIGN.md")));
  auto line = std::find(design.begin(), design.end(),
                        "### Configuration (YAML file = the node's private parameters, "
                        "loadable with `rosparam load`)");
  ASSERT_NE(line, design.end());
  for (line += 2; line != design.end() && *line != "```"; ++line) {
    const std::string text = trimmed(line->substr(0, line->find('#')));
    const std::size_t colon = text.find(':');
    const std::string key = text.substr(0, colon);
    const std::string value = trimmed(text.substr(colon + 1));
    if (value.empty() || key == "shape" || key == "integrator") {
      if (key == "shape") EXPECT_EQ(value, toString(roller.params.shape));
      if (key == "integrator") EXPECT_EQ(value, toString(rod.params.integrator));
      continue;
    }
    SCOPED_TRACE(*line);
    ++checked;
    if (key == "type") {
      type = value;
    } else if (key == "world_frame") {
      EXPECT_EQ(value, world.world_frame);
    } else if (key == "race") {
      EXPECT_EQ(value, world.race ? "true" : "false");
    } else if (line->rfind("  ", 0) != 0) {
      ASSERT_EQ(world_numbers.count(key), 1u);
      EXPECT_EQ(std::stod(value), world_numbers.at(key));
    } else if (type == "rod") {
      const auto* numeric = findKey(bodyType<RodConfig>().keys, key);
      ASSERT_TRUE(numeric && numeric->isNumber());
      EXPECT_EQ(std::stod(value), numeric->number(rod));
    } else {
      const auto* numeric = findKey(bodyType<RollerConfig>().keys, key);
      ASSERT_TRUE(numeric && numeric->isNumber());
      EXPECT_EQ(std::stod(value), numeric->number(roller));
    }
  }
  EXPECT_GT(checked, 20);
}

// DESIGN.md's "Where to add a key, a topic, a service, a body type" against the tree: every file it names
// exists (a header or source by its path under include/rigid_body_sim/ or src/, others from the package's
// root), and every type it names (a class, a struct or an alias) is declared in a header.
TEST(Docs, WhereToAddNamesWhatIsThere) {
  const std::string design = slurp(packageFile("docs/DESIGN.md"));
  const std::size_t start = design.find("## Where to add a key, a topic, a service, a body type");
  ASSERT_NE(start, std::string::npos);
  const std::string section = design.substr(start, design.find("\n## ", start + 1) - start);
  std::string headers;
  for (const auto& entry : fs::recursive_directory_iterator(packageFile("include/rigid_body_sim"))) {
    if (entry.path().extension() == ".h") headers += slurp(entry.path());
  }
  int files = 0;
  int classes = 0;
  const std::vector<std::string> quoted = split(section, '`');
  for (std::size_t i = 1; i < quoted.size(); i += 2) {  // the odd pieces are between backquotes
    const std::string& name = quoted[i];
    const std::string ext = fs::path(name).extension().string();
    if (ext == ".h" || ext == ".cpp" || ext == ".cfg" || ext == ".md" || ext == ".py") {
      ++files;
      const bool there = fs::exists(packageFile(name)) || fs::exists(packageFile("src/" + name)) ||
                         fs::exists(packageFile("include/rigid_body_sim/" + name));
      EXPECT_TRUE(there) << name;
    } else if (!name.empty() && std::isupper(static_cast<unsigned char>(name[0])) &&
               name.find_first_of(" (/.") == std::string::npos) {
      ++classes;
      const std::string type = name.substr(name.rfind(':') == std::string::npos ? 0 : name.rfind(':') + 1);
      const bool declared = headers.find("class " + type) != std::string::npos ||
                            headers.find("struct " + type) != std::string::npos ||
                            headers.find("using " + type + " =") != std::string::npos;
      EXPECT_TRUE(declared) << name << " is declared in no header";
    }
  }
  EXPECT_GT(files, 8);
  EXPECT_GT(classes, 3);
}
