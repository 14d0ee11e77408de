// What the rviz panel follows, from the master's lists (discoverBodies): the node's bodies, or a replay.
#include <gtest/gtest.h>

#include "rigid_body_sim/rviz/discovery.h"

using namespace rigid_body_sim;

namespace {

const std::string kRod = "rigid_body_sim/RodState", kRoller = "rigid_body_sim/RollerState";

void publish(MasterLists& lists, const std::string& topic, const std::string& type, const std::string& node) {
  lists.topic_types[topic] = type;
  lists.publishers[topic].push_back(node);
}

// What sim_node offers: its services, a reconfigure server and a state topic per body.
MasterLists liveNode() {
  MasterLists lists;
  lists.services = {"/sim/pause", "/sim/unpause", "/sim/step"};
  for (const auto& [body, type] : {std::pair{"rod", kRod}, std::pair{"sphere", kRoller}}) {
    publish(lists, std::string("/sim/") + body + "/parameter_descriptions",
            "dynamic_reconfigure/ConfigDescription", "/sim");
    publish(lists, std::string("/sim/") + body + "/state", type, "/sim");
  }
  return lists;
}

// What playback.launch's player offers: the recorded topics and its pause_playback.
MasterLists replay() {
  MasterLists lists;
  lists.services = {"/player/pause_playback", "/player/set_rate"};
  publish(lists, "/sim/rod/state", kRod, "/player");
  publish(lists, "/sim/sphere/state", kRoller, "/player");
  publish(lists, "/sim/scene", "visualization_msgs/MarkerArray", "/player");
  publish(lists, "/clock", "rosgraph_msgs/Clock", "/player");
  return lists;
}

}  // namespace

TEST(PanelDiscovery, TheNodesBodiesAreItsReconfigureServers) {
  const Discovery found = discoverBodies(liveNode(), "/sim");
  EXPECT_EQ(found.source, BodySource::Node);
  EXPECT_EQ(found.bodies, (std::map<std::string, std::string>{{"rod", kRod}, {"sphere", kRoller}}));
  EXPECT_TRUE(found.player.empty());
}

TEST(PanelDiscovery, AServerWhoseStateIsNotYetPublishedHasNoType) {
  MasterLists lists = liveNode();
  lists.topic_types.erase("/sim/rod/state");
  EXPECT_EQ(discoverBodies(lists, "/sim").bodies.at("rod"), "");
}

TEST(PanelDiscovery, StatesPlayedByAnotherNodeAreAReplay) {
  const Discovery found = discoverBodies(replay(), "/sim");
  EXPECT_EQ(found.source, BodySource::Replay);
  EXPECT_EQ(found.bodies, (std::map<std::string, std::string>{{"rod", kRod}, {"sphere", kRoller}}));
  EXPECT_EQ(found.player, "/player");
  EXPECT_EQ(found.pause_service, "/player/pause_playback");
}

TEST(PanelDiscovery, APlayerWithoutPausePlaybackIsFollowedWithoutIt) {
  MasterLists lists = replay();
  lists.services.clear();
  const Discovery found = discoverBodies(lists, "/sim");
  EXPECT_EQ(found.source, BodySource::Replay);
  EXPECT_EQ(found.player, "/player");
  EXPECT_TRUE(found.pause_service.empty());
}

TEST(PanelDiscovery, TheNodeWinsOverAReplayOfItsTopics) {
  MasterLists lists = liveNode();
  publish(lists, "/sim/rod/state", kRod, "/player");
  EXPECT_EQ(discoverBodies(lists, "/sim").source, BodySource::Node);
}

TEST(PanelDiscovery, TheNodesOwnStatesWithoutItsServicesAreNoReplay) {
  MasterLists lists = liveNode();  // starting: its states advertised before its services
  lists.services.clear();
  EXPECT_EQ(discoverBodies(lists, "/sim").source, BodySource::Node);
}

TEST(PanelDiscovery, OnlyTheNodesNamespaceAndDirectBodiesCount) {
  MasterLists lists;
  publish(lists, "/left/sim/rod/state", kRod, "/player");
  publish(lists, "/sim/rod/extra/state", kRod, "/player");
  publish(lists, "/simulation/rod/state", kRod, "/player");
  publish(lists, "/sim/state", kRod, "/player");
  EXPECT_TRUE(discoverBodies(lists, "/sim").bodies.empty());
  const Discovery left = discoverBodies(lists, "/left/sim");
  EXPECT_EQ(left.source, BodySource::Replay);
  EXPECT_EQ(left.bodies, (std::map<std::string, std::string>{{"rod", kRod}}));
}

TEST(PanelDiscovery, NothingPublishedIsTheNodeWithNoBodies) {
  const Discovery found = discoverBodies(MasterLists{}, "/sim");
  EXPECT_EQ(found.source, BodySource::Node);
  EXPECT_TRUE(found.bodies.empty());
}
