#!/usr/bin/env python3
"""Each saved view's rules (view_rules.py) at every marker instant of a minute's run, on what the node
publishes: `simulate --bag` writes the node's scene, labels, boards and transforms for the view's config, and
every instant of it is projected with the view's camera in rviz's 3-D view at 1600x900. The picture tests
look at a few moments with rviz itself; this looks at all 600 of a minute, without a display.

    views_over_a_run.py SIMULATE [--duration S] [--work DIR]

Prints, per case, the instants checked and every finding that fails (at most 5 per rule); exits 1 if any."""
import argparse
import os
import subprocess
import sys
import tempfile
from typing import Any, Dict, List, Tuple

import rosbag
import yaml
from rigid_body_sim.sim_tools import body_spec, load_config

import picture_check as pc
import view_rules as rules

PACKAGE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# (view, config, changes as the panel makes them: {body: {key: value}}) for each saved view as its launch
# opens it, and with a change of each kind (the demo's: pictures_rviz_look_change's).
CASES: List[Tuple[str, str, Dict[str, Dict[str, float]]]] = [
    ("sim.rviz", "demo.yaml", {}),
    ("sim.rviz", "demo.yaml", {"sphere": {"incline_angle": 0.85}, "cylinder": {"incline_length": 3.5},
                               "ring": {"radius": 0.16}, "rod": {"length": 1.5}}),
    ("lesson_race.rviz", "race_below.yaml", {}),
    ("lesson_race.rviz", "race_below.yaml", {"cylinder": {"incline_angle": 0.6}}),
    ("lesson_race.rviz", "race_below.yaml", {"sphere": {"incline_length": 3.5}, "ring": {"radius": 0.2}}),
    ("lesson_race.rviz", "race_slip.yaml", {}),
    ("lesson_race.rviz", "race_block.yaml", {}),
    ("lesson_above.rviz", "race_above.yaml", {}),
    ("incline.rviz", "incline.yaml", {}),
    ("rod.rviz", "rod.yaml", {}),
    ("lesson_rod.rviz", "rod.yaml", {}),
    ("lesson_rod.rviz", "rod.yaml", {"rod": {"floor_mu": 0.3}}),
]
SHOWN = 5  # failures printed per rule and case


def case_config(case: int, config: str, changes: Dict[str, Dict[str, float]], work: str) -> str:
    """The config as the launch loads it, with the panel's changes made: a file in work."""
    with open(os.path.join(PACKAGE, "config", config)) as f:
        loaded = yaml.safe_load(f)
    for body, keys in changes.items():
        loaded["bodies"][body].update(keys)
    path = os.path.join(work, f"{case}_{config}")
    with open(path, "w") as f:
        yaml.safe_dump(loaded, f)
    return path


def check_run(bag: str, view: Dict[str, Any], specs: List[Any],
              grid: Dict[str, Any]) -> Tuple[int, Dict[str, List[str]]]:
    """(instants checked, {rule: lines of its failures}): the rules at every instant the node sent labels,
    once everything of that instant (its transforms) is in, through the view's camera (following its Target
    Frame, as rviz does)."""
    scene = rules.PublishedScene()
    failed: Dict[str, List[str]] = {}
    instants = 0
    target = view.get("Target Frame", "<Fixed Frame>")

    def check(t: Any) -> None:
        followed = scene.frames[target][1] if target in scene.frames else (0.0, 0.0, 0.0)
        camera = pc.Camera.from_rviz(view, rules.RENDER_AT_1600X900, followed)
        for finding in rules.view_checks(scene, camera, specs, grid, rules.RENDER_SLACK):
            if not finding.ok:
                rule = finding.what.split(" (")[0]
                failed.setdefault(rule, []).append(f"t = {t.to_sec():.2f} s: {finding.line()}")

    pending = None  # the instant of the latest labels, checked once a later instant starts
    with rosbag.Bag(bag) as opened:
        for topic, message, t in opened.read_messages(topics=["/tf", "/tf_static", "/sim/scene", "/sim/markers"]):
            if pending is not None and t > pending:
                check(pending)
                instants += 1
                pending = None
            if topic in ("/tf", "/tf_static"):
                scene.on_tf(message)
            else:
                scene.on_markers(message, topic)
                if topic == "/sim/markers":
                    pending = t
    if pending is not None:
        check(pending)
        instants += 1
    return instants, failed


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("simulate", help="the simulate executable")
    parser.add_argument("--duration", type=float, default=60.0, help="simulated seconds of each run")
    parser.add_argument("--work", help="where the configs and bags go (default: a temporary folder)")
    args = parser.parse_args()
    failures = 0
    with tempfile.TemporaryDirectory() as temporary:
        work = args.work or temporary
        os.makedirs(work, exist_ok=True)
        for case, (view_name, config_name, changes) in enumerate(CASES):
            config = case_config(case, config_name, changes, work)
            bag = config[:-len(".yaml")] + ".bag"
            done = subprocess.run([args.simulate, config, "--duration", str(args.duration), "--bag", bag,
                                   "--out-dir", config[:-len(".yaml")]], capture_output=True, text=True)
            if done.returncode != 0:
                print(f"simulate {config} failed: {done.stderr.strip()}")
                return 1
            with open(os.path.join(PACKAGE, "rviz", view_name)) as f:
                manager = yaml.safe_load(f)["Visualization Manager"]
            grid: Dict[str, Any] = next((d for d in manager["Displays"] if d.get("Class") == "rviz/Grid"), {})
            loaded = load_config(config)
            specs = [body_spec(loaded, name) for name in loaded["bodies"]]
            instants, failed = check_run(bag, manager["Views"]["Current"], specs, grid)
            print(f"{view_name} on {config_name}{' with ' + str(changes) if changes else ''}: {instants} instants "
                  f"of {args.duration:g} s, {sum(map(len, failed.values()))} failures")
            for lines in failed.values():
                print("\n".join("  " + line for line in lines[:SHOWN]))
                if len(lines) > SHOWN:
                    print(f"  ... and {len(lines) - SHOWN} more")
            failures += sum(map(len, failed.values())) + (instants < args.duration * 10 - 1)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
