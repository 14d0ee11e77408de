// The .cfg files against the core: every number of a reconfigure server is a numeric key of the core, with
// the same default and no range of its own (minus to plus infinity: a server clamps a request into its
// range before the node sees it, so that any bound would turn a refused value into another value, refused
// for the wrong number or silently accepted; the core's ranges are the only ones), and a config goes to a
// request and back unchanged.
#include <gtest/gtest.h>

#include <limits>
#include <set>
#include <string>

#include <boost/pointer_cast.hpp>

#include "rigid_body_sim/ros/reconfigure.h"

using namespace rigid_body_sim;

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

template <class Request, class Config>
void expectNumbersAreTheCoreKeys(const std::vector<NumericKey<Config>>& keys, Config defaults) {
  using Number = typename Request::template ParamDescription<double>;
  std::set<std::string> numbers;
  for (const auto& description : Request::__getParamDescriptions__()) {
    const auto number = boost::dynamic_pointer_cast<const Number>(description);
    if (!number) continue;
    numbers.insert(number->name);
    const NumericKey<Config>* key = findKey(keys, number->name);
    ASSERT_NE(key, nullptr) << number->name << " is in the .cfg but is no key of the core";
    EXPECT_EQ(Request::__getMin__().*(number->field), -kInfinity) << number->name << ": min";
    EXPECT_EQ(Request::__getMax__().*(number->field), kInfinity) << number->name << ": max";
    EXPECT_EQ(Request::__getDefault__().*(number->field), key->field(defaults))
        << number->name << ": default";
  }
  for (const auto& key : keys)
    EXPECT_EQ(numbers.count(key.name), 1u) << key.name << " is missing in the .cfg";
}

}  // namespace

TEST(ReconfigureCfg, RodNumbersAreTheCoreKeys) {
  expectNumbersAreTheCoreKeys<RodReconfigureConfig>(rodNumericKeys(), RodConfig{});
  EXPECT_EQ(RodReconfigureConfig::__getDefault__().integrator, toString(RodParams{}.integrator));
}

TEST(ReconfigureCfg, RollerNumbersAreTheCoreKeys) {
  expectNumbersAreTheCoreKeys<RollerReconfigureConfig>(rollerNumericKeys(), RollerConfig{});
  EXPECT_EQ(RollerReconfigureConfig::__getDefault__().shape, toString(RollerParams{}.shape));
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
  config.params = {1.5, 2.0, 3000.0, 9.8, Integrator::Rk4};
  config.initial = {0.1, 2.5, 0.7, -1.0, 0.5, 3.0};
  const RodConfig back = fromReconfigure("rod", toReconfigure(config), RodConfig{});
  EXPECT_EQ(back.params.length, 1.5);
  EXPECT_EQ(back.params.mass, 2.0);
  EXPECT_EQ(back.params.k, 3000.0);
  EXPECT_EQ(back.params.integrator, Integrator::Rk4);
  EXPECT_FALSE(initialChanged(back, config));
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
