// sim_node's services. ~spawn, ~delete, ~set_state and ~reset turn a request into the command of a change
// (built on the stepping thread from the running world, a ConfigError its refusal) and hand it to the node's
// one path for every change (docs/commands.md); ~get_config, ~get_events, ~pause, ~unpause and ~step hand
// their work to the node likewise. The services' callbacks run on the spinner thread.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <std_srvs/Empty.h>

#include "rigid_body_sim/Delete.h"
#include "rigid_body_sim/GetConfig.h"
#include "rigid_body_sim/GetEvents.h"
#include "rigid_body_sim/SetState.h"
#include "rigid_body_sim/Spawn.h"
#include "rigid_body_sim/Step.h"
#include "rigid_body_sim/core/world.h"

namespace rigid_body_sim {

// A change of the world as the stepping thread answers it.
struct ChangeAnswer {
  bool accepted = false;
  std::string why;                      // "ok", or the one refusal line
  double t = 0.0;                       // the simulated time it applied at (its ~commands entry's t), or then
  std::optional<WorldCommand> command;  // as applied; none for a request that changes nothing
  WorldConfig config;                   // the world's after it
};
// Makes the command of a change from the running world: none if it changes nothing; a ConfigError is its
// refusal.
using BuildCommand = std::function<std::optional<WorldCommand>(const World& world)>;
// The node's one path for every change: `kind` and `body` name it in a refusal.
using ChangeWorld =
    std::function<ChangeAnswer(const std::string& kind, const std::string& body, const BuildCommand& build)>;

class NodeServices {
 public:
  struct Calls {
    ChangeWorld change;
    std::function<WorldConfig()> config;                                      // ~get_config: what runs
    std::function<void(bool paused)> pause;                                   // ~pause, ~unpause
    std::function<void(std::uint64_t steps, Step::Response& response)> step;  // ~step
    std::function<std::vector<Event>()> events;                               // ~get_events
  };
  // Advertises every service in `private_node`.
  NodeServices(ros::NodeHandle private_node, Calls calls);

 private:
  // A change of one body: `fill` puts in what the request brings (a ConfigError refuses it); the response
  // says whether it applied, the one line if not, and (~spawn) the time it applied at.
  template <class Response>
  bool answer(WorldCommand::Kind kind, const std::string& body,
              const std::function<void(WorldCommand&)>& fill, Response& response);
  bool onSpawn(Spawn::Request& request, Spawn::Response& response);
  bool onDelete(Delete::Request& request, Delete::Response& response);
  bool onSetState(SetState::Request& request, SetState::Response& response);
  bool onGetConfig(GetConfig::Request& request, GetConfig::Response& response);
  bool onGetEvents(GetEvents::Request& request, GetEvents::Response& response);
  bool onReset(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onStep(Step::Request& request, Step::Response& response);

  Calls calls_;
  std::vector<ros::ServiceServer> services_;
};

}  // namespace rigid_body_sim
