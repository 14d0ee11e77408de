// Ending the roslaunch that started this node, without making the node `required`: roslaunch raises its
// alarm ("REQUIRED process has died") at any end of a required node, a normal one included, and under
// rostest it kills the test nodes with it (a rospy test killed so leaves an empty result, which rostest
// counts as passed). A roslaunch that gets SIGINT ends every node it started (a recorder closes its bag)
// and exits 0, as on Ctrl-C.
#pragma once

#include <sys/types.h>

namespace rigid_body_sim {

// Sends SIGINT to the parent process if it is roslaunch; never to rostest (whose tests decide when its
// launch ends) or a shell. True if it did; logs which (INFO), and a failure to send (ERROR): a caller
// needs to do nothing more.
bool endParentRoslaunch();

// SIGINT to `process`, as endParentRoslaunch sends it; a failure is logged in one ERROR line naming the
// pid and the reason. True if sent.
bool interruptRoslaunch(pid_t process);

}  // namespace rigid_body_sim
