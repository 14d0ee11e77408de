#!/usr/bin/env python3
"""The scripts that read bags and configs, on small bags written here: scripts/soak_bagcheck.py (a count
per topic, each checked on its own), scripts/bag_summary.py (every event of a run that rigid_body_sim.core
recorded, at its instant to the bit, with its values; bodies spawned or only in the events; a body with a single
state; a missing bag: one line),
test/pictures' reading of rviz's log (none there: a finding) and bench/run_bench.py's 1 kHz config.
Usage: test_scripts.py   (with the package's devel space sourced, for its messages)"""
import importlib.abc
import importlib.util
import os
import pathlib
import re
import subprocess
import sys
import tempfile
import unittest
from typing import Any, Dict, List, Tuple

import rosbag
import rospy
import yaml
from tf2_msgs.msg import TFMessage
from rigid_body_sim import core
from rigid_body_sim.msg import Event, EventField, RodState, RollerState
from rigid_body_sim.sim_tools import LISTED

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
SCRIPTS = os.path.join(ROOT, "scripts")


def write_bag(path: str, messages: Dict[str, List[Any]]) -> None:
    with rosbag.Bag(path, "w") as bag:
        for topic, msgs in messages.items():
            for i, msg in enumerate(msgs):
                bag.write(topic, msg, rospy.Time(1 + i))


def run_script(*args: str) -> "subprocess.CompletedProcess[str]":
    return subprocess.run([sys.executable, *args], capture_output=True, text=True)


class Case(unittest.TestCase):
    def setUp(self) -> None:
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self) -> None:
        self.tmp.cleanup()

    def path(self, name: str) -> str:
        return os.path.join(self.tmp.name, name)

    def write_config(self, config: Dict[str, Any]) -> str:
        with open(self.path("config.yaml"), "w") as f:
            yaml.safe_dump(config, f)
        return self.path("config.yaml")


class SoakBagcheck(Case):
    """A soak of 2 s at publish_rate 1: 2 states of the rod and 2 /tf (t = 1 and 2: the node, started paused,
    sent t = 0 before the recorder subscribed), 3 /tf_static (at the start and at each reconfigure)."""

    def check(self, states: int, tfs: int) -> "subprocess.CompletedProcess[str]":
        config = self.write_config({"publish_rate": 1.0, "rate": 1000.0, "bodies": {"rod": {"type": "rod"}}})
        write_bag(self.path("soak.bag"), {"/sim/rod/state": [RodState()] * states, "/tf": [TFMessage()] * tfs,
                                          "/tf_static": [TFMessage()] * 3})
        return run_script(os.path.join(SCRIPTS, "soak_bagcheck.py"), self.path("soak.bag"), config, "2")

    def test_every_count_as_expected_passes(self) -> None:
        result = self.check(2, 2)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertNotIn("MISMATCH", result.stdout)

    def test_an_extra_message_does_not_hide_a_missing_one(self) -> None:
        result = self.check(3, 1)
        self.assertEqual(result.stdout.count("MISMATCH"), 2, result.stdout)
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)

    def test_extra_messages_alone_fail(self) -> None:
        result = self.check(3, 2)
        self.assertIn("MISMATCH", result.stdout)
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)


DEMO = os.path.join(ROOT, "config", "demo.yaml")
Summary = Dict[str, Tuple[str, List[str]]]


def summarised(stdout: str) -> Summary:
    """bag_summary's output after the topics' counts: {body: (its line after the name, its kinds' lines)}."""
    bodies: Summary = {}
    current = ""
    for line in stdout.splitlines()[1:]:
        if line.startswith("  /"):
            continue  # a topic's count
        if line.startswith("  "):
            bodies[current][1].append(line.strip())
        else:
            current, _, rest = line.partition(": ")
            bodies[current] = (rest, [])
    return bodies


def kind_line(line: str) -> Tuple[str, int, List[Tuple[float, Dict[str, Any]]]]:
    """A kind's line: the kind, how often, and each instant listed with its values (numbers as float)."""
    found = re.fullmatch(r"(\w+): (once|\d+ times), at t = (.*) s", line)
    assert found, line
    listed = []
    for item in found.group(3).split(", "):
        instant, _, pairs = item.partition(" (")
        values: Dict[str, Any] = {}
        for pair in pairs.rstrip(")").split():
            name, text = pair.split("=")
            values[name] = float(text) if re.fullmatch(r"[-+.e\d]+|nan|-?inf", text) else text
        listed.append((float(instant), values))
    return found.group(1), 1 if found.group(2) == "once" else int(found.group(2).split()[0]), listed


def event(t: float, body: str, type_name: str, kind: str, **values: Any) -> Event:
    message = Event(t=t, body=body, type=type_name, kind=kind)
    message.values = [EventField(name=name, text=value) if isinstance(value, str) else
                      EventField(name=name, number=value) for name, value in values.items()]
    return message


class BagSummary(Case):
    def summary(self, *args: str) -> Summary:
        result = run_script(os.path.join(SCRIPTS, "bag_summary.py"), *args)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertEqual(result.stderr, "")
        return summarised(result.stdout)

    def test_every_event_at_its_instant(self) -> None:
        """A run of demo.yaml recorded by rigid_body_sim.core, its events as the core returned them: each body's
        kinds, how often, every instant to the bit (0.565892621098528, not a sample's 0.58) with its values."""
        _, events = core.World(pathlib.Path(DEMO)).run(6.0, bag=self.path("run.bag"), events=True)
        bodies = self.summary(self.path("run.bag"), DEMO)
        with open(DEMO) as f:
            self.assertEqual(list(bodies), list(yaml.safe_load(f)["bodies"]))
        for body, (_, lines) in bodies.items():
            mine = [e for e in events if e["body"] == body]
            self.assertEqual(sorted(kind_line(line)[0] for line in lines), sorted({e["kind"] for e in mine}), body)
            for line in lines:
                kind, often, listed = kind_line(line)
                happened = [e for e in mine if e["kind"] == kind]
                self.assertEqual(often, len(happened), line)
                self.assertEqual(listed, [(e["t"], e["values"]) for e in happened[:LISTED]], line)
        slips = [e["t"] for e in events if e["body"] == "bowler" and e["kind"] == "slip_to_roll"]
        self.assertIn(f"slip_to_roll: {len(slips)} times, at t = 0.565892621098528 (closed_form=0.565892621098528), ",
                      bodies["bowler"][1][0])

    def test_a_spawned_body_and_one_only_in_the_events(self) -> None:
        config = self.write_config({"bodies": {"rod": {"type": "rod"}, "ball": {"type": "roller"}}})
        rod, hoop = RodState(), RollerState()
        rod.energy, hoop.t, hoop.mode = 19.6, 0.5, "rolling"
        write_bag(self.path("run.bag"), {
            "/sim/rod/state": [rod], "/sim/hoop/state": [hoop],
            "/sim/events": [event(0.123456789012345, "hoop", "roller", "slip_to_roll"),
                            event(0.75, "hoop", "roller", "finished", lap_time=0.75, place=2.0),
                            event(0.8, "hoop", "roller", "lap_restarted", cause="race"),
                            event(1.5, "ghost", "block", "came_to_rest")]})
        bodies = self.summary(self.path("run.bag"), config)
        with open(config) as f:
            self.assertEqual(list(bodies), [*yaml.safe_load(f)["bodies"], "hoop", "ghost"])  # the config's first
        self.assertEqual(bodies["ball"], ("in the config, nothing in the bag", []))
        self.assertTrue(bodies["hoop"][0].startswith("t 0.5 .. 0.5 s (a single sample)"), bodies["hoop"])
        self.assertTrue(bodies["hoop"][0].endswith("; final mode rolling (not in the config)"), bodies["hoop"])
        self.assertEqual(bodies["hoop"][1], ["slip_to_roll: once, at t = 0.123456789012345 s",
                                             "finished: once, at t = 0.75 (lap_time=0.75 place=2) s",
                                             "lap_restarted: once, at t = 0.8 (cause=race) s"])
        self.assertEqual(bodies["ghost"], ("no states (not in the config)", ["came_to_rest: once, at t = 1.5 s"]))
        # Without a config: the bag's bodies as they first appear, none noted.
        self.assertEqual(list(self.summary(self.path("run.bag"))), ["rod", "hoop", "ghost"])

    def test_a_body_with_a_single_state(self) -> None:
        config = self.write_config({"bodies": {"rod": {"type": "rod"}, "ball": {"type": "roller"}}})
        rod, ball = RodState(), RollerState()
        rod.y, rod.energy = 4.0, 19.6
        ball.mode, ball.energy = "rolling", 1.0
        write_bag(self.path("run.bag"), {"/sim/rod/state": [rod], "/sim/ball/state": [ball]})
        bodies = self.summary(self.path("run.bag"), config)
        self.assertEqual(bodies["rod"], ("t 0 .. 0 s (a single sample), energy 19.6 -> 19.6 J (min 19.6, max 19.6)",
                                         []))
        self.assertEqual(bodies["ball"][0], "t 0 .. 0 s (a single sample), energy 1 -> 1 J (min 1, max 1); "
                                            "final mode rolling")

    def test_a_missing_bag_is_one_line(self) -> None:
        config = self.write_config({"bodies": {"rod": {"type": "rod"}}})
        result = run_script(os.path.join(SCRIPTS, "bag_summary.py"), self.path("missing.bag"), config)
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        self.assertEqual(result.stderr.splitlines(),
                         [f"bag_summary.py: bag {self.path('missing.bag')}: No such file or directory"])
        self.assertEqual(result.stdout, "")


class RvizLog(Case):
    """The pictures' "no ERROR line in rviz's log" reads rviz's output where roslaunch keeps it: a log folder
    without it is a finding, never a clean log."""

    def error_lines(self) -> List[str]:
        rviz_log = load_module(os.path.join(ROOT, "test", "pictures", "rviz_log.py"))
        os.environ["ROS_LOG_DIR"] = self.tmp.name
        try:
            lines: List[str] = rviz_log.rviz_error_lines()
        finally:
            del os.environ["ROS_LOG_DIR"]
        return lines

    def test_no_output_of_rviz_is_a_line(self) -> None:
        self.assertEqual(self.error_lines(), [f"no output of rviz in {self.path('latest')}"])

    def test_its_error_lines_or_none(self) -> None:
        os.mkdir(self.path("run"))
        os.symlink(self.path("run"), self.path("latest"))
        with open(self.path("run/rviz-2-stdout.log"), "w") as f:
            f.write("[ INFO] loaded\n[ERROR] PluginlibFactory: failed\n")
        self.assertEqual(self.error_lines(), ["[ERROR] PluginlibFactory: failed"])
        with open(self.path("run/rviz-2-stdout.log"), "w") as f:
            f.write("[ INFO] loaded\n")
        self.assertEqual(self.error_lines(), [])


def load_module(path: str) -> Any:
    """A module of another folder's tool or test (bench/, test/pictures/), loaded from its file: neither folder
    is a package, nor on this script's path."""
    name = os.path.splitext(os.path.basename(path))[0]
    spec = importlib.util.spec_from_file_location(name, path)
    # isinstance, not `is not None`: bullseye's typeshed types spec.loader as a protocol without exec_module.
    assert spec is not None and isinstance(spec.loader, importlib.abc.Loader)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


class RunBench(Case):
    def test_the_1khz_config_whatever_the_source_writes(self) -> None:
        run_bench = load_module(os.path.join(ROOT, "bench", "run_bench.py"))
        for text in ("publish_rate: 50.0\n", "publish_rate: 50\n", "publish_rate:   5e1\n", ""):
            with open(self.path("source.yaml"), "w") as f:
                f.write(text + "rate: 1000.0\nbodies: {rod: {type: rod}}\n")
            run_bench.write_with_publish_rate(self.path("source.yaml"), self.path("1khz.yaml"), 1000.0)
            with open(self.path("1khz.yaml")) as f:
                written = yaml.safe_load(f)
            self.assertEqual(written["publish_rate"], 1000.0, repr(text))
            self.assertEqual(written["bodies"], {"rod": {"type": "rod"}}, repr(text))


if __name__ == "__main__":
    unittest.main(verbosity=2)
