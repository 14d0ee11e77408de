// Every key of every body type through every round trip the package makes, generated from the body types'
// descriptions (core/parameters.h), so that a key added to a description is tested here without a line
// more: random valid values, text keys included, through
//   a config file -> load -> the writer (~get_config, the command log's config) -> load,
//   a reconfigure request and back (from the defaults and from another random body),
//   a command's payload (the command log) and a bag of commands -> replay,
// each bit for bit; and a run started from the written config equal, state for state, to the run it was
// taken from.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <random>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "rigid_body_sim/core/description.h"
#include "rigid_body_sim/core/state_fields.h"
#include "rigid_body_sim/core/world.h"
#include "rigid_body_sim/io/config_loader.h"
#include "rigid_body_sim/io/config_writer.h"
#include "rigid_body_sim/io/csv_writer.h"
#include "rigid_body_sim/ros/bag_recorder.h"
#include "rigid_body_sim/ros/command_log.h"
#include "rigid_body_sim/ros/reconfigure.h"
#include "rigid_body_sim/run/replay.h"
#include "test_util.h"

using namespace rigid_body_sim;
using namespace rigid_body_sim::test;

namespace {

constexpr double kRate = 1000.0;
constexpr int kDrawsPerKey = 40;  // tries for a value that the config with the others takes

// A value of a number key in its range, within a box a run can afford: log-uniform over [1e-3, 1e5] for a
// positive key (stiff and soft floors alike), uniform over the range cut to [-100, 100] for the others; the
// bounds themselves now and then. Random doubles have all 17 digits: a round trip must keep every bit.
double drawNumber(const Range& range, std::mt19937_64& random) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double lo = std::max(range.min, -100.0);
  const double hi = std::min(range.max, 100.0);
  const double pick = unit(random);
  if (pick < 0.05 && !range.min_open) return range.min;
  if (pick < 0.1 && !range.max_open && range.max <= 100.0) return range.max;
  if (range.min == 0.0 && range.min_open) {
    const double a = std::log(1e-3);
    const double b = std::log(std::min(range.max, 1e5));
    return std::exp(a + unit(random) * (b - a));
  }
  return lo + unit(random) * (hi - lo);
}

// A text a key takes: one of an enum's names, `auto` or a count, a seed.
template <class Config>
std::string drawText(const BodyKey<Config>& key, std::mt19937_64& random) {
  if (key.choices) {
    const auto names = key.choices();
    return names[std::uniform_int_distribution<std::size_t>(0, names.size() - 1)(random)];
  }
  if (key.counts) {
    const auto count = std::uniform_int_distribution<int>(0, 50)(random);
    return count == 0 ? "auto" : std::to_string(count);
  }
  return std::to_string(std::uniform_int_distribution<std::uint64_t>(0, (1ull << 53) - 1)(random));
}

template <class Config>
bool takes(const Config& config) {
  try {
    validate("body", config);
    validateSubsteps("body", config, kRate);
    return true;
  } catch (const ConfigError&) {
    return false;
  }
}

// A random valid config of a body type with every written key drawn (one that relations refuse keeps its
// last valid value: a roller's inertia_factor stays its shape's unless the shape is custom); returns the
// text of its keys as a config file's flow map. `seeded` (a rod): theta0 drawn and given as a seed.
template <class Config>
std::string drawBody(std::mt19937_64& random, bool seeded, Config& config) {
  config = Config{};
  for (const auto& key : bodyType<Config>().keys) {
    if (!key.written()) continue;  // seed: drawn below, as theta0's other form
    for (int draw = 0; draw < kDrawsPerKey; ++draw) {
      Config next = config;
      if (key.isNumber()) {
        key.field(next) = drawNumber(key.range, random);
      } else {
        setKeyText("body", key, drawText(key, random), next);
      }
      if (takes(next)) {
        config = next;
        break;
      }
    }
  }
  std::string seed;
  if (seeded) {
    const auto& key = *findKey(bodyType<Config>().keys, "seed");
    seed = drawText(key, random);
    setKeyText("body", key, seed, config);
  }
  std::string text = "{type: " + std::string(bodyType<Config>().type);
  for (const auto& key : bodyType<Config>().keys) {
    if (seeded && std::string(key.name) == "theta0") continue;
    if (key.written()) text += ", " + std::string(key.name) + ": " + key.text(config);
  }
  return text + (seeded ? ", seed: " + seed : "") + "}";
}

// A random world: `count` bodies of each type (the first rod with a seed), every key drawn.
WorldConfig drawWorld(std::mt19937_64& random, int count, std::string* text) {
  *text = "rate: " + formatNumber(kRate) + "\npublish_rate: 50\ngravity: " +
          formatNumber(1.0 + 19.0 * std::uniform_real_distribution<double>(0, 1)(random)) +
          "\nrace: " + (random() % 2 ? "true" : "false") + "\nbodies:\n";
  BodyTypes::forEach([&](auto type) {
    using Type = decltype(type);
    for (int i = 0; i < count; ++i) {
      typename Type::Config config;
      // The first of a type with a seed key gives it instead of theta0.
      const bool seeded = i == 0 && findKey(Type::description().keys, "seed") != nullptr;
      *text += "  " + std::string(Type::kName) + std::to_string(i) + ": " + drawBody(random, seeded, config) +
               "\n";
    }
  });
  return parseWorldConfigText(*text, "drawn");
}

template <class Config>
void expectSameKeys(const Config& a, const Config& b, const std::string& what) {
  for (const auto& key : bodyType<Config>().keys) {
    if (key.written()) EXPECT_EQ(key.text(a), key.text(b)) << what << ": key " << key.name;
  }
}

void expectSameWorld(const WorldConfig& a, const WorldConfig& b, const std::string& what) {
  EXPECT_EQ(toYaml(a), toYaml(b)) << what;
  ASSERT_EQ(a.bodies.size(), b.bodies.size()) << what;
  EXPECT_EQ(formatNumber(a.gravity), formatNumber(b.gravity)) << what;
  EXPECT_EQ(a.race, b.race) << what;
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    ASSERT_EQ(a.bodies[i].name, b.bodies[i].name);
    ASSERT_EQ(typeName(a.bodies[i]), typeName(b.bodies[i]));
    std::visit(
        [&](const auto& x) {
          const auto& y = std::get<std::decay_t<decltype(x)>>(b.bodies[i].config);
          expectSameKeys(x, y, what + ", body " + a.bodies[i].name);
          EXPECT_EQ(formatNumber(x.params.gravity), formatNumber(y.params.gravity));
        },
        a.bodies[i].config);
  }
}

// The loader reads every drawn value: each key of the text is the config's, bit for bit.
void expectReadAsWritten(const WorldConfig& config, const std::string& text) {
  for (const auto& body : config.bodies) {
    const std::size_t line = text.find("  " + body.name + ": {");
    ASSERT_NE(line, std::string::npos);
    const std::string map = text.substr(line, text.find('\n', line) - line);
    std::visit(
        [&](const auto& c) {
          for (const auto& key : bodyType<std::decay_t<decltype(c)>>().keys) {
            const std::string entry = ", " + std::string(key.name) + ": ";
            const std::size_t at = map.find(entry);
            if (!key.written() || at == std::string::npos) continue;
            const std::size_t start = at + entry.size();
            const std::string value = map.substr(start, map.find_first_of(",}", start) - start);
            EXPECT_EQ(key.text(c), value) << body.name << "." << key.name;
          }
        },
        body.config);
  }
}

// The CSV files of a folder, by name.
std::map<std::string, std::string> csvFiles(const std::filesystem::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() == ".csv") files[entry.path().filename()] = slurp(entry.path());
  }
  return files;
}

class KeyRoundTrips : public FolderTest {
 protected:
  std::mt19937_64 random_{20261126};
};

}  // namespace

// Every key a description lists is a number with a field and range, or a text with a reader; every state
// field that set_state takes has the key whose range it takes.
template <class Type>
void expectWellDescribed() {
  using Config = typename Type::Config;
  for (const auto& key : bodyType<Config>().keys) {
    SCOPED_TRACE(key.name);
    EXPECT_TRUE(key.isNumber() || key.read) << "neither a number nor a text";
    EXPECT_FALSE(key.allowed().empty());
    EXPECT_NE(std::string(key.meaning), "");
  }
  for (const auto& field : stateFieldNames<Type>(true))
    EXPECT_NE(keyOfStateField<Config>(field), nullptr) << field;
}

TEST(BodyTypes, EveryKeyIsReadableAndEveryStateFieldHasItsKey) {
  BodyTypes::forEach([](auto type) {
    SCOPED_TRACE(decltype(type)::kName);
    expectWellDescribed<decltype(type)>();
  });
}

// The panel's spawn list: every registered type, each entry a body the loader reads as a body of it (an
// entry named for a choice: that choice of one of its text keys), no name twice; the rollers by the text's
// four shapes.
TEST(BodyTypes, EverySpawnChoiceIsABodyOfItsType) {
  std::set<std::string> labels, types;
  for (const SpawnChoice& choice : spawnChoices()) {
    SCOPED_TRACE(choice.body);
    EXPECT_TRUE(labels.insert(choice.label).second) << choice.label << " twice";
    const BodyConfig body = parseBodyText("spawned", choice.body);
    types.insert(typeName(body));
    if (choice.label == typeName(body)) continue;
    std::visit(
        [&](const auto& config) {
          bool named = false;
          for (const auto& key : bodyType<std::decay_t<decltype(config)>>().keys)
            named = named || (!key.isNumber() && key.text(config) == choice.label);
          EXPECT_TRUE(named) << choice.label << " is none of its text keys' values";
        },
        body.config);
  }
  EXPECT_EQ(types, std::set<std::string>(bodyTypeNames().begin(), bodyTypeNames().end()));
  for (const char* shape : {"sphere", "cylinder", "ring", "spherical_shell"})
    EXPECT_EQ(labels.count(shape), 1u);
}

// config text -> load -> writer (what ~get_config returns, the command log's config) -> load.
TEST_F(KeyRoundTrips, ConfigFileWriterAndLoaderKeepEveryKey) {
  for (int world = 0; world < 200; ++world) {
    std::string text;
    const WorldConfig loaded = drawWorld(random_, 2, &text);
    SCOPED_TRACE(text);
    expectReadAsWritten(loaded, text);
    const WorldConfig again = parseWorldConfigText(toYaml(loaded), "written");
    expectSameWorld(loaded, again, "written and read again");
    EXPECT_EQ(toYaml(again), toYaml(loaded));
    if (HasFailure()) return;
  }
}

// A reconfigure request of a random body and back: from the defaults, and from another random body.
template <class Config>
void expectReconfigureRoundTrip(std::mt19937_64& random) {
  Config config;
  Config other;
  drawBody(random, false, config);
  drawBody(random, false, other);
  expectSameKeys(config, fromReconfigure("body", toReconfigure(config), Config{}), "from the defaults");
  expectSameKeys(config, fromReconfigure("body", toReconfigure(config), other), "from another body");
}

TEST_F(KeyRoundTrips, ReconfigureRequestKeepsEveryKey) {
  for (int draw = 0; draw < 300 && !HasFailure(); ++draw) {
    BodyTypes::forEach(
        [&](auto type) { expectReconfigureRoundTrip<typename decltype(type)::Config>(random_); });
  }
}

// Every command's payload, as the command log carries it, gives back the command.
TEST_F(KeyRoundTrips, CommandPayloadsKeepEveryKey) {
  for (int draw = 0; draw < 100; ++draw) {
    std::string text;
    WorldCommand config;
    config.kind = WorldCommand::Kind::Config;
    config.world = drawWorld(random_, 1, &text);
    const WorldCommand back = commandFromText("config", 0, "", payloadYaml(config));
    expectSameWorld(config.world, back.world, "config command");
    for (const auto& body : config.world.bodies) {
      for (const auto kind : {WorldCommand::Kind::Reconfigure, WorldCommand::Kind::Spawn}) {
        WorldCommand command;
        command.kind = kind;
        command.body = body.name;
        command.config = body;
        const WorldCommand parsed = commandFromText(toString(kind), 7, body.name, payloadYaml(command));
        WorldConfig a;
        WorldConfig b;
        a.bodies = {command.config};
        b.bodies = {parsed.config};
        std::visit([&](auto& c) { c.params.gravity = config.world.gravity; }, b.bodies[0].config);
        expectSameWorld(a, b, toString(kind) + " of " + body.name);
      }
    }
    if (HasFailure()) return;
  }
}

// A run started from the written config is the run it was taken from, state for state: every key that
// reaches the physics is written (a rod's substeps at a stiff k among them).
TEST_F(KeyRoundTrips, RunFromTheWrittenConfigIsTheSameRun) {
  for (int draw = 0; draw < 20; ++draw) {
    std::string text;
    const WorldConfig config = drawWorld(random_, 2, &text);
    World original(config);
    World restored(parseWorldConfigText(toYaml(config), "written"));
    for (int step = 0; step < 500; ++step) {
      original.step();
      restored.step();
      for (std::size_t i = 0; i < original.bodies().size(); ++i) {
        ASSERT_EQ(csvRow(original.time(), original.bodies()[i]),
                  csvRow(restored.time(), restored.bodies()[i]))
            << text << "step " << step;
      }
    }
  }
}

// A recorded run (its commands in a bag: the config, then a reconfigure of every body to another random
// config of its type, a spawn) replayed from the bag equals the run of those commands, sample for sample.
TEST_F(KeyRoundTrips, ReplayFromTheCommandLogIsTheSameRun) {
  for (int draw = 0; draw < 10; ++draw) {
    std::string text;
    std::vector<WorldCommand> commands(1);
    commands[0].kind = WorldCommand::Kind::Config;
    commands[0].world = drawWorld(random_, 1, &text);
    std::int64_t step = 100;
    std::string drawn;
    for (const auto& body : drawWorld(random_, 1, &drawn).bodies) {
      WorldCommand reconfigure;
      reconfigure.kind = WorldCommand::Kind::Reconfigure;
      reconfigure.body = body.name;
      reconfigure.config = body;
      reconfigure.step = step;
      step += 100;
      commands.push_back(reconfigure);
    }
    WorldCommand spawn = commands.back();
    spawn.kind = WorldCommand::Kind::Spawn;
    spawn.body = spawn.config.name = "spawned";
    spawn.step = step;
    commands.push_back(spawn);

    OfflineOptions options;
    options.duration = 1.0;
    options.out_dir = (dir_ / "run").string();
    options.bag = (dir_ / "run.bag").string();
    std::filesystem::create_directories(options.out_dir);
    replayRun(commands, options, bagOpener());
    const RecordedRun recorded = readRecordedRun(options.bag);
    ASSERT_EQ(recorded.commands.size(), commands.size());
    OfflineOptions again = options;
    again.out_dir = (dir_ / "replay").string();
    again.bag.clear();
    std::filesystem::create_directories(again.out_dir);
    replayRun(recorded.commands, again);
    EXPECT_EQ(csvFiles(options.out_dir), csvFiles(again.out_dir)) << text << drawn;
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    if (HasFailure()) return;
  }
}
