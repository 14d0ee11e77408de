#include "rigid_body_sim/ros/launch_end.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <ros/console.h>

namespace rigid_body_sim {

namespace {

// Whether the process runs the program `name`: its command line's first or second word (an interpreter's
// script: python3 /usr/bin/roslaunch ...) is that program.
bool runs(pid_t process, const std::string& name) {
  std::ifstream cmdline("/proc/" + std::to_string(process) + "/cmdline");
  std::string word;
  for (int i = 0; i < 2 && std::getline(cmdline, word, '\0'); ++i) {
    if (std::filesystem::path(word).filename() == name) return true;
  }
  return false;
}

}  // namespace

bool endParentRoslaunch() {
  const pid_t parent = getppid();
  if (!runs(parent, "roslaunch")) {
    ROS_INFO("not started by roslaunch (rostest, a shell): this node ends alone");
    return false;
  }
  ROS_INFO("ending the roslaunch that started this node (pid %d), as Ctrl-C would", static_cast<int>(parent));
  return interruptRoslaunch(parent);
}

bool interruptRoslaunch(pid_t process) {
  if (kill(process, SIGINT) == 0) return true;
  const int error = errno;
  ROS_ERROR("could not send SIGINT to the roslaunch that started this node (pid %d): %s; end it by hand",
            static_cast<int>(process), std::strerror(error));
  return false;
}

}  // namespace rigid_body_sim
