#include "rigid_body_sim/ros/command_log.h"

#include <optional>
#include <set>

#include <rosbag/bag.h>
#include <rosbag/view.h>

#include "rigid_body_sim/io/config_writer.h"
#include "rigid_body_sim/ros/bag_recorder.h"
#include "rigid_body_sim/ros/body_types_ros.h"

namespace rigid_body_sim {

namespace {

const std::string kReplay = "(replay)";
const char* const kCommandTopic = "/sim/commands";

// /sim/commands, or the bag's one topic of type rigid_body_sim/Command.
std::string commandTopic(rosbag::Bag& bag, const std::string& path) {
  rosbag::View all(bag);
  std::set<std::string> topics;
  for (const rosbag::ConnectionInfo* connection : all.getConnections()) {
    if (connection->datatype == ros::message_traits::datatype<rigid_body_sim::Command>()) {
      topics.insert(connection->topic);
    }
  }
  if (topics.count(kCommandTopic)) return kCommandTopic;
  if (topics.size() == 1) return *topics.begin();
  throw ConfigError(kReplay, "bag", "'" + path + "'",
                    topics.empty() ? "a bag with /sim/commands (record it: sim.launch record:=true)"
                                   : "a bag with /sim/commands or a single topic of rigid_body_sim/Command");
}

// The simulated time of a state of any body type, or of a command; 0 for another message.
double simulatedTimeOf(const rosbag::MessageInstance& message) {
  std::optional<double> t;
  BodyTypes::forEach([&](auto type) {
    if (const auto state = message.instantiate<typename RosBodyType<decltype(type)>::StateMsg>())
      t = state->t;
  });
  if (t) return *t;
  if (const auto command = message.instantiate<rigid_body_sim::Command>()) return command->t;
  return 0.0;
}

}  // namespace

rigid_body_sim::Command toMessage(const WorldCommand& command, std::uint32_t index, double t,
                                  const ros::Time& stamp, const std::string& world_frame) {
  rigid_body_sim::Command message;
  message.header.seq = index;
  message.header.stamp = stamp;
  message.header.frame_id = world_frame;
  message.step = static_cast<std::uint64_t>(command.step);
  message.t = t;
  message.kind = toString(command.kind);
  message.body = command.body;
  message.yaml = payloadYaml(command);
  return message;
}

RecordedRun readRecordedRun(const std::string& path) {
  const std::unique_ptr<rosbag::Bag> bag = newBag();
  try {
    bag->open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& error) {
    throw ConfigError("cannot read bag '" + path + "': " + error.what());
  }
  const std::string topic = commandTopic(*bag, path);
  RecordedRun run;
  for (const rosbag::MessageInstance& message : rosbag::View(*bag)) {
    run.end_time = std::max(run.end_time, simulatedTimeOf(message));
    if (message.getTopic() != topic) continue;
    const auto command = message.instantiate<rigid_body_sim::Command>();
    const std::uint32_t expected = static_cast<std::uint32_t>(run.commands.size());
    if (command->header.seq != expected) {
      throw ConfigError(
          kReplay, topic, "seq " + std::to_string(command->header.seq),
          "seq " + std::to_string(expected) + " (the commands without a gap, from the config at 0)");
    }
    run.commands.push_back(commandFromText(command->kind, static_cast<std::int64_t>(command->step),
                                           command->body, command->yaml));
  }
  return run;
}

}  // namespace rigid_body_sim
