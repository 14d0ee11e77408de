#!/usr/bin/env python3
"""sim_node's output checked against the offline tool, live, in a recording and in its playback.

- As fast as possible (real_time_factor 0) for 60 s of simulated time, a listener receives every state
  exactly once: 60 * publish_rate + 1 per body, at t = j / publish_rate, the last at 60 s (60 * rate steps),
  each equal to `simulate`'s CSV row at that t, bit for bit; /clock never 0, never back, to 60 s.
- As fast as possible for 600 s with the node's own recorder (~bag): the bag has every state of every
  publishing instant from t = 0, each equal to the CSV, bit for bit.
- Through sim.launch record:=true use_sim_time:=true: the bag is closed, has every topic, each body's states
  at every publishing instant exactly once, stamped in simulated time (t + 1 ns), equal to the CSV.
- playback.launch (rosbag play --clock, once every topic has a subscriber) delivers every recorded state to a
  listener, in order.

Usage: test_record_playback.py SIMULATE_EXE SIM_NODE_EXE CONFIG.yaml   (with the package's devel space sourced)
"""
import argparse
import csv
import math
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import unittest
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Tuple

import rosbag
import rosgraph
import rospy
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Empty
from rigid_body_sim import core, runs
from rigid_body_sim.testing import STATE_TYPES
from rigid_body_sim.sim_tools import (Config, free_port, load_config, play_until, state_fields, subscribe_to_the_rest,
                                      wait_for, world_value)

States = Dict[str, List[Any]]


@dataclass(frozen=True)
class Tools:
    """What the tests run, from the command line."""
    simulate: str
    sim_node: str
    config: str


def as_row(msg: Any) -> List[Any]:
    """A state message as the values of simulate's CSV row (numbers as floats, mode as text)."""
    return [getattr(msg, f) for f in state_fields(msg)]


def sim_stamp(t: float) -> Any:
    """The node's stamp for simulated time t: 1 ns + ros::Duration(t) (which rounds to the nearest ns)."""
    sec = math.floor(t)
    return rospy.Time(0, 1) + rospy.Duration(int(sec), int(math.floor((t - sec) * 1e9 + 0.5)))


class Master:
    """A roscore of its own on a free port, and this process as a rospy node on it."""

    def __init__(self) -> None:
        self.port = free_port()
        self.env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{self.port}")
        self.process = subprocess.Popen(["roscore", "-p", str(self.port)], env=self.env,
                                        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.environ["ROS_MASTER_URI"] = self.env["ROS_MASTER_URI"]
        wait_for("roscore", rosgraph.Master("/listener").is_online, 30.0, period=0.2)
        if not rospy.core.is_initialized():
            rospy.init_node("listener", anonymous=True, disable_signals=True)

    def run(self, args: List[str], timeout: float = 120) -> "subprocess.CompletedProcess[str]":
        return subprocess.run(args, env=self.env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              timeout=timeout)

    def stop(self) -> None:
        self.process.terminate()
        self.process.wait(timeout=20)


class Listener:
    """Every state message of every body, in arrival order (unbounded queues: nothing dropped here)."""

    def __init__(self, config: Config) -> None:
        self.states: States = {name: [] for name in config["bodies"]}
        self.subs = [rospy.Subscriber(f"/sim/{name}/state",
                                      STATE_TYPES[body["type"]],
                                      lambda msg, name=name: self.states[name].append(msg), queue_size=None)
                     for name, body in config["bodies"].items()]

    def wait_connected(self, timeout: float = 20) -> None:
        wait_for("a publisher of the state topics", lambda: all(sub.get_num_connections() for sub in self.subs),
                 timeout)

    def has_every_state_at(self, last_t: float) -> bool:
        """Every body's state at last_t has come: each topic delivers in order, and a full queue drops its
        oldest message, never the newest, so all that was published before has come too."""
        return all(msgs and msgs[-1].t == last_t for msgs in self.states.values())

    def close(self, last_t: float, timeout: float = 30) -> None:
        """After every body's state at last_t has come."""
        wait_for(f"every body's state at t = {last_t:g}", lambda: self.has_every_state_at(last_t), timeout)
        for sub in self.subs:
            sub.unregister()


class NodeOutput(unittest.TestCase):
    tools: Tools  # set by main()
    config: Config
    publish_rate: float
    tmp: str
    csv: Dict[str, Tuple[List[str], List[List[Any]]]]
    master: Master

    @classmethod
    def setUpClass(cls) -> None:
        cls.config = load_config(cls.tools.config)
        cls.publish_rate = float(world_value(cls.config, "publish_rate"))
        cls.tmp = tempfile.mkdtemp(prefix="rbs_record_")
        cls.csv = cls.simulated(60.0)
        cls.master = Master()

    @classmethod
    def simulated(cls, duration: float) -> Dict[str, Tuple[List[str], List[List[Any]]]]:
        """`simulate`'s CSV rows of the config for `duration`, by body: the core's states."""
        out = os.path.join(cls.tmp, f"csv{duration:g}")
        subprocess.run([cls.tools.simulate, cls.tools.config, "--duration", f"{duration:g}", "--out-dir", out],
                       check=True, stdout=subprocess.DEVNULL)
        rows = {}
        for name in cls.config["bodies"]:
            with open(os.path.join(out, f"{name}.csv")) as f:
                reader = csv.reader(f)
                header = next(reader)
                rows[name] = (header, [[cell if key == "mode" else float(cell) for key, cell in zip(header, row)]
                                       for row in reader])
        return rows

    @classmethod
    def tearDownClass(cls) -> None:
        cls.master.stop()
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def expect_every_sample(self, states: States, duration: float, what: str, first: int = 0,
                            csv_rows: Optional[Dict[str, Tuple[List[str], List[List[Any]]]]] = None) -> None:
        """Each body's states: every publishing instant from sample `first` up to duration exactly once, each
        equal to the CSV (the 60 s one unless `csv_rows`). Before `first`, samples may be missing (published
        before the test subscribed)."""
        samples = int(round(duration * self.publish_rate))
        for name, msgs in states.items():
            msgs = [m for m in msgs if m.t >= first / self.publish_rate]
            ts = [m.t for m in msgs]
            self.assertEqual(len(ts), samples + 1 - first, f"{what}: {name} has {len(ts)} states for {duration:g} s")
            self.assertEqual(ts, [j / self.publish_rate for j in range(first, samples + 1)], f"{what}: {name}")
            header, rows = (csv_rows or self.csv)[name]
            for row, msg in zip(rows[first:], msgs):
                self.assertEqual(header, state_fields(msg), name)
                self.assertEqual(row, as_row(msg), f"{what}: {name} at t = {msg.t}")

    def test_as_fast_as_possible_every_state_once(self) -> None:
        self.master.run(["rosparam", "load", self.tools.config, "/sim"])
        node = subprocess.Popen([self.tools.sim_node, "__name:=sim", "_real_time_factor:=0", "_duration:=60",
                                 "_start_paused:=true", "_publish_clock:=true"],
                                env=self.master.env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        clocks: List[Any] = []
        try:
            # The node publishes its first /clock (latched) and the states at t = 0, then waits. Subscribing
            # after that first /clock, this test gets it once, as the latched copy: a subscriber that
            # connects while a latched topic publishes gets that message twice (the copy and the message).
            rospy.wait_for_service("/sim/unpause", timeout=20.0)
            rospy.wait_for_message("/clock", Clock, timeout=20.0)
            listener = Listener(self.config)
            clock_sub = rospy.Subscriber("/clock", Clock, lambda msg: clocks.append(msg.clock), queue_size=None)
            listener.wait_connected()
            wait_for("a /clock publisher", lambda: clock_sub.get_num_connections() > 0, 20.0)
        except (TimeoutError, rospy.ROSException) as error:
            node.kill()
            raise AssertionError(f"{error}; the node said:\n" + node.communicate()[0])
        rospy.ServiceProxy("/sim/unpause", Empty)()
        log, _ = node.communicate(timeout=120)
        listener.close(60.0)
        clock_sub.unregister()
        self.assertEqual(node.returncode, 0, log)
        self.assertIn("simulated 60.000 s", log)
        # The states at t = 0 came before this test subscribed: every one after, exactly once.
        self.expect_every_sample(listener.states, 60.0, "live, real_time_factor 0", first=1)
        self.assertEqual(clocks[0], sim_stamp(0.0), "the first /clock is the latched one of t = 0")
        not_increasing = [i for i in range(1, len(clocks)) if clocks[i] <= clocks[i - 1]]
        self.assertEqual(not_increasing, [], "/clock not strictly increasing at: " + ", ".join(
            f"[{i}] {clocks[i - 1].to_sec()} -> {clocks[i].to_sec()}" for i in not_increasing[:5]))
        self.assertEqual(clocks[-1], sim_stamp(60.0))

    def test_as_fast_as_possible_600_s_in_the_nodes_own_bag(self) -> None:
        """At real_time_factor 0 a subscriber may fall behind, the node's own recorder (~bag) never: 600 s of
        simulated time, every state at every publishing instant from t = 0, each equal to the core's."""
        bag_path = os.path.join(self.tmp, "own.bag")
        self.master.run(["rosparam", "load", self.tools.config, "/sim"])
        node = self.master.run([self.tools.sim_node, "__name:=sim", "_real_time_factor:=0", "_duration:=600",
                                "_start_paused:=false", f"_bag:={bag_path}"], timeout=300)
        self.assertEqual(node.returncode, 0, node.stdout[-3000:])
        states: States = {}
        with rosbag.Bag(bag_path) as bag:
            for topic, msg, _ in bag.read_messages(topics=[f"/sim/{name}/state" for name in self.config["bodies"]]):
                states.setdefault(topic.split("/")[2], []).append(msg)
        self.assertEqual(set(states), set(self.config["bodies"]))
        self.expect_every_sample(states, 600.0, "the node's own bag, real_time_factor 0",
                                 csv_rows=self.simulated(600.0))

    def test_recording_and_playback(self) -> None:
        duration = 15.0
        bag_path = os.path.join(self.tmp, "run.bag")
        launch = self.master.run(
            ["roslaunch", "rigid_body_sim", "sim.launch", f"config:={self.tools.config}", "record:=true",
             f"bag:={bag_path}", "use_sim_time:=true", "real_time_factor:=5", f"duration:={duration:g}"])
        self.assertTrue(os.path.exists(bag_path), "no bag; roslaunch said:\n" + launch.stdout[-3000:])
        self.assertFalse(os.path.exists(bag_path + ".active"), "the recorder did not close the bag")
        recorded: States = {}
        with rosbag.Bag(bag_path) as bag:
            for topic, msg, _ in bag.read_messages():
                recorded.setdefault(topic, []).append(msg)
        topics = {"/tf", "/tf_static", "/sim/scene", "/sim/markers", "/sim/commands", "/sim/events"}
        topics |= {f"/sim/{name}/state" for name in self.config["bodies"]}
        self.assertEqual(set(recorded), topics)
        # Every event of the run, each at its instant, as the core's World has them (bit for bit).
        _, happened = core.World(pathlib.Path(self.tools.config)).run(duration, events=True)
        self.assertEqual([runs.event_record(m) for m in recorded["/sim/events"]], happened)
        for m in recorded["/sim/events"]:
            self.assertEqual(m.header.stamp, sim_stamp(m.t), f"{m.kind} of {m.body} at t = {m.t}")

        states = {name: recorded[f"/sim/{name}/state"] for name in self.config["bodies"]}
        self.expect_every_sample(states, duration, "recorded")
        for name, msgs in states.items():
            for a, b in zip(msgs, msgs[1:]):
                self.assertGreater(b.header.stamp, a.header.stamp, f"{name} at t = {b.t}")
            for m in msgs:
                self.assertEqual(m.header.stamp, sim_stamp(m.t), f"{name} at t = {m.t}")

        listener = Listener(self.config)
        # The player starts once every topic has a subscriber: the listener's states, and the rest here. It
        # stays past the bag's end until the listener has the last states (keep_alive:=true).
        rest = subscribe_to_the_rest(bag_path, [sub.name for sub in listener.subs])
        said = play_until(bag_path, f"every body's state at t = {duration:g}",
                          lambda: listener.has_every_state_at(duration), 120.0, self.master.env, ["rate:=5"])
        listener.close(duration)
        for sub in rest:
            sub.unregister()
        for name in self.config["bodies"]:
            self.assertEqual([as_row(m) for m in listener.states[name]], [as_row(m) for m in states[name]],
                             f"{name} played back; roslaunch said:\n" + said)


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("simulate", help="the simulate executable")
    parser.add_argument("sim_node", help="the sim_node executable")
    parser.add_argument("config", help="the config both run")
    args, unittest_args = parser.parse_known_args()
    NodeOutput.tools = Tools(args.simulate, args.sim_node, os.path.abspath(args.config))
    unittest.main(argv=sys.argv[:1] + unittest_args, verbosity=2, warnings="ignore")


if __name__ == "__main__":
    main()
