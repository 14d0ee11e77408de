#!/usr/bin/env python3
"""rigid_body_sim.sim_tools against the C++ it describes: its defaults and units are the core's exported description
(rigid_body_sim.description), and what simulate does with a config that leaves every key out; its
shape factors are the ones the core's rolling friction follows; a CSV header and a state message name the same
fields; the event kinds and roles it knows are those simulate writes, a bag's events read as events.csv's, and
its lines give each instant as events.csv writes it; it reads a sweep's header as simulate writes it, and has
words for every column a sweep adds.
Usage: test_sim_tools.py SIMULATE_EXE   (with the package's devel space sourced, for the .cfg modules)"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys
import tempfile
import unittest
from typing import Dict, List, Tuple

import rosbag
from rigid_body_sim.cfg import RollerReconfigureConfig
from rigid_body_sim import runs, sim_tools


def csv_rows(path: str) -> List[Dict[str, str]]:
    with open(path) as f:
        header = f.readline().strip().split(",")
        return [dict(zip(header, line.strip().split(","))) for line in f]


class SimulateCase(unittest.TestCase):
    simulate: str  # set by main()

    def setUp(self) -> None:
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self) -> None:
        self.tmp.cleanup()

    def run_simulate(self, config: str, *args: str) -> Tuple[str, str]:
        """Runs simulate on a config text in a folder of its own (its working folder); returns the folder and
        what simulate printed."""
        folder = tempfile.mkdtemp(dir=self.tmp.name)
        with open(os.path.join(folder, "config.yaml"), "w") as f:
            f.write(config)
        result = subprocess.run([self.simulate, "config.yaml", *args], cwd=folder, check=True, capture_output=True,
                                text=True)
        return folder, result.stdout


class Defaults(SimulateCase):
    def test_inertia_factors_are_the_cores(self) -> None:
        """The named shapes' c, which the description does not carry: the roller's default is the sphere's."""
        self.assertEqual(sim_tools.INERTIA_FACTORS[sim_tools.DEFAULTS["roller"]["shape"]],
                         RollerReconfigureConfig.defaults["inertia_factor"])

    def test_world_defaults_are_what_simulate_does(self) -> None:
        folder, summary = self.run_simulate("bodies: {rod: {type: rod}}", "--duration", "1", "--bag", "run.bag")
        self.assertIn(f"in {sim_tools.WORLD_DEFAULTS['rate']:.0f} steps", summary)  # a simulated second
        rows = csv_rows(os.path.join(folder, "rod.csv"))
        self.assertEqual(len(rows) - 1, sim_tools.WORLD_DEFAULTS["publish_rate"])  # samples in a second
        self.assertEqual(float(rows[1]["t"]), 1 / sim_tools.WORLD_DEFAULTS["publish_rate"])
        rod = sim_tools.DEFAULTS["rod"]  # E = M g y0 + M vx0^2 / 2 at t = 0
        gravity = (float(rows[0]["energy"]) - 0.5 * rod["mass"] * rod["vx0"] ** 2) / (rod["mass"] * rod["y0"])
        self.assertAlmostEqual(gravity, sim_tools.WORLD_DEFAULTS["gravity"], delta=1e-12)
        with rosbag.Bag(os.path.join(folder, "run.bag")) as bag:
            _, tf_static, _ = next(bag.read_messages(topics=["/tf_static"]))
        self.assertEqual(tf_static.transforms[0].header.frame_id, sim_tools.WORLD_DEFAULTS["world_frame"])

    def test_shape_factors_are_the_cores(self) -> None:
        """Rolling, friction on the body is -M g sin(phi) c / (1 + c) and the normal force M g cos(phi), so
        r = friction / (normal tan(phi)) gives c = -r / (1 + r)."""
        for shape, c in sim_tools.INERTIA_FACTORS.items():
            config = f"bodies: {{b: {{type: roller, shape: {shape}, incline_angle: 0.1}}}}"
            folder, _ = self.run_simulate(config, "--duration", "0")
            row = csv_rows(os.path.join(folder, "b.csv"))[0]
            self.assertEqual(row["mode"], "rolling", shape)
            r = float(row["friction"]) / (float(row["normal"]) * math.tan(0.1))
            self.assertAlmostEqual(-r / (1 + r), c, delta=1e-12, msg=shape)


class Runs(SimulateCase):
    def test_the_csv_names_the_state_messages_fields_and_their_numbers(self) -> None:
        folder, _ = self.run_simulate("bodies: {rod: {type: rod}, ball: {type: roller}}", "--duration", "0.1",
                                      "--bag", "run.bag")
        states = sim_tools.read_states(os.path.join(folder, "run.bag"))
        self.assertEqual(sorted(states), ["ball", "rod"])
        for name, msgs in states.items():
            with open(os.path.join(folder, f"{name}.csv")) as f:
                self.assertEqual(f.readline().strip().split(","), sim_tools.state_fields(msgs[0]), name)
                numbers = [float(v) for v in f.readline().strip().split(",") if re.fullmatch(r"[-+.e\d]+|nan", v)]
                self.assertEqual(sim_tools.state_numbers(msgs[0]), numbers, name)

    def test_body_spec_fills_in_the_defaults(self) -> None:
        config = {"bodies": {"rod": {"type": "rod", "k": 5.0}, "ring": {"type": "roller", "shape": "ring"},
                             "odd": {"type": "roller", "inertia_factor": 0.3}}}
        rod, ring, odd = sim_tools.body_specs(config)
        self.assertEqual(rod, sim_tools.RodSpec("rod", 1.0, 0.5, 5.0))
        assert isinstance(ring, sim_tools.RollerSpec) and isinstance(odd, sim_tools.RollerSpec)
        self.assertEqual((ring.c, ring.radius, ring.slope), (1.0, 0.1, 5.0))
        self.assertEqual((odd.shape, odd.c), ("custom", 0.3))


# Every type with events within 3 s: the rod's contacts and restarts (off its short floor, some in contact), the
# rollers' grip, finishes and restarts (short slopes), a block launched up its slope to a stop, another sliding
# down to its finishes.
EVENTFUL = """bodies:
  rod: {type: rod, y0: 1.0, theta0: 0.3, floor_length: 2.0, vx0: 1.5}
  bowler: {type: roller, incline_angle: 0.05, incline_length: 2.0, v0: 2.5, omega0: 10.0, mu_d: 0.2}
  ring: {type: roller, shape: ring, incline_length: 1.0}
  sled: {type: block, incline_angle: 0.05, v0: -1.0, x0: 1.0}
  crate: {type: block, incline_angle: 0.3, incline_length: 1.0, mu_s: 0.1, mu_d: 0.1}
"""


def listed(line: str) -> Tuple[str, int, List[str], str]:
    """A line of event_lines: its kind, how often, the instants it lists (as written) and the last instant it
    names after them ("" when it lists them all)."""
    found = re.fullmatch(r"(\w+): (once|\d+ times), at t = (.*) s", line)
    assert found, line
    kind, often, items = found.group(1), found.group(2), found.group(3).split(", ")
    last = ""
    if items[-1].startswith("the last at "):
        last = items.pop()[len("the last at "):]
        items.pop()  # "and N more"
    return kind, 1 if often == "once" else int(often.split()[0]), [item.split(" (")[0] for item in items], last


class Events(SimulateCase):
    def test_the_kinds_and_roles_are_those_simulate_writes(self) -> None:
        folder, _ = self.run_simulate(EVENTFUL, "--duration", "3")
        happened = runs.read_events(folder)
        kinds = {(event["type"], event["kind"]) for event in happened}
        for type_name, kind in kinds:
            self.assertIn(kind, sim_tools.EVENT_ROLES[type_name], type_name)
        self.assertEqual({event["type"] for event in happened}, set(sim_tools.EVENT_ROLES))  # every type: events
        for event in happened:
            # A finish carries its lap's time and a restart its cause (docs/events.md): what a role means.
            if sim_tools.role(event) == "finish":
                self.assertIn("lap_time", event["values"], event)
            if sim_tools.role(event) == "restart":
                self.assertIn("cause", event["values"], event)
        self.assertEqual({sim_tools.role(event) for event in happened}, {"", "finish", "restart"})

    def test_the_lines_give_every_instant_as_events_csv_writes_it(self) -> None:
        folder, _ = self.run_simulate(EVENTFUL, "--duration", "10")
        with open(os.path.join(folder, runs.EVENTS_FILE), newline="") as f:
            rows = list(csv.DictReader(f))
        lines = sim_tools.event_lines(runs.read_events(folder))
        self.assertEqual(list(lines), list(dict.fromkeys(row["body"] for row in rows)))
        long_enough = False
        for body, body_lines in lines.items():
            kinds = [listed(line)[0] for line in body_lines]
            declared = list(sim_tools.EVENT_ROLES[next(row["type"] for row in rows if row["body"] == body)])
            self.assertEqual(kinds, sorted(kinds, key=declared.index), body)
            for line in body_lines:
                kind, often, instants, last = listed(line)
                written = [row["t"] for row in rows if row["body"] == body and row["kind"] == kind]
                self.assertEqual(often, len(written), line)
                self.assertEqual(instants, written[:sim_tools.LISTED], line)  # the CSV's text, to the character
                self.assertEqual(last, written[-1] if len(written) > sim_tools.LISTED else "", line)
                long_enough |= len(written) > sim_tools.LISTED
        self.assertTrue(long_enough, "a kind with more instants than a line lists")  # that case is exercised

    def test_a_bags_events_are_events_csvs(self) -> None:
        folder, _ = self.run_simulate(EVENTFUL, "--duration", "3", "--out-dir", "run", "--bag", "run.bag")
        from_csv = runs.read_events(os.path.join(folder, "run"))
        self.assertGreater(len(from_csv), 0)
        self.assertEqual(sim_tools.read_bag_events(os.path.join(folder, "run.bag")), from_csv)

    def test_the_namespace_of_a_bags_events(self) -> None:
        self.assertEqual(sim_tools.events_namespace(["/tf", "/sim/rod/state", "/sim/events"]), "/sim")
        self.assertEqual(sim_tools.events_namespace(["/left/sim/rod/state", "/left/sim/events"]), "/left/sim")
        self.assertEqual(sim_tools.events_namespace(["/sim/rod/state"]), "/sim")

    def test_number_text_is_the_shortest_round_trip(self) -> None:
        for value in (0.565892621098528, 0.1 + 0.2, 1e-7, 2.0, -3.0, 1.5e300):
            text = sim_tools.number_text(value)
            self.assertEqual(float(text), value, text)
        self.assertEqual((sim_tools.number_text(1.0), sim_tools.number_text("A")), ("1", "A"))


class Sweeps(SimulateCase):
    def test_a_sweep_header_is_read_as_simulate_writes_it(self) -> None:
        config = "bodies: {rod: {type: rod}, ball: {type: roller}}"
        folder, _ = self.run_simulate(config, "--duration", "0.1", "--sweep", "ball.v0=0:1:2",
                                      "--sweep", "rod.k=10:20:2")
        with open(os.path.join(folder, "sweep.csv")) as f:
            header = f.readline().strip().split(",")
        states, _ = self.run_simulate(config, "--duration", "0.1")
        self.assertTrue(sim_tools.is_sweep_header(header))
        columns = sim_tools.sweep_columns(header)
        self.assertEqual(columns.keys, ["ball.v0", "rod.k"])
        self.assertEqual(sorted(columns.fields), ["ball", "rod"])
        for body in columns.fields:
            with open(os.path.join(states, f"{body}.csv")) as f:
                state = f.readline().strip().split(",")[1:]  # after t
            self.assertEqual(columns.fields[body][:len(state)], state, body)
            added = columns.fields[body][len(state):]
            self.assertEqual(columns.results(body), added, body)
            self.assertEqual(added[0], sim_tools.FIRST_SWEEP_RESULT, body)
            for field in added:
                self.assertIn(field, sim_tools.SWEEP_RESULT_LABELS, f"{body}.{field}")

    def test_a_run_header_is_no_sweep_header(self) -> None:
        folder, _ = self.run_simulate("bodies: {rod: {type: rod}}", "--duration", "0.1")
        with open(os.path.join(folder, "rod.csv")) as f:
            self.assertFalse(sim_tools.is_sweep_header(f.readline().strip().split(",")))

    def test_key_unit_names_the_unit_of_a_swept_key(self) -> None:
        config = {"bodies": {"rod": {"type": "rod"}, "ball": {"type": "roller"}}}
        self.assertEqual(sim_tools.key_unit(config, "rod.k"), "N/m")
        self.assertEqual(sim_tools.key_unit(config, "ball.mu_s"), "")
        self.assertEqual(sim_tools.key_unit(config, "ball.incline_angle"), "rad")
        self.assertEqual(sim_tools.labelled("energy drift", "J"), "energy drift (J)")
        self.assertEqual(sim_tools.labelled("bounces", ""), "bounces")


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("simulate", help="the simulate executable")
    args, unittest_args = parser.parse_known_args()
    SimulateCase.simulate = os.path.abspath(args.simulate)
    unittest.main(argv=sys.argv[:1] + unittest_args, verbosity=2)


if __name__ == "__main__":
    main()
