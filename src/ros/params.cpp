#include "rigid_body_sim/ros/params.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <sstream>

#include <ros/param.h>

#include "rigid_body_sim/core/node_interface.h"
#include "rigid_body_sim/io/config_loader.h"

namespace rigid_body_sim {

namespace {

const std::string kNode = "(node)";

double numberOption(const YAML::Node& params, const std::string& key, double fallback, const Range& range) {
  if (!params[key]) return fallback;
  double value = NAN;
  try {
    value = params[key].as<double>();
  } catch (const YAML::Exception&) {
    throw ConfigError(kNode, key, "'" + params[key].Scalar() + "'", range.describe());
  }
  if (!range.contains(value)) throw ConfigError(kNode, key, formatNumber(value), range.describe());
  return value;
}

bool boolOption(const YAML::Node& params, const std::string& key, bool fallback) {
  if (!params[key]) return fallback;
  try {
    return params[key].as<bool>();
  } catch (const YAML::Exception&) {
    throw ConfigError(kNode, key, "'" + params[key].Scalar() + "'", "true or false");
  }
}

// Empty, or letters, digits, _ and / starting with a letter and ending in /, no empty level ("a//b"): what
// tf2 takes as the start of a frame id, and a prefix that keeps the frame's own name apart ("left" would
// make "leftrod").
bool isFramePrefix(const std::string& prefix) {
  if (prefix.empty()) return true;
  if (!std::isalpha(static_cast<unsigned char>(prefix[0])) || prefix.find("//") != std::string::npos ||
      prefix.back() != '/')
    return false;
  return std::all_of(prefix.begin(), prefix.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '/';
  });
}

std::string framePrefixOption(const YAML::Node& params, const std::string& key) {
  const std::string allowed =
      "empty, or letters, digits, _ and / starting with a letter and ending in / (e.g. left/)";
  if (!params[key]) return "";
  if (!params[key].IsScalar()) throw ConfigError(kNode, key, "(not a text)", allowed);
  const std::string prefix = params[key].Scalar();
  if (!isFramePrefix(prefix)) throw ConfigError(kNode, key, "'" + prefix + "'", allowed);
  return prefix;
}

bool isMap(XmlRpc::XmlRpcValue& value) { return value.getType() == XmlRpc::XmlRpcValue::TypeStruct; }

}  // namespace

XmlRpc::XmlRpcValue privateParams(const ros::NodeHandle& private_node) {
  XmlRpc::XmlRpcValue params;
  if (!ros::param::get(private_node.getNamespace(), params)) {
    throw ConfigError("no parameters in " + private_node.getNamespace() +
                      ": load a config (rosparam load, or the launch files' config arg)");
  }
  return params;
}

namespace {
// True for a text that YAML 1.1 reads as a number or a boolean when it is not quoted (rosparam's reading).
bool readsAsNumberOrBool(const std::string& text) {
  try {
    const YAML::Node plain = YAML::Load(text);
    double number = 0.0;
    bool boolean = false;
    return plain.IsScalar() && plain.Tag() == "?" &&
           (YAML::convert<double>::decode(plain, number) || YAML::convert<bool>::decode(plain, boolean));
  } catch (const YAML::Exception&) {
    return false;  // no scalar at all: a text
  }
}
}  // namespace

YAML::Node toYaml(XmlRpc::XmlRpcValue& value) {
  switch (value.getType()) {
    case XmlRpc::XmlRpcValue::TypeStruct: {
      YAML::Node map(YAML::NodeType::Map);
      for (auto& entry : value) map[entry.first] = toYaml(entry.second);
      return map;
    }
    case XmlRpc::XmlRpcValue::TypeArray: {
      YAML::Node list(YAML::NodeType::Sequence);
      for (int i = 0; i < value.size(); ++i) list.push_back(toYaml(value[i]));
      return list;
    }
    case XmlRpc::XmlRpcValue::TypeBoolean: return YAML::Node(static_cast<bool>(value) ? "true" : "false");
    case XmlRpc::XmlRpcValue::TypeInt: return YAML::Node(static_cast<int>(value));
    case XmlRpc::XmlRpcValue::TypeDouble: {
      // Full precision, so that a value reads back exactly.
      std::ostringstream text;
      text.precision(17);
      text << static_cast<double>(value);
      return YAML::Node(text.str());
    }
    case XmlRpc::XmlRpcValue::TypeString: {
      // A string that a file would have given as a number or a boolean was quoted there ("0.5", "true"): it
      // is tagged as the parser tags a quoted scalar ("!"), so that the loader refuses it where a number or
      // a boolean is due with the same line as for the file. Any other text reads as the file's plain one.
      YAML::Node text(static_cast<std::string>(value));
      if (readsAsNumberOrBool(text.Scalar())) text.SetTag("!");
      return text;
    }
    default: return YAML::Node();
  }
}

NodeOptions parseNodeOptions(XmlRpc::XmlRpcValue& private_namespace) {
  namespace names = node_interface;
  const YAML::Node yaml = toYaml(private_namespace);
  NodeOptions options;
  options.real_time_factor = numberOption(yaml, names::kRealTimeFactor, options.real_time_factor, {0.0, 1e6});
  options.publish_clock = boolOption(yaml, names::kPublishClock, options.publish_clock);
  options.duration = numberOption(yaml, names::kDuration, options.duration, {0.0, 1e7});
  options.start_delay = numberOption(yaml, names::kStartDelay, options.start_delay, {0.0, 60.0});
  options.start_on_subscribers = boolOption(yaml, names::kStartOnSubscribers, options.start_on_subscribers);
  options.start_paused = boolOption(yaml, names::kStartPaused, options.start_paused);
  options.frame_prefix = framePrefixOption(yaml, names::kFramePrefix);
  if (yaml[names::kMarkerRate]) {
    options.marker_rate = numberOption(yaml, names::kMarkerRate, 0.0, {0.0, 1e6, true});
  }
  options.trail_length = numberOption(yaml, names::kTrailLength, options.trail_length, {0.0, 3600.0});
  options.label_critical_angles =
      boolOption(yaml, names::kLabelCriticalAngles, options.label_critical_angles);
  if (yaml[names::kBag]) {
    if (!yaml[names::kBag].IsScalar()) throw ConfigError(kNode, names::kBag, "(not a text)", "a file path");
    options.bag = yaml[names::kBag].Scalar();
  }
  options.end_launch = boolOption(yaml, names::kEndLaunch, options.end_launch);
  return options;
}

double markerRate(const NodeOptions& options, double publish_rate) {
  if (!options.marker_rate) return std::min(MarkerOptions().pieces_rate, publish_rate);
  const Range range{0.0, publish_rate, true};
  if (!range.contains(*options.marker_rate)) {
    throw ConfigError(kNode, node_interface::kMarkerRate, formatNumber(*options.marker_rate),
                      range.describe() + " (at most publish_rate)");
  }
  return *options.marker_rate;
}

MarkerOptions markerOptions(const NodeOptions& options, double publish_rate) {
  return {options.trail_length, markerRate(options, publish_rate), options.label_critical_angles};
}

WorldConfig parseNodeConfig(XmlRpc::XmlRpcValue& private_namespace) {
  YAML::Node config(YAML::NodeType::Map);
  if (!isMap(private_namespace)) return parseWorldConfig(config);
  const auto& options = node_interface::optionNames();
  std::set<std::string> ignored(options.begin(), options.end());
  if (private_namespace.hasMember("bodies") && isMap(private_namespace["bodies"])) {
    for (auto& body : private_namespace["bodies"]) ignored.insert(body.first);
  }
  for (auto& entry : private_namespace) {
    if (!ignored.count(entry.first)) config[entry.first] = toYaml(entry.second);
  }
  return parseWorldConfig(config);
}

}  // namespace rigid_body_sim
