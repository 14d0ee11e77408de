#!/usr/bin/env python3
"""Summary of a rigid_body_sim recording: messages per topic, slip-to-roll times, the rod's bounces and
energy drift. The config gives each rod's length."""
import argparse
import sys
from typing import Any, Callable, Dict, List, Tuple

import rosbag
import yaml
from rigid_body_sim.sim_tools import (BlockSpec, RodSpec, RollerSpec, body_of_state_topic, body_spec, load_config,
                                      rod_end_below_floor)


def roller_line(msgs: List[Any], _: RollerSpec) -> str:
    rolls = [b.t for a, b in zip(msgs, msgs[1:]) if a.mode == "slipping" and b.mode == "rolling"]
    sampling = f"sampled every {msgs[1].t - msgs[0].t:g} s" if len(msgs) > 1 else "a single sample"
    return (", slip-to-roll seen at t = " + (", ".join(f"{t:g}" for t in rolls) or "never") +
            f" ({sampling}); final mode {msgs[-1].mode}")


def rod_line(msgs: List[Any], rod: RodSpec) -> str:
    contacts = [rod_end_below_floor(m.y, m.theta, rod.length) for m in msgs]
    bounces = sum(1 for a, b in zip(contacts, contacts[1:]) if b and not a)
    drift = max(abs(m.energy - msgs[0].energy) for m in msgs) / abs(msgs[0].energy)
    return f", {bounces} bounces seen, largest energy swing {100 * drift:.2f} %"


def block_line(msgs: List[Any], _: BlockSpec) -> str:
    return f"; final mode {msgs[-1].mode}"


# What each body type's line adds, by its `type`.
LINES: Dict[str, Callable[[List[Any], Any], str]] = {RodSpec.TYPE: rod_line, RollerSpec.TYPE: roller_line,
                                                     BlockSpec.TYPE: block_line}


def read_bag(path: str) -> Tuple[Dict[str, int], Dict[str, List[Any]]]:
    """Messages per topic, and each body's states in order."""
    counts: Dict[str, int] = {}
    states: Dict[str, List[Any]] = {}
    with rosbag.Bag(path) as bag:
        for topic, msg, _ in bag.read_messages():
            counts[topic] = counts.get(topic, 0) + 1
            body = body_of_state_topic(topic)
            if body is not None:
                states.setdefault(body, []).append(msg)
    return counts, states


def reason(error: Exception) -> str:
    """Why a file could not be read, on one line (an OSError without its errno; YAML's mark joined up)."""
    return getattr(error, "strerror", None) or " ".join(str(error).split())


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("bag", help="a bag of sim_node (sim.launch record:=true) or of simulate --bag")
    parser.add_argument("config", help="the run's YAML config")
    args = parser.parse_args()
    # A file that cannot be read is the caller's mistake: one line naming it, not a traceback.
    try:
        config = load_config(args.config)
    except (OSError, yaml.YAMLError) as error:
        print(f"bag_summary.py: config {args.config}: {reason(error)}", file=sys.stderr)
        return 1
    try:
        counts, states = read_bag(args.bag)
    except (OSError, rosbag.ROSBagException) as error:
        print(f"bag_summary.py: bag {args.bag}: {reason(error)}", file=sys.stderr)
        return 1
    print("messages per topic:")
    for topic in sorted(counts):
        print(f"  {topic:24s} {counts[topic]}")
    for name, msgs in states.items():
        spec = body_spec(config, name)
        line = f"{name}: t {msgs[0].t:g} .. {msgs[-1].t:g} s, energy {msgs[0].energy:.6g} -> {msgs[-1].energy:.6g} J"
        print(line + LINES[spec.TYPE](msgs, spec))
    return 0


if __name__ == "__main__":
    sys.exit(main())
