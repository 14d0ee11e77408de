// Writes what the node publishes into a bag with the rosbag C++ API: no master needed. Topic names are
// the node's (launch files name it `sim`): /tf, /tf_static, /sim/markers, /sim/<body>/state.
#pragma once

#include <string>
#include <vector>

#include <rosbag/bag.h>

#include "rigid_body_sim/adapters/ros_conversions.h"

namespace rigid_body_sim {

std::string stateTopic(const std::string& node_namespace, const std::string& body);
std::string markerTopic(const std::string& node_namespace);

class BagRecorder {
 public:
  // Writes to `path`.active and renames it to `path` on close(), as `rosbag record` does.
  BagRecorder(const std::string& path, std::string node_namespace = "/sim");
  ~BagRecorder();
  BagRecorder(const BagRecorder&) = delete;
  BagRecorder& operator=(const BagRecorder&) = delete;

  void writeStatic(const std::vector<geometry_msgs::TransformStamped>& transforms,
                   const visualization_msgs::MarkerArray& markers, const ros::Time& stamp);
  void write(const Snapshot& snapshot, const std::vector<Body>& bodies, const ros::Time& stamp);
  void close();

 private:
  std::string path_;
  std::string node_namespace_;
  rosbag::Bag bag_;
  bool open_ = false;
};

}  // namespace rigid_body_sim
