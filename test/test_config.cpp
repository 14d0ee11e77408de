// The config loader: good files load with the text's values, every kind of bad value is refused with
// one line naming the body, the key, the value and what is allowed.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "rigid_body_sim/core/constants.h"
#include "rigid_body_sim/core/node_interface.h"
#include "rigid_body_sim/io/config_loader.h"
#include "test_util.h"

using namespace rigid_body_sim;

namespace {

WorldConfig parse(const std::string& yaml) { return parseWorldConfig(YAML::Load(yaml)); }

const RodConfig& rodOf(const WorldConfig& config, std::size_t i = 0) {
  return std::get<RodConfig>(config.bodies.at(i).config);
}
const RollerConfig& rollerOf(const WorldConfig& config, std::size_t i = 0) {
  return std::get<RollerConfig>(config.bodies.at(i).config);
}

std::string refusal(const std::string& yaml) {
  return test::refusalOf([&] { parse(yaml); });
}

}  // namespace

TEST(ConfigFiles, ShippedFilesLoad) {
  for (const char* name : {"rod.yaml", "incline.yaml", "demo.yaml"}) {
    SCOPED_TRACE(name);
    const WorldConfig config = loadWorldConfigFile(std::string(RBS_CONFIG_DIR) + "/" + name);
    EXPECT_EQ(config.rate, 1000.0);
    EXPECT_EQ(config.publish_rate, 50.0);
    EXPECT_FALSE(config.bodies.empty());
  }
}

TEST(ConfigFiles, RodFileIsTheTextsRod) {
  const WorldConfig config = loadWorldConfigFile(std::string(RBS_CONFIG_DIR) + "/rod.yaml");
  const RodConfig& rod = rodOf(config);
  EXPECT_EQ(rod.params.mass, 0.5);
  EXPECT_EQ(rod.params.length, 1.0);
  EXPECT_EQ(rod.params.k, 1000.0);
  EXPECT_EQ(rod.params.integrator, Integrator::EulerCromer);
  EXPECT_EQ(rod.initial.y, 4.0);
  EXPECT_EQ(rod.initial.vx, 2.0);
  EXPECT_EQ(rod.params.gravity, 9.8);
}

TEST(ConfigFiles, InclineFileShowsTheCriticalAngleTable) {
  // On the shipped slope the sphere is below its critical angle, the cylinder and the ring above.
  const WorldConfig config = loadWorldConfigFile(std::string(RBS_CONFIG_DIR) + "/incline.yaml");
  ASSERT_EQ(config.bodies.size(), 3u);
  EXPECT_TRUE(Roller::canRoll(rollerOf(config, 0).params));
  EXPECT_FALSE(Roller::canRoll(rollerOf(config, 1).params));
  EXPECT_FALSE(Roller::canRoll(rollerOf(config, 2).params));
}

TEST(ConfigDefaults, MissingKeysTakeTheTextsValues) {
  const WorldConfig config = parse("bodies: {rod: {type: rod}, ball: {type: roller}}");
  EXPECT_EQ(config.rate, 1000.0);
  EXPECT_EQ(config.publish_rate, 50.0);
  EXPECT_EQ(config.gravity, 9.8);
  EXPECT_EQ(config.world_frame, "world");
  const RodConfig& rod = rodOf(config);
  EXPECT_EQ(rod.params.mass, 0.5);
  EXPECT_EQ(rod.params.length, 1.0);
  EXPECT_EQ(rod.params.k, 1000.0);
  EXPECT_EQ(rod.initial.x, 0.0);
  EXPECT_EQ(rod.initial.y, 4.0);
  EXPECT_EQ(rod.initial.vx, 2.0);
  EXPECT_EQ(rod.initial.theta, 0.3);
  EXPECT_EQ(rod.initial.omega, 0.0);
  const RollerConfig& ball = rollerOf(config, 1);
  EXPECT_EQ(ball.params.shape, Shape::Sphere);
  EXPECT_DOUBLE_EQ(ball.params.inertia_factor, 0.4);
  EXPECT_EQ(ball.params.mu_s, 0.3);
  EXPECT_EQ(ball.params.mu_d, 0.2);
  EXPECT_EQ(ball.params.incline_angle, 0.349);
}

TEST(ConfigDefaults, FloorIsUnboundedUnlessGiven) {
  // The text's floor: no floor_length (or 0) is unbounded, and x0 may be anywhere on it.
  EXPECT_EQ(rodOf(parse("bodies: {rod: {type: rod, x0: -3}}")).params.floor_length, 0.0);
  EXPECT_EQ(rodOf(parse("bodies: {rod: {type: rod, floor_length: 0, x0: -3}}")).params.floor_length, 0.0);
  const RodConfig bounded = rodOf(parse("bodies: {rod: {type: rod, floor_length: 12.5, x0: 12.5}}"));
  EXPECT_EQ(bounded.params.floor_length, 12.5);
  EXPECT_EQ(bounded.initial.x, 12.5);  // both ends of the floor are on it
}

TEST(ConfigDefaults, GravityReachesEveryBody) {
  const WorldConfig config = parse("gravity: 1.62\nbodies: {rod: {type: rod}, ball: {type: roller}}");
  EXPECT_EQ(rodOf(config).params.gravity, 1.62);
  EXPECT_EQ(rollerOf(config, 1).params.gravity, 1.62);
}

TEST(ConfigShapes, NamedShapesAndExplicitFactor) {
  const WorldConfig config = parse(
      "bodies: {a: {type: roller, shape: ring}, b: {type: roller, shape: spherical_shell},"
      " c: {type: roller, inertia_factor: 0.7}, d: {type: roller, shape: cylinder}}");
  EXPECT_EQ(rollerOf(config, 0).params.inertia_factor, 1.0);
  EXPECT_DOUBLE_EQ(rollerOf(config, 1).params.inertia_factor, 2.0 / 3.0);
  EXPECT_EQ(rollerOf(config, 2).params.shape, Shape::Custom);
  EXPECT_EQ(rollerOf(config, 2).params.inertia_factor, 0.7);
  EXPECT_EQ(rollerOf(config, 3).params.inertia_factor, 0.5);
}

TEST(ConfigSubsteps, AutoByDefaultOrAStableWholeNumber) {
  const auto substepsOf = [](const std::string& yaml) {
    return std::get<RodConfig>(parse(yaml).bodies[0].config).params.substeps;
  };
  EXPECT_EQ(substepsOf("bodies: {rod: {type: rod}}"), kAutoSubsteps);
  EXPECT_EQ(substepsOf("bodies: {rod: {type: rod, substeps: auto}}"), kAutoSubsteps);
  EXPECT_EQ(substepsOf("bodies: {rod: {type: rod, k: 50000, substeps: 1}}"), 1);  // omega_c dt = 0.63
  EXPECT_EQ(substepsOf("bodies: {rod: {type: rod, k: 5e6, substeps: 4}}"), 4);    // 6.32 / 4 < 2
  // The bound follows the rate: omega_c dt = 2 exactly at k = 5e5 and rate 1000 is refused.
  EXPECT_NE(refusal("bodies: {rod: {type: rod, k: 5e5, substeps: 1}}"), "");
  EXPECT_EQ(refusal("rate: 2000\nbodies: {rod: {type: rod, k: 5e5, substeps: 1}}"), "");
}

TEST(ConfigSubsteps, AutoSplittingIsSaidOncePerRodThatItSplits) {
  EXPECT_TRUE(autoSubstepNotes(parse("bodies: {rod: {type: rod}}")).empty());  // the text's k
  const auto notes = autoSubstepNotes(parse(
      "bodies: {soft: {type: rod}, stiff: {type: rod, k: 5000}, fixed: {type: rod, k: 5000, substeps: 1}, "
      "ball: {type: roller}}"));
  ASSERT_EQ(notes.size(), 1u);
  for (const char* part :
       {"body 'stiff'", "into 2 sub-steps", "omega_c dt = 0.2", "k = 5000", "1 is the text's scheme"}) {
    EXPECT_NE(notes[0].find(part), std::string::npos) << part << " in: " << notes[0];
  }
}

TEST(ConfigSeed, SeedDrawsAReproducibleAngle) {
  const double a = rodOf(parse("bodies: {rod: {type: rod, seed: 42}}")).initial.theta;
  const double b = rodOf(parse("bodies: {rod: {type: rod, seed: 42}}")).initial.theta;
  const double c = rodOf(parse("bodies: {rod: {type: rod, seed: 43}}")).initial.theta;
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  EXPECT_GE(a, 0.0);
  EXPECT_LT(a, 2 * kPi);
  EXPECT_EQ(a, theta0FromSeed(42));
}

TEST(ConfigSeed, DrawsSpreadOverTheCircle) {
  // 1000 seeds fill each quarter of [0, 2 pi) with roughly a quarter of the draws.
  int quarters[4] = {0, 0, 0, 0};
  for (unsigned long long seed = 0; seed < 1000; ++seed) {
    quarters[static_cast<int>(theta0FromSeed(seed) / (kPi / 2))]++;
  }
  for (const int count : quarters) {
    EXPECT_GT(count, 200);
    EXPECT_LT(count, 300);
  }
}

struct BadInput {
  const char* what;
  const char* yaml;
  std::vector<const char*> expected;  // fragments of the one-line message
};

class ConfigRefusal : public ::testing::TestWithParam<BadInput> {};

TEST_P(ConfigRefusal, NamesBodyKeyValueAndRange) {
  const BadInput& bad = GetParam();
  const std::string message = refusal(bad.yaml);
  EXPECT_NE(message, "");
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  for (const char* fragment : bad.expected) {
    EXPECT_NE(message.find(fragment), std::string::npos) << "missing '" << fragment << "' in: " << message;
  }
}

INSTANTIATE_TEST_SUITE_P(
    EveryKind, ConfigRefusal,
    ::testing::Values(
        BadInput{"negative k", "bodies: {rod: {type: rod, k: -5}}", {"'rod'", "'k'", "-5", "(0, "}},
        BadInput{"zero mass", "bodies: {rod: {type: rod, mass: 0}}", {"'rod'", "'mass'", "value 0", "(0, "}},
        BadInput{"nan length", "bodies: {rod: {type: rod, length: .nan}}", {"'length'", "nan"}},
        BadInput{"infinite k", "bodies: {rod: {type: rod, k: .inf}}", {"'k'", "inf", "finite"}},
        BadInput{"absurd mass", "bodies: {rod: {type: rod, mass: 1e300}}", {"'mass'", "1e+300", "1e+09]"}},
        BadInput{"string for number",
                 "bodies: {rod: {type: rod, y0: high}}",
                 {"'rod'", "'y0'", "'high'", "a finite number in [0, 1e+06]"}},
        BadInput{"list for number",
                 "bodies: {rod: {type: rod, y0: [1, 2]}}",
                 {"'y0'", "(a list)", "a finite number"}},
        BadInput{"unknown rod key",
                 "bodies: {rod: {type: rod, stiffness: 5}}",
                 {"'rod'", "'stiffness'", "no such key", "k"}},
        BadInput{"unknown roller key",
                 "bodies: {b: {type: roller, mu: 0.5}}",
                 {"'b'", "'mu'", "no such key", "mu_s"}},
        BadInput{"unknown world key",
                 "rates: 10\nbodies: {rod: {type: rod}}",
                 {"(world)", "'rates'", "no such key"}},
        BadInput{"unknown integrator",
                 "bodies: {rod: {type: rod, integrator: leapfrog}}",
                 {"'integrator'", "'leapfrog'", "euler_cromer"}},
        BadInput{"zero substeps",
                 "bodies: {rod: {type: rod, substeps: 0}}",
                 {"'rod'", "'substeps'", "value '0'", "auto or a whole number in [1, 1e+09]"}},
        BadInput{"fractional substeps", "bodies: {rod: {type: rod, substeps: 1.5}}", {"'substeps'", "1.5"}},
        BadInput{"substeps a word", "bodies: {rod: {type: rod, substeps: many}}", {"'substeps'", "'many'"}},
        BadInput{"substeps unstable",
                 "bodies: {rod: {type: rod, k: 5e6, substeps: 3}}",  // omega_c dt = 6.32: N >= 4
                 {"'rod'", "'substeps'", "value 3", "N >= 4", "omega_c dt / N < 2", "k = 5e+06"}},
        BadInput{"unknown body type",
                 "bodies: {box: {type: cube}}",
                 {"'box'", "'type'", "'cube'", "rod, roller or block"}},
        BadInput{"missing type", "bodies: {box: {mass: 1}}", {"'box'", "'type'", "rod, roller or block"}},
        BadInput{"unknown shape",
                 "bodies: {b: {type: roller, shape: cube}}",
                 {"'b'", "'shape'", "'cube'", "sphere"}},
        BadInput{"custom without factor",
                 "bodies: {b: {type: roller, shape: custom}}",
                 {"'shape'", "inertia_factor"}},
        BadInput{"factor contradicts shape",
                 "bodies: {b: {type: roller, shape: ring, inertia_factor: 0.3}}",
                 {"'inertia_factor'", "0.3", "ring"}},
        BadInput{
            "zero factor", "bodies: {b: {type: roller, inertia_factor: 0}}", {"'inertia_factor'", "(0, "}},
        BadInput{"negative mu_s",
                 "bodies: {b: {type: roller, mu_s: -0.1, mu_d: 0}}",
                 {"'b'", "'mu_s'", "-0.1", "[0, "}},
        BadInput{"mu_d above mu_s",
                 "bodies: {b: {type: roller, mu_s: 0.2, mu_d: 0.5}}",
                 {"'mu_d'", "0.5", "mu_s = 0.2"}},
        BadInput{"vertical slope",
                 "bodies: {b: {type: roller, incline_angle: 1.5707963267948966}}",
                 {"'incline_angle'", "1.5707963267948966)"}},
        BadInput{"negative slope",
                 "bodies: {b: {type: roller, incline_angle: -0.1}}",
                 {"'incline_angle'", "-0.1"}},
        BadInput{"zero radius", "bodies: {b: {type: roller, radius: 0}}", {"'radius'", "value 0"}},
        BadInput{"x0 past the slope",
                 "bodies: {b: {type: roller, x0: 6, incline_length: 5}}",
                 {"'x0'", "6", "incline_length = 5"}},
        BadInput{"negative x0", "bodies: {b: {type: roller, x0: -1}}", {"'x0'", "-1"}},
        BadInput{"rod x0 past its floor",
                 "bodies: {rod: {type: rod, floor_length: 5, x0: 6}}",
                 {"'rod'", "'x0'", "6", "floor_length = 5"}},
        BadInput{"rod x0 before its floor",
                 "bodies: {rod: {type: rod, floor_length: 5, x0: -0.5}}",
                 {"'x0'", "-0.5", "[0, floor_length = 5]"}},
        BadInput{"negative floor_length",
                 "bodies: {rod: {type: rod, floor_length: -1}}",
                 {"'rod'", "'floor_length'", "-1", "[0, 1e+06]"}},
        BadInput{"seed and theta0", "bodies: {rod: {type: rod, seed: 1, theta0: 0.5}}", {"'seed'", "theta0"}},
        BadInput{"fractional seed", "bodies: {rod: {type: rod, seed: 1.5}}", {"'seed'", "whole number"}},
        BadInput{"zero rate", "rate: 0\nbodies: {rod: {type: rod}}", {"(world)", "'rate'", "value 0"}},
        BadInput{"publish_rate not dividing",
                 "publish_rate: 30\nbodies: {rod: {type: rod}}",
                 {"'publish_rate'", "30", "divisor of rate = 1000"}},
        BadInput{"publish_rate above rate",
                 "rate: 100\npublish_rate: 200\nbodies: {rod: {type: rod}}",
                 {"'publish_rate'", "200"}},
        BadInput{"negative gravity", "gravity: -9.8\nbodies: {rod: {type: rod}}", {"'gravity'", "-9.8"}},
        BadInput{"missing bodies", "rate: 1000", {"'bodies'", "(missing)"}},
        BadInput{"bodies not a map", "bodies: [rod]", {"'bodies'", "(a list)"}},
        BadInput{"empty bodies", "bodies: {}", {"'bodies'", "at least one body"}},
        BadInput{"body not a map", "bodies: {rod: 5}", {"'rod'", "'5'"}},
        BadInput{"invalid body name", "bodies: {'my rod': {type: rod}}", {"'my rod'", "letters, digits"}},
        BadInput{"name starting with digit", "bodies: {'2rod': {type: rod}}", {"'2rod'"}},
        BadInput{"body named like world", "bodies: {world: {type: rod}}", {"'world'", "differ"}},
        BadInput{"invalid world_frame",
                 "world_frame: /map\nbodies: {rod: {type: rod}}",
                 {"'world_frame'", "'/map'"}},
        BadInput{"file is a list", "[1, 2]", {"(world)", "(a list)"}},
        BadInput{"empty document", "", {"(world)", "(nothing)"}}));

TEST(ConfigFileErrors, MissingFileAndSyntaxError) {
  try {
    loadWorldConfigFile("/nonexistent/rigid_body_sim.yaml");
    FAIL() << "accepted a missing file";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/rigid_body_sim.yaml"), std::string::npos);
  }
  const test::PrivateDir dir("config_bad_syntax");
  const std::string path = (dir.path() / "bad_syntax.yaml").string();
  FILE* file = std::fopen(path.c_str(), "w");
  ASSERT_NE(file, nullptr);
  std::fputs("bodies: {rod: {type: rod\n", file);
  std::fclose(file);
  try {
    loadWorldConfigFile(path);
    FAIL() << "accepted a YAML syntax error";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("not valid YAML"), std::string::npos) << error.what();
  }
}

TEST(ConfigDuplicates, DuplicateBodyNamesAreRefused) {
  // yaml-cpp keeps both entries of a duplicated key; the loader must not silently pick one.
  EXPECT_NE(refusal("bodies:\n  rod: {type: rod}\n  rod: {type: rod, k: 5}\n").find("'rod'"),
            std::string::npos);
}

// Found by the fuzzer / the bad-input tables: a key that is a list or a map made yaml-cpp throw its own
// exception instead of a ConfigError; a newline in a name broke the one-line message.
// A key given twice: yaml-cpp keeps both, rosparam the last, map[key] the first: refused wherever a map is
// read (a config file, a spawned body, a set_state), naming the key and the second value.
TEST(ConfigDuplicates, AKeyGivenTwiceIsRefused) {
  EXPECT_EQ(
      refusal("bodies: {rod: {type: rod, k: 1000, k: 2000}}"),
      "body 'rod', key 'k': value '2000' (the key given twice) is not allowed (allowed: each key once)");
  EXPECT_NE(refusal("rate: 1000\nrate: 500\nbodies: {rod: {type: rod}}").find("body '(world)', key 'rate'"),
            std::string::npos);
  const std::string spawn =
      test::refusalOf([] { parseBodyText("hoop", "{type: roller, mass: 1, mass: 2}"); });
  EXPECT_EQ(
      spawn,
      "body 'hoop', key 'mass': value '2' (the key given twice) is not allowed (allowed: each key once)");
  const std::string state = test::refusalOf([] { parseStateText("rod", "{x: 1, x: 2}"); });
  EXPECT_EQ(state,
            "body 'rod', key 'x': value '2' (the key given twice) is not allowed (allowed: each key once)");
}

// A second YAML document ("---") would be dropped without a word by a reader that takes the first: refused
// wherever YAML text is read (a config file, a spawned body, a set_state), with one line that says so.
TEST(ConfigDocuments, ASecondDocumentIsRefused) {
  EXPECT_EQ(test::refusalOf([] {
              parseWorldConfigText("bodies: {rod: {type: rod}}\n---\nbodies: {ball: {type: roller}}", "test");
            }),
            "config file 'test' holds 2 YAML documents (allowed: one; '---' starts another)");
  EXPECT_EQ(test::refusalOf([] { parseBodyText("hoop", "{type: roller}\n---\n{type: rod}"); }),
            "body 'hoop' holds 2 YAML documents (allowed: one; '---' starts another)");
  EXPECT_EQ(test::refusalOf([] { parseStateText("rod", "{x: 1}\n---\n{x: 2}"); }),
            "state of body 'rod' holds 2 YAML documents (allowed: one; '---' starts another)");
  EXPECT_EQ(test::refusalOf([] {
              parseWorldConfigText("bodies: {rod: {type: rod}}\n...\nbodies: {ball: {type: roller}}", "test");
            }),
            "config file 'test' holds 2 YAML documents (allowed: one; '---' starts another)");
  // One document with its optional markers is one document, comments and a directive around it too.
  EXPECT_EQ(test::refusalOf([] { parseWorldConfigText("---\nbodies: {rod: {type: rod}}\n...\n", "test"); }),
            "");
  EXPECT_EQ(test::refusalOf([] {
              parseWorldConfigText(
                  "%YAML 1.2\n# a rod\n--- # the world\nbodies: {rod: {type: rod}}\n...\n# end\n", "test");
            }),
            "");
}

// A quoted number is text: refused where a number is asked, in a config file and a spawned body alike.
TEST(ConfigNumbers, AQuotedNumberIsRefused) {
  const std::string message = refusal("bodies: {rod: {type: rod, mass: \"1\"}}");
  EXPECT_NE(message.find("body 'rod', key 'mass': value \"1\" (quoted: a text) is not allowed"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("without quotes"), std::string::npos) << message;
  EXPECT_NE(test::refusalOf([] { parseStateText("rod", "{x: '1'}"); }).find("(quoted: a text)"),
            std::string::npos);
  EXPECT_EQ(test::refusalOf([] { parseStateText("rod", "{x: 1e3}"); }), "");  // unquoted: a number
}

// Names are at most 64 characters (they name topics, services, frames and lines of text).
TEST(ConfigNames, ALongNameIsRefused) {
  EXPECT_EQ(refusal("bodies: {a" + std::string(63, 'b') + ": {type: rod}}"), "");
  const std::string message = refusal("bodies: {a" + std::string(64, 'b') + ": {type: rod}}");
  EXPECT_NE(message.find("at most 64 characters"), std::string::npos) << message;
}

// Brackets yaml-cpp 0.6 (Debian 11) loops on until memory runs out are refused before it sees them: one left
// open, a ':' right before ']', nesting beyond 32; brackets in quotes and comments do not count.
TEST(ConfigOddYaml, BracketsAreCheckedBeforeYamlCppSeesThem) {
  const auto refusal = [](const std::string& text) {
    return test::refusalOf([&] { parseWorldConfigText(text, "x.yaml"); });
  };
  EXPECT_EQ(refusal("x: [a, b"),
            "config file 'x.yaml' is not valid YAML: the '[' at line 1, column 4 is not closed");
  for (const std::string text : {"[:", "[a:", "bodies: {rod: {type: rod, k: [1, 2}}"}) {
    EXPECT_NE(refusal(text).find("is not closed"), std::string::npos) << text;
  }
  for (const std::string text : {"[:]", "[a:]", "{a: [b:]}"}) {
    EXPECT_NE(refusal(text).find("a ':' right before ']'"), std::string::npos) << text;
  }
  // yaml-cpp reads a # right after '[', '{', ',' or a quoted scalar as a comment or not: refused.
  EXPECT_EQ(
      refusal("{a,#}\n:"),
      "config file 'x.yaml' is not valid YAML here: a '#' right after ',' at line 1, column 4 (a comment "
      "needs a blank before its '#')");
  for (const std::string text : {"[#]\n:", "{a: b,#}\n:", "{a: [#]}\n:", "{\"a\"#}\n:", "0,#: {:"}) {
    EXPECT_NE(refusal(text).find("a comment needs a blank before its '#'"), std::string::npos) << text;
  }
  // Where yaml-cpp opens a quoted scalar differs from YAML: brackets must balance with quotes read or not.
  EXPECT_NE(refusal(":{\": {:]\"}").find("a ':' right before ']'"), std::string::npos);
  // In a block, ',' is a plain character: the quote after it opens no quoted scalar, and the '{' is open.
  EXPECT_NE(refusal("0,\": {:").find("the '{' at line 1, column 6 is not closed"), std::string::npos);
  EXPECT_EQ(refusal("bodies: {rod: {type: rod, integrator: euler#cromer}}").find("'#'"),
            std::string::npos);  // inside a plain scalar, # is a character
  EXPECT_EQ(refusal("bodies: {rod: {type: rod, k:\x04 5}}"),
            "config file 'x.yaml' is not valid YAML: the control character \\x04 at line 1, column 29");
  EXPECT_NE(refusal(std::string(33, '[') + std::string(33, ']')).find("nests lists and maps 33 deep"),
            std::string::npos);
  const std::string fine =
      "# a comment with [ and {: ]\nbodies: {rod: {type: rod, integrator: 'euler_cromer'}}";
  EXPECT_EQ(refusal(fine), "");
  EXPECT_EQ(test::refusalOf([] { parseBodyText("hoop", "{type: roller, shape: \"ring\"} # [ not closed"); }),
            "");
}

TEST(ConfigOddYaml, KeysThatAreListsOrMapsAreRefusedAsUnknownKeys) {
  for (const char* yaml : {"bodies: {rod: {type: rod, [k]: 1}}", "{[rate]: 1, bodies: {rod: {type: rod}}}",
                           "bodies: {{a: 1}: {type: rod}}"}) {
    SCOPED_TRACE(yaml);
    try {
      parse(yaml);
      ADD_FAILURE() << "accepted";
    } catch (const ConfigError& error) {
      EXPECT_EQ(std::string(error.what()).find('\n'), std::string::npos);
    } catch (const std::exception& error) {
      ADD_FAILURE() << "not a ConfigError: " << error.what();
    }
  }
}

TEST(ConfigOddYaml, ControlCharactersAreEscapedAndLongValuesCut) {
  EXPECT_EQ(
      refusal("bodies: {\"a\\nb\": {type: rod}}"),
      "body '(world)', key 'bodies': value 'a\\nb' is not allowed (allowed: body names of letters, digits "
      "and _ starting with a letter, at most 64 characters)");
  EXPECT_NE(refusal("bodies: {rod: {type: rod, \"k\\tx\": 1}}").find("key 'k\\x09x'"), std::string::npos);
  const std::string message = refusal("bodies: {rod: {type: rod, y0: " + std::string(5000, 'x') + "}}");
  EXPECT_LT(message.size(), 300u) << message;
  EXPECT_NE(message.find("'" + std::string(79, 'x') + "..."), std::string::npos) << message;
}

TEST(ConfigNames, FramesAndReservedNamesAreRefused) {
  // Every TF frame is distinct: a body may not be named like another body's fixed frame.
  EXPECT_NE(refusal("bodies: {rod: {type: rod}, rod_floor: {type: rod}}").find("'rod_floor'"),
            std::string::npos);
  EXPECT_NE(refusal("world_frame: ball_slope\nbodies: {ball: {type: roller}}").find("'ball'"),
            std::string::npos);
  std::vector<std::string> reserved = worldKeys();
  for (const auto& name : node_interface::ownNames()) reserved.push_back(name);
  for (const auto& name : reserved) {
    EXPECT_NE(refusal("bodies: {" + name + ": {type: rod}}").find("node's own"), std::string::npos) << name;
  }
  // Names that merely resemble them are fine.
  EXPECT_NO_THROW(parse("bodies: {rod: {type: rod}, rod_slope: {type: rod}, steps: {type: roller}}"));
}

TEST(ConfigNumbers, OutOfDoubleRangeNamesTheKeysRange) {
  EXPECT_NE(refusal("bodies: {rod: {type: rod, k: 1e400}}")
                .find("'1e400' is not allowed (allowed: a finite number in (0, 1e+12])"),
            std::string::npos);
}

TEST(ConfigFileErrors, DirectoryAndEmptyFile) {
  const test::PrivateDir dir("config_empty");
  EXPECT_THROW(loadWorldConfigFile(dir.path().string()), ConfigError);
  const std::string path = (dir.path() / "empty.yaml").string();
  std::fclose(std::fopen(path.c_str(), "w"));
  try {
    loadWorldConfigFile(path);
    FAIL() << "accepted an empty file";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("(nothing)"), std::string::npos) << error.what();
  }
}
