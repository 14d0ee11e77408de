#!/usr/bin/env python3
"""Checks a bag recorded through sim.launch against what sim_node published up to its last sample at T:
the states of every body at t = 0, 1/publish_rate, ... and at T, and one /tf message per sample.
  check_bag.py BAG CONFIG T complete            every sample up to T (a bag closed by Ctrl-C)
  check_bag.py BAG CONFIG T prefix ACTIVE_SIZE  the samples up to some t <= T, missing at most what one
                                                unflushed chunk holds (a bag recovered by rosbag reindex)
Both from t = 0: sim.launch starts stepping once the recorder has subscribed to every state topic and /tf."""
import argparse
import sys
from typing import Any, Dict, List, NoReturn, Set

import rosbag
from rigid_body_sim.sim_tools import load_config, steps_per_sample, world_value

CHUNK = 768 * 1024  # rosbag record's default --chunksize (768 kB)


def fail(message: str) -> NoReturn:
    sys.exit(f"check_bag: FAILED: {message}")


class Recorded:
    """Per state topic the steps of its samples, the stamps of every topic, and the bytes of all messages."""

    def __init__(self, path: str, rate: float) -> None:
        self.steps: Dict[str, List[int]] = {}
        self.stamps: Dict[str, Set[Any]] = {}
        self.raw_bytes = 0
        with rosbag.Bag(path) as bag:
            for topic, msg, _ in bag.read_messages():
                if topic.endswith("/state"):
                    self.steps.setdefault(topic, []).append(round(msg.t * rate))
                    self.stamps.setdefault(topic, set()).add(msg.header.stamp)
                elif topic == "/tf":
                    self.stamps.setdefault("/tf", set()).add(msg.transforms[0].header.stamp)
            for _, data, *_ in bag.read_messages(raw=True):
                self.raw_bytes += len(data[1])


def check_states(recorded: Recorded, topic: str, published: List[int], last: int, complete: bool,
                 rate: float, t_end: float) -> int:
    """The samples of one state topic run from t = 0 on without a gap; returns their count."""
    got = recorded.steps.get(topic, [])
    if not got:
        fail(f"no message on {topic}")
    if got[0] != published[0]:
        fail(f"{topic}: the first sample is at step {got[0]}, not at t = 0: the recorder missed the start")
    want = published[:len(got)]
    if got != want:
        gaps = [s for s in want if s not in got][:5]
        fail(f"{topic}: samples missing or out of order (first expected-but-missing steps: {gaps})")
    if complete and got[-1] != last:
        fail(f"{topic}: ends at step {got[-1]}, the node's last sample was at step {last}")
    print(f"{topic:22s} {len(got):5d} samples, t from {got[0] / rate:g} to {got[-1] / rate:g} s "
          f"(the node published up to {t_end:g} s)")
    return len(got)


def main() -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    parser.add_argument("bag")
    parser.add_argument("config")
    parser.add_argument("t_end", type=float, help="the time of the node's last sample (s)")
    parser.add_argument("mode", choices=["complete", "prefix"])
    parser.add_argument("active_size", type=int, nargs="?", default=0, help="prefix: bytes of the .bag.active")
    args = parser.parse_args()
    config = load_config(args.config)
    rate, per_sample = float(world_value(config, "rate")), steps_per_sample(config)
    last = round(args.t_end * rate)
    published = list(range(0, last + 1, per_sample)) + ([last] if last % per_sample else [])
    recorded = Recorded(args.bag, rate)
    bodies = [f"/sim/{name}/state" for name in config["bodies"]]
    count = max(check_states(recorded, topic, published, last, args.mode == "complete", rate, args.t_end)
                for topic in bodies)
    state_stamps: Set[Any] = set().union(*(recorded.stamps[topic] for topic in bodies))
    tf = recorded.stamps.get("/tf", set())
    if args.mode == "complete" and tf != state_stamps:
        fail(f"/tf has {len(tf)} sample times, the states {len(state_stamps)}")
    if args.mode == "prefix":
        missing = len(published) - count
        bytes_per_sample = recorded.raw_bytes / count
        allowed = CHUNK / bytes_per_sample + 2
        print(f"recovered {recorded.raw_bytes} bytes of messages ({bytes_per_sample:.0f} a sample) from a "
              f".bag.active of {args.active_size} bytes; {missing} samples lost, at most {allowed:.0f} (one chunk) "
              "allowed")
        if missing > allowed:
            fail(f"{missing} samples lost: more than one unflushed chunk")
    print("check_bag: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
