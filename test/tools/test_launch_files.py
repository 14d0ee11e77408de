#!/usr/bin/env python3
"""rod.launch and incline.launch take every argument of sim.launch but config, with the same defaults and docs,
and every argument has a doc (roslaunch --ros-args shows it).

Usage: test_launch_files.py LAUNCH_DIR
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ElementTree
from typing import Dict, Tuple

Args = Dict[str, Tuple[str, str]]  # name: (default, doc)


def launch_args(path: str) -> Args:
    """The top-level <arg>s of a launch file."""
    root = ElementTree.parse(path).getroot()
    return {arg.get("name", ""): (arg.get("default", ""), arg.get("doc", "")) for arg in root.findall("arg")}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("launch_dir")
    launch_dir = parser.parse_args().launch_dir
    sim = launch_args(os.path.join(launch_dir, "sim.launch"))
    failures = [f"sim.launch: {name} has no doc" for name, (_, doc) in sim.items() if not doc]
    del sim["config"]
    for wrapper in ("rod.launch", "incline.launch"):
        args = launch_args(os.path.join(launch_dir, wrapper))
        for name in sorted(set(sim) | set(args)):
            if args.get(name) != sim.get(name):
                failures.append(f"{wrapper}: {name} is {args.get(name)}, sim.launch has {sim.get(name)}")
    print("\n".join(failures) or "launch files: ok")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
