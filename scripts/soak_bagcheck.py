#!/usr/bin/env python3
"""Checks a soak's bag: every state topic and /tf must hold 1 + duration * publish_rate messages (the t = 0
sample and every sample after it), /tf_static one. Usage: soak_bagcheck.py BAG CONFIG DURATION"""
import sys

import rosbag
import yaml


def main():
    bag_path, config_path, duration = sys.argv[1], sys.argv[2], int(sys.argv[3])
    with open(config_path) as f:
        config = yaml.safe_load(f)
    expected = {f"/sim/{name}/state": 1 + duration * round(float(config.get("publish_rate", 50)))
                for name in config["bodies"]}
    expected["/tf"] = 1 + duration * round(float(config.get("publish_rate", 50)))
    expected["/tf_static"] = 1
    with rosbag.Bag(bag_path) as bag:
        topics = bag.get_type_and_topic_info().topics
    missing = 0
    for topic, want in sorted(expected.items()):
        got = topics[topic].message_count if topic in topics else 0
        missing += want - got
        print(f"{topic:24s} recorded {got:8d} of {want:8d}" + ("" if got == want else "  MISMATCH"))
    if missing:
        sys.exit(f"soak: the bag misses {missing} messages")


if __name__ == "__main__":
    main()
