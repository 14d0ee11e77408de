// formatNumber: the text std::to_chars(first, last, double) writes (libstdc++'s plain overload), made with
// the C library alone, because libstdc++ before GCC 11 (Ubuntu 20.04, Debian 11) has no floating to_chars.
//
// to_chars writes the fewest significant digits that read back as the value (Ryu), the one nearest the
// value among those, and lays them out fixed or scientific, whichever is shorter (fixed on a tie).
// snprintf("%.*e") rounds correctly to any digit count and strtod reads correctly (in the default rounding
// mode, which nothing here changes), so trying digit counts finds the same digits;
// test/test_number_format.cpp compares the bytes with to_chars.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

#include "rigid_body_sim/core/parameters.h"

namespace rigid_body_sim {

namespace {

// 17 significant digits tell every double apart: half their spacing is at most 5e-17 of the value, less
// than the 2^-54 of it that the narrowest side of a round-trip interval has.
constexpr int kMaxDigits = 17;

// A positive decimal, mantissa * 10^exponent (mantissa < 10^18).
struct Decimal {
  std::uint64_t mantissa;
  int exponent;
};

std::uint64_t powerOfTen(int n) {
  std::uint64_t power = 1;
  for (int i = 0; i < n; ++i) power *= 10;
  return power;
}

// The `digits`-digit decimal nearest to `value` (> 0), half to even, as the C library rounds: a mantissa
// of exactly `digits` digits. Only the digits and the exponent are read: the radix character of snprintf
// follows LC_NUMERIC (which Qt sets from the environment).
Decimal printedWithDigits(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*e", digits - 1, value);
  Decimal decimal{0, 0};
  const char* c = text;
  for (; *c != 'e'; ++c) {
    if (*c >= '0' && *c <= '9')
      decimal.mantissa = decimal.mantissa * 10 + static_cast<std::uint64_t>(*c - '0');
  }
  decimal.exponent = std::atoi(c + 1) - (digits - 1);
  return decimal;
}

// The same from `seventeen`, the 17-digit one, without printing again (printing costs most of the time).
// Rounding it again gives the same decimal unless it lies exactly halfway between two of `digits`
// digits: `value` may then lie on either side (or on it), and only the C library knows.
Decimal nearestWithDigits(double value, const Decimal& seventeen, int digits) {
  if (digits == kMaxDigits) return seventeen;
  const std::uint64_t unit = powerOfTen(kMaxDigits - digits);
  const std::uint64_t dropped = seventeen.mantissa % unit;
  if (dropped == unit / 2) return printedWithDigits(value, digits);
  Decimal nearest{seventeen.mantissa / unit + (dropped > unit / 2 ? 1 : 0),
                  seventeen.exponent + kMaxDigits - digits};
  if (nearest.mantissa == powerOfTen(digits)) {  // rounded up to the next power of ten
    nearest.mantissa /= 10;
    ++nearest.exponent;
  }
  return nearest;
}

// Whether `decimal` reads back as `value`. Written without a radix point, so the locale cannot matter.
bool readsBackAs(const Decimal& decimal, double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%llue%d", static_cast<unsigned long long>(decimal.mantissa),
                decimal.exponent);
  return std::strtod(text, nullptr) == value;
}

// Whether the values that read back as `value` reach farther above it than below: at a power of two the
// spacing of doubles below is half that above (the smallest normal excepted: subnormals keep its spacing).
bool hasNarrowLowerSide(double value) {
  int exponent = 0;
  return std::frexp(value, &exponent) == 0.5 && value > std::numeric_limits<double>::min();
}

// The `digits`-digit decimal to_chars picks, if one reads back as `value`: the nearest one; failing
// that, at a power of two, the next one above, which may fall in the wider upper side of the interval
// while the nearest, below, misses the narrower lower one. (Elsewhere the interval is symmetric, and a
// decimal farther than the nearest one cannot be in it when the nearest is not.)
bool pickWithDigits(double value, const Decimal& seventeen, int digits, Decimal& picked) {
  const Decimal nearest = nearestWithDigits(value, seventeen, digits);
  if (readsBackAs(nearest, value)) {
    picked = nearest;
    return true;
  }
  if (!hasNarrowLowerSide(value)) return false;
  // mantissa + 1 may be 10^digits: the same value as 10^(digits-1) a decade up.
  const Decimal above{nearest.mantissa + 1, nearest.exponent};
  if (!readsBackAs(above, value)) return false;
  picked = above;
  return true;
}

// The fewest digits that read back (Ryu's shortest), without trailing zeros. A decimal of d digits is
// also one of d + 1, so whether some decimal of d digits reads back is monotonic in d: search. Computed
// values mostly need 16 or 17 digits, so 16 and 15 are tried first, then the rest is bisected.
Decimal shortestDecimal(double value) {
  const Decimal seventeen = printedWithDigits(value, kMaxDigits);
  Decimal best = seventeen;
  int fewest_known = kMaxDigits;  // `best` has this many digits and reads back
  int too_few = 0;                // no decimal of this many digits reads back
  int digits = kMaxDigits - 1;
  while (fewest_known - too_few > 1) {
    if (pickWithDigits(value, seventeen, digits, best)) {
      fewest_known = digits;
    } else {
      too_few = digits;
    }
    digits = fewest_known >= kMaxDigits - 1 ? fewest_known - 1 : (too_few + fewest_known) / 2;
  }
  while (best.mantissa % 10 == 0) {
    best.mantissa /= 10;
    ++best.exponent;
  }
  return best;
}

// Scientific as to_chars writes it: d[.ddd]e±XX, the exponent at least two digits.
std::string scientific(const std::string& digits, int exponent) {
  std::string text = digits.substr(0, 1);
  if (digits.size() > 1) text += "." + digits.substr(1);
  text += exponent < 0 ? "e-" : "e+";
  const int magnitude = std::abs(exponent);
  if (magnitude < 10) text += '0';
  return text + std::to_string(magnitude);
}

// Fixed with a fraction: the digits of mantissa * 10^exponent, exponent < 0.
std::string fixedFraction(const std::string& digits, int exponent) {
  const int whole = static_cast<int>(digits.size()) + exponent;  // digits before the point
  if (whole <= 0) return "0." + std::string(static_cast<std::size_t>(-whole), '0') + digits;
  return digits.substr(0, static_cast<std::size_t>(whole)) + "." +
         digits.substr(static_cast<std::size_t>(whole));
}

// A whole number in fixed form: to_chars writes its exact value, as printf("%.0f") does, not the shortest
// digits padded with zeros (2^70 is 1180591620717411303424, not 1180591620717411300000). Below 10^22 here.
std::string wholeNumber(double magnitude) {
  char text[64];
  std::snprintf(text, sizeof text, "%.0f", magnitude);
  return text;
}

// `magnitude` (finite, > 0) as to_chars writes it. Its rule (libstdc++ floating_to_chars.cc): fixed when
// the shortest decimal's exponent e is in [-(n + 3), 5] for n digits, [-3, 4] for one digit (no point in
// scientific then): exactly where fixed is not longer than scientific.
std::string positiveText(double magnitude) {
  const Decimal shortest = shortestDecimal(magnitude);
  const std::string digits = std::to_string(shortest.mantissa);
  const int count = static_cast<int>(digits.size());
  const int lowest_fixed = count == 1 ? -3 : -(count + 3);
  const int highest_fixed = count == 1 ? 4 : 5;
  if (shortest.exponent < lowest_fixed || shortest.exponent > highest_fixed) {
    return scientific(digits, shortest.exponent + count - 1);
  }
  if (shortest.exponent >= 0) return wholeNumber(magnitude);
  return fixedFraction(digits, shortest.exponent);
}

}  // namespace

std::string formatNumber(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  const std::string sign = std::signbit(value) ? "-" : "";
  if (value == 0) return sign + "0";
  return sign + positiveText(std::fabs(value));
}

// The C library rounds; its "-0.00" of a small negative number (or of -0) loses the sign. The radix
// character follows LC_NUMERIC (which Qt sets from the environment): a point is what readers here expect.
std::string formatFixed(double value, int decimals) {
  if (!std::isfinite(value)) return formatNumber(value);
  char text[400];  // DBL_MAX has 309 digits before the point
  std::snprintf(text, sizeof text, "%.*f", std::clamp(decimals, 0, 30), value);
  std::string fixed(text);
  for (char& c : fixed) {
    if (c == ',') c = '.';
  }
  if (fixed[0] == '-' && fixed.find_first_not_of("-0.") == std::string::npos) fixed.erase(0, 1);
  return fixed;
}

}  // namespace rigid_body_sim
