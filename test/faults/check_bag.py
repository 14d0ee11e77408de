#!/usr/bin/env python3
"""Checks a bag recorded through sim.launch against what sim_node published up to its last sample at T:
the states of every body at t = 0, 1/publish_rate, ... and at T, and one /tf message per sample.
  check_bag.py BAG CONFIG T complete          every sample up to T (a bag closed by Ctrl-C)
  check_bag.py BAG CONFIG T prefix ACTIVE_SIZE  the samples up to some t <= T, missing at most what one
                                                unflushed chunk holds (a bag recovered by rosbag reindex)
A recorder that subscribed late may lack the first samples: the samples must then run on without a gap
from the first recorded one."""
import sys

import rosbag
import yaml

CHUNK = 768 * 1024  # rosbag record's default --chunksize (768 kB)


def fail(message):
    sys.exit(f"check_bag: FAILED: {message}")


def main():
    bag_path, config_path, t_end, mode = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4]
    with open(config_path) as f:
        config = yaml.safe_load(f)
    rate, publish_rate = float(config.get("rate", 1000)), float(config.get("publish_rate", 50))
    per_sample = round(rate / publish_rate)
    last = round(t_end * rate)
    published = list(range(0, last + 1, per_sample)) + ([last] if last % per_sample else [])

    steps, stamps, raw_bytes = {}, {}, 0
    with rosbag.Bag(bag_path) as bag:
        for topic, msg, _ in bag.read_messages():
            if topic.endswith("/state"):
                steps.setdefault(topic, []).append(round(msg.t * rate))
                stamps.setdefault(topic, set()).add(msg.header.stamp)
            elif topic == "/tf":
                stamps.setdefault("/tf", set()).add(msg.transforms[0].header.stamp)
        for _, data, *_ in bag.read_messages(raw=True):
            raw_bytes += len(data[1])
    bodies = [f"/sim/{name}/state" for name in config["bodies"]]
    recorded = 0
    for topic in bodies:
        got = steps.get(topic, [])
        if not got:
            fail(f"no message on {topic}")
        if got[0] not in published:
            fail(f"{topic}: first sample at step {got[0]} was never published")
        start = published.index(got[0])
        want = published[start:start + len(got)]
        if got != want:
            gaps = [s for s in want if s not in got][:5]
            fail(f"{topic}: samples missing or out of order (first expected-but-missing steps: {gaps})")
        if mode == "complete" and got[-1] != last:
            fail(f"{topic}: ends at step {got[-1]}, the node's last sample was at step {last}")
        recorded = max(recorded, len(got))
        print(f"{topic:22s} {len(got):5d} samples, t from {got[0] / rate:g} to {got[-1] / rate:g} s "
              f"(the node published up to {t_end:g} s)")
    rod_stamps = set().union(*(stamps[topic] for topic in bodies))
    tf = stamps.get("/tf", set())
    if mode == "complete" and tf != rod_stamps:
        fail(f"/tf has {len(tf)} sample times, the states {len(rod_stamps)}")
    if mode == "prefix":
        missing = len(published) - recorded
        bytes_per_sample = raw_bytes / recorded
        allowed = CHUNK / bytes_per_sample + 2
        print(f"recovered {raw_bytes} bytes of messages ({bytes_per_sample:.0f} a sample) from a .bag.active of "
              f"{sys.argv[5]} bytes; {missing} samples lost, at most {allowed:.0f} (one chunk) allowed")
        if missing > allowed:
            fail(f"{missing} samples lost: more than one unflushed chunk")
    print("check_bag: ok")


if __name__ == "__main__":
    main()
