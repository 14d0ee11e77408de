#!/usr/bin/env python3
"""rod.launch and incline.launch take every argument of sim.launch but config, with the same defaults and docs
(rviz_config: the same doc, its default the wrapper's own rviz/<wrapper>.rviz); lesson.launch too, but with its
part choosing the config (config/race_<part>.yaml, or rod.yaml) and the view, its doc naming every part ("slip:"),
rviz and critical_angles on by default;
and every argument of sim.launch and playback.launch has a doc (roslaunch --ros-args shows it). playback.launch's
player is required (the launch ends with the bag) without rviz or with close_at_end, and only then; start_paused
passes --pause, keep_alive --keep-alive.

Usage: test_launch_files.py LAUNCH_DIR
"""
import argparse
import itertools
import os
import re
import sys
import xml.etree.ElementTree as ElementTree
from typing import Dict, List, Tuple

Args = Dict[str, Tuple[str, str]]  # name: (default, doc)
LESSON_VIEW = ("$(eval find('rigid_body_sim') + '/rviz/lesson_' + {'rod': 'rod', 'above': 'above'}.get(arg('part'), "
               "'race') + '.rviz')")


def launch_args(path: str) -> Args:
    """The top-level <arg>s of a launch file."""
    root = ElementTree.parse(path).getroot()
    return {arg.get("name", ""): (arg.get("default", ""), arg.get("doc", "")) for arg in root.findall("arg")}


def player(launch_dir: str, argv: List[str]) -> Tuple[bool, str]:
    """playback.launch's player with these arguments, as roslaunch loads it: (required, its arguments)."""
    import roslaunch.config
    import roslaunch.xmlloader
    config = roslaunch.config.ROSLaunchConfig()
    roslaunch.xmlloader.XmlLoader().load(os.path.join(launch_dir, "playback.launch"), config,
                                         argv=["bag:=/tmp/run.bag"] + argv, verbose=False)
    node = next(n for n in config.nodes if n.name == "player")
    return bool(node.required), str(node.args)


def playback_failures(launch_dir: str) -> List[str]:
    args = launch_args(os.path.join(launch_dir, "playback.launch"))
    failures = [f"playback.launch: {name} has no doc" for name, (_, doc) in args.items() if not doc]
    failures += [f"playback.launch: {name} has no default" for name, (default, _) in args.items()
                 if not default and name != "bag"]
    for rviz, close_at_end, start_paused, keep_alive in itertools.product(("true", "false"), repeat=4):
        argv = [f"rviz:={rviz}", f"close_at_end:={close_at_end}", f"start_paused:={start_paused}",
                f"keep_alive:={keep_alive}"]
        required, words = player(launch_dir, argv)
        if required != (rviz == "false" or close_at_end == "true"):
            failures.append(f"playback.launch {' '.join(argv)}: player required is {required}")
        flags = words.split()
        if ("--pause" in flags) != (start_paused == "true") or ("--keep-alive" in flags) != (keep_alive == "true"):
            failures.append(f"playback.launch {' '.join(argv)}: player's arguments {words}")
    if player(launch_dir, [])[0]:
        failures.append("playback.launch: the player is required by default (rviz would close at the end)")
    return failures


def lesson_parts(launch_dir: str) -> List[str]:
    """lesson.launch's parts: rod, and a race for every config/race_<part>.yaml."""
    configs = os.listdir(os.path.join(launch_dir, os.pardir, "config"))
    return ["rod"] + sorted(name[len("race_"):-len(".yaml")] for name in configs
                            if name.startswith("race_") and name.endswith(".yaml"))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("launch_dir")
    launch_dir = parser.parse_args().launch_dir
    sim = launch_args(os.path.join(launch_dir, "sim.launch"))
    failures = [f"sim.launch: {name} has no doc" for name, (_, doc) in sim.items() if not doc]
    del sim["config"]
    part_default, part_doc = launch_args(os.path.join(launch_dir, "lesson.launch")).get("part", ("", ""))
    failures += [f"lesson.launch: part's doc does not name {part}"
                 for part in lesson_parts(launch_dir) if not re.search(rf"\b{part}[,:]", part_doc)]
    lesson = dict(sim, rviz=("true", sim["rviz"][1]), critical_angles=("true", sim["critical_angles"][1]),
                  rviz_config=(LESSON_VIEW, sim["rviz_config"][1]), part=("below", part_doc))
    for wrapper in ("rod.launch", "incline.launch", "lesson.launch"):
        args = launch_args(os.path.join(launch_dir, wrapper))
        own_view = "$(find rigid_body_sim)/rviz/" + wrapper.replace(".launch", ".rviz")
        expected = lesson if wrapper == "lesson.launch" else dict(sim, rviz_config=(own_view, sim["rviz_config"][1]))
        for name in sorted(set(expected) | set(args)):
            if args.get(name) != expected.get(name):
                failures.append(f"{wrapper}: {name} is {args.get(name)}, expected {expected.get(name)}")
    failures += playback_failures(launch_dir)
    print("\n".join(failures) or "launch files: ok")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
