// A SIGINT that cannot be sent to the roslaunch to end is reported by launch_end itself, in one ERROR line
// naming the pid and the reason: its callers ignore what it returns.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>
#include <utility>
#include <vector>

#include <ros/console.h>

#include "rigid_body_sim/ros/launch_end.h"

namespace {

// Every line rosconsole logs, with its level.
class CapturedLog : public ros::console::LogAppender {
 public:
  void log(ros::console::Level level, const char* text, const char*, const char*, int) override {
    lines.emplace_back(level, text);
  }
  std::vector<std::pair<ros::console::Level, std::string>> lines;
};

// Registered once for the process and never deregistered: Debian 11's rosconsole crashes in
// deregister_appender (a SEGV under ASan).
CapturedLog& capturedLog() {
  static CapturedLog* const log = [] {
    auto* appender = new CapturedLog;
    ros::console::register_appender(appender);
    return appender;
  }();
  return *log;
}

TEST(LaunchEnd, AFailedInterruptIsOneErrorLineWithThePidAndTheReason) {
  const pid_t gone = fork();
  ASSERT_GE(gone, 0);
  if (gone == 0) _exit(0);
  ASSERT_EQ(waitpid(gone, nullptr, 0), gone);  // reaped: no process has that pid now (ESRCH)
  CapturedLog& log = capturedLog();
  log.lines.clear();
  EXPECT_FALSE(rigid_body_sim::interruptRoslaunch(gone));
  ASSERT_EQ(log.lines.size(), 1u);
  EXPECT_EQ(log.lines[0].first, ros::console::levels::Error);
  const std::string& line = log.lines[0].second;
  EXPECT_NE(line.find("pid " + std::to_string(gone)), std::string::npos) << line;
  EXPECT_NE(line.find("No such process"), std::string::npos) << line;
}

}  // namespace
