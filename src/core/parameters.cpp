// The world's keys and the checks that concern the whole world; each body type checks its own keys
// (src/core/types/).
#include "rigid_body_sim/core/parameters.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <utility>

#include "rigid_body_sim/core/names.h"

namespace rigid_body_sim {

namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

}  // namespace

Range rateRange() { return {1.0, 1e6, false, false}; }
Range publishRateRange() { return {0.0, 1e6, true, false}; }
Range gravityRange() { return {0.0, 1e3, false, false}; }

bool dividesRate(double rate, double divisor) {
  if (!(divisor > 0) || !std::isfinite(rate) || !std::isfinite(divisor)) return false;
  const double ratio = rate / divisor;
  return ratio >= 1.0 - 1e-9 && std::abs(ratio - std::round(ratio)) <= 1e-9 * ratio;
}

std::string typeName(const BodyConfig& body) {
  return std::visit([](const auto& config) -> std::string { return TypeOfConfig<decltype(config)>::kName; },
                    body.config);
}

const std::vector<std::string>& bodyTypeNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all;
    BodyTypes::forEach([&](auto type) { all.emplace_back(decltype(type)::kName); });
    return all;
  }();
  return names;
}

const std::vector<std::string>& worldKeys() {
  static const std::vector<std::string> keys = {"rate",        "publish_rate", "gravity",
                                                "world_frame", "race",         "bodies"};
  return keys;
}

void validate(const WorldConfig& config, const std::vector<std::string>& reserved_names) {
  const std::string world = "(world)";
  if (!rateRange().contains(config.rate)) {
    throw ConfigError(world, "rate", formatNumber(config.rate), rateRange().describe());
  }
  if (!publishRateRange().contains(config.publish_rate) || !dividesRate(config.rate, config.publish_rate)) {
    throw ConfigError(world, "publish_rate", formatNumber(config.publish_rate),
                      "a divisor of rate = " + formatNumber(config.rate) + " (rate / publish_rate whole)");
  }
  if (!gravityRange().contains(config.gravity)) {
    throw ConfigError(world, "gravity", formatNumber(config.gravity), gravityRange().describe());
  }
  if (!isValidName(config.world_frame)) {
    throw ConfigError(world, "world_frame", "'" + config.world_frame + "'",
                      "a name of letters, digits and _ starting with a letter, at most " +
                          std::to_string(kMaxNameLength) + " characters");
  }
  if (config.bodies.empty()) {
    throw ConfigError(world, "bodies", "(none)", "a map of at least one body");
  }
  if (config.bodies.size() > kMaxBodies) {
    throw ConfigError(world, "bodies", std::to_string(config.bodies.size()) + " bodies",
                      "at most " + std::to_string(kMaxBodies) + " bodies");
  }
  std::set<std::string> frames{config.world_frame};
  std::vector<std::string> reserved = worldKeys();
  reserved.insert(reserved.end(), reserved_names.begin(), reserved_names.end());
  for (const auto& body : config.bodies) {
    if (!isValidName(body.name)) {
      throw ConfigError(world, "bodies", "'" + body.name + "'",
                        "body names of letters, digits and _ starting with a letter, at most " +
                            std::to_string(kMaxNameLength) + " characters");
    }
    if (std::find(reserved.begin(), reserved.end(), body.name) != reserved.end()) {
      throw ConfigError(
          world, "bodies", "'" + body.name + "'",
          "a name other than the node's own keys, topics and services (" + joined(reserved) + ")");
    }
    // Each body brings two TF frames, its own and its fixed frame (<name>_floor or <name>_slope), and those
    // its type adds (a rod's ground frame, on an unbounded floor, which a reconfigure may make it).
    std::vector<std::string> its_frames{body.name, fixedFrameOf(body)};
    std::visit(
        [&](const auto& config) {
          for (auto& frame : TypeOfConfig<decltype(config)>::extraFrames(body.name))
            its_frames.push_back(frame);
        },
        body.config);
    if (!std::all_of(its_frames.begin(), its_frames.end(),
                     [&](const std::string& frame) { return frames.insert(frame).second; })) {
      throw ConfigError(world, "bodies", "'" + body.name + "'",
                        "names whose TF frames (<name>, <name>_floor or <name>_slope, a rod's <name>_ground) "
                        "differ from each other and from world_frame");
    }
    std::visit(
        [&](const auto& body_config) {
          validate(body.name, body_config);
          validateSubsteps(body.name, body_config, config.rate);
        },
        body.config);
  }
}

namespace {
// One line per body whose `note` for the config at the world's rate is not empty.
template <class Note>
std::vector<std::string> linesOf(const WorldConfig& config, Note note) {
  std::vector<std::string> lines;
  for (const auto& body : config.bodies) {
    std::string line =
        std::visit([&](const auto& c) { return note(body.name, c, config.rate); }, body.config);
    if (!line.empty()) lines.push_back(std::move(line));
  }
  return lines;
}
}  // namespace

std::vector<std::string> slowRunWarnings(const WorldConfig& config) {
  return linesOf(config, [](const std::string& body, const auto& c, double rate) {
    return slowRunWarning(body, c, rate);
  });
}

std::vector<std::string> autoSubstepNotes(const WorldConfig& config) {
  return linesOf(config, [](const std::string& body, const auto& c, double rate) {
    return autoSubstepNote(body, c, rate);
  });
}

}  // namespace rigid_body_sim
