#include "rigid_body_sim/adapters/bag_recorder.h"

#include <cstdio>

#include <boost/make_shared.hpp>

namespace rigid_body_sim {

std::string stateTopic(const std::string& node_namespace, const std::string& body) {
  return node_namespace + "/" + body + "/state";
}

std::string markerTopic(const std::string& node_namespace) { return node_namespace + "/markers"; }

BagRecorder::BagRecorder(const std::string& path, std::string node_namespace)
    : path_(path), node_namespace_(std::move(node_namespace)) {
  bag_.open(path_ + ".active", rosbag::bagmode::Write);
  open_ = true;
}

BagRecorder::~BagRecorder() {
  // An unfinished recording stays as <path>.active, the way `rosbag record` leaves one.
  if (open_) bag_.close();
}

void BagRecorder::writeStatic(const std::vector<geometry_msgs::TransformStamped>& transforms,
                              const visualization_msgs::MarkerArray& markers, const ros::Time& stamp) {
  // /tf_static is latched: a player hands it to late subscribers as a live node would.
  // rosbag stores a given connection header as it is: without type, md5sum and definition, Python's
  // rosbag (rosbag info, scripts) cannot read the bag.
  auto latched = boost::make_shared<ros::M_string>();
  (*latched)["type"] = ros::message_traits::datatype<tf2_msgs::TFMessage>();
  (*latched)["md5sum"] = ros::message_traits::md5sum<tf2_msgs::TFMessage>();
  (*latched)["message_definition"] = ros::message_traits::definition<tf2_msgs::TFMessage>();
  (*latched)["latching"] = "1";
  (*latched)["callerid"] = node_namespace_;
  tf2_msgs::TFMessage message;
  message.transforms = transforms;
  bag_.write("/tf_static", stamp, message, latched);
  bag_.write(markerTopic(node_namespace_), stamp, markers);
}

void BagRecorder::write(const Snapshot& snapshot, const std::vector<Body>& bodies, const ros::Time& stamp) {
  bag_.write("/tf", stamp, snapshot.tf);
  bag_.write(markerTopic(node_namespace_), stamp, snapshot.markers);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const std::string topic = stateTopic(node_namespace_, bodies[i].name);
    std::visit([&](const auto& msg) { bag_.write(topic, stamp, msg); }, snapshot.states[i]);
  }
}

void BagRecorder::close() {
  if (!open_) return;
  bag_.close();
  open_ = false;
  if (std::rename((path_ + ".active").c_str(), path_.c_str()) != 0) {
    throw rosbag::BagException("cannot rename '" + path_ + ".active' to '" + path_ + "'");
  }
}

}  // namespace rigid_body_sim
