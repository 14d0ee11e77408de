#!/usr/bin/env python3
"""The scripts that read bags and configs, on small bags written here: scripts/soak_bagcheck.py (a count
per topic, each checked on its own), scripts/bag_summary.py (a body with a single state; a missing bag: one line),
test/pictures' reading of rviz's log (none there: a finding) and bench/run_bench.py's 1 kHz config.
Usage: test_scripts.py   (with the package's devel space sourced, for its messages)"""
import importlib.abc
import importlib.util
import os
import subprocess
import sys
import tempfile
import unittest
from typing import Any, Dict, List

import rosbag
import rospy
import yaml
from tf2_msgs.msg import TFMessage
from rigid_body_sim.msg import RodState, RollerState

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


class BagSummary(Case):
    def test_a_body_with_a_single_state(self) -> None:
        config = self.write_config({"bodies": {"rod": {"type": "rod"}, "ball": {"type": "roller"}}})
        rod, ball = RodState(), RollerState()
        rod.y, rod.energy = 4.0, 19.6
        ball.mode, ball.energy = "rolling", 1.0
        write_bag(self.path("run.bag"), {"/sim/rod/state": [rod], "/sim/ball/state": [ball]})
        result = run_script(os.path.join(SCRIPTS, "bag_summary.py"), self.path("run.bag"), config)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertIn("ball: t 0 .. 0 s", result.stdout)
        self.assertIn("a single sample", result.stdout)
        self.assertIn("rod: t 0 .. 0 s", result.stdout)

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
