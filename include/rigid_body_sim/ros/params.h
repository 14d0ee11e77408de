// The node's private parameters -> its options, and the same YAML tree a config file gives, so that one
// loader serves the node and `simulate`.
#pragma once

#include <optional>
#include <string>

#include <ros/node_handle.h>
#include <xmlrpcpp/XmlRpcValue.h>
#include <yaml-cpp/yaml.h>

#include "rigid_body_sim/core/parameters.h"
#include "rigid_body_sim/ros/scene.h"

namespace rigid_body_sim {

// The node's own options (private parameters beside the config keys; names in core/node_interface.h).
struct NodeOptions {
  double real_time_factor = 1.0;      // 1 = wall-clock pace, 0 = as fast as possible
  bool publish_clock = false;         // publish /clock (simulated time) for use_sim_time users
  double duration = 0.0;              // simulated seconds before the node shuts down; 0 = run until stopped
  double start_delay = 0.0;           // wall seconds before stepping starts (lets a recorder subscribe first)
  bool start_on_subscribers = false;  // start before start_delay once every state topic and /tf is subscribed
  bool start_paused = false;          // publish the first state, then wait for ~unpause or ~step
  std::string frame_prefix;           // in front of every frame published but world_frame ("left/": left/rod)
  std::optional<double> marker_rate;  // Hz of ~markers (trail pieces, labels); unset: markerRate()'s default
  double trail_length = MarkerOptions().seconds;  // simulated seconds of trail; 0 = no trails
  bool label_critical_angles = false;             // a roller's label: its critical angle, not its energy
  std::string bag;  // if set, the node writes every publication into this bag itself (as simulate --bag)
  // When the duration ends, end the roslaunch that started this node too (SIGINT, as Ctrl-C does): its
  // recorder and rviz with it. Never a rostest: its tests decide when it ends.
  bool end_launch = false;
};

// ~markers' rate: the option, at most publish_rate (refused above it in one line, as any bad option);
// unset: MarkerOptions' pieces_rate (10 Hz), or publish_rate if that is lower.
double markerRate(const NodeOptions& options, double publish_rate);
// The markers of the options (trail length, markerRate, labels): those of ~markers and of the node's bag.
MarkerOptions markerOptions(const NodeOptions& options, double publish_rate);

// The node's private namespace from the parameter server; throws ConfigError when it holds nothing.
XmlRpc::XmlRpcValue privateParams(const ros::NodeHandle& private_node);

// Converts a parameter-server value (maps, lists, numbers, strings, booleans) to YAML.
YAML::Node toYaml(XmlRpc::XmlRpcValue& value);

// The options in the private namespace; a missing one keeps its default. Throws ConfigError naming the
// option, its value and its range.
NodeOptions parseNodeOptions(XmlRpc::XmlRpcValue& private_namespace);

// The config in the private namespace, loaded and validated as a config file is: the node's options and
// the namespaces of the reconfigure servers (one per body) are left out; any other key stays, so that the
// loader refuses a typo. Throws ConfigError.
WorldConfig parseNodeConfig(XmlRpc::XmlRpcValue& private_namespace);

}  // namespace rigid_body_sim
