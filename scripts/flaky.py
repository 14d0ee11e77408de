#!/usr/bin/python3
"""make flaky: runs the suites that start a master (ctest labels node, script, pictures, web) RUNS times and
prints, per test, its failures out of RUNS and its time; exits 1 if any test failed once.

Every round is one ctest run as `make test` runs it (--jobs tests at once, two rviz or Chromium at most, a fresh
ROS_HOME, the loopback by address).
The output of every failed test is kept in KEEP/round<i>/ (ctest's log and its JUnit file).
With --hog N, N processes spin on the CPU for the whole run: the busy machine the tests must pass on.
"""
from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import time
import xml.etree.ElementTree as ElementTree
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, Iterator, List


@dataclass
class Record:
    """One test over every round."""
    runs: int = 0
    failures: List[int] = field(default_factory=list)  # the rounds it failed in
    seconds: List[float] = field(default_factory=list)


@dataclass
class Outcome:
    """One test in one round."""
    name: str
    failed: bool
    seconds: float


def short_name(name: str) -> str:
    """A rostest's ctest name without catkin's prefix: `rostest states.test`."""
    prefix = "_ctest_rigid_body_sim_rostest_test_rostest_"
    return "rostest " + name[len(prefix):] if name.startswith(prefix) else name


def read_junit(path: Path) -> List[Outcome]:
    """The tests of a ctest --output-junit file: a <failure> (or a status other than run) is a failure."""
    outcomes = []
    for case in ElementTree.parse(path).getroot().iter("testcase"):
        failed = case.find("failure") is not None or case.get("status", "run") not in ("run", "")
        outcomes.append(Outcome(short_name(case.get("name", "?")), failed, float(case.get("time", "0") or 0)))
    return outcomes


def run_round(build: Path, labels: str, jobs: int, folder: Path) -> List[Outcome]:
    """One ctest run of the labelled tests; its log, JUnit file and ROS_HOME (the nodes' logs) go to `folder`."""
    home = str(folder / "ros_home")
    # Debian's python3 first (rostest's nodes import ROS's modules), as the Makefile does.
    env = dict(os.environ, ROS_HOME=home, ROS_IP="127.0.0.1", PATH="/usr/bin:" + os.environ.get("PATH", ""))
    env.pop("ROS_HOSTNAME", None)
    junit = folder / "ctest.xml"
    with open(folder / "ctest.log", "w") as log:
        subprocess.run(["ctest", "-j", str(jobs), "-L", labels, "--output-on-failure", "--output-junit",
                        str(junit.resolve())],
                       cwd=build, env=env, stdout=log, stderr=subprocess.STDOUT)
    if not junit.exists():
        raise SystemExit(f"flaky: ctest wrote no {junit}; see {folder / 'ctest.log'}")
    outcomes = read_junit(junit)
    if not outcomes:  # a round of nothing would count as "every test passed"
        raise SystemExit(f"flaky: no test has a label of {labels!r}; see {folder / 'ctest.log'}")
    return outcomes


@contextmanager
def cpu_hogs(count: int) -> Iterator[None]:
    """`count` processes that keep a core busy each (at normal priority, as another user's job would)."""
    hogs = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(count)]
    try:
        yield
    finally:
        for hog in hogs:
            hog.kill()
            hog.wait()


def table(records: Dict[str, Record], rounds: int, wall: float) -> str:
    """The Markdown table: per test its failures out of the rounds and its time."""
    lines = [f"| test | failures of {rounds} | rounds failed | mean time (s) | max time (s) |",
             "|---|---:|---|---:|---:|"]
    for name, record in sorted(records.items()):
        failed = ", ".join(str(r) for r in record.failures) or "-"
        lines.append(f"| {name} | {len(record.failures)} of {record.runs} | {failed} | "
                     f"{statistics.mean(record.seconds):.1f} | {max(record.seconds):.1f} |")
    total = sum(sum(r.seconds) for r in records.values())
    lines.append(f"\n{len(records)} tests, {rounds} rounds, {total:.0f} s of tests, {wall:.0f} s wall "
                 f"({wall / max(1, rounds):.0f} s a round)")
    return "\n".join(lines)


def parse_args() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default="build", help="the build folder, its tests built")
    parser.add_argument("--runs", type=int, default=10, help="rounds (default 10)")
    parser.add_argument("--labels", default="node|script|pictures|web", help="ctest -L: the labels to run")
    parser.add_argument("--keep", default="build/flaky", help="where the logs of the rounds with a failure go")
    parser.add_argument("--jobs", type=int, default=(os.cpu_count() or 1) + 2,
                        help="ctest -j: tests at once, as `make test` runs them (default: two more than the cores)")
    parser.add_argument("--hog", type=int, default=0, help="processes that keep a core busy each, all along")
    return parser.parse_args()


def main() -> int:
    args = parse_args()
    build = Path(args.build).resolve()
    keep = Path(args.keep).resolve()
    shutil.rmtree(keep, ignore_errors=True)
    records: Dict[str, Record] = {}
    began = time.monotonic()
    with cpu_hogs(args.hog):
        run_rounds(args.runs, build, args.labels, args.jobs, keep, records)
    busy = f", {args.hog} cores kept busy" if args.hog else ""
    print(table(records, args.runs, time.monotonic() - began) + busy)
    flaky = [name for name, record in records.items() if record.failures]
    print("flaky: " + (f"{len(flaky)} tests failed at least once: {', '.join(sorted(flaky))}" if flaky
                       else "every test passed every round"))
    return 1 if flaky else 0


def run_rounds(runs: int, build: Path, labels: str, jobs: int, keep: Path, records: Dict[str, Record]) -> None:
    """Every round, its outcomes added to `records`; a round's logs kept if a test failed in it."""
    for index in range(1, runs + 1):
        folder = keep / f"round{index}"
        folder.mkdir(parents=True)
        round_began = time.monotonic()
        outcomes = run_round(build, labels, jobs, folder)
        for outcome in outcomes:
            record = records.setdefault(outcome.name, Record())
            record.runs += 1
            record.seconds.append(outcome.seconds)
            if outcome.failed:
                record.failures.append(index)
        failed = [o.name for o in outcomes if o.failed]
        print(f"flaky: round {index} of {runs}: {len(outcomes)} tests in {time.monotonic() - round_began:.0f} s, "
              + (f"FAILED: {', '.join(failed)} (log in {folder})" if failed else "all passed"), flush=True)
        if failed:
            # The picture tests' screenshots, findings and roslaunch logs of this round: the next overwrites them.
            pictures = build / "test_results" / "pictures"
            if pictures.is_dir():
                shutil.copytree(pictures, folder / "pictures")
        else:
            shutil.rmtree(folder)


if __name__ == "__main__":
    sys.exit(main())
