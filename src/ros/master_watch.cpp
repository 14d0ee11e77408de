#include "rigid_body_sim/ros/master_watch.h"

#include <xmlrpcpp/XmlRpcClient.h>

#include <ros/master.h>
#include <ros/network.h>
#include <ros/this_node.h>
#include <ros/xmlrpc_manager.h>

namespace rigid_body_sim {

MasterView askMaster() {
  XmlRpc::XmlRpcValue args, response, payload;
  args[0] = ros::this_node::getName();
  args[1] = ros::this_node::getName();
  // execute() is false both without an answer and with an answer that is an error ("unknown node"):
  // only the answer itself (code, message, value) tells them apart.
  const bool known = ros::master::execute("lookupNode", args, response, payload, false);
  if (!known) {
    const bool answered = response.getType() == XmlRpc::XmlRpcValue::TypeArray && response.size() == 3;
    return answered ? MasterView::Forgot : MasterView::Unreachable;
  }
  const bool ours = payload.getType() == XmlRpc::XmlRpcValue::TypeString &&
                    static_cast<std::string>(payload) == ros::XMLRPCManager::instance()->getServerURI();
  return ours ? MasterView::Knows : MasterView::Forgot;
}

bool shutDownNode(const std::string& name, const std::string& reason, std::string* why) {
  XmlRpc::XmlRpcValue args, response, payload;
  args[0] = ros::this_node::getName();
  args[1] = name;
  std::string host;
  std::uint32_t port = 0;
  if (!ros::master::execute("lookupNode", args, response, payload, false) ||
      payload.getType() != XmlRpc::XmlRpcValue::TypeString ||
      !ros::network::splitURI(static_cast<std::string>(payload), host, port)) {
    *why = "the master knows no node " + name;
    return false;
  }
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue request, answer;
  request[0] = ros::this_node::getName();
  request[1] = reason;
  if (!client.execute("shutdown", request, answer)) {
    *why = name + " did not answer at " + static_cast<std::string>(payload);
    return false;
  }
  return true;
}

}  // namespace rigid_body_sim
