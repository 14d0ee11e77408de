// Whether the ROS master still knows this process. roscpp registers a node, its topics and services once:
// a master that restarts (a new process at the same URI) knows nothing of them, and the node, unlisted
// and unreachable, would go on for nothing. roscpp cannot register a running node again, so the node
// watches for this and ends (sim.launch respawn:=true then starts it afresh).
#pragma once

namespace rigid_body_sim {

enum class MasterView {
  Knows,        // the master lists this node at this process's XML-RPC address
  Forgot,       // the master answers but lists no such node, or another process under its name
  Unreachable,  // no answer (the master is down, or restarting): nothing to decide yet
};

// Asks the master (lookupNode of this node's own name); a few milliseconds, no retry.
MasterView askMaster();

}  // namespace rigid_body_sim
