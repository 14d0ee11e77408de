#include "rigid_body_sim/io/config_writer.h"

#include "rigid_body_sim/io/config_loader.h"

namespace rigid_body_sim {

namespace {

// Names (bodies, frames, keys, enum values) are validated to [A-Za-z0-9_]: plain YAML scalars as they are.
std::string entry(const std::string& key, const std::string& value) { return key + ": " + value; }

// Every key its type writes, in the description's order: what the loader reads back to the same config.
template <class Config>
std::string bodyKeys(const Config& config) {
  const BodyType<Config>& type = bodyType<Config>();
  std::string out = entry("type", type.type);
  for (const auto& key : type.keys) {
    if (key.written()) out += ", " + entry(key.name, key.text(config));
  }
  return out;
}

WorldCommand::Kind kindFrom(const std::string& name) {
  const auto kind = commandKindFromString(name);
  if (!kind) {
    throw ConfigError("(command)", "kind", "'" + name + "'",
                      "config, reconfigure, spawn, delete, set_state or reset");
  }
  return *kind;
}

}  // namespace

std::string toYaml(const WorldConfig& config) {
  std::string out = entry("rate", formatNumber(config.rate)) + "\n" +
                    entry("publish_rate", formatNumber(config.publish_rate)) + "\n" +
                    entry("gravity", formatNumber(config.gravity)) + "\n" +
                    entry("world_frame", config.world_frame) + "\n" +
                    entry("race", config.race ? "true" : "false") + "\nbodies:\n";
  for (const auto& body : config.bodies) out += "  " + entry(body.name, toYaml(body)) + "\n";
  return out;
}

std::string toYaml(const BodyConfig& body) {
  return "{" + std::visit([](const auto& config) { return bodyKeys(config); }, body.config) + "}";
}

std::string toYaml(const std::vector<StateValue>& state) {
  std::string out;
  for (const auto& value : state)
    out += (out.empty() ? "" : ", ") + entry(value.field, formatNumber(value.value));
  return "{" + out + "}";
}

std::string payloadYaml(const WorldCommand& command) {
  switch (command.kind) {
    case WorldCommand::Kind::Config: return toYaml(command.world);
    case WorldCommand::Kind::Reconfigure:
    case WorldCommand::Kind::Spawn: return toYaml(command.config);
    case WorldCommand::Kind::SetState: return toYaml(command.state);
    case WorldCommand::Kind::Delete:
    case WorldCommand::Kind::Reset: return "";
  }
  return "";
}

WorldCommand commandFromText(const std::string& kind, std::int64_t step, const std::string& body,
                             const std::string& yaml) {
  WorldCommand command;
  command.kind = kindFrom(kind);
  command.step = step;
  command.body = body;
  switch (command.kind) {
    case WorldCommand::Kind::Config: command.world = parseWorldConfigText(yaml, "(config command)"); break;
    case WorldCommand::Kind::Reconfigure:
    case WorldCommand::Kind::Spawn: command.config = parseBodyText(body, yaml); break;
    case WorldCommand::Kind::SetState: command.state = parseStateText(body, yaml); break;
    case WorldCommand::Kind::Delete:
    case WorldCommand::Kind::Reset: break;
  }
  return command;
}

}  // namespace rigid_body_sim
