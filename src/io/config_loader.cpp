#include "rigid_body_sim/io/config_loader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <set>
#include <sstream>

#include "rigid_body_sim/core/constants.h"
#include "rigid_body_sim/core/node_interface.h"

namespace rigid_body_sim {

namespace {

const std::string kWorld = "(world)";

std::string describe(const YAML::Node& node) {
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  if (node.IsMap()) return "(a map)";
  if (node.IsSequence()) return "(a list)";
  return "(nothing)";
}

// A map key as text; a key that is itself a map or a list (YAML allows it) has no name to look up.
std::string keyName(const YAML::Node& key) { return key.IsScalar() ? key.Scalar() : describe(key); }

// `allowed` says what the key takes, for the message when the text is no number at all (or one out of
// a double's range, such as 1e400).
double asNumber(const std::string& body, const std::string& key, const YAML::Node& node,
                const std::string& allowed = "a number") {
  // A quoted scalar ("1") is text, tagged "!" by the parser: a number is written without quotes.
  if (node.IsScalar() && node.Tag() == "!") throw quotedTextRefusal(body, key, node.Scalar(), allowed);
  try {
    if (node.IsScalar()) return node.as<double>();
  } catch (const YAML::Exception&) {
  }
  throw ConfigError(body, key, describe(node), allowed);
}

std::string asString(const std::string& body, const std::string& key, const YAML::Node& node,
                     const std::string& allowed) {
  if (!node.IsScalar()) throw ConfigError(body, key, describe(node), allowed);
  return node.Scalar();
}

// The booleans of YAML 1.1, as rosparam reads a file for the node: true, yes, on / false, no, off, any case.
bool asBool(const std::string& body, const std::string& key, const YAML::Node& node) {
  const std::string allowed = "true or false (or yes, no, on, off)";
  if (node.IsScalar() && node.Tag() == "!") {  // quoted: a text, as a quoted number is
    throw quotedTextRefusal(body, key, node.Scalar(), allowed);
  }
  std::string text = asString(body, key, node, allowed);
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char ch) { return std::tolower(ch); });
  if (text == "true" || text == "yes" || text == "on") return true;
  if (text == "false" || text == "no" || text == "off") return false;
  throw ConfigError(body, key, describe(node), allowed);
}

// "a, b and c" with last_separator " and ".
template <class Names>
std::string joined(const Names& names, const char* last_separator = ", ") {
  std::string out;
  std::size_t i = 0;
  for (const auto& name : names) {
    if (i > 0) out += i + 1 == names.size() ? last_separator : ", ";
    out += name;
    ++i;
  }
  return out;
}

// Refuses a key given twice in `map`: YAML forbids it, yaml-cpp keeps both, and readers would disagree on
// which counts (map[key] finds the first, rosparam keeps the last).
void refuseRepeatedKeys(const std::string& body, const YAML::Node& map) {
  std::set<std::string> seen;
  for (const auto& entry : map) {
    const std::string key = keyName(entry.first);
    if (!seen.insert(key).second) {
      throw ConfigError(body, key, describe(entry.second) + " (the key given twice)", "each key once");
    }
  }
}

// Refuses any key of `map` not in `known`, so that a typo cannot fall back to a default silently, and any
// key given twice.
void refuseUnknownKeys(const std::string& body, const YAML::Node& map, const std::set<std::string>& known) {
  for (const auto& entry : map) {
    const std::string key = keyName(entry.first);
    if (!known.count(key)) {
      throw ConfigError(body, key, describe(entry.second), "no such key; known keys: " + joined(known));
    }
  }
  refuseRepeatedKeys(body, map);
}

// A body's keys, as its type describes them: read in the description's order (a roller's shape before its
// inertia_factor), each number or text checked as the key takes it; then what depends on which keys were
// given. Unknown and repeated keys are refused first.
template <class Config>
Config parseKeys(const std::string& body, const YAML::Node& map) {
  const BodyType<Config>& type = bodyType<Config>();
  std::set<std::string> known{"type"};
  for (const auto& key : type.keys) known.insert(key.name);
  refuseUnknownKeys(body, map, known);
  Config config;
  std::vector<std::string> given;
  for (const auto& key : type.keys) {
    const YAML::Node value = map[key.name];
    if (!value) continue;
    given.push_back(key.name);
    if (key.isNumber()) {
      key.field(config) = asNumber(body, key.name, value, key.allowed());
    } else {
      setKeyText(body, key, asString(body, key.name, value, key.allowed()), config);
    }
  }
  type.complete(body, given, config);
  return config;
}

BodyConfig parseBody(const std::string& name, const YAML::Node& map) {
  if (!map.IsMap()) throw ConfigError(name, "(body)", describe(map), "a map of the body's keys");
  const std::string types = oneOf(bodyTypeNames());
  if (!map["type"]) throw ConfigError(name, "type", "(missing)", types);
  const std::string type = asString(name, "type", map["type"], types);
  std::optional<BodyConfig> body;
  BodyTypes::forEach([&](auto each) {
    using Type = decltype(each);
    if (type == Type::kName) body = BodyConfig{name, parseKeys<typename Type::Config>(name, map)};
  });
  if (!body) throw ConfigError(name, "type", "'" + type + "'", types);
  return *body;
}

std::vector<BodyConfig> parseBodies(const YAML::Node& bodies) {
  if (!bodies) throw ConfigError(kWorld, "bodies", "(missing)", "a map of bodies by name");
  if (!bodies.IsMap()) throw ConfigError(kWorld, "bodies", describe(bodies), "a map of bodies by name");
  std::vector<BodyConfig> parsed;
  for (const auto& entry : bodies) {
    parsed.push_back(parseBody(keyName(entry.first), entry.second));
  }
  return parsed;
}

// Lists and maps written in brackets ([ ], { }) are checked before yaml-cpp sees them: yaml-cpp 0.6 (Debian
// 11) loops allocating until memory runs out on a bracket left open or a ':' right before ']' or the end
// ("[:", "[a:]", "{k:\x04}": it reads \x04 as the end; found by the fuzzer), and deep nesting recurses;
// ~spawn takes such text from anyone. Control characters, which YAML does not allow, go first. A config
// needs four levels.
constexpr int kMaxFlowDepth = 32;

struct FlowScan {
  int deepest = 0;          // the deepest nesting
  std::string open_at_end;  // "the '[' at line L, column C": the outermost bracket left open (invalid YAML)
  bool colon_before_close = false;  // ":]" inside brackets: no value after the ':'
  std::string control;              // "\\x04 at line L, column C": a character YAML does not allow
  std::string hash_unspaced;        // "a '#' right after ',' at line L, column C": a comment or not?
};

// Brackets in `text`, outside quoted scalars and comments. As in YAML, a quote opens a quoted scalar only
// where a node starts (not inside a plain scalar: "it's"), and # begins a comment only at a line's start or
// after a blank. A # right after '[', '{', ',' or a quoted scalar is refused: yaml-cpp reads some of those
// as comments and some not ("{a,#}" leaves its '{' open; "0,#: {:" does not), and yaml-cpp 0.6 allocates
// until memory runs out on either misreading (found by the fuzzer on Debian 11). Where yaml-cpp opens a
// quoted scalar differs from YAML too (":{\": {:]\"}"), so the text is also scanned with `quotes` false,
// every quote a plain character, and must pass both readings.
FlowScan scanFlow(const std::string& text, bool quotes) {
  FlowScan scan;
  int depth = 0;
  char quote = 0;
  bool quote_closed = false;  // the character before ended a quoted scalar
  bool comment = false;
  char previous = '\n';
  char last_mark = '\n';   // the last character but blanks
  bool mark_opens = true;  // whether it is an indicator after which a node may start
  int line = 1;
  int column = 0;
  for (const char ch : text) {
    ++column;
    const auto code = static_cast<unsigned char>(ch);
    if ((code < 0x20 && ch != '\t' && ch != '\n' && ch != '\r') || code == 0x7f) {
      static const char* hex = "0123456789abcdef";
      if (scan.control.empty()) {
        scan.control = std::string("\\x") + hex[code >> 4] + hex[code & 15] + " at line " +
                       std::to_string(line) + ", column " + std::to_string(column);
      }
    }
    // A node (so a quoted scalar) starts at a line's start or after an indicator ('[', '{', ',', or ':', '-',
    // '?' with a blank after them), blanks between.
    const bool blank_before = previous == ' ' || previous == '\t';
    const bool scalar_may_start =
        mark_opens && (std::string(":-?").find(last_mark) == std::string::npos || blank_before);
    const bool after_quote = quote_closed;
    quote_closed = false;
    if (comment) {
      comment = ch != '\n';
    } else if (quote) {
      quote_closed = ch == quote;
      quote = ch == quote ? 0 : quote;  // an escaped \" ends it early: what follows counts, never less
    } else if ((ch == '"' || ch == '\'') && scalar_may_start && quotes) {
      quote = ch;
    } else if (ch == '#' && (blank_before || previous == '\n')) {
      comment = true;
    } else if (ch == '#' && (after_quote || std::string("[{,").find(previous) != std::string::npos)) {
      if (scan.hash_unspaced.empty()) {
        scan.hash_unspaced = "a '#' right after '" + std::string(1, previous) + "' at line " +
                             std::to_string(line) + ", column " + std::to_string(column);
      }
    } else if (ch == '[' || ch == '{') {
      if (depth == 0)
        scan.open_at_end = "the '" + std::string(1, ch) + "' at line " + std::to_string(line) + ", column " +
                           std::to_string(column);
      scan.deepest = std::max(scan.deepest, ++depth);
    } else if ((ch == ']' || ch == '}') && depth > 0) {
      scan.colon_before_close = scan.colon_before_close || (ch == ']' && previous == ':');
      --depth;
    }
    if (ch == '\n') {
      ++line;
      column = 0;
    }
    if (ch != ' ' && ch != '\t') {
      const bool after_blank = blank_before || previous == '\n';  // '-' and '?' are indicators only there
      // ',' separates entries only inside brackets: in a block, "0,\"" is one plain scalar.
      mark_opens = std::string("\n[{:").find(ch) != std::string::npos || (ch == ',' && depth > 0) ||
                   ((ch == '-' || ch == '?') && after_blank);
      last_mark = ch;
    }
    previous = ch;
  }
  if (depth == 0) scan.open_at_end.clear();
  return scan;
}

void checkFlowScan(const FlowScan& scan, const std::string& what) {
  if (!scan.control.empty()) {
    throw ConfigError(what + " is not valid YAML: the control character " + scan.control);
  }
  if (scan.deepest > kMaxFlowDepth) {
    throw ConfigError(what + " nests lists and maps " + std::to_string(scan.deepest) +
                      " deep (allowed: at most " + std::to_string(kMaxFlowDepth) + ")");
  }
  if (!scan.hash_unspaced.empty()) {
    throw ConfigError(what + " is not valid YAML here: " + scan.hash_unspaced +
                      " (a comment needs a blank before its '#')");
  }
  if (!scan.open_at_end.empty())
    throw ConfigError(what + " is not valid YAML: " + scan.open_at_end + " is not closed");
  if (scan.colon_before_close) {
    throw ConfigError(what +
                      " is not valid YAML here: a ':' right before ']' (a key needs a value, or no ':')");
  }
}

void checkFlow(const std::string& text, const std::string& what) {
  for (const bool quotes : {true, false}) checkFlowScan(scanFlow(text, quotes), what);
}

// The YAML documents of `text`, counted from its lines: a line "---" (alone or before content) starts one,
// and so does content where none has begun or after a line "..." ended one. YAML forbids both markers at a
// line's start inside any scalar, so the lines tell. Counted here, not by yaml-cpp's LoadAll: yaml-cpp 0.6
// and 0.7 allocate until memory runs out on some text after a first document (found by the fuzzer), which
// Load never reads.
int documentCount(const std::string& text) {
  int documents = 0;
  bool open = false;  // a document has begun and no "..." has ended it
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto marker = [&line](const char* mark) {
      return line.rfind(mark, 0) == 0 && (line.size() == 3 || line[3] == ' ' || line[3] == '\t');
    };
    const std::size_t first = line.find_first_not_of(" \t");
    const bool content = first != std::string::npos && line[first] != '#' && !(line[0] == '%' && !open);
    if (marker("---")) {
      ++documents;  // the first, or another after one begun
      open = true;
    } else if (marker("...")) {
      open = false;
    } else if (content && !open) {
      ++documents;  // one without a marker
      open = true;
    }
  }
  return documents;
}

YAML::Node loadText(const std::string& text, const std::string& what) {
  checkFlow(text, what);
  // A second document would otherwise be dropped without a word (YAML::Load reads the first).
  if (const int documents = documentCount(text); documents > 1) {
    throw ConfigError(what + " holds " + std::to_string(documents) +
                      " YAML documents (allowed: one; '---' starts another)");
  }
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& error) {
    throw ConfigError(what + " is not valid YAML: " + error.what());
  }
}

}  // namespace

ConfigError quotedTextRefusal(const std::string& body, const std::string& key, const std::string& text,
                              const std::string& allowed) {
  return ConfigError(body, key, "\"" + text + "\" (quoted: a text)", allowed + ", without quotes");
}

WorldConfig parseWorldConfig(const YAML::Node& root) {
  if (!root.IsMap()) {
    throw ConfigError(kWorld, "(file)", describe(root), "a map with " + joined(worldKeys(), " and "));
  }
  refuseUnknownKeys(kWorld, root, {worldKeys().begin(), worldKeys().end()});
  WorldConfig config;
  if (root["rate"]) config.rate = asNumber(kWorld, "rate", root["rate"], rateRange().describe());
  if (root["publish_rate"]) {
    config.publish_rate = asNumber(kWorld, "publish_rate", root["publish_rate"], "a divisor of rate");
  }
  if (root["gravity"])
    config.gravity = asNumber(kWorld, "gravity", root["gravity"], gravityRange().describe());
  if (root["world_frame"]) {
    config.world_frame = asString(kWorld, "world_frame", root["world_frame"], "a frame name");
  }
  if (root["race"]) config.race = asBool(kWorld, "race", root["race"]);
  config.bodies = parseBodies(root["bodies"]);
  for (auto& body : config.bodies) {
    std::visit([&](auto& body_config) { body_config.params.gravity = config.gravity; }, body.config);
  }
  validate(config, node_interface::ownNames());
  return config;
}

WorldConfig parseWorldConfigText(const std::string& text, const std::string& source) {
  return parseWorldConfig(loadText(text, "config file '" + source + "'"));
}

BodyConfig parseBodyText(const std::string& name, const std::string& text) {
  return parseBody(name, loadText(text, "body '" + name + "'"));
}

std::vector<StateValue> parseStateText(const std::string& body, const std::string& text) {
  const YAML::Node map = loadText(text, "state of body '" + body + "'");
  if (!map.IsMap()) throw ConfigError(body, "(state)", describe(map), "a map of state fields to numbers");
  refuseRepeatedKeys(body, map);
  std::vector<StateValue> state;
  for (const auto& entry : map) {
    const std::string field = keyName(entry.first);
    state.push_back({field, asNumber(body, field, entry.second)});
  }
  return state;
}

WorldConfig loadWorldConfigFile(const std::string& path) {
  std::error_code ignored;
  std::ifstream file(path);
  if (!file || std::filesystem::is_directory(path, ignored)) {
    throw ConfigError("cannot read config file '" + path + "'");
  }
  const std::string text{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  if (file.bad()) throw ConfigError("cannot read config file '" + path + "'");
  return parseWorldConfigText(text, path);
}

}  // namespace rigid_body_sim
