#include "rigid_body_sim/core/description.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
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

// The number keys a choice of a text key gives the same value whatever they held before, and that value (a
// roller's shape sets its inertia_factor; custom keeps the one given).
template <class Config>
std::vector<std::pair<std::string, double>> setsOf(const BodyKey<Config>& key, const std::string& choice) {
  Config moved;  // every number key away from its default
  for (const auto& other : bodyType<Config>().keys) {
    if (other.isNumber()) other.field(moved) = other.number(moved) + 1.0;
  }
  Config from_defaults, from_moved = moved;
  setKeyText("description", key, choice, from_defaults);
  setKeyText("description", key, choice, from_moved);
  std::vector<std::pair<std::string, double>> values;
  for (const auto& other : bodyType<Config>().keys) {
    if (!other.isNumber() || other.number(from_defaults) != other.number(from_moved)) continue;
    if (other.number(from_moved) != other.number(moved))
      values.emplace_back(other.name, other.number(from_moved));
  }
  return values;
}

// What each choice of a text key sets besides itself, by choice.
template <class Config>
std::string choiceSets(const BodyKey<Config>& key) {
  if (!key.choices) return "{}";
  std::vector<std::pair<std::string, std::string>> sets;
  for (const auto& choice : key.choices()) {
    std::vector<std::pair<std::string, std::string>> values;
    for (const auto& [name, value] : setsOf(key, choice)) values.emplace_back(name, number(value));
    sets.emplace_back(choice, object(values));
  }
  return object(sets);
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
    members.emplace_back("sets", choiceSets(key));
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
  std::vector<std::string> events;
  for (const auto& kind : Type::kEventKinds) {
    const char* role = kind.role == EventRole::Finish    ? "finish"
                       : kind.role == EventRole::Restart ? "restart"
                                                         : "";
    events.push_back(
        object({{"name", quoted(kind.name)}, {"meaning", quoted(kind.meaning)}, {"role", quoted(role)}}));
  }
  return object({{"keys", list(keys)},
                 {"state_fields", list(fields)},
                 {"event_kinds", list(events)},
                 {"fixed_frame_suffix", quoted(Type::kFixedFrameSuffix)},
                 {"races", Type::kRaces ? "true" : "false"},
                 {"sweep_column", quoted(Type::kSweepColumn.name)},
                 {"sweep_event", quoted(Type::kSweepColumn.event)},
                 {"sweep_label", quoted(Type::kSweepColumn.label)},
                 {"sweep_unit", quoted(Type::kSweepColumn.unit)}});
}

// A world key: its JSON description and its row in the docs' table.
struct WorldKey {
  const char* name;
  const char* unit;
  std::string value;  // the default, as JSON writes it
  std::string shown;  // the default, as the docs' table shows it
  std::optional<Range> range;
  std::string allowed;  // the docs' table's "allowed" beyond the interval and unit
  const char* meaning;

  std::string json() const {
    std::vector<std::pair<std::string, std::string>> members{
        {"name", quoted(name)}, {"unit", quoted(unit)}, {"default", value}, {"meaning", quoted(meaning)}};
    if (range) members.emplace_back("range", rangeOf(*range));
    return object(members);
  }
};

std::vector<WorldKey> worldKeyDescriptions() {
  const WorldConfig world;
  const auto numberKey = [](const char* name, const char* unit, double value, const Range& range,
                            const char* meaning) {
    return WorldKey{name, unit, number(value), formatNumber(value), range, "", meaning};
  };
  WorldKey publish_rate = numberKey("publish_rate", "Hz", world.publish_rate, publishRateRange(),
                                    "samples per simulated second, a divisor of rate");
  publish_rate.allowed = ", dividing `rate`";
  const std::string bool_default = world.race ? "true" : "false";
  return {
      numberKey("rate", "Hz", world.rate, rateRange(), "physics steps per simulated second"),
      publish_rate,
      numberKey("gravity", "m/s^2", world.gravity, gravityRange(), "copied into every body"),
      {"world_frame", "", quoted(world.world_frame), "`" + world.world_frame + "`", std::nullopt,
       "letters, digits, `_`, starting with a letter, at most 64 characters", "the TF frame of the world"},
      {"race", "", bool_default, bool_default, std::nullopt, "true or false",
       "true: the bodies on slopes (rollers and blocks) start together, each waits at the end of its "
       "slope with its time and place beside the closed form's, and all start again together 2 s after "
       "the last is down; false: each restarts alone"}};
}

// A number key's "allowed" cell: its interval, then its unit.
std::string intervalCell(const Range& range, const std::string& unit) {
  const std::string text = range.describe();
  return text.substr(text.find_first_of("[(")) + (unit.empty() ? "" : " " + unit);
}

template <class Type>
std::string keyTable() {
  const typename Type::Config defaults;
  std::string table = "| key | default | allowed | what |\n|---|---|---|---|\n";
  for (const auto& key : Type::description().keys) {
    table += "| `" + std::string(key.name) + "` | " + (key.written() ? key.text(defaults) : "(none)") +
             " | " + (key.isNumber() ? intervalCell(key.range, key.unit) : key.allowed()) + " | " +
             key.meaning + " |\n";
  }
  return table;
}

std::string worldKeyTable() {
  std::string table = "| key | default | allowed | what |\n|---|---|---|---|\n";
  for (const auto& key : worldKeyDescriptions()) {
    table += "| `" + std::string(key.name) + "` | " + key.shown + " | " +
             (key.range ? intervalCell(*key.range, key.unit) : "") + key.allowed + " | " + key.meaning +
             " |\n";
  }
  return table + "| `bodies` | (required) | a map of 1 to " + std::to_string(kMaxBodies) +
         " bodies, by name: names as `world_frame`, every TF frame distinct, none a world key nor one of the "
         "node's own names | the bodies, each with its `type` and its type's keys |\n";
}

}  // namespace

std::string keyTableMarkdown(const std::string& name) {
  if (name == "world") return worldKeyTable();
  std::string table;
  BodyTypes::forEach([&](auto type) {
    if (name == decltype(type)::kName) table = keyTable<decltype(type)>();
  });
  if (table.empty()) throw std::invalid_argument("no body type '" + name + "' and not the world");
  return table;
}

std::string eventTableMarkdown(const std::string& name) {
  for (const auto& [type, kinds] : eventKindsByType()) {
    if (type != name) continue;
    std::string table = "| event | meaning |\n| --- | --- |\n";
    for (const auto& kind : kinds) table += "| `" + kind.name + "` | " + kind.meaning + " |\n";
    return table;
  }
  throw std::invalid_argument("no body type '" + name + "'");
}

std::string withKeyTables(const std::string& doc) {
  // "<!-- keys of NAME: ..." (keyTableMarkdown) and "<!-- events of NAME: ..." (eventTableMarkdown).
  static const std::string kKeys = "<!-- keys of ", kEvents = "<!-- events of ";
  static const std::string kBeginEnd = ": generated by make figures -->\n";
  static const std::string kEnd = "<!-- end of generated keys -->";
  std::string out;
  std::size_t from = 0;
  while (true) {
    const std::size_t keys = doc.find(kKeys, from);
    const std::size_t events = doc.find(kEvents, from);
    const std::size_t at = std::min(keys, events);
    if (at == std::string::npos) break;
    const std::string& begin = at == keys ? kKeys : kEvents;
    const std::size_t name_end = doc.find(kBeginEnd, at);
    const std::size_t end = doc.find(kEnd, at);
    if (name_end == std::string::npos || end == std::string::npos || end < name_end) {
      throw std::invalid_argument("a '" + begin + "NAME" + kBeginEnd.substr(0, kBeginEnd.size() - 1) +
                                  "' with no '" + kEnd + "' after it");
    }
    const std::size_t body = name_end + kBeginEnd.size();
    const std::string name = doc.substr(at + begin.size(), name_end - at - begin.size());
    out += doc.substr(from, body - from) + (at == keys ? keyTableMarkdown(name) : eventTableMarkdown(name));
    from = end;
  }
  return out + doc.substr(from);
}

std::vector<SpawnChoice> spawnChoices() {
  std::vector<SpawnChoice> found;
  BodyTypes::forEach([&](auto type) {
    using Type = decltype(type);
    const std::string name = Type::kName;
    const std::size_t before = found.size();
    for (const auto& key : Type::description().keys) {
      if (!key.choices) continue;
      for (const auto& choice : key.choices()) {
        if (!setsOf(key, choice).empty())
          found.push_back({choice, "{type: " + name + ", " + key.name + ": " + choice + "}"});
      }
    }
    if (found.size() == before) found.push_back({name, "{type: " + name + "}"});
  });
  return found;
}

std::string bodyTypesJson() {
  std::vector<std::pair<std::string, std::string>> types;
  BodyTypes::forEach([&](auto type) { types.emplace_back(decltype(type)::kName, typeOf<decltype(type)>()); });
  std::vector<std::string> world_keys;
  for (const auto& key : worldKeyDescriptions()) world_keys.push_back(key.json());
  return object({{"types", object(types)},
                 {"world", list(world_keys)},
                 {"max_bodies", std::to_string(kMaxBodies)},
                 {"energy_drift", object({{"name", quoted(kEnergyDriftColumn)},
                                          {"label", quoted("energy drift")},
                                          {"unit", quoted("J")}})}}) +
         "\n";
}

}  // namespace rigid_body_sim
