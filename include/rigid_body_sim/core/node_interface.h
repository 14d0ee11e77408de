// The names sim_node takes in its private namespace beside the config's keys: its options, topics and
// services, listed once. The node reads its options (ros/params.h) and advertises under these names. A body
// shares that namespace, so the World's validation of a config reserves them (ownNames()) for every program
// that reads one: a file `simulate` runs is one the node runs too. Plain names: no ROS header.
#pragma once

#include <string>
#include <vector>

namespace rigid_body_sim::node_interface {

// Options (private parameters)
inline constexpr const char* kRealTimeFactor = "real_time_factor";
inline constexpr const char* kPublishClock = "publish_clock";
inline constexpr const char* kDuration = "duration";
inline constexpr const char* kStartDelay = "start_delay";
inline constexpr const char* kStartPaused = "start_paused";
inline constexpr const char* kStartOnSubscribers = "start_on_subscribers";
inline constexpr const char* kFramePrefix = "frame_prefix";
inline constexpr const char* kMarkerRate = "marker_rate";
inline constexpr const char* kTrailLength = "trail_length";
inline constexpr const char* kLabelCriticalAngles = "label_critical_angles";
inline constexpr const char* kBag = "bag";
inline constexpr const char* kEndLaunch = "end_launch";
// Topics and services (each body adds ~<body>/state and its reconfigure server ~<body>)
inline constexpr const char* kMarkers = "markers";
inline constexpr const char* kScene = "scene";
inline constexpr const char* kReset = "reset";
inline constexpr const char* kPause = "pause";
inline constexpr const char* kUnpause = "unpause";
inline constexpr const char* kStep = "step";
inline constexpr const char* kSpawn = "spawn";
inline constexpr const char* kDelete = "delete";
inline constexpr const char* kSetState = "set_state";
inline constexpr const char* kGetConfig = "get_config";
inline constexpr const char* kCommands = "commands";        // every accepted change of the world, latched
inline constexpr const char* kEvents = "events";            // what happened, an Event a message, none dropped
inline constexpr const char* kGetEvents = "get_events";     // the current run's events, for a late subscriber
inline constexpr const char* kPaused = "paused";            // whether stepping is paused, latched
inline constexpr const char* kInteractive = "interactive";  // the interactive marker server's namespace

// A body's state topic, relative to the node's private namespace.
inline std::string stateTopic(const std::string& body) { return body + "/state"; }

// In a namespace other than the root, the node also sends its transforms on these topics of that namespace
// (/left/tf, /left/tf_static beside /tf, /tf_static), so that a recorder of the namespace records only
// its own instance's transforms.
inline constexpr const char* kNamespaceTf = "tf";
inline constexpr const char* kNamespaceTfStatic = "tf_static";

inline const std::vector<std::string>& optionNames() {
  static const std::vector<std::string> names = {
      kRealTimeFactor,     kPublishClock,        kDuration,    kStartDelay,
      kStartOnSubscribers, kStartPaused,         kFramePrefix, kMarkerRate,
      kTrailLength,        kLabelCriticalAngles, kBag,         kEndLaunch};
  return names;
}

// Every name above: what the config loader refuses as a body name.
inline const std::vector<std::string>& ownNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all = optionNames();
    all.insert(all.end(), {kMarkers, kScene, kReset, kPause, kUnpause, kStep, kSpawn, kDelete, kSetState,
                           kGetConfig, kCommands, kEvents, kGetEvents, kPaused, kInteractive});
    return all;
  }();
  return names;
}

}  // namespace rigid_body_sim::node_interface
