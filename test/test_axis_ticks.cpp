// niceTicks: the panel's chart ticks are distinct numbers, never "-0", and a flat series gets a readable
// span.
#include "rigid_body_sim/rviz/axis_ticks.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

namespace rigid_body_sim {
namespace {

void expectDistinctAndCovering(const AxisTicks& ticks, double low, double high) {
  const std::set<std::string> distinct(ticks.labels.begin(), ticks.labels.end());
  EXPECT_EQ(distinct.size(), ticks.labels.size());
  EXPECT_GE(ticks.labels.size(), 3u);
  EXPECT_LE(ticks.labels.size(), 12u);
  EXPECT_LE(ticks.low, low);
  EXPECT_GE(ticks.high, high);
  for (const std::string& label : ticks.labels)
    EXPECT_FALSE(label[0] == '-' && label.find_first_not_of("-0.") == std::string::npos) << label;
}

// The friction of a slipping body, constant: its ticks read -1.67 -1.67 -1.68 ... before.
TEST(AxisTicks, ConstantSeriesGetsAReadableSpan) {
  const AxisTicks ticks = niceTicks(-1.6758, -1.6758);
  EXPECT_EQ(ticks.labels, (std::vector<std::string>{"-1.9", "-1.8", "-1.7", "-1.6", "-1.5", "-1.4"}));
  EXPECT_DOUBLE_EQ(ticks.step, 0.1);
  expectDistinctAndCovering(ticks, -1.6758, -1.6758);
}

TEST(AxisTicks, ZeroAndTinyValuesHaveNoNegativeZero) {
  const AxisTicks zero = niceTicks(0, 0);
  EXPECT_EQ(zero.labels, (std::vector<std::string>{"-0.10", "-0.05", "0.00", "0.05", "0.10"}));
  expectDistinctAndCovering(niceTicks(-3e-17, 2e-17), -3e-17, 2e-17);
  // Steps summed across zero (-0.3 + 0.1 + 0.1 + 0.1 is not 0): each tick is k * step, written rounded.
  const AxisTicks across = niceTicks(-0.3, 0.3);
  EXPECT_EQ(across.labels, (std::vector<std::string>{"-0.4", "-0.2", "0.0", "0.2", "0.4"}));
}

TEST(AxisTicks, StepsOfOneTwoOrFive) {
  EXPECT_EQ(niceTicks(-50, 90).labels, (std::vector<std::string>{"-100", "-50", "0", "50", "100"}));
  EXPECT_DOUBLE_EQ(niceTicks(0, 8).step, 2);
  EXPECT_DOUBLE_EQ(niceTicks(0, 0.4).step, 0.1);
  EXPECT_DOUBLE_EQ(niceTicks(1000, 3500).step, 1000);
  for (const double span : {1e-6, 3e-3, 0.7, 13.0, 420.0, 9e5}) {
    for (const double start : {-2 * span, -0.5 * span, 0.0, 7 * span}) {
      const AxisTicks ticks = niceTicks(start, start + span);
      expectDistinctAndCovering(ticks, start, start + span);
    }
  }
}

}  // namespace
}  // namespace rigid_body_sim
