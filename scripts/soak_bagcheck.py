#!/usr/bin/env python3
"""Checks a soak's bag: every state topic and /tf must hold 1 + duration * publish_rate messages (the t = 0
sample and every sample after it), /tf_static one."""
import argparse
import sys

import rosbag

from sim_tools import load_config, world_value


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("bag")
    parser.add_argument("config", help="the soak's YAML config")
    parser.add_argument("duration", type=int, help="simulated seconds of the soak")
    args = parser.parse_args()
    config = load_config(args.config)
    samples = 1 + args.duration * round(float(world_value(config, "publish_rate")))
    expected = {f"/sim/{name}/state": samples for name in config["bodies"]}
    expected["/tf"] = samples
    expected["/tf_static"] = 1
    with rosbag.Bag(args.bag) as bag:
        topics = bag.get_type_and_topic_info().topics
    missing = 0
    for topic, want in sorted(expected.items()):
        got = topics[topic].message_count if topic in topics else 0
        missing += want - got
        print(f"{topic:24s} recorded {got:8d} of {want:8d}" + ("" if got == want else "  MISMATCH"))
    if missing:
        sys.exit(f"soak: the bag misses {missing} messages")
    return 0


if __name__ == "__main__":
    sys.exit(main())
