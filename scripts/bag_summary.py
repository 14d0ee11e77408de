#!/usr/bin/env python3
"""Summary of a rigid_body_sim recording: messages per topic, slip-to-roll times, the rod's bounces and
energy drift. Usage: bag_summary.py BAG CONFIG.yaml (the config gives each rod's length)."""
import math
import sys

import rosbag
import yaml


def rod_ends_below_floor(msg, length):
    half = 0.5 * length * math.sin(msg.theta)
    return msg.y + half < 0.0 or msg.y - half < 0.0


def main(bag_path, config_path):
    with open(config_path) as f:
        bodies = yaml.safe_load(f)["bodies"]
    counts, states = {}, {}
    with rosbag.Bag(bag_path) as bag:
        for topic, msg, _ in bag.read_messages():
            counts[topic] = counts.get(topic, 0) + 1
            if topic.endswith("/state"):
                states.setdefault(topic.split("/")[-2], []).append(msg)
    print("messages per topic:")
    for topic in sorted(counts):
        print(f"  {topic:24s} {counts[topic]}")
    for name, msgs in states.items():
        first, last = msgs[0], msgs[-1]
        line = f"{name}: t {first.t:g} .. {last.t:g} s, energy {first.energy:.6g} -> {last.energy:.6g} J"
        if hasattr(msg := first, "mode"):
            rolls = [b.t for a, b in zip(msgs, msgs[1:]) if a.mode == "slipping" and b.mode == "rolling"]
            line += ", slip-to-roll seen at t = " + (", ".join(f"{t:g}" for t in rolls) or "never")
            line += f" (sampled every {msgs[1].t - msgs[0].t:g} s); final mode {last.mode}"
        else:
            length = bodies[name].get("length", 1.0)
            contacts = [rod_ends_below_floor(m, length) for m in msgs]
            bounces = sum(1 for a, b in zip(contacts, contacts[1:]) if b and not a)
            drift = max(abs(m.energy - first.energy) for m in msgs) / abs(first.energy)
            line += f", {bounces} bounces seen, largest energy swing {100 * drift:.2f} %"
        print(line)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
