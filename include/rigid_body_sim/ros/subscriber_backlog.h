#pragma once

#include <cstdint>

namespace rigid_body_sim {

// How many messages this node has handed to its subscribers' connections so far, over every topic it
// publishes (roscpp's per-connection statistics, as `rosnode info` reads them). A number that still grows
// after the node stopped publishing means a subscriber is still taking what is queued for it.
std::uint64_t messagesHandedToSubscribers();

}  // namespace rigid_body_sim
