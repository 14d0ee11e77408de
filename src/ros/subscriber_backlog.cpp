#include "rigid_body_sim/ros/subscriber_backlog.h"

#include <string>
#include <vector>

#include <ros/publication.h>
#include <ros/topic_manager.h>

namespace rigid_body_sim {

std::uint64_t messagesHandedToSubscribers() {
  std::vector<std::string> topics;
  ros::TopicManager::instance()->getAdvertisedTopics(topics);
  std::uint64_t sent = 0;
  for (const auto& topic : topics) {
    const ros::PublicationPtr publication = ros::TopicManager::instance()->lookupPublication(topic);
    if (!publication) continue;  // unadvertised meanwhile
    // [topic, [[connection id, bytes sent, messages sent, connected], ...]] (ros/publication.cpp)
    XmlRpc::XmlRpcValue stats = publication->getStats();
    XmlRpc::XmlRpcValue& connections = stats[1];
    for (int i = 0; i < connections.size(); ++i) sent += static_cast<std::uint32_t>(int(connections[i][2]));
  }
  return sent;
}

}  // namespace rigid_body_sim
