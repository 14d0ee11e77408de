// The node's private parameters (as the parameter server gives them) -> its options and its config, with
// no master: defaults, ranges, and the keys that are not config (options, reconfigure namespaces).
#include <gtest/gtest.h>

#include <string>
#include <tuple>

#include "rigid_body_sim/core/node_interface.h"
#include "rigid_body_sim/ros/params.h"
#include "test_util.h"

using namespace rigid_body_sim;

namespace {

// A private namespace holding a config of one rod, as `rosparam load` leaves it.
XmlRpc::XmlRpcValue oneRod() {
  XmlRpc::XmlRpcValue params;
  params["rate"] = 1000.0;
  params["bodies"]["rod"]["type"] = std::string("rod");
  params["bodies"]["rod"]["k"] = 2000;
  return params;
}

std::string refusal(XmlRpc::XmlRpcValue params) {
  return test::refusalOf([&] {
    parseNodeOptions(params);
    parseNodeConfig(params);
  });
}

}  // namespace

TEST(NodeOptions, EveryOptionIsReadAndAMissingOneKeepsItsDefault) {
  XmlRpc::XmlRpcValue params = oneRod();
  const NodeOptions defaults = parseNodeOptions(params);
  params["real_time_factor"] = 0;
  params["publish_clock"] = true;
  params["duration"] = 30.0;
  params["start_delay"] = 2.5;
  params["start_paused"] = true;
  params["start_on_subscribers"] = true;
  params["end_launch"] = true;
  params["label_critical_angles"] = true;
  const NodeOptions options = parseNodeOptions(params);
  EXPECT_FALSE(defaults.label_critical_angles);
  EXPECT_TRUE(options.label_critical_angles);
  EXPECT_FALSE(defaults.start_paused);
  EXPECT_TRUE(options.start_paused);
  EXPECT_FALSE(defaults.end_launch);
  EXPECT_TRUE(options.end_launch);
  EXPECT_FALSE(defaults.start_on_subscribers);
  EXPECT_TRUE(options.start_on_subscribers);
  EXPECT_EQ(std::make_tuple(defaults.real_time_factor, defaults.publish_clock, defaults.duration,
                            defaults.start_delay),
            std::make_tuple(1.0, false, 0.0, 0.0));
  EXPECT_EQ(
      std::make_tuple(options.real_time_factor, options.publish_clock, options.duration, options.start_delay),
      std::make_tuple(0.0, true, 30.0, 2.5));
}

TEST(NodeOptions, ABadOptionIsRefusedInOneLine) {
  XmlRpc::XmlRpcValue negative = oneRod();
  negative["real_time_factor"] = -1.0;
  EXPECT_EQ(refusal(negative),
            "body '(node)', key 'real_time_factor': value -1 is not allowed (allowed: a finite number in [0, "
            "1e+06])");
  XmlRpc::XmlRpcValue text = oneRod();
  text["publish_clock"] = std::string("maybe");
  EXPECT_NE(refusal(text).find("'maybe' is not allowed (allowed: true or false)"), std::string::npos);
  XmlRpc::XmlRpcValue long_delay = oneRod();
  long_delay["start_delay"] = 1e6;
  EXPECT_NE(refusal(long_delay).find("'start_delay'"), std::string::npos);
}

TEST(NodeOptions, TheMarkerRateIsAtMostThePublishRate) {
  XmlRpc::XmlRpcValue params = oneRod();
  EXPECT_EQ(markerRate(parseNodeOptions(params), 50.0), 10.0);
  EXPECT_EQ(markerRate(parseNodeOptions(params), 4.0), 4.0) << "the default, no more than publish_rate";
  params["marker_rate"] = 25.0;
  params["trail_length"] = 0.0;
  const NodeOptions options = parseNodeOptions(params);
  EXPECT_EQ(markerRate(options, 50.0), 25.0);
  EXPECT_EQ(options.trail_length, 0.0);
  EXPECT_EQ(
      test::refusalOf([&] { markerRate(options, 20.0); }),
      "body '(node)', key 'marker_rate': value 25 is not allowed (allowed: a finite number in (0, 20] (at "
      "most publish_rate))");
  params["marker_rate"] = 0.0;
  EXPECT_NE(refusal(params).find("'marker_rate'"), std::string::npos);
  params["marker_rate"] = 10.0;
  params["trail_length"] = -1.0;
  EXPECT_NE(refusal(params).find("'trail_length'"), std::string::npos);
}

TEST(NodeOptions, FramePrefixIsEmptyByDefaultAndAPrefixOfFrameIds) {
  XmlRpc::XmlRpcValue params = oneRod();
  EXPECT_EQ(parseNodeOptions(params).frame_prefix, "");
  for (const std::string prefix : {"", "left/", "robots/left/", "left_/", "a1/b_2/"}) {
    params["frame_prefix"] = prefix;
    EXPECT_EQ(parseNodeOptions(params).frame_prefix, prefix);
  }
  for (const std::string bad : {"/left/", "1left/", "left//", "le ft/", "left\n", "léft/", "left", "left_"}) {
    SCOPED_TRACE(bad);
    XmlRpc::XmlRpcValue refused = oneRod();
    refused["frame_prefix"] = bad;
    const std::string message = refusal(refused);
    EXPECT_NE(message.find("key 'frame_prefix'"), std::string::npos) << message;
    EXPECT_NE(message.find("starting with a letter and ending in /"), std::string::npos) << message;
  }
}

TEST(NodeConfig, LeavesOutTheOptionsAndTheReconfigureNamespaces) {
  XmlRpc::XmlRpcValue params = oneRod();
  for (const auto& option : node_interface::optionNames()) params[option] = 1;
  params["rod"]["k"] = 5.0;  // what the rod's reconfigure server keeps in ~rod
  const WorldConfig config = parseNodeConfig(params);
  ASSERT_EQ(config.bodies.size(), 1u);
  EXPECT_EQ(std::get<RodConfig>(config.bodies[0].config).params.k, 2000.0);
}

TEST(NodeConfig, AnyOtherKeyIsRefusedAsAConfigFileWouldBe) {
  XmlRpc::XmlRpcValue typo = oneRod();
  typo["rates"] = 100;
  EXPECT_NE(refusal(typo).find("'rates'"), std::string::npos);
  XmlRpc::XmlRpcValue named_like_a_service = oneRod();
  named_like_a_service["bodies"]["step"]["type"] = std::string("roller");
  EXPECT_NE(refusal(named_like_a_service).find("node's own"), std::string::npos);
}
