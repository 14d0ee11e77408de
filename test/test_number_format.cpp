// Tests of formatNumber (src/core/number_format.cpp) against std::to_chars(first, last, double), byte for
// byte: the plain overload, which libstdc++ has only from GCC 11 on.
//
// test/data/number_format_reference.csv holds what std::to_chars wrote for referenceValues() below
// (20,071 doubles), one row each: its bits as 16 hex digits, a comma, the text. It was made once, with
// g++ 12.2 and the libstdc++ of Debian 12, by a throwaway program (not kept) that was this file plus
//   std::string formatNumber(double) { std::abort(); }  // the table must not depend on it
//   int main() {  // linked with -lgtest, without gtest_main: the tests are not run
//     for (const double value : referenceValues())
//       std::printf("%016llx,%s\n", bits of value, text of std::to_chars(buffer, buffer + 64, value));
//   }
// Its rows check formatNumber on every platform, with or without floating to_chars; they carry their
// bits, so a platform need not make the same values again. Where to_chars exists, formatNumber is also
// compared with it live on the same values and on a million random doubles (about 2 s).
#include "rigid_body_sim/core/parameters.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>  // __cpp_lib_to_chars; std::to_chars for double only under it
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace rigid_body_sim {
namespace {

constexpr std::uint64_t kTableSeed = 20240601;  // the table's rows (its structured sets: kTableSeed + 1)
constexpr std::size_t kTableRandomCount = 4000;
constexpr std::uint64_t kLiveSeed = 7;  // the live comparison with to_chars
constexpr std::size_t kLiveRandomCount = 1000000;
constexpr std::uint64_t kPropertySeed = 11;
constexpr std::size_t kPropertyRandomCount = 50000;

double fromBits(std::uint64_t bits) {
  double value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

std::uint64_t bitsOf(double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

double parsed(const std::string& text) { return std::strtod(text.c_str(), nullptr); }

// `value` and the doubles either side of it.
void addWithNeighbours(std::vector<double>& values, double value) {
  values.push_back(value);
  values.push_back(std::nextafter(value, -std::numeric_limits<double>::infinity()));
  values.push_back(std::nextafter(value, std::numeric_limits<double>::infinity()));
}

// Finite doubles of random bit patterns, every exponent and sign alike. mt19937_64's sequence is fixed by
// the standard, so a seed gives the same doubles everywhere.
std::vector<double> randomDoubles(std::uint64_t seed, std::size_t count) {
  std::mt19937_64 random(seed);
  std::vector<double> values;
  while (values.size() < count) {
    const double value = fromBits(random());
    if (std::isfinite(value)) values.push_back(value);
  }
  return values;
}

// The ends of the range, zeros, and a few everyday values.
std::vector<double> extremes() {
  using limits = std::numeric_limits<double>;
  std::vector<double> values = {0.0, -0.0, 1.0, 0.1, 0.2, 0.3, 1.0 / 3, 2.0 / 3, 9.81, 1e-3, 299792458.0};
  for (const double value :
       {limits::denorm_min(), limits::min(), limits::max(), 3.141592653589793, 2.718281828459045}) {
    addWithNeighbours(values, value);
  }
  return values;
}

// Every power of two, subnormal ones included: at those (but the smallest normal) the doubles below are
// twice as close as those above, so the interval that reads back is lopsided.
std::vector<double> powersOfTwo() {
  std::vector<double> values;
  for (int exponent = -1074; exponent <= 1023; ++exponent)
    addWithNeighbours(values, std::ldexp(1.0, exponent));
  return values;
}

std::vector<double> powersOfTen() {
  std::vector<double> values;
  for (int exponent = -323; exponent <= 308; ++exponent) {
    addWithNeighbours(values, parsed("1e" + std::to_string(exponent)));
  }
  return values;
}

// The smallest and largest subnormals and random ones.
std::vector<double> subnormals(std::mt19937_64& random) {
  std::vector<double> values;
  const std::uint64_t largest = 0x000fffffffffffff;
  for (std::uint64_t i = 0; i < 100; ++i) {
    values.push_back(fromBits(1 + i));
    values.push_back(fromBits(largest - i));
  }
  for (int i = 0; i < 300; ++i) values.push_back(fromBits(random() & largest));
  return values;
}

// Whole numbers where doubles stop being consecutive integers (2^53) and beyond, and small ones.
std::vector<double> integers() {
  std::vector<double> values;
  for (int i = -100; i <= 100; ++i) {
    values.push_back(9007199254740992.0 + i);
    values.push_back(18014398509481984.0 + 2 * i);
  }
  for (int i = 0; i <= 100; ++i) values.push_back(i);
  for (int exponent = 1; exponent <= 22; ++exponent) {
    const double power = parsed("1e" + std::to_string(exponent));
    values.push_back(power - 1);
    values.push_back(power + 1);
  }
  return values;
}

// Decimals of 1 to 17 digits whose last digit is at 10^e, e from -(digits + 6) to 7: across the
// bounds where to_chars switches between fixed and scientific (1e-04 but 0.00012; 10000 but 1e+05).
std::vector<double> aroundTheSwitch() {
  std::vector<double> values;
  for (const char* pattern : {"12345678912345678", "99999999999999999"}) {
    for (int digits = 1; digits <= 17; ++digits) {
      for (int exponent = -(digits + 6); exponent <= 7; ++exponent) {
        addWithNeighbours(values, parsed(std::string(pattern, digits) + "e" + std::to_string(exponent)));
      }
    }
  }
  return values;
}

// Random values in each decade from 1e-8 to 1e23, and random short decimals (1 to 6 digits).
std::vector<double> decades(std::mt19937_64& random) {
  std::vector<double> values;
  for (int exponent = -8; exponent <= 23; ++exponent) {
    for (int i = 0; i < 20; ++i) {
      const double unit = static_cast<double>(random() >> 11) * 0x1p-53;  // [0, 1)
      values.push_back((1 + 9 * unit) * parsed("1e" + std::to_string(exponent)));
    }
  }
  for (int i = 0; i < 1500; ++i) {
    const std::uint64_t mantissa = random() % 1000000;
    const int exponent = static_cast<int>(random() % 38) - 12;
    values.push_back(parsed(std::to_string(mantissa) + "e" + std::to_string(exponent)));
  }
  return values;
}

// All sets but the random bit patterns, with every fifth value also negated.
std::vector<double> structuredValues() {
  std::mt19937_64 random(kTableSeed + 1);
  std::vector<double> values;
  for (const auto& set : {extremes(), powersOfTwo(), powersOfTen(), subnormals(random), integers(),
                          aroundTheSwitch(), decades(random)}) {
    values.insert(values.end(), set.begin(), set.end());
  }
  for (std::size_t i = 0, size = values.size(); i < size; i += 5) values.push_back(-values[i]);
  return values;
}

// The table's doubles: the structured sets and random bit patterns, by bits, each once.
[[maybe_unused]] std::vector<double> referenceValues() {  // unused where to_chars is missing
  std::vector<double> values = structuredValues();
  const std::vector<double> random = randomDoubles(kTableSeed, kTableRandomCount);
  values.insert(values.end(), random.begin(), random.end());
  std::vector<std::uint64_t> bits;
  for (const double value : values) bits.push_back(bitsOf(value));
  std::sort(bits.begin(), bits.end());
  bits.erase(std::unique(bits.begin(), bits.end()), bits.end());
  values.clear();
  for (const std::uint64_t b : bits) values.push_back(fromBits(b));
  return values;
}

std::string hexBits(double value) {
  char text[20];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(bitsOf(value)));
  return text;
}

// Counts mismatches, reporting the first few only (a wrong rule would otherwise print thousands).
class Mismatches {
 public:
  void check(double value, const std::string& got, const std::string& want) {
    if (got == want) return;
    if (++count_ <= 20)
      ADD_FAILURE() << hexBits(value) << ": formatNumber gives " << got << ", want " << want;
  }
  int count() const { return count_; }

 private:
  int count_ = 0;
};

TEST(NumberFormat, MatchesTheToCharsTable) {
  std::ifstream file(std::string(RBS_TEST_DATA_DIR) + "/number_format_reference.csv");
  ASSERT_TRUE(file) << "no number_format_reference.csv in " << RBS_TEST_DATA_DIR;
  Mismatches mismatches;
  std::size_t rows = 0;
  for (std::string line; std::getline(file, line); ++rows) {
    ASSERT_TRUE(line.size() > 17 && line[16] == ',') << "bad row " << rows + 1 << ": " << line;
    const double value = fromBits(std::stoull(line.substr(0, 16), nullptr, 16));
    mismatches.check(value, formatNumber(value), line.substr(17));
  }
  EXPECT_GT(rows, 15000u);  // a cut file would pass too easily
  EXPECT_EQ(mismatches.count(), 0) << "of " << rows << " rows";
}

TEST(NumberFormat, NonFiniteValues) {
  EXPECT_EQ(formatNumber(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(formatNumber(-std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(formatNumber(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(formatNumber(-std::numeric_limits<double>::infinity()), "-inf");
}

TEST(NumberFormat, KnownTexts) {
  EXPECT_EQ(formatNumber(-0.0), "-0");
  EXPECT_EQ(formatNumber(1e22), "1e+22");
  EXPECT_EQ(formatNumber(5e-324), "5e-324");
  EXPECT_EQ(formatNumber(1.5e-7), "1.5e-07");
  EXPECT_EQ(formatNumber(1e-4), "1e-04");
  EXPECT_EQ(formatNumber(1.2e-4), "0.00012");
  EXPECT_EQ(formatNumber(1e4), "10000");
  EXPECT_EQ(formatNumber(1e5), "1e+05");
  EXPECT_EQ(formatNumber(std::ldexp(1.0, 70)), "1180591620717411303424");     // exact, as printf("%.0f")
  EXPECT_EQ(formatNumber(std::ldexp(1.0, -1017)), "7.120236347223045e-307");  // nearest does not read back
}

// A panel's numbers: rounded, never a negative zero.
TEST(NumberFormat, FixedHasNoNegativeZero) {
  EXPECT_EQ(formatFixed(-0.0, 3), "0.000");
  EXPECT_EQ(formatFixed(-1e-9, 3), "0.000");
  EXPECT_EQ(formatFixed(-0.0004999, 3), "0.000");
  EXPECT_EQ(formatFixed(-0.0005001, 3), "-0.001");
  EXPECT_EQ(formatFixed(-0.4, 0), "0");
  EXPECT_EQ(formatFixed(-1.6751, 2), "-1.68");
  EXPECT_EQ(formatFixed(2.5, 1), "2.5");
  EXPECT_EQ(formatFixed(12.0, 0), "12");
  EXPECT_EQ(formatFixed(-std::numeric_limits<double>::infinity(), 3), "-inf");
}

#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
std::string toChars(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

TEST(NumberFormat, MatchesToCharsLive) {
  std::vector<double> values = randomDoubles(kLiveSeed, kLiveRandomCount);
  const std::vector<double> structured = referenceValues();
  values.insert(values.end(), structured.begin(), structured.end());
  const auto start = std::chrono::steady_clock::now();
  Mismatches mismatches;
  for (const double value : values) mismatches.check(value, formatNumber(value), toChars(value));
  const std::chrono::duration<double> seconds = std::chrono::steady_clock::now() - start;
  std::printf("%zu doubles compared with std::to_chars in %.2f s\n", values.size(), seconds.count());
  EXPECT_EQ(mismatches.count(), 0) << "of " << values.size();
}
#endif

// The significant digits of a text and the power of ten of the last one: "-0.0125" -> 125, -4.
struct Digits {
  std::string digits;
  int exponent;
};

Digits significantDigits(const std::string& text) {
  const std::size_t e = std::min(text.find('e'), text.size());
  Digits result{"", e < text.size() ? std::stoi(text.substr(e + 1)) : 0};
  bool after_point = false;
  for (std::size_t i = 0; i < e; ++i) {
    const char c = text[i];
    if (c == '.') after_point = true;
    if (c < '0' || c > '9') continue;  // the sign, the point
    if (after_point) --result.exponent;
    if (c != '0' || !result.digits.empty()) result.digits += c;
  }
  while (result.digits.size() > 1 && result.digits.back() == '0') {
    result.digits.pop_back();
    ++result.exponent;
  }
  return result;
}

// Whether some decimal of fewer significant digits than `shown` reads back as `magnitude`. Those nearest
// to its value are its digits cut by one and that plus one in the last place; one farther away
// reading back would make these read back too (they lie between it and the value).
bool fewerDigitsReadBack(const Digits& shown, double magnitude) {
  if (shown.digits.size() < 2) return false;
  const std::uint64_t cut = std::stoull(shown.digits.substr(0, shown.digits.size() - 1));
  for (const std::uint64_t mantissa : {cut, cut + 1}) {
    if (parsed(std::to_string(mantissa) + "e" + std::to_string(shown.exponent + 1)) == magnitude) return true;
  }
  return false;
}

TEST(NumberFormat, ReadsBackWithNoFewerDigitsPossible) {
  std::vector<double> values = randomDoubles(kPropertySeed, kPropertyRandomCount);
  const std::vector<double> structured = structuredValues();
  values.insert(values.end(), structured.begin(), structured.end());
  int failures = 0;
  for (const double value : values) {
    const std::string text = formatNumber(value);
    const Digits shown = significantDigits(text);
    bool good = bitsOf(parsed(text)) == bitsOf(value);
    // A whole number beyond 2^53 written fixed shows its exact value (as printf's "%.0f"), digits that the
    // shortest form leaves out included: it need not be short.
    const bool exact_whole = std::fabs(value) >= 0x1p53 && text.find_first_of(".e") == std::string::npos;
    if (!exact_whole)
      good = good && shown.digits.size() <= 17 && !fewerDigitsReadBack(shown, std::fabs(value));
    if (!good && ++failures <= 20) ADD_FAILURE() << hexBits(value) << ": " << text;
  }
  EXPECT_EQ(failures, 0) << "of " << values.size();
}

}  // namespace
}  // namespace rigid_body_sim
