// A bag's messages as bytes, in the order written, for tests that compare what the node publishes or
// records with what `simulate --bag` writes, byte for byte.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <ros/serialization.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>

namespace rigid_body_sim::test {

struct BagMessage {
  std::string topic;
  ros::Time time;
  std::vector<std::uint8_t> bytes;
  bool operator==(const BagMessage& other) const {
    return topic == other.topic && time == other.time && bytes == other.bytes;
  }
};

template <class Message>
std::vector<std::uint8_t> bytesOf(const Message& message) {
  std::vector<std::uint8_t> bytes(ros::serialization::serializationLength(message));
  ros::serialization::OStream stream(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  ros::serialization::serialize(stream, message);
  return bytes;
}

// Every message of the bag at `path`, or of its `topics` if given.
inline std::vector<BagMessage> messagesOf(const std::string& path,
                                          const std::vector<std::string>& topics = {}) {
  rosbag::Bag bag(path);
  rosbag::View view;
  if (topics.empty())
    view.addQuery(bag);
  else
    view.addQuery(bag, rosbag::TopicQuery(topics));
  std::vector<BagMessage> messages;
  for (const rosbag::MessageInstance& m : view) {
    BagMessage message{m.getTopic(), m.getTime(), std::vector<std::uint8_t>(m.size())};
    ros::serialization::OStream stream(message.bytes.data(),
                                       static_cast<std::uint32_t>(message.bytes.size()));
    m.write(stream);
    messages.push_back(std::move(message));
  }
  return messages;
}

// Where two lists of messages first differ, for a failure that says where.
inline std::string firstDifference(const std::vector<BagMessage>& a, const std::vector<BagMessage>& b) {
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    if (!(a[i] == b[i]))
      return "message " + std::to_string(i) + ": " + a[i].topic + " at " + std::to_string(a[i].time.toSec()) +
             " vs " + b[i].topic + " at " + std::to_string(b[i].time.toSec());
  }
  return "counts " + std::to_string(a.size()) + " vs " + std::to_string(b.size());
}

}  // namespace rigid_body_sim::test
