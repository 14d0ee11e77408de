#include "rigid_body_sim/rviz/discovery.h"

#include <algorithm>

namespace rigid_body_sim {

namespace {

const std::string kDescriptions = "/parameter_descriptions";
const std::string kState = "/state";

// The body of a topic <prefix><body><suffix> (a body name holds no '/'), or "".
std::string bodyOf(const std::string& topic, const std::string& prefix, const std::string& suffix) {
  if (topic.size() <= prefix.size() + suffix.size() || topic.rfind(prefix, 0) != 0 ||
      topic.compare(topic.size() - suffix.size(), suffix.size(), suffix) != 0)
    return "";
  const std::string body = topic.substr(prefix.size(), topic.size() - prefix.size() - suffix.size());
  return body.find('/') == std::string::npos ? body : "";
}

std::string typeOf(const MasterLists& master, const std::string& topic) {
  const auto found = master.topic_types.find(topic);
  return found == master.topic_types.end() ? "" : found->second;
}

Discovery nodeBodies(const MasterLists& master, const std::string& node) {
  Discovery found;
  for (const auto& [topic, type] : master.topic_types) {
    const std::string body = bodyOf(topic, node + "/", kDescriptions);
    if (!body.empty()) found.bodies[body] = typeOf(master, node + "/" + body + kState);
  }
  return found;
}

// The state topics' publishers other than the node itself: the first of them plays the recording.
Discovery replayBodies(const MasterLists& master, const std::string& node) {
  Discovery found;
  found.source = BodySource::Replay;
  for (const auto& [topic, type] : master.topic_types) {
    const std::string body = bodyOf(topic, node + "/", kState);
    const auto by = master.publishers.find(topic);
    if (body.empty() || by == master.publishers.end()) continue;
    const auto& nodes = by->second;
    const auto other = std::find_if(nodes.begin(), nodes.end(), [&](const auto& n) { return n != node; });
    if (other == nodes.end()) continue;
    found.bodies[body] = type;
    if (found.player.empty()) found.player = *other;
  }
  const std::string pause = found.player + "/" + kPlayerPauseService;
  if (!found.player.empty() && master.services.count(pause)) found.pause_service = pause;
  return found;
}

}  // namespace

Discovery discoverBodies(const MasterLists& master, const std::string& node) {
  if (!master.services.count(node + "/pause")) {
    Discovery replay = replayBodies(master, node);
    if (!replay.bodies.empty()) return replay;
  }
  return nodeBodies(master, node);
}

}  // namespace rigid_body_sim
