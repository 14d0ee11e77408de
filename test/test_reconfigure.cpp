// The .cfg files against the body types' descriptions (core/parameters.h): each server holds exactly the
// keys a description writes, a number as a double and a text as a string, with the description's default,
// level (KeyChange) and meaning ("meaning (unit)": the panel shows the unit), and no range of its own (minus
// to plus infinity: a server clamps a request into its range before the node sees it, so that any bound
// would turn a refused value into another value, refused for the wrong number or silently accepted; the
// core's ranges are the only ones). Every key through a request and back: test_key_round_trips.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <set>
#include <string>

#include <boost/pointer_cast.hpp>

#include "rigid_body_sim/ros/reconfigure.h"

using namespace rigid_body_sim;

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

template <class Request, class Config>
void expectCfgIsTheDescription() {
  using Number = typename Request::template ParamDescription<double>;
  using Text = typename Request::template ParamDescription<std::string>;
  const Config defaults;
  std::set<std::string> served;
  for (const auto& description : Request::__getParamDescriptions__()) {
    SCOPED_TRACE(description->name);
    served.insert(description->name);
    const BodyKey<Config>* key = findKey(bodyType<Config>().keys, description->name);
    ASSERT_NE(key, nullptr) << "in the .cfg but no key of the body type";
    ASSERT_TRUE(key->written()) << "a key that is never written has no value to serve";
    const std::string unit = *key->unit ? std::string(" (") + key->unit + ")" : "";
    EXPECT_EQ(description->description, key->meaning + unit);
    EXPECT_EQ(description->level, static_cast<std::uint32_t>(key->change));
    const auto number = boost::dynamic_pointer_cast<const Number>(description);
    const auto text = boost::dynamic_pointer_cast<const Text>(description);
    if (key->isNumber()) {
      ASSERT_TRUE(number) << "a number in the core, no double in the .cfg";
      EXPECT_EQ(Request::__getMin__().*(number->field), -kInfinity) << "min";
      EXPECT_EQ(Request::__getMax__().*(number->field), kInfinity) << "max";
      EXPECT_EQ(Request::__getDefault__().*(number->field), key->number(defaults)) << "default";
    } else {
      ASSERT_TRUE(text) << "a text in the core, no string in the .cfg";
      EXPECT_EQ(Request::__getDefault__().*(text->field), key->text(defaults)) << "default";
    }
  }
  for (const auto& key : bodyType<Config>().keys) {
    if (key.written()) EXPECT_EQ(served.count(key.name), 1u) << key.name << " is missing in the .cfg";
  }
}

}  // namespace

TEST(ReconfigureCfg, RodServerHoldsTheRodsKeys) {
  expectCfgIsTheDescription<RodReconfigureConfig, RodConfig>();
}

TEST(ReconfigureCfg, RollerServerHoldsTheRollersKeys) {
  expectCfgIsTheDescription<RollerReconfigureConfig, RollerConfig>();
}

// A server clamps every request (config.__clamp__()) before its callback: a value far outside the core's
// range must reach the node unchanged, to be refused naming it.
TEST(ReconfigureCfg, ClampingLeavesEveryValueAsAsked) {
  RodReconfigureConfig rod;
  rod.k = -5.0;
  rod.floor_length = -1e300;
  rod.__clamp__();
  EXPECT_EQ(rod.k, -5.0);
  EXPECT_EQ(rod.floor_length, -1e300);
  RollerReconfigureConfig roller;
  roller.mu_s = -1.0;
  roller.incline_angle = 4.0;
  roller.__clamp__();
  EXPECT_EQ(roller.mu_s, -1.0);
  EXPECT_EQ(roller.incline_angle, 4.0);
}

TEST(Reconfigure, RodConfigGoesThereAndBack) {
  RodConfig config;
  config.params.length = 1.5;
  config.params.mass = 2.0;
  config.params.k = 3000.0;
  config.params.integrator = Integrator::Rk4;
  config.params.floor_length = 12.0;
  config.params.substeps = 3;
  config.initial = {0.1, 2.5, 0.7, -1.0, 0.5, 3.0};
  const RodConfig back = fromReconfigure("rod", toReconfigure(config), RodConfig{});
  EXPECT_EQ(back.params.length, 1.5);
  EXPECT_EQ(back.params.mass, 2.0);
  EXPECT_EQ(back.params.k, 3000.0);
  EXPECT_EQ(back.params.integrator, Integrator::Rk4);
  EXPECT_EQ(back.params.floor_length, 12.0);
  EXPECT_EQ(back.params.substeps, 3);
  EXPECT_FALSE(initialChanged(back, config));
}

TEST(Reconfigure, SubstepsAreAutoOrAWholeNumber) {
  RodReconfigureConfig request = toReconfigure(RodConfig{});
  EXPECT_EQ(request.substeps, "auto");
  request.substeps = "1";
  EXPECT_EQ(fromReconfigure("rod", request, RodConfig{}).params.substeps, 1);
  for (const char* bad : {"0", "1.5", "", "many"}) {
    request.substeps = bad;
    try {
      fromReconfigure("rod", request, RodConfig{});
      ADD_FAILURE() << bad << " was accepted";
    } catch (const ConfigError& error) {
      EXPECT_NE(std::string(error.what()).find("body 'rod', key 'substeps'"), std::string::npos)
          << error.what();
    }
  }
}

TEST(Reconfigure, RollerShapeBringsItsFactorAndCustomKeepsTheRequested) {
  RollerConfig sphere;
  sphere.initial = {1.0, 2.0, 3.0, -4.0};
  sphere.params.mu_s = 0.5;
  RollerReconfigureConfig request = toReconfigure(sphere);
  EXPECT_EQ(request.mu_s, 0.5);
  EXPECT_EQ(request.x0, 1.0);
  EXPECT_FALSE(initialChanged(fromReconfigure("ball", request, sphere), sphere));

  request.shape = "ring";
  EXPECT_EQ(fromReconfigure("ball", request, sphere).params.inertia_factor, 1.0);
  request.shape = "custom";
  request.inertia_factor = 0.25;
  const RollerConfig custom = fromReconfigure("ball", request, sphere);
  EXPECT_EQ(custom.params.shape, Shape::Custom);
  EXPECT_EQ(custom.params.inertia_factor, 0.25);
  request.shape = "cube";
  EXPECT_THROW(fromReconfigure("ball", request, sphere), ConfigError);
}
