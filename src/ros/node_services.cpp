#include "rigid_body_sim/ros/node_services.h"

#include <type_traits>

#include "rigid_body_sim/core/node_interface.h"
#include "rigid_body_sim/io/config_loader.h"
#include "rigid_body_sim/io/config_writer.h"

namespace rigid_body_sim {

NodeServices::NodeServices(ros::NodeHandle private_node, Calls calls) : calls_(std::move(calls)) {
  namespace names = node_interface;
  services_.push_back(private_node.advertiseService(names::kSpawn, &NodeServices::onSpawn, this));
  services_.push_back(private_node.advertiseService(names::kDelete, &NodeServices::onDelete, this));
  services_.push_back(private_node.advertiseService(names::kSetState, &NodeServices::onSetState, this));
  services_.push_back(private_node.advertiseService(names::kGetConfig, &NodeServices::onGetConfig, this));
  services_.push_back(private_node.advertiseService(names::kGetEvents, &NodeServices::onGetEvents, this));
  services_.push_back(private_node.advertiseService(names::kReset, &NodeServices::onReset, this));
  services_.push_back(private_node.advertiseService(names::kPause, &NodeServices::onPause, this));
  services_.push_back(private_node.advertiseService(names::kUnpause, &NodeServices::onUnpause, this));
  services_.push_back(private_node.advertiseService(names::kStep, &NodeServices::onStep, this));
}

template <class Response>
bool NodeServices::answer(WorldCommand::Kind kind, const std::string& body,
                          const std::function<void(WorldCommand&)>& fill, Response& response) {
  const ChangeAnswer answer = calls_.change(toString(kind), body, [&](const World&) {
    WorldCommand command;
    command.kind = kind;
    command.body = body;
    fill(command);
    return std::optional(command);
  });
  response.success = answer.accepted;
  response.message = answer.why;
  if constexpr (std::is_same_v<Response, Spawn::Response>) response.t = answer.t;
  return true;
}

bool NodeServices::onSpawn(Spawn::Request& request, Spawn::Response& response) {
  const auto body = [&](WorldCommand& command) {
    command.config = parseBodyText(request.name, request.body);
  };
  return answer(WorldCommand::Kind::Spawn, request.name, body, response);
}

bool NodeServices::onDelete(Delete::Request& request, Delete::Response& response) {
  const auto nothing = [](WorldCommand&) {};  // a delete brings no payload
  return answer(WorldCommand::Kind::Delete, request.name, nothing, response);
}

bool NodeServices::onSetState(SetState::Request& request, SetState::Response& response) {
  const auto state = [&](WorldCommand& command) {
    command.state = parseStateText(request.name, request.state);
  };
  return answer(WorldCommand::Kind::SetState, request.name, state, response);
}

bool NodeServices::onGetConfig(GetConfig::Request&, GetConfig::Response& response) {
  response.yaml = toYaml(calls_.config());
  return true;
}

bool NodeServices::onGetEvents(GetEvents::Request&, GetEvents::Response& response) {
  response.events = calls_.events();
  return true;
}

bool NodeServices::onReset(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  Delete::Response ignored;                   // ~reset answers nothing: a refusal is its WARN line alone
  const auto nothing = [](WorldCommand&) {};  // nor a reset
  return answer(WorldCommand::Kind::Reset, "", nothing, ignored);
}

bool NodeServices::onPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  calls_.pause(true);
  return true;
}

bool NodeServices::onUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  calls_.pause(false);
  return true;
}

bool NodeServices::onStep(Step::Request& request, Step::Response& response) {
  calls_.step(request.steps, response);
  if (!response.success) ROS_WARN_STREAM("~step " << response.message);
  return true;
}

}  // namespace rigid_body_sim
