// A line-by-line C++ transcription of the textbook's Python program for the bouncing rod (Euler-Cromer),
// used as a test oracle. It keeps the text's 3-vectors, its order of operations and its signed zeros,
// and shares no code with the core, so that agreeing with it means following the text.
#pragma once

#include <vector>

namespace rbs_test {

// The text's constants (m, L, g, h0, v0, k, dt, time); theta[0] is the caller's.
struct TextParams {
  double m = 0.5;
  double g = 9.8;
  double h0 = 4.0;
  double L = 1.0;
  double time = 10.0;
  double dt = 0.001;
  double k = 1000.0;
  double v0 = 2.0;
};

// One row of the text's arrays: t[i], r[i][0..1], theta[i], v[i][0..1], omega[i].
struct OracleSample {
  double t, x, y, theta, vx, vy, omega;
};

// n = int(round(time/dt)) as in the text.
int textSampleCount(const TextParams& p = {});

// Runs the text's loop `for i in range(n-1)` for n samples (n_samples < 0: the text's n); returns n rows.
std::vector<OracleSample> runTextProgram(double theta0, int n_samples = -1, const TextParams& p = {});

}  // namespace rbs_test
