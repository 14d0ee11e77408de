// The dynamic_reconfigure server of each body of a node, at <private namespace>/<body>, with the body's
// keys (cfg/*.cfg). A request is handed to the node as a change of the body's running config; the server
// then shows what runs (a refused or partly refused request snaps back).
//
// Owned by the spinner thread: every call, and every server callback, comes from it. The servers start
// after stepping has (each takes four calls to the master: the first states of a thousand bodies do not
// wait), a batch per callback behind those waiting, so that the node's services answer meanwhile. A body
// spawned meanwhile has its own already; one deleted meanwhile gets none.
#pragma once

#include <atomic>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "rigid_body_sim/core/command.h"
#include "rigid_body_sim/core/parameters.h"
#include "rigid_body_sim/ros/body_reconfigure_server.h"
#include "rigid_body_sim/ros/body_types_ros.h"

namespace rigid_body_sim {

class ReconfigureServers {
 public:
  // The body's config as a request asks for it, from the config that runs (ConfigError: a name no enum
  // allows).
  using Reconfigured = std::function<BodyConfig(const BodyConfig& running)>;
  // Makes the change `reconfigured` of body `name` (or refuses it); returns the body's config as it runs
  // afterwards, none if there is no such body.
  using Change =
      std::function<std::optional<BodyConfig>(const std::string& name, const Reconfigured& reconfigured)>;
  // The config body `name` runs now, none if there is no such body.
  using Lookup = std::function<std::optional<BodyConfig>(const std::string& name)>;

  ReconfigureServers(ros::NodeHandle private_node, Change change, Lookup lookup);
  ~ReconfigureServers();  // its callbacks still waiting are dropped
  ReconfigureServers(const ReconfigureServers&) = delete;
  ReconfigureServers& operator=(const ReconfigureServers&) = delete;

  // Behind the callbacks waiting: a server for each body of the world `config()` gives then, one per
  // callback.
  void startAll(std::function<WorldConfig()> config);
  void stop();  // no server starts from now on (the node shuts down)

  // After an accepted command: a spawned body's server starts, a deleted one's goes, a reconfigured one
  // shows the values that now run.
  void follow(const WorldCommand& command);

  // `body` with numeric keys set as a request to its server sets them (the same parsing): a drop in rviz.
  static BodyConfig withKeys(const BodyConfig& body, const std::map<std::string, double>& keys);

 private:
  template <class Type>
  using ServerOf = std::unique_ptr<BodyReconfigureServer<typename RosBodyType<Type>::Reconfigure>>;
  template <class List>
  struct ServerVariant;
  template <class... Types>
  struct ServerVariant<BodyTypeList<Types...>> {
    using type = std::variant<ServerOf<Types>...>;
  };
  using BodyServer = ServerVariant<BodyTypes>::type;  // the server of the body's type

  void defer(std::function<void()> work);  // behind the callbacks waiting on the spinner thread
  void startNext();
  void start(const BodyConfig& body);
  BodyServer serverOf(const BodyConfig& body);  // any thread: touches nothing of this object but mutex_
  template <class Config, class Request>
  void onRequest(const std::string& name, Request& request);

  ros::NodeHandle private_node_;
  Change change_;
  Lookup lookup_;
  std::atomic<bool> stopped_{false};
  boost::recursive_mutex mutex_;               // held while a server changes or calls back
  std::map<std::string, BodyServer> servers_;  // by body name
  std::deque<std::string> waiting_;            // bodies whose server startAll has yet to start
};

}  // namespace rigid_body_sim
