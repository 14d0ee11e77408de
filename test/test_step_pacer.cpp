// The node's pace against the wall clock: which step is due at a wall time, and when a step is due.
#include <gtest/gtest.h>

#include <limits>

#include "rigid_body_sim/run/step_pacer.h"

using namespace rigid_body_sim;

TEST(StepPacer, WallPaceIsRateStepsPerWallSecondFromTheAnchor) {
  StepPacer pacer(1000.0, 1.0);
  pacer.restart(100.0, 50);
  EXPECT_EQ(pacer.dueSteps(100.0), 50);
  EXPECT_EQ(pacer.dueSteps(100.0009), 50);
  EXPECT_EQ(pacer.dueSteps(100.001), 51);
  EXPECT_EQ(pacer.dueSteps(101.0), 1050);
  EXPECT_EQ(pacer.dueSteps(160.0), 60050);  // a late wake-up: every step missed is due at once
  EXPECT_EQ(pacer.wallTimeOf(1050), 101.0);
  // A wake-up exactly at a step's due time finds that step due (never rounded just below).
  for (std::int64_t steps = 50; steps < 200000; steps += 997) {
    EXPECT_EQ(pacer.dueSteps(pacer.wallTimeOf(steps)), steps) << steps;
  }
}

TEST(StepPacer, FactorScalesThePaceAndZeroIsAsFastAsPossible) {
  StepPacer twice(1000.0, 2.0);
  twice.restart(10.0, 0);
  EXPECT_EQ(twice.dueSteps(11.0), 2000);
  EXPECT_EQ(twice.wallTimeOf(2000), 11.0);
  StepPacer slow(1000.0, 0.5);
  slow.restart(10.0, 0);
  EXPECT_EQ(slow.dueSteps(12.0), 1000);
  StepPacer fastest(1000.0, 0.0);
  fastest.restart(10.0, 7);
  EXPECT_TRUE(fastest.asFastAsPossible());
  EXPECT_EQ(fastest.dueSteps(10.0), std::numeric_limits<std::int64_t>::max());
  EXPECT_EQ(fastest.wallTimeOf(1000), 10.0);
}

TEST(StepPacer, RestartAnchorsAgainAfterAPause) {
  StepPacer pacer(1000.0, 1.0);
  pacer.restart(0.0, 0);
  EXPECT_EQ(pacer.dueSteps(5.0), 5000);
  pacer.restart(20.0, 5000);  // paused from 5 s to 20 s of wall time: nothing is due for the pause
  EXPECT_EQ(pacer.dueSteps(20.0), 5000);
  EXPECT_EQ(pacer.dueSteps(21.0), 6000);
}
