#!/usr/bin/env python3
"""A run changed while it runs, recorded, equals its replay bit for bit.

sim.launch record:=true at wall-clock pace; a script changes the world with every kind of change: a
reconfigure through dynparam, ~spawn, ~set_state, ~delete, ~reset, ~pause / ~step / ~unpause (with changes
while paused). Then `simulate --replay BAG --sample-rate RATE` rebuilds the run from /sim/commands alone, and
every state message in the bag equals the replay's CSV row at its t, field for field, bit for bit, and every
event in the bag (/sim/events) the replay's events.csv row. The bag's
commands are numbered 0, 1, 2, ... from the config, with every kind of change among them. The replay with
`--bag OUT` holds the bag's commands and state messages unchanged, and OUT replays to the same CSV files.

Usage: test_replay.py SIMULATE_EXE CONFIG.yaml   (with the package's devel space sourced)
"""
import argparse
import csv
import math
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import unittest
from typing import Any, Dict, List

import rosbag
import rosgraph
import rospy
from rigid_body_sim import runs
from rigid_body_sim.msg import RodState
from rigid_body_sim.sim_tools import (body_of_state_topic, free_port, load_config, read_states, state_fields,
                                      wait_for, world_value)
from rigid_body_sim.srv import Delete, SetState, Spawn, Step
from std_srvs.srv import Empty

ARGS: Any = None


class Script:
    """The changes, each through the node's own interface, paced by the rod's simulated time."""

    def __init__(self) -> None:
        self.latest_t = -1.0
        rospy.Subscriber("/sim/rod/state", RodState, self.on_rod, queue_size=100)

    def on_rod(self, msg: RodState) -> None:
        self.latest_t = msg.t

    def wait_sim(self, seconds: float) -> None:
        start = self.latest_t
        wait_for(f"{seconds} s of simulated time after {start}", lambda: self.latest_t >= start + seconds, 60.0)

    @staticmethod
    def call(name: str, kind: Any, *args: Any) -> Any:
        rospy.wait_for_service(name, timeout=30.0)
        return rospy.ServiceProxy(name, kind)(*args)

    @staticmethod
    def wait_recorded(topic: str) -> None:
        """Until the recorder (rosbag record finds new topics by polling) subscribes to `topic`."""
        def subscribed() -> bool:
            _, subscribers, _ = rosgraph.Master("/replay_script").getSystemState()
            return any(name == topic and "/record" in nodes for name, nodes in subscribers)
        wait_for(f"the recorder on {topic}", subscribed, 30.0, period=0.1)

    def ok(self, name: str, kind: Any, *args: Any) -> None:
        response = self.call(name, kind, *args)
        assert response.success, f"{name}{args}: {response.message}"

    def run(self, env: Dict[str, str]) -> None:
        wait_for("the rod's first states", lambda: self.latest_t > 0.1, 60.0)
        subprocess.run(["rosrun", "dynamic_reconfigure", "dynparam", "set", "/sim/rod", "k", "2000"], env=env,
                       check=True, timeout=60, stdout=subprocess.DEVNULL)
        self.wait_sim(0.3)
        self.ok("/sim/spawn", Spawn, "hoop", "{type: roller, shape: ring, incline_angle: 0.4, x0: 0.5}")
        self.wait_recorded("/sim/hoop/state")
        self.wait_sim(0.3)
        self.ok("/sim/set_state", SetState, "hoop", "{x: 1.25, v: 0.7}")
        self.ok("/sim/set_state", SetState, "rod", "{y: 2.5, omega: -1.5}")
        self.wait_sim(0.3)
        self.ok("/sim/delete", Delete, "cylinder")
        self.wait_sim(0.3)
        self.call("/sim/reset", Empty)
        self.wait_sim(0.3)
        self.call("/sim/pause", Empty)
        self.ok("/sim/step", Step, 7)  # off the publishing grid: published where it ends
        self.ok("/sim/set_state", SetState, "sphere", "{x: 0.3}")  # while paused: shows with the next step
        self.ok("/sim/step", Step, 13)
        self.ok("/sim/spawn", Spawn, "stick", "{type: rod, y0: 3, seed: 5}")
        self.wait_recorded("/sim/stick/state")
        self.call("/sim/unpause", Empty)
        self.wait_sim(0.5)


def csv_rows(folder: str) -> Dict[str, Dict[float, List[str]]]:
    """{body: {t: the row's values after t}} from the replay's CSV files."""
    rows: Dict[str, Dict[float, List[str]]] = {}
    for name in os.listdir(folder):
        if name == runs.EVENTS_FILE:
            continue
        with open(os.path.join(folder, name), newline="") as handle:
            reader = csv.reader(handle)
            next(reader)
            rows[name[:-len(".csv")]] = {float(row[0]): row[1:] for row in reader}
    return rows


def same(value: Any, text: str) -> bool:
    """A message field and a CSV cell: numbers bit for bit (the CSV's shortest round-trip form), or text."""
    return value == text if isinstance(value, str) else float(text).hex() == float(value).hex()


def commands_of(bag_path: str) -> List[Any]:
    """What a command says, its stamp aside (the node's is wall time, a replay's simulated time)."""
    with rosbag.Bag(bag_path) as bag:
        return [(m.header.seq, m.step, m.t.hex(), m.kind, m.body, m.yaml)
                for _, m, _ in bag.read_messages(topics=["/sim/commands"])]


def states_of(bag_path: str) -> Dict[Any, List[str]]:
    """{(body, t): every field of the state message, numbers in hex} of a bag."""
    return {(body, msg.t): [v if isinstance(v, str) else float(v).hex()
                            for v in (getattr(msg, f) for f in state_fields(msg))]
            for body, msgs in read_states(bag_path).items() for msg in msgs}


class Replay(unittest.TestCase):
    def setUp(self) -> None:
        self.tmp = tempfile.mkdtemp(prefix="rbs_replay_")

    def tearDown(self) -> None:
        shutil.rmtree(self.tmp, ignore_errors=True)

    def test_replay_equals_the_recorded_run(self) -> None:
        port = free_port()
        # Debian's python3 first: dynparam and roslaunch run on whatever python3 PATH finds.
        env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_HOME=self.tmp, ROS_IP="127.0.0.1",
                   PATH="/usr/bin:" + os.environ.get("PATH", ""))
        env.pop("ROS_HOSTNAME", None)
        os.environ.update({k: env[k] for k in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")})
        bag_path = os.path.join(self.tmp, "run.bag")
        launch = subprocess.Popen(["roslaunch", "-p", str(port), "rigid_body_sim", "sim.launch",
                                   f"config:={ARGS.config}", "record:=true", f"bag:={bag_path}"],
                                  env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        try:
            wait_for("the master", lambda: subprocess.run(["rostopic", "list"], env=env, capture_output=True)
                     .returncode == 0, 60.0, period=0.2)
            rospy.init_node("replay_script", anonymous=True, disable_signals=True)
            Script().run(env)
        finally:
            launch.send_signal(signal.SIGINT)
            output, _ = launch.communicate(timeout=60)
        wait_for("the closed bag", lambda: os.path.exists(bag_path), 30.0)
        self.assertFalse(os.path.exists(bag_path + ".active"), output[-3000:])

        rate = world_value(load_config(ARGS.config), "rate")
        out_dir = os.path.join(self.tmp, "replay")
        again = os.path.join(self.tmp, "again.bag")
        replay = subprocess.run([ARGS.simulate, "--replay", bag_path, "--sample-rate", f"{rate:g}",
                                 "--out-dir", out_dir, "--bag", again], capture_output=True, text=True, timeout=300)
        self.assertEqual(replay.returncode, 0, replay.stderr)
        rows = csv_rows(out_dir)

        kinds: List[str] = []
        compared: Dict[str, int] = {}
        recorded_ts: Dict[str, List[float]] = {}
        with rosbag.Bag(bag_path) as bag:
            for topic, msg, _ in bag.read_messages():
                if topic == "/sim/commands":
                    self.assertEqual(msg.header.seq, len(kinds), "a gap in the commands")
                    kinds.append(msg.kind)
                    continue
                body = body_of_state_topic(topic)
                if body is None:
                    continue
                self.assertIn(msg.t, rows[body], f"{body} at t = {msg.t!r}: no replayed row")
                row = rows[body][msg.t]
                for field, cell in zip(state_fields(msg)[1:], row):
                    self.assertTrue(same(getattr(msg, field), cell),
                                    f"{body} at t = {msg.t!r}: {field} {getattr(msg, field)!r} vs {cell}")
                compared[body] = compared.get(body, 0) + 1
                recorded_ts.setdefault(body, []).append(msg.t)
        self.assertEqual(kinds[0], "config")
        for kind in ("reconfigure", "spawn", "set_state", "delete", "reset"):
            self.assertIn(kind, kinds)
        # Every body of the run, spawned and deleted ones included, was recorded and compared.
        self.assertEqual(set(compared), set(rows))
        self.assertIn("stick", rows)
        self.every_publishing_instant_recorded(recorded_ts)
        # What happened, bit for bit: the node's events (its changes' restarts among them) are the replay's, up
        # to the replay's end (its last recorded state: the node may have stepped on a little before its end).
        end = max(t for body_rows in rows.values() for t in body_rows)
        recorded_events = [event for event in runs.read_bag_events(bag_path) if event["t"] <= end]
        self.assertEqual(recorded_events, runs.read_events(out_dir))
        self.assertIn("reset", {event["values"].get("cause") for event in recorded_events})
        self.assertEqual(runs.read_bag_events(again), recorded_events)
        print(f"{len(recorded_events)} events equal to the replay's", file=sys.stderr)
        print(f"{sum(compared.values())} state messages equal to the replay ({compared}), {len(kinds)} commands",
              file=sys.stderr)
        self.replayed_bag_holds_the_run(bag_path, again, rate, out_dir)

    def every_publishing_instant_recorded(self, recorded_ts: Dict[str, List[float]]) -> None:
        """The config's bodies that live through the run: a state at every publishing instant from t = 0 to
        their last (the recorder subscribes before stepping starts), besides those where a ~step ended."""
        publish_rate = world_value(load_config(ARGS.config), "publish_rate")
        for body in set(load_config(ARGS.config)["bodies"]) - {"cylinder"}:  # the script deletes the cylinder
            ts = recorded_ts[body]
            on_grid = {round(t * publish_rate) for t in ts if abs(t * publish_rate - round(t * publish_rate)) < 1e-6}
            last = math.floor(max(ts) * publish_rate + 1e-6)  # the last instant on the grid at or before it
            missing = sorted(set(range(last + 1)) - on_grid)
            self.assertEqual(missing, [], f"{body}: no state at t = {[k / publish_rate for k in missing[:5]]}")
            self.assertGreater(last, 100, f"{body}: a run of {max(ts)} s is too short to compare")
            print(f"{body}: a state at each of the {last + 1} publishing instants to t = {last / publish_rate:g} s",
                  file=sys.stderr)

    def replayed_bag_holds_the_run(self, bag_path: str, again: str, rate: float, out_dir: str) -> None:
        """The replay's --bag: the recorded commands and states unchanged in it, and it replays the same."""
        self.assertEqual(commands_of(again), commands_of(bag_path))
        written = states_of(again)
        recorded = states_of(bag_path)
        for key, fields in recorded.items():
            self.assertEqual(written.get(key), fields, f"{key[0]} at t = {key[1]!r} in the replay's bag")
        out_again = os.path.join(self.tmp, "replay_again")
        replay = subprocess.run([ARGS.simulate, "--replay", again, "--sample-rate", f"{rate:g}",
                                 "--out-dir", out_again], capture_output=True, text=True, timeout=300)
        self.assertEqual(replay.returncode, 0, replay.stderr)
        self.assertEqual(csv_rows(out_again), csv_rows(out_dir))
        print(f"--bag: {len(recorded)} recorded states and the commands unchanged in it; it replays the same",
              file=sys.stderr)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("simulate")
    parser.add_argument("config")
    ARGS, rest = parser.parse_known_args()
    unittest.main(argv=[sys.argv[0]] + rest)
