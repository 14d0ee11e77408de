#include "rigid_body_sim/ros/params.h"

#include <sstream>

namespace rigid_body_sim {

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
    case XmlRpc::XmlRpcValue::TypeString: return YAML::Node(static_cast<std::string>(value));
    default: return YAML::Node();
  }
}

YAML::Node configFromParams(XmlRpc::XmlRpcValue& private_namespace, const std::set<std::string>& ignored) {
  YAML::Node config(YAML::NodeType::Map);
  if (private_namespace.getType() != XmlRpc::XmlRpcValue::TypeStruct) return config;
  for (auto& entry : private_namespace) {
    if (!ignored.count(entry.first)) config[entry.first] = toYaml(entry.second);
  }
  return config;
}

}  // namespace rigid_body_sim
