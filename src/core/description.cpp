#include "rigid_body_sim/core/description.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "rigid_body_sim/core/parameters.h"
#include "rigid_body_sim/core/state_fields.h"

namespace rigid_body_sim {

namespace {

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (const char ch : text) {
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (static_cast<unsigned char>(ch) < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", ch);
      out += escaped;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

// A number as JSON writes it: shortest round-trip digits (JSON has no infinity: a null).
std::string number(double value) { return std::isfinite(value) ? formatNumber(value) : "null"; }

std::string list(const std::vector<std::string>& items) {
  std::string out = "[";
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + items[i];
  return out + "]";
}

std::string object(const std::vector<std::pair<std::string, std::string>>& members) {
  std::string out = "{";
  for (std::size_t i = 0; i < members.size(); ++i) {
    out += (i ? ", " : "") + quoted(members[i].first) + ": " + members[i].second;
  }
  return out + "}";
}

std::string rangeOf(const Range& range) {
  return object({{"min", number(range.min)},
                 {"max", number(range.max)},
                 {"min_open", range.min_open ? "true" : "false"},
                 {"max_open", range.max_open ? "true" : "false"}});
}

template <class Config>
std::string keyOf(const BodyKey<Config>& key) {
  const Config defaults;
  std::vector<std::pair<std::string, std::string>> members{
      {"name", quoted(key.name)},
      {"kind", quoted(key.isNumber() ? "number" : "text")},
      {"unit", quoted(key.unit)},
      {"meaning", quoted(key.meaning)},
      {"level", std::to_string(static_cast<int>(key.change))},
      {"restarts", key.change == KeyChange::Restart ? "true" : "false"},
      {"written", key.written() ? "true" : "false"},
      {"lesson", key.lesson ? "true" : "false"},
      {"allowed", quoted(key.allowed())},
      {"state_field", key.state_field ? quoted(key.state_field) : "null"}};
  if (key.isNumber()) {
    members.emplace_back("default", number(key.number(defaults)));
    members.emplace_back("range", rangeOf(key.range));
  } else {
    members.emplace_back("default", key.written() ? quoted(key.text(defaults)) : "null");
    std::vector<std::string> choices;
    if (key.choices) {
      for (const auto& choice : key.choices()) choices.push_back(quoted(choice));
    }
    members.emplace_back("choices", list(choices));
    members.emplace_back("counts", key.counts ? "true" : "false");
  }
  return object(members);
}

template <class Type>
std::string typeOf() {
  std::vector<std::string> keys;
  for (const auto& key : Type::description().keys) keys.push_back(keyOf(key));
  std::vector<std::string> fields;
  for (const auto& field : Type::kStateFields) {
    fields.push_back(object({{"name", quoted(field.name)},
                             {"unit", quoted(field.unit)},
                             {"kind", quoted(field.text ? "text" : "number")},
                             {"settable", field.settable() ? "true" : "false"}}));
  }
  return object({{"keys", list(keys)},
                 {"state_fields", list(fields)},
                 {"fixed_frame_suffix", quoted(Type::kFixedFrameSuffix)},
                 {"races", Type::kRaces ? "true" : "false"},
                 {"sweep_column", quoted(Type::kSweepColumn.name)}});
}

std::string worldKey(const char* name, const char* unit, const std::string& value, const Range* range,
                     const char* meaning) {
  std::vector<std::pair<std::string, std::string>> members{
      {"name", quoted(name)}, {"unit", quoted(unit)}, {"default", value}, {"meaning", quoted(meaning)}};
  if (range) members.emplace_back("range", rangeOf(*range));
  return object(members);
}

}  // namespace

std::string bodyTypesJson() {
  std::vector<std::pair<std::string, std::string>> types;
  BodyTypes::forEach([&](auto type) { types.emplace_back(decltype(type)::kName, typeOf<decltype(type)>()); });
  const WorldConfig world;
  const Range rate = rateRange(), publish_rate = publishRateRange(), gravity = gravityRange();
  const std::vector<std::string> world_keys{
      worldKey("rate", "Hz", number(world.rate), &rate, "physics steps per simulated second"),
      worldKey("publish_rate", "Hz", number(world.publish_rate), &publish_rate,
               "samples per simulated second, a divisor of rate"),
      worldKey("gravity", "m/s^2", number(world.gravity), &gravity, "copied into every body"),
      worldKey("world_frame", "", quoted(world.world_frame), nullptr, "the TF frame of the world"),
      worldKey("race", "", world.race ? "true" : "false", nullptr,
               "the bodies on slopes start together and wait at the end of their slopes")};
  return object({{"types", object(types)},
                 {"world", list(world_keys)},
                 {"max_bodies", std::to_string(kMaxBodies)}}) +
         "\n";
}

}  // namespace rigid_body_sim
