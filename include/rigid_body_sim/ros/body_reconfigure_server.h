// One body's dynamic_reconfigure server: the protocol of dynamic_reconfigure::Server (the set_parameters
// service; the latched parameter_descriptions and parameter_updates; the values mirrored on the parameter
// server, for `rosparam get`), for any client of it (rqt_reconfigure, dynamic_reconfigure's Client), with
// the request type the .cfg generates. What differs is the cost of a start: the library's server reads each
// key from the parameter server and writes it back at its start, and again at each update, one call to the
// master a key each time (some 40 calls a body: 21 s until the last of a thousand bodies had one); this one
// registers its three interfaces and mirrors every key in one call. It takes no value from the parameter
// server: the node gives every key's value (its config, validated).
#pragma once

#include <exception>
#include <functional>
#include <utility>

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <ros/ros.h>
#include <xmlrpcpp/XmlRpcValue.h>
#include <boost/thread/recursive_mutex.hpp>

namespace rigid_body_sim {

// A config message's values as one struct for the parameter server.
XmlRpc::XmlRpcValue parameterValues(const dynamic_reconfigure::Config& config);

template <class Request>
class BodyReconfigureServer {
 public:
  // Rewrites a request (clamped to the .cfg's bounds, as the library's server does) to what runs.
  using Callback = std::function<void(Request& request)>;

  // Serves under `node`'s namespace, showing `initial`; `mutex` is held around every later change and
  // callback. The service comes last: a request finds everything else in place. Servers of different
  // bodies may be made at once on several threads (their calls to the master then overlap).
  BodyReconfigureServer(const ros::NodeHandle& node, boost::recursive_mutex& mutex, const Request& initial,
                        Callback callback)
      : node_(node), mutex_(mutex), callback_(std::move(callback)), config_(initial) {
    descriptions_ =
        node_.advertise<dynamic_reconfigure::ConfigDescription>("parameter_descriptions", 1, true);
    descriptions_.publish(Request::__getDescriptionMessage__());
    updates_ = node_.advertise<dynamic_reconfigure::Config>("parameter_updates", 1, true);
    show();
    service_ = node_.advertiseService("set_parameters", &BodyReconfigureServer::onSet, this);
  }
  BodyReconfigureServer(const BodyReconfigureServer&) = delete;
  BodyReconfigureServer& operator=(const BodyReconfigureServer&) = delete;

  // Shows `config`: on parameter_updates and the parameter server.
  void update(const Request& config) {
    const boost::recursive_mutex::scoped_lock lock(mutex_);
    config_ = config;
    show();
  }

 private:
  bool onSet(dynamic_reconfigure::Reconfigure::Request& request,
             dynamic_reconfigure::Reconfigure::Response& response) {
    const boost::recursive_mutex::scoped_lock lock(mutex_);
    Request asked = config_;
    asked.__fromMessage__(request.config);
    asked.__clamp__();
    try {
      callback_(asked);
    } catch (const std::exception& error) {  // as the library's server: the request then shows as asked
      ROS_WARN("Reconfigure callback failed with exception %s: ", error.what());
    }
    update(asked);
    asked.__toMessage__(response.config);
    return true;
  }

  void show() {
    dynamic_reconfigure::Config message;
    config_.__toMessage__(message);
    node_.setParam("", parameterValues(message));
    updates_.publish(message);
  }

  ros::NodeHandle node_;
  boost::recursive_mutex& mutex_;
  Callback callback_;
  Request config_;
  ros::ServiceServer service_;
  ros::Publisher descriptions_;
  ros::Publisher updates_;
};

}  // namespace rigid_body_sim
