#!/usr/bin/env python3
"""Summary of a rigid_body_sim recording: messages per topic; per body its states' span and energy, then a line
per kind of its events (the bag's /sim/events) with their exact instants and what each adds: finish times and
places, slip-to-roll, came to rest, a rod's contacts. Every body the bag holds is summarised, one spawned while
it ran too; the config (optional) orders them and names those it has that the bag does not."""
import argparse
import sys
from typing import Any, Dict, List, Tuple

import rosbag
import yaml
from rigid_body_sim import runs
from rigid_body_sim.sim_tools import Event, body_of_state_topic, event_lines, events_namespace, load_config


def read_bag(path: str) -> Tuple[Dict[str, int], Dict[str, List[Any]], List[Event]]:
    """Messages per topic, each body's states in order, and the events."""
    counts: Dict[str, int] = {}
    states: Dict[str, List[Any]] = {}
    with rosbag.Bag(path) as bag:
        for topic, msg, _ in bag.read_messages():
            counts[topic] = counts.get(topic, 0) + 1
            body = body_of_state_topic(topic)
            if body is not None:
                states.setdefault(body, []).append(msg)
    return counts, states, runs.read_bag_events(path, events_namespace(counts))


def states_line(msgs: List[Any]) -> str:
    """The span of a body's states, its energy first and last, and the texts of its last state (a mode)."""
    if not msgs:
        return "no states"
    sampling = f"{len(msgs)} samples every {msgs[1].t - msgs[0].t:g} s" if len(msgs) > 1 else "a single sample"
    energies = [m.energy for m in msgs]
    texts = [f"final {name} {getattr(msgs[-1], name)}" for name, kind in zip(msgs[-1].__slots__, msgs[-1]._slot_types)
             if kind == "string"]
    return "; ".join([f"t {msgs[0].t:g} .. {msgs[-1].t:g} s ({sampling}), energy {energies[0]:.6g} -> "
                      f"{energies[-1]:.6g} J (min {min(energies):.6g}, max {max(energies):.6g})", *texts])


def reason(error: Exception) -> str:
    """Why a file could not be read, on one line (an OSError without its errno; YAML's mark joined up)."""
    return getattr(error, "strerror", None) or " ".join(str(error).split())


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("bag", help="a bag of sim_node (sim.launch record:=true) or of simulate --bag")
    parser.add_argument("config", nargs="?", help="the run's YAML config: its bodies first, in its order")
    args = parser.parse_args()
    # A file that cannot be read is the caller's mistake: one line naming it, not a traceback.
    configured: List[str] = []
    if args.config:
        try:
            config = load_config(args.config)
        except (OSError, yaml.YAMLError) as error:
            print(f"bag_summary.py: config {args.config}: {reason(error)}", file=sys.stderr)
            return 1
        bodies = config.get("bodies") if isinstance(config, dict) else None
        configured = list(bodies) if isinstance(bodies, dict) else []
    try:
        counts, states, events = read_bag(args.bag)
    except (OSError, rosbag.ROSBagException) as error:
        print(f"bag_summary.py: bag {args.bag}: {reason(error)}", file=sys.stderr)
        return 1
    print("messages per topic:")
    for topic in sorted(counts):
        print(f"  {topic:24s} {counts[topic]}")
    lines = event_lines(events)
    # The config's bodies, then any other the bag holds (spawned while it ran), as they first appear.
    for name in dict.fromkeys([*configured, *states, *lines]):
        if name not in states and name not in lines:
            print(f"{name}: in the config, nothing in the bag")
            continue
        spawned = " (not in the config)" if configured and name not in configured else ""
        print(f"{name}: {states_line(states.get(name, []))}{spawned}")
        for line in lines.get(name, []):
            print(f"  {line}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
