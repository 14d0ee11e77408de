#include "rigid_body_sim/ros/reconfigure_servers.h"

#include <utility>

#include <ros/callback_queue.h>
#include <boost/make_shared.hpp>

#include "rigid_body_sim/ros/reconfigure.h"

namespace rigid_body_sim {

namespace {

// A callback on the spinner thread's queue, behind those waiting.
class Deferred : public ros::CallbackInterface {
 public:
  explicit Deferred(std::function<void()> work) : work_(std::move(work)) {}
  CallResult call() override {
    work_();
    return Success;
  }

 private:
  std::function<void()> work_;
};

template <class Config>
Config withKeysOf(const std::string& body, const Config& current, const std::map<std::string, double>& keys) {
  auto request = toReconfigure(current);
  dynamic_reconfigure::Config asked;
  for (const auto& [key, value] : keys) {
    dynamic_reconfigure::DoubleParameter parameter;
    parameter.name = key;
    parameter.value = value;
    asked.doubles.push_back(parameter);
  }
  request.__fromMessage__(asked);
  return fromReconfigure(body, request, current);
}

}  // namespace

ReconfigureServers::ReconfigureServers(ros::NodeHandle private_node, Change change, Lookup lookup)
    : private_node_(std::move(private_node)), change_(std::move(change)), lookup_(std::move(lookup)) {}

ReconfigureServers::~ReconfigureServers() {
  ros::getGlobalCallbackQueue()->removeByID(reinterpret_cast<std::uint64_t>(this));
}

BodyConfig ReconfigureServers::withKeys(const BodyConfig& body, const std::map<std::string, double>& keys) {
  return {body.name, std::visit(
                         [&](const auto& config) -> decltype(BodyConfig::config) {
                           return withKeysOf(body.name, config, keys);
                         },
                         body.config)};
}

void ReconfigureServers::defer(std::function<void()> work) {
  ros::getGlobalCallbackQueue()->addCallback(boost::make_shared<Deferred>(std::move(work)),
                                             reinterpret_cast<std::uint64_t>(this));
}

void ReconfigureServers::startAll(std::function<WorldConfig()> config) {
  defer([this, config = std::move(config)] {
    for (const auto& body : config().bodies) waiting_.push_back(body.name);
    startNext();
  });
}

void ReconfigureServers::stop() { stopped_ = true; }

void ReconfigureServers::startNext() {
  while (!waiting_.empty() && ros::ok() && !stopped_) {
    const std::string name = waiting_.front();
    waiting_.pop_front();
    if (servers_.count(name)) continue;
    const std::optional<BodyConfig> body = lookup_(name);
    if (!body) continue;
    start(*body);
    defer([this] { startNext(); });
    return;
  }
}

// The body's values go to its server before its callback is set, so that they win over the .cfg defaults;
// the first callback then finds nothing to change.
void ReconfigureServers::start(const BodyConfig& body) {
  const ros::NodeHandle body_node(private_node_, body.name);
  const std::string name = body.name;
  std::visit(
      [&](const auto& config) {
        using Config = std::decay_t<decltype(config)>;
        using Request = typename RosBodyType<TypeOfConfig<Config>>::Reconfigure;
        auto server = std::make_unique<dynamic_reconfigure::Server<Request>>(mutex_, body_node);
        server->updateConfig(toReconfigure(config));
        server->setCallback([this, name](Request& request, uint32_t) { onRequest<Config>(name, request); });
        servers_[name] = std::move(server);
      },
      body.config);
}

// The request is rewritten to what runs, so that the server shows the truth.
template <class Config, class Request>
void ReconfigureServers::onRequest(const std::string& name, Request& request) {
  const auto runs = change_(name, [&](const BodyConfig& running) {
    return BodyConfig{name, fromReconfigure(name, request, std::get<Config>(running.config))};
  });
  if (runs) request = toReconfigure(std::get<Config>(runs->config));
}

void ReconfigureServers::follow(const WorldCommand& command) {
  if (command.kind == WorldCommand::Kind::Spawn) start(command.config);
  if (command.kind == WorldCommand::Kind::Delete) servers_.erase(command.body);
  const auto server = servers_.find(command.body);  // none yet: it will start with the values that run then
  if (command.kind != WorldCommand::Kind::Reconfigure || server == servers_.end()) return;
  std::visit(
      [&](const auto& config) {  // a reconfigure keeps the body's type (World::apply refuses another)
        if (auto* running = std::get_if<ServerOf<TypeOfConfig<decltype(config)>>>(&server->second)) {
          (*running)->updateConfig(toReconfigure(config));
        }
      },
      command.config.config);
}

}  // namespace rigid_body_sim
