#!/usr/bin/env python3
"""Checks a soak's bag: every state topic and /tf must hold duration * publish_rate messages (every sample
after t = 0: the node, started paused, sent that one before the recorder subscribed); /tf_static 1 + duration
* bodies (the node's fixed frames at the start, and again at each reconfigure: every body every second)."""
import argparse
import sys
from typing import Dict

import rosbag

from rigid_body_sim.sim_tools import load_config, world_value


def report(expected: Dict[str, int], recorded: Dict[str, int]) -> int:
    """Prints a line per topic; returns how many topics hold other than their expected count (an extra
    message on one topic never makes up for a missing one on another)."""
    wrong = 0
    for topic, want in sorted(expected.items()):
        got = recorded.get(topic, 0)
        wrong += got != want
        print(f"{topic:24s} recorded {got:8d} of {want:8d}" + ("" if got == want else "  MISMATCH"))
    return wrong


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("bag")
    parser.add_argument("config", help="the soak's YAML config")
    parser.add_argument("duration", type=int, help="simulated seconds of the soak")
    args = parser.parse_args()
    config = load_config(args.config)
    samples = args.duration * round(float(world_value(config, "publish_rate")))
    expected = {f"/sim/{name}/state": samples for name in config["bodies"]}
    expected["/tf"] = samples
    expected["/tf_static"] = 1 + args.duration * len(config["bodies"])
    with rosbag.Bag(args.bag) as bag:
        topics = bag.get_type_and_topic_info().topics
    wrong = report(expected, {topic: info.message_count for topic, info in topics.items()})
    if wrong:
        print(f"soak: {wrong} of {len(expected)} topics hold other than their expected count", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
