// The errors and number forms every key shares.
#include "rigid_body_sim/core/body_key.h"

#include <cmath>
#include <limits>

#include "types/key_builders.h"

namespace rigid_body_sim {

namespace {

// What a message shows of a value or name: the rest of an overlong one is cut.
constexpr std::size_t kMaxShownLength = 80;

// Escapes control characters, so that a message stays one line, and cuts what is longer than max_length.
std::string printable(const std::string& text, std::size_t max_length = std::string::npos) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (out.size() >= max_length) return out + "...";
    const auto ch = static_cast<unsigned char>(text[i]);
    if (ch == '\n') {
      out += "\\n";
    } else if (ch < 0x20 || ch == 0x7f) {
      static const char* hex = "0123456789abcdef";
      out += std::string("\\x") + hex[ch >> 4] + hex[ch & 15];
    } else {
      out += static_cast<char>(ch);
    }
  }
  return out;
}

}  // namespace

ConfigError::ConfigError(const std::string& body, const std::string& key, const std::string& value,
                         const std::string& allowed)
    : std::runtime_error("body '" + printable(body, kMaxShownLength) + "', key '" +
                         printable(key, kMaxShownLength) + "': value " + printable(value, kMaxShownLength) +
                         " is not allowed (allowed: " + printable(allowed) + ")") {}

ConfigError::ConfigError(const std::string& message) : std::runtime_error(printable(message)) {}

bool Range::contains(double value) const {
  if (!std::isfinite(value)) return false;
  const bool above_min = min_open ? value > min : value >= min;
  const bool below_max = max_open ? value < max : value <= max;
  return above_min && below_max;
}

std::string Range::describe() const {
  return std::string("a finite number in ") + (min_open ? "(" : "[") + formatNumber(min) + ", " +
         formatNumber(max) + (max_open ? ")" : "]");
}

std::string oneOf(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    out += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  }
  return out;
}

namespace keys {

void checkDerived(const std::string& body, const std::string& keys, const std::string& quantity, double value,
                  bool positive) {
  const bool good = positive ? std::isnormal(value) && value > 0.0 : std::isfinite(value);
  if (!good) {
    throw ConfigError(body, keys, quantity + " = " + formatNumber(value),
                      positive ? "values whose " + quantity + " is a finite positive number (at least " +
                                     formatNumber(std::numeric_limits<double>::min()) + ")"
                               : "values whose " + quantity + " is finite");
  }
}

void checkFriction(const std::string& body, double mu_s, double mu_d) {
  if (mu_d > mu_s) {
    throw ConfigError(body, "mu_d", formatNumber(mu_d),
                      "a finite number in [0, mu_s = " + formatNumber(mu_s) + "]");
  }
}

void checkOnSlope(const std::string& body, const char* key, double x, double incline_length) {
  if (x > incline_length) {
    throw ConfigError(
        body, key, formatNumber(x),
        "a position on the slope, in [0, incline_length = " + formatNumber(incline_length) + "]");
  }
}

}  // namespace keys

}  // namespace rigid_body_sim
