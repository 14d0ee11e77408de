// A progress bar on stderr for long offline runs and sweeps. It draws only when stderr is a terminal,
// so that tests, pipes and CI logs stay clean, and only once a run has lasted a moment, so that short
// runs never flash one.
#pragma once

#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>

namespace rigid_body_sim {

class ProgressBar {
 public:
  // `total` units of work (samples, variants); `unit` names them in the bar.
  ProgressBar(std::int64_t total, std::string unit, bool enabled = isatty(STDERR_FILENO) != 0)
      : total_(total),
        unit_(std::move(unit)),
        enabled_(enabled && total > 0),
        start_(Clock::now()),
        last_draw_(start_) {}
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  ~ProgressBar() {
    if (drawn_) std::fputs("\n", stderr);  // an interrupted run: end the line, claim nothing
  }

  // Cheap enough to call per sample: redraws at most every kRedraw, and not before kQuiet has passed.
  void update(std::int64_t done) {
    if (!enabled_) return;
    const auto now = Clock::now();
    if (now - start_ < kQuiet || now - last_draw_ < kRedraw) return;
    last_draw_ = now;
    draw(done, now);
  }

  // Ends the bar at 100 % with a newline (only if one was drawn).
  void finish() {
    if (drawn_) {
      draw(total_, Clock::now());
      std::fputs("\n", stderr);
    }
    drawn_ = false;
    enabled_ = false;
  }

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr auto kQuiet = std::chrono::milliseconds(500);
  static constexpr auto kRedraw = std::chrono::milliseconds(100);
  static constexpr int kWidth = 30;

  void draw(std::int64_t done, Clock::time_point now) {
    const double fraction = static_cast<double>(done) / static_cast<double>(total_);
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
    const int filled = static_cast<int>(fraction * kWidth);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(kWidth, ' ');
    std::fprintf(stderr, "\r[%s] %3.0f%%  %lld/%lld %s  %.0f s left ", bar.c_str(), 100.0 * fraction,
                 static_cast<long long>(done), static_cast<long long>(total_), unit_.c_str(), eta);
    std::fflush(stderr);
    drawn_ = true;
  }

  std::int64_t total_;
  std::string unit_;
  bool enabled_;
  bool drawn_ = false;
  Clock::time_point start_;
  Clock::time_point last_draw_;
};

}  // namespace rigid_body_sim
