// The YAML writer: what it writes loads back to the same values bit for bit, a body's map parses as in a
// config file, and a command's payload gives back the command.
#include <gtest/gtest.h>

#include <cstring>
#include <type_traits>

#include "rigid_body_sim/core/world.h"
#include "rigid_body_sim/io/config_loader.h"
#include "rigid_body_sim/io/config_writer.h"

using namespace rigid_body_sim;

namespace {

std::string configPath(const std::string& name) { return std::string(RBS_CONFIG_DIR) + "/" + name; }

// Numbers that print long: a round trip through a decimal text with fewer digits would change them.
WorldConfig awkward() {
  WorldConfig config = loadWorldConfigFile(configPath("demo.yaml"));
  config.gravity = 9.80665;
  for (auto& body : config.bodies) {
    std::visit([&](auto& c) { c.params.gravity = config.gravity; }, body.config);
    if (auto* rod = std::get_if<RodConfig>(&body.config)) {
      rod->initial.theta = theta0FromSeed(42);
      rod->params.k = 1234.5678901234567;
      rod->initial.vx = -0.0;
    }
    if (auto* roller = std::get_if<RollerConfig>(&body.config)) roller->params.incline_angle = 0.1 + 0.2;
  }
  return config;
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every key the body's type writes, numbers bit for bit (test_key_round_trips does the same for random
// values of every key).
template <class Config>
void expectSameKeys(const Config& a, const Config& b) {
  for (const auto& key : bodyType<Config>().keys) {
    if (key.isNumber()) {
      EXPECT_TRUE(sameBits(key.number(a), key.number(b)))
          << key.name << ": " << key.number(a) << " vs " << key.number(b);
    } else if (key.written()) {
      EXPECT_EQ(key.text(a), key.text(b)) << key.name;
    }
  }
}

void expectSameBody(const BodyConfig& a, const BodyConfig& b) {
  ASSERT_EQ(a.name, b.name);
  ASSERT_EQ(typeName(a), typeName(b));
  std::visit([&](const auto& x) { expectSameKeys(x, std::get<std::decay_t<decltype(x)>>(b.config)); },
             a.config);
}

void expectSameConfig(const WorldConfig& a, const WorldConfig& b) {
  EXPECT_TRUE(sameBits(a.rate, b.rate));
  EXPECT_TRUE(sameBits(a.publish_rate, b.publish_rate));
  EXPECT_TRUE(sameBits(a.gravity, b.gravity));
  EXPECT_EQ(a.world_frame, b.world_frame);
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    expectSameBody(a.bodies[i], b.bodies[i]);
    // A body's gravity is the world's (a body's own map has none).
    std::visit([&](const auto& body) { EXPECT_TRUE(sameBits(body.params.gravity, a.gravity)); },
               b.bodies[i].config);
  }
}

}  // namespace

TEST(ConfigWriter, WhatItWritesLoadsAsAConfigBitForBit) {
  for (const auto& file : {"demo.yaml", "rod.yaml", "incline.yaml"}) {
    const WorldConfig config = loadWorldConfigFile(configPath(file));
    const std::string text = toYaml(config);
    const WorldConfig back = parseWorldConfigText(text, "written");
    expectSameConfig(config, back);
    EXPECT_EQ(toYaml(back), text) << file;
  }
  const WorldConfig config = awkward();
  expectSameConfig(config, parseWorldConfigText(toYaml(config), "written"));
}

TEST(ConfigWriter, ARunningWorldsConfigLoadsAsItRuns) {
  World world(awkward());
  WorldCommand spawn;
  spawn.kind = WorldCommand::Kind::Spawn;
  spawn.body = "hoop";
  spawn.config = parseBodyText("hoop", "{type: roller, shape: ring, incline_angle: 0.4}");
  world.apply(spawn);
  expectSameConfig(world.config(), parseWorldConfigText(toYaml(world.config()), "get_config"));
}

TEST(ConfigWriter, ABodysMapParsesAsInAConfigFile) {
  const std::string body = "{type: rod, k: 2000, seed: 7, integrator: rk4}";
  const WorldConfig file = parseWorldConfigText("bodies:\n  stick: " + body + "\n", "inline");
  expectSameBody(parseBodyText("stick", body), file.bodies[0]);
  EXPECT_THROW(parseBodyText("stick", "{type: rod, colour: red}"), ConfigError);
  EXPECT_THROW(parseBodyText("stick", "{type: rod"), ConfigError);
  EXPECT_THROW(parseBodyText("stick", ""), ConfigError);
}

TEST(ConfigWriter, EveryCommandsPayloadGivesBackTheCommand) {
  const WorldConfig config = awkward();
  WorldCommand spawn;
  spawn.kind = WorldCommand::Kind::Spawn;
  spawn.step = 12;
  spawn.body = config.bodies[0].name;
  spawn.config = config.bodies[0];
  const WorldCommand back = commandFromText("spawn", 12, spawn.body, payloadYaml(spawn));
  EXPECT_EQ(back.kind, WorldCommand::Kind::Spawn);
  EXPECT_EQ(back.step, 12);
  expectSameBody(back.config, spawn.config);

  WorldCommand set;
  set.kind = WorldCommand::Kind::SetState;
  set.body = "rod";
  set.state = {{"x", 0.1 + 0.2}, {"omega", -0.0}};
  const WorldCommand state = commandFromText("set_state", 0, "rod", payloadYaml(set));
  ASSERT_EQ(state.state.size(), 2u);
  EXPECT_EQ(state.state[0].field, "x");
  EXPECT_TRUE(sameBits(state.state[0].value, 0.1 + 0.2));
  EXPECT_TRUE(sameBits(state.state[1].value, -0.0));

  WorldCommand whole;
  whole.kind = WorldCommand::Kind::Config;
  whole.world = config;
  expectSameConfig(commandFromText("config", 0, "", payloadYaml(whole)).world, config);
  EXPECT_EQ(commandFromText("reset", 5, "", "").kind, WorldCommand::Kind::Reset);
  EXPECT_EQ(commandFromText("delete", 5, "rod", "").body, "rod");
  EXPECT_THROW(commandFromText("teleport", 5, "rod", ""), ConfigError);
  EXPECT_THROW(commandFromText("set_state", 5, "rod", "[1, 2]"), ConfigError);
}
