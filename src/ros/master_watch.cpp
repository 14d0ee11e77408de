#include "rigid_body_sim/ros/master_watch.h"

#include <ros/master.h>
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

}  // namespace rigid_body_sim
