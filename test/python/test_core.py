#!/usr/bin/env python3
"""rigid_body_sim.core (the core's Python module) against `simulate`, the truth it claims to be:
- a World's run equals simulate's CSV bit for bit, for random valid configs of every body type (drawn from
  the key descriptions the module exports) and sample rates, read back by rigid_body_sim.runs, and the state
  messages of simulate --bag (the node's) read back from the bag;
- a refused config is a ValueError whose message is the line simulate --check prints after "simulate: "
  (every row of test/bad_input/configs.yaml), a refused change one with the node's line, the world unchanged;
- a sweep equals simulate --sweep's sweep.csv, and another Python thread runs while it does (the GIL released);
- a run with a bag writes the bag simulate --bag writes, byte for byte, and it reads back into the run's arrays;
  a run without one loads no ROS library;
- core.body_types() is the exported description (body_types.json) as json reads it;
- the typing stub core.pyi names what the module has (mypy's stubtest).
Usage: test_core.py SIMULATE_EXE   (with the package's devel or install space sourced)"""
import argparse
import ast
import json
import math
import os
import pathlib
import random
import subprocess
import sys
import tempfile
import threading
import time
import unittest
from typing import Any, Dict, List, Set, Tuple

import numpy
import yaml

import rigid_body_sim.core as core  # a compiled module; mypy reads its stub, rigid_body_sim/core.pyi
from rigid_body_sim import description, runs

HERE = os.path.dirname(os.path.abspath(__file__))
BAD_INPUT = os.path.join(HERE, "..", "bad_input", "configs.yaml")
CONFIG_DIR = os.path.join(HERE, "..", "..", "config")
SEED = 46  # the draws below are reproducible: a failure names its config
Run = Dict[str, Dict[str, numpy.ndarray]]


def draw_body(rng: random.Random, keys: List[Dict[str, Any]]) -> Dict[str, Any]:
    """A body of a type with each key a config file writes left out or drawn near its default (within its
    range), or among its choices: most draws are valid, and World says which are not."""
    body: Dict[str, Any] = {}
    for key in keys:
        if rng.random() < 0.5 or not key["written"]:
            continue
        if key["kind"] == "text":
            if key["choices"]:
                body[key["name"]] = rng.choice(key["choices"])
        else:
            low, high = key["range"]["min"], key["range"]["max"]  # None: unbounded
            value = key["default"] * rng.uniform(0.5, 1.5) + rng.uniform(-1.0, 1.0)
            body[key["name"]] = min(max(value, -math.inf if low is None else low), math.inf if high is None else high)
    return body


def draw_config(rng: random.Random) -> Tuple[Dict[str, Any], float]:
    """A valid config of one to three bodies of random types, and a sample rate that divides its rate."""
    types = core.body_types()["types"]
    while True:
        rate = rng.choice([500.0, 1000.0, 2000.0])
        config: Dict[str, Any] = {"rate": rate, "publish_rate": 50.0, "race": rng.random() < 0.2, "bodies": {}}
        for i in range(rng.randint(1, 3)):
            kind = rng.choice(sorted(types))
            config["bodies"][f"b{i}"] = dict(type=kind, **draw_body(rng, types[kind]["keys"]))
        try:
            core.World(config)
        except ValueError:
            continue
        return config, rng.choice([rate, rate / 10, 50.0])


def bag_messages(path: str) -> List[Tuple[str, int, str, str, bytes, Dict[str, str]]]:
    """A bag's messages in their order, each as it is stored: topic, time (ns), type, md5sum, the serialised
    message and its connection's header."""
    import rosbag  # only here: the other tests need no ROS

    with rosbag.Bag(path) as bag:
        return [(topic, stamp.to_nsec(), raw[0], raw[2], bytes(raw[1]), dict(header))
                for topic, raw, stamp, header in bag.read_messages(raw=True, return_connection_header=True)]


def bits(array: numpy.ndarray) -> Any:
    return array.view(numpy.uint64) if array.dtype == numpy.float64 else array


class CoreCase(unittest.TestCase):
    simulate: str  # set by main()

    def setUp(self) -> None:
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self) -> None:
        self.tmp.cleanup()

    def simulate_run(self, config: Dict[str, Any], *args: str) -> Tuple[subprocess.CompletedProcess, str]:
        folder = tempfile.mkdtemp(dir=self.tmp.name)
        path = os.path.join(folder, "config.yaml")
        with open(path, "w") as f:
            yaml.safe_dump(config, f, sort_keys=False)
        done = subprocess.run([self.simulate, path, "--out-dir", folder, *args], capture_output=True, text=True,
                              timeout=60)
        return done, folder

    def assert_same_run(self, mine: Run, theirs: Run, what: str) -> None:
        self.assertEqual(sorted(mine), sorted(theirs), what)
        for body in mine:
            self.assertEqual(list(mine[body]), list(theirs[body]), f"{what}: {body}'s fields")
            for field, values in mine[body].items():
                self.assertEqual(values.dtype, theirs[body][field].dtype, f"{what}: {body}.{field}")
                self.assertTrue(numpy.array_equal(bits(values), bits(theirs[body][field])),
                                f"{what}: {body}.{field} differs")

    def test_runs_equal_simulate_bit_for_bit(self) -> None:
        rng = random.Random(SEED)
        kinds: Set[str] = set()
        kinds_seen: Set[str] = set()
        for n in range(20):
            config, sample_rate = draw_config(rng)
            kinds.update(body["type"] for body in config["bodies"].values())
            duration = rng.choice([1.0, 2.0, 2.5])
            what = f"config {n} {config} at {sample_rate} Hz for {duration} s"
            done, folder = self.simulate_run(config, "--duration", repr(duration), "--sample-rate", repr(sample_rate))
            self.assertEqual(done.returncode, 0, what + ": " + done.stderr)
            world = core.World(config)
            samples, happened = world.run(duration, sample_rate=sample_rate, events=True)
            self.assert_same_run(samples, runs.read_run(folder), what)
            self.assertEqual(world.t, duration, what)
            # The events, bit for bit (float() of events.csv's shortest round-trip numbers gives the doubles).
            self.assertEqual(happened, runs.read_events(folder), what)
            kinds_seen.update(f"{event['type']}.{event['kind']}" for event in happened)
        self.assertEqual(kinds, set(core.body_types()["types"]), "every body type drawn")
        self.assertGreater(len(kinds_seen), len(kinds), f"events of several kinds compared: {kinds_seen}")

    def test_text_rod_and_demo_for_ten_seconds(self) -> None:
        for name in ["rod.yaml", "demo.yaml"]:
            path = os.path.join(CONFIG_DIR, name)
            with open(path) as f:
                config = yaml.safe_load(f)
            done, folder = self.simulate_run(config)
            self.assertEqual(done.returncode, 0, done.stderr)
            world = core.World(pathlib.Path(path))
            self.assert_same_run(world.run(10.0), runs.read_run(folder), name)
            world.reset()  # time goes on; the same run again from t = 10 s, its states those of a fresh world
            again = world.run(10.0)
            fresh = core.World(config).run(10.0)
            for body in fresh:
                for field in fresh[body]:
                    if field != "t":
                        self.assertTrue(numpy.array_equal(bits(again[body][field]), bits(fresh[body][field])))

    def test_events_after_steps_and_changes(self) -> None:
        """World.events() after steps: the closed form's slip-to-roll instant of a ball launched sliding
        (t = -u0 / (du/dt), section 16.3.2), in the state it carries (u = 0); a reset's restart after it."""
        world = core.World({"bodies": {"ball": {"type": "roller", "v0": 3.0, "mu_s": 0.3, "mu_d": 0.2}}})
        kinds = [kind["name"] for kind in core.body_types()["types"]["roller"]["event_kinds"]]
        self.assertIn("slip_to_roll", kinds)
        world.step(1000)
        happened = world.events()
        self.assertEqual([event["kind"] for event in happened], ["slip_to_roll"])
        rolled = happened[0]
        c, phi, g = 0.4, 0.349, 9.8
        dudt = g * (math.sin(phi) - 0.2 * math.cos(phi) * (1 + c) / c)
        self.assertAlmostEqual(rolled["t"], -3.0 / dudt, delta=1e-12)
        self.assertEqual(rolled["state"]["mode"], "rolling")
        self.assertEqual(rolled["state"]["omega"], -rolled["state"]["v"] / 0.1)
        self.assertEqual(world.events(), [], "read once")
        world.reset()
        restart = world.events()
        self.assertEqual([(e["kind"], e["values"]["cause"], e["t"]) for e in restart],
                         [("lap_restarted", "reset", 1.0)])

    def test_a_bag_reads_back_into_the_same_arrays(self) -> None:
        path = os.path.join(CONFIG_DIR, "demo.yaml")
        with open(path) as f:
            config = yaml.safe_load(f)
        bag = os.path.join(self.tmp.name, "run.bag")
        done, folder = self.simulate_run(config, "--duration", "3", "--bag", bag)  # the node's messages
        self.assertEqual(done.returncode, 0, done.stderr)
        mine = core.World(pathlib.Path(path)).run(3.0)
        self.assert_same_run(mine, runs.read_bag(bag), "demo.yaml's bag")
        self.assert_same_run(mine, runs.read_run(folder), "demo.yaml's CSV")

    def test_steps_and_state(self) -> None:
        world = core.World({"rate": 1000, "bodies": {"rod": {"type": "rod"}, "ball": {"type": "roller"}}})
        self.assertEqual(world.bodies, ["rod", "ball"])
        world.step(1234)
        self.assertEqual(world.steps, 1234)
        self.assertEqual(world.t, 1234 / 1000)
        run = core.World(world.config()).run(1.234, sample_rate=1000)
        for body in ["rod", "ball"]:
            state = world.state(body)
            self.assertEqual(list(state), [f for f in run[body] if f != "t"])
            for field, value in state.items():
                self.assertEqual(value, run[body][field][-1].item(), f"{body}.{field}")

    def test_refused_configs_say_what_simulate_check_says(self) -> None:
        with open(BAD_INPUT) as f:
            rows = yaml.safe_load(f)
        checked = 0
        for row in rows:
            if "config" not in row or row.get("args"):
                continue
            path = os.path.join(self.tmp.name, "bad.yaml")
            with open(path, "w") as f:
                f.write(row["config"])
            done = subprocess.run([self.simulate, path, "--check"], capture_output=True, text=True, timeout=60)
            self.assertEqual(done.returncode, 1, row["what"])
            line = done.stderr.strip()
            with self.assertRaises(ValueError, msg=row["what"]) as refused:
                core.World(pathlib.Path(path))
            self.assertEqual("simulate: " + str(refused.exception), line, row["what"])
            if path not in line:  # the text itself: the same line (a syntax error names its source instead)
                with self.assertRaises(ValueError, msg=row["what"]) as refused:
                    core.World(row["config"])
                self.assertEqual("simulate: " + str(refused.exception), line, row["what"])
            checked += 1
        self.assertGreater(checked, 40)

    def test_refused_changes_leave_the_world_unchanged(self) -> None:
        config = {"bodies": {"rod": {"type": "rod"}, "ball": {"type": "roller", "mu_s": 0.2, "mu_d": 0.1}}}
        world = core.World(config)
        twin = core.World(config)
        world.step(700)
        twin.step(700)
        refusals = [
            ("reconfigure", "rod", lambda: world.set("rod", k=-5)),
            ("reconfigure", "ball", lambda: world.set("ball", mu_d=0.5)),
            ("reconfigure", "ball", lambda: world.set("ball", shape="cube")),
            ("reconfigure", "rod", lambda: world.set("rod", stiffness=5)),
            ("reconfigure", "nobody", lambda: world.set("nobody", k=5)),
            ("set_state", "ball", lambda: world.set_state("ball", x=99.0)),
            ("set_state", "rod", lambda: world.set_state("rod", energy=1.0)),
            ("set_state", "rod", lambda: world.set_state("rod", y=float("nan"))),
            ("spawn", "rod", lambda: world.spawn("rod", {"type": "rod"})),
            ("spawn", "box", lambda: world.spawn("box", {"type": "cube"})),
            ("spawn", "hoop", lambda: world.spawn("hoop", "{type: roller, mu_d: 2, mu_s: 1}")),
            ("spawn", "rate", lambda: world.spawn("rate", {"type": "rod"})),
            ("delete", "nobody", lambda: world.delete("nobody")),
        ]
        for kind, body, change in refusals:
            before = world.config()
            with self.assertRaises(ValueError, msg=f"{kind} {body}") as refused:
                change()
            self.assertTrue(str(refused.exception).startswith(f"refused {kind} of '{body}', simulation unchanged: "),
                            str(refused.exception))
            self.assertEqual(world.config(), before, f"{kind} {body}")
        # The loader's own line for the same value in a file.
        with self.assertRaises(ValueError) as loader:
            core.World({"bodies": {"rod": {"type": "rod", "k": -5}}})
        with self.assertRaises(ValueError) as changed:
            world.set("rod", k=-5)
        self.assertEqual(str(changed.exception), "refused reconfigure of 'rod', simulation unchanged: "
                         + str(loader.exception))
        lone = core.World({"bodies": {"rod": {"type": "rod"}}})
        with self.assertRaises(ValueError):
            lone.delete("rod")  # a world keeps one body
        self.assert_same_run(world.run(2.0, sample_rate=1000), twin.run(2.0, sample_rate=1000), "after refusals")

    def test_a_text_where_a_number_is_asked_is_refused_as_in_a_file(self) -> None:
        """Every number key of every type: a str from Python is refused with the line a quoted value in a
        config file gets, and changes nothing."""
        checked = 0
        for kind, described in core.body_types()["types"].items():
            world = core.World({"bodies": {"b": {"type": kind}}})
            for key in described["keys"]:
                if "range" not in key or not key["written"]:
                    continue  # a text key, or one no file writes
                with self.assertRaises(ValueError) as loader:
                    core.World(f'{{bodies: {{b: {{type: {kind}, {key["name"]}: "0.3"}}}}}}')
                before = world.config()
                with self.assertRaises(ValueError, msg=f"{kind}.{key['name']}") as changed:
                    world.set("b", **{key["name"]: "0.3"})
                self.assertEqual(str(changed.exception),
                                 "refused reconfigure of 'b', simulation unchanged: " + str(loader.exception))
                self.assertIn("(quoted: a text)", str(loader.exception))
                self.assertEqual(world.config(), before)
                checked += 1
        self.assertGreater(checked, 20)

    def test_changes_go_through_the_one_path(self) -> None:
        world = core.World({"bodies": {"rod": {"type": "rod"}}})
        world.step(100)
        world.set("rod", k=2000.0, integrator="velocity_verlet")
        world.spawn("hoop", {"type": "roller", "shape": "ring", "incline_angle": 0.4})
        world.set_state("rod", y=2.5, omega=1.0)
        saved = yaml.safe_load(world.config())
        self.assertEqual(saved["bodies"]["rod"]["k"], 2000)
        self.assertEqual(saved["bodies"]["rod"]["integrator"], "velocity_verlet")
        self.assertEqual(saved["bodies"]["hoop"]["inertia_factor"], 1)
        self.assertEqual(world.state("rod")["y"], 2.5)
        self.assertEqual(world.state("hoop")["x"], 0.0)
        world.delete("hoop")
        self.assertEqual(world.bodies, ["rod"])
        world.reset()
        self.assertEqual(world.state("rod")["y"], saved["bodies"]["rod"]["y0"])
        self.assertEqual(world.t, 0.1)
        # The saved config is one simulate runs: what sim_node loads.
        done, folder = self.simulate_run(yaml.safe_load(world.config()), "--duration", "1")
        self.assertEqual(done.returncode, 0, done.stderr)

    def test_sweep_equals_simulate_and_releases_the_gil(self) -> None:
        config = {"bodies": {"rod": {"type": "rod"}, "ball": {"type": "roller"}}}
        specs = ["rod.theta0=0:6.283185307179586:201", "ball.mu_s=0.25:0.5:2"]
        done, folder = self.simulate_run(config, *[a for s in specs for a in ("--sweep", s)])
        self.assertEqual(done.returncode, 0, done.stderr)
        swept: Dict[str, Any] = {}
        ticks: List[float] = []
        window: List[float] = []

        def sweep() -> None:
            window.append(time.monotonic())
            swept.update(core.World(config).sweep(specs))
            window.append(time.monotonic())

        worker = threading.Thread(target=sweep)
        worker.start()
        deadline = time.monotonic() + 60
        while worker.is_alive() and time.monotonic() < deadline:
            now = time.monotonic()
            if not ticks or now - ticks[-1] >= 0.001:  # a tick a millisecond at most: the list stays short
                ticks.append(now)
        worker.join(timeout=max(0.0, deadline - time.monotonic()))
        self.assertFalse(worker.is_alive(), "the sweep took more than 60 s")
        start, end = window
        inside = [start] + [t for t in ticks if start < t < end] + [end]
        gap = max(b - a for a, b in zip(inside, inside[1:]))
        self.assertGreater(end - start, 0.05, "a sweep long enough to tell")
        self.assertLess(gap, 0.5 * (end - start), "this thread ran while the sweep did")
        self.assert_same_run({"sweep": swept}, {"sweep": runs.read_csv(os.path.join(folder, "sweep.csv"))},
                             "sweep")
        with self.assertRaises(ValueError):
            core.World(config).sweep(["rod.stiffness=1:2:3"])

    def test_key_descriptions_are_the_exported_ones(self) -> None:
        types = core.body_types()
        # The one description: the document describe_body_types wrote beside the module, as json reads it.
        with open(os.path.join(os.path.dirname(core.__file__), "body_types.json"), encoding="utf-8") as f:
            self.assertEqual(types, json.load(f))
        self.assertEqual(types, description.load())
        rod = {key["name"]: key for key in types["types"]["rod"]["keys"]}
        self.assertEqual(rod["k"]["unit"], "N/m")
        self.assertEqual(rod["k"]["default"], 1000.0)
        self.assertEqual(rod["theta0"]["state_field"], "theta")
        self.assertTrue(rod["x0"]["restarts"])
        self.assertEqual(rod["integrator"]["choices"], ["euler_cromer", "velocity_verlet", "rk4"])
        # Every default is what a body of that type without keys runs with, and its state fields a run's.
        for kind, described in types["types"].items():
            world = core.World({"bodies": {"b": {"type": kind}}})
            saved = yaml.safe_load(world.config())["bodies"]["b"]
            for key in described["keys"]:
                if key["written"]:
                    self.assertEqual(saved[key["name"]], key["default"], f"{kind}.{key['name']}")
            self.assertEqual([field["name"] for field in described["state_fields"]], list(world.state("b")))

    def test_a_bag_from_python_is_simulates(self) -> None:
        for name, duration, sample_rate in [("demo.yaml", "3", None), ("rod.yaml", "2.5", 100.0)]:
            path = os.path.join(CONFIG_DIR, name)
            with open(path) as f:
                config = yaml.safe_load(f)
            theirs = os.path.join(self.tmp.name, name + ".simulate.bag")
            args = ["--duration", duration, "--bag", theirs]
            if sample_rate:
                args += ["--sample-rate", repr(sample_rate)]
            done, folder = self.simulate_run(config, *args)
            self.assertEqual(done.returncode, 0, done.stderr)
            mine = os.path.join(self.tmp.name, name + ".core.bag")
            run = core.World(pathlib.Path(path)).run(float(duration), sample_rate=sample_rate,
                                                     bag=pathlib.Path(mine))
            self.assertEqual(bag_messages(mine), bag_messages(theirs), name)
            with open(mine, "rb") as a, open(theirs, "rb") as b:
                self.assertTrue(a.read() == b.read(), f"{name}: the two bag files, byte for byte")
            self.assert_same_run(run, runs.read_bag(mine), f"{name}'s bag read back")
            self.assert_same_run(run, runs.read_run(folder), f"{name}'s CSV")
        # Only a World as loaded: a bag begins with its config at t = 0.
        world = core.World({"bodies": {"rod": {"type": "rod"}}})
        world.step(3)
        with self.assertRaises(ValueError) as refused:
            world.run(1.0, bag=os.path.join(self.tmp.name, "late.bag"))
        self.assertEqual(str(refused.exception), "a bag is the run of a World as loaded (t = 0, nothing "
                         "changed), as simulate --bag writes it; this one is at t = 0.003 after 0 change(s)")
        self.assertEqual(world.steps, 3)
        self.assertFalse(os.path.exists(os.path.join(self.tmp.name, "late.bag.active")))
        changed = core.World({"bodies": {"rod": {"type": "rod"}}})
        changed.set("rod", k=2000)
        with self.assertRaises(ValueError):
            changed.run(1.0, bag=os.path.join(self.tmp.name, "late.bag"))

    def test_a_world_without_a_bag_loads_no_ros_library(self) -> None:
        program = ("import sys\nfrom rigid_body_sim import core\n"
                   "core.World({'bodies': {'rod': {'type': 'rod'}}}).run(1.0)\n"
                   "with open('/proc/self/maps') as f: maps = f.read()\n"
                   "core.World({'bodies': {'rod': {'type': 'rod'}}}).run(1.0, bag=sys.argv[1])\n"
                   "with open('/proc/self/maps') as f: print('libroscpp' in maps, 'librosbag' in maps, "
                   "'librosbag' in f.read())\n")
        done = subprocess.run([sys.executable, "-c", program, os.path.join(self.tmp.name, "rod.bag")],
                              capture_output=True, text=True, timeout=60)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertEqual(done.stdout.split(), ["False", "False", "True"], "roscpp, rosbag before; rosbag after")
        with self.assertRaises(RuntimeError) as failed:
            core.World({"bodies": {"rod": {"type": "rod"}}}).run(1.0, bag=os.path.join(self.tmp.name, "no", "x.bag"))
        self.assertIn(os.path.join(self.tmp.name, "no", "x.bag.active"), str(failed.exception))

    def test_the_example_runs_as_a_student_runs_it(self) -> None:
        """examples/python/text_vs_core.py as docs/python.md gives it: it ends well and draws its figure, the
        text's rod and the World's agree over the first 3 s (before the bounces grow a last bit of numpy's
        sin and cos), and the rollers follow the closed form to 1e-12 m (the docs: about 1e-13)."""
        example = os.path.join(HERE, "..", "..", "examples", "python", "text_vs_core.py")
        with tempfile.TemporaryDirectory() as folder:
            figure = os.path.join(folder, "text_vs_core.png")
            done = subprocess.run([sys.executable, example, "--figure", figure], capture_output=True, text=True,
                                  timeout=60)
            self.assertEqual(done.returncode, 0, done.stderr)
            self.assertGreater(os.path.getsize(figure), 10000, done.stdout)
        first_3s = [float(line.split("over the first 3 s ")[1].split(",")[0])
                    for line in done.stdout.splitlines() if "over the first 3 s" in line]
        closed = [float(line.split("largest |core - closed form| ")[1].split(" m")[0])
                  for line in done.stdout.splitlines() if "closed form|" in line]
        self.assertEqual(len(first_3s), 3, done.stdout)  # x, y, theta
        self.assertEqual(len(closed), 3, done.stdout)  # sphere, cylinder, ring
        self.assertLessEqual(max(first_3s), 1e-9, done.stdout)
        self.assertLessEqual(max(closed), 1e-12, done.stdout)

    def test_the_stub_is_the_modules(self) -> None:
        stub = os.path.join(os.path.dirname(core.__file__), "core.pyi")
        with open(stub) as f:
            tree = ast.parse(f.read())
        public = {node.name: node for node in tree.body
                  if isinstance(node, (ast.ClassDef, ast.FunctionDef)) and not node.name.startswith("_")}
        self.assertEqual(set(public), {name for name in dir(core) if not name.startswith("_")})
        world = public["World"]
        assert isinstance(world, ast.ClassDef)
        members = {node.name for node in world.body if isinstance(node, ast.FunctionDef)}
        self.assertEqual(members - {"__init__"}, {name for name in dir(core.World) if not name.startswith("_")})
        # mypy's stubtest: every name, property and function of the stub against the module as it runs. Its
        # mypy build must not fail on what is not the stub's: Debian 11's numpy has no type hints, and its
        # mypy (0.812) cannot type catkin's generated rigid_body_sim/__init__.py (its __path__).
        with tempfile.NamedTemporaryFile("w", suffix=".ini") as config:
            config.write("[mypy]\nignore_missing_imports = True\n[mypy-rigid_body_sim]\nignore_errors = True\n")
            config.flush()
            done = subprocess.run([sys.executable, "-m", "mypy.stubtest", "--concise", "--mypy-config-file",
                                   config.name, "rigid_body_sim.core"],
                                  capture_output=True, text=True, timeout=100,
                                  env=dict(os.environ, MYPYPATH=os.path.dirname(os.path.dirname(stub))))
        self.assertEqual(done.returncode, 0, done.stdout + done.stderr)


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("simulate", help="the simulate executable")
    args, unittest_args = parser.parse_known_args()
    CoreCase.simulate = os.path.abspath(args.simulate)
    unittest.main(argv=sys.argv[:1] + unittest_args, verbosity=2)


if __name__ == "__main__":
    main()
