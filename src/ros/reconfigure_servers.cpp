#include "rigid_body_sim/ros/reconfigure_servers.h"

#include <algorithm>
#include <thread>
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

XmlRpc::XmlRpcValue parameterValues(const dynamic_reconfigure::Config& config) {
  XmlRpc::XmlRpcValue values;
  for (const auto& parameter : config.bools) values[parameter.name] = static_cast<bool>(parameter.value);
  for (const auto& parameter : config.ints) values[parameter.name] = parameter.value;
  for (const auto& parameter : config.strs) values[parameter.name] = parameter.value;
  for (const auto& parameter : config.doubles) values[parameter.name] = parameter.value;
  return values;
}

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

// A batch of servers at a time, made on kStartThreads threads at once: each server's four calls to the
// master wait mostly for the master, which answers each call on a thread of its own. The spinner thread
// waits for the batch (at most some 0.1 s), then the callbacks behind it run.
void ReconfigureServers::startNext() {
  constexpr std::size_t kBatch = 64;
  constexpr std::size_t kStartThreads = 4;
  std::vector<BodyConfig> batch;
  while (!waiting_.empty() && batch.size() < kBatch && ros::ok() && !stopped_) {
    const std::string name = waiting_.front();
    waiting_.pop_front();
    if (servers_.count(name)) continue;
    if (std::optional<BodyConfig> body = lookup_(name)) batch.push_back(std::move(*body));
  }
  if (batch.empty()) return;
  std::vector<BodyServer> made(batch.size());
  std::vector<std::thread> threads;
  for (std::size_t first = 0; first < std::min(kStartThreads, batch.size()); ++first) {
    threads.emplace_back([&, first] {
      for (std::size_t i = first; i < batch.size(); i += kStartThreads) made[i] = serverOf(batch[i]);
    });
  }
  for (auto& thread : threads) thread.join();
  for (std::size_t i = 0; i < batch.size(); ++i) servers_[batch[i].name] = std::move(made[i]);
  defer([this] { startNext(); });
}

void ReconfigureServers::start(const BodyConfig& body) { servers_[body.name] = serverOf(body); }

ReconfigureServers::BodyServer ReconfigureServers::serverOf(const BodyConfig& body) {
  const ros::NodeHandle body_node(private_node_, body.name);
  const std::string name = body.name;
  return std::visit(
      [&](const auto& config) -> BodyServer {
        using Config = std::decay_t<decltype(config)>;
        using Request = typename RosBodyType<TypeOfConfig<Config>>::Reconfigure;
        return std::make_unique<BodyReconfigureServer<Request>>(
            body_node, mutex_, toReconfigure(config),
            [this, name](Request& request) { onRequest<Config>(name, request); });
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
          (*running)->update(toReconfigure(config));
        }
      },
      command.config.config);
}

}  // namespace rigid_body_sim
