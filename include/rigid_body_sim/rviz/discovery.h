// What the SimPanel follows, from what the master lists: the node's bodies (its reconfigure servers), or a
// replay of a recording, when the node is not there but its bodies' state topics are published by another
// node (rosbag play). Pure: the panel's worker asks the master and hands its lists in.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

namespace rigid_body_sim {

// The master's lists: published topics with their types and publishers, and services.
struct MasterLists {
  std::map<std::string, std::string> topic_types;
  std::map<std::string, std::vector<std::string>> publishers;
  std::set<std::string> services;
};

enum class BodySource { Node, Replay };

struct Discovery {
  BodySource source = BodySource::Node;
  std::map<std::string, std::string> bodies;  // name -> state message type ("" while not published)
  std::string player;                         // Replay: the node that publishes the states
  std::string pause_service;                  // Replay: the player's pause_playback, "" if it has none
};

// rosbag play's service (std_srvs/SetBool: true pauses, false resumes), under the player's node name.
inline constexpr const char* kPlayerPauseService = "pause_playback";

// `node` is the node's resolved name (/sim). A replay: no <node>/pause service, and <node>/<body>/state
// topics published by a node other than `node`. Otherwise the node's bodies: its
// <node>/<body>/parameter_descriptions topics.
Discovery discoverBodies(const MasterLists& master, const std::string& node);

}  // namespace rigid_body_sim
