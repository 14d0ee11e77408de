#!/usr/bin/env python3
"""rigid_body_sim.sim_tools against the C++ it describes: its defaults and units are the core's exported description
(rigid_body_sim.description), and what simulate does with a config that leaves every key out; its
shape factors are the ones the core's rolling friction follows; a CSV header and a state message name the same
fields; it reads a sweep's header as simulate writes it, and has words for every column a sweep adds.
Usage: test_sim_tools.py SIMULATE_EXE   (with the package's devel space sourced, for the .cfg modules)"""
import argparse
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
from rigid_body_sim import sim_tools


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

    def test_a_rod_end_is_below_the_floor_when_its_height_is_negative(self) -> None:
        self.assertFalse(sim_tools.rod_end_below_floor(0.6, 1.0, 1.0))
        self.assertTrue(sim_tools.rod_end_below_floor(0.4, math.pi / 2, 1.0))
        self.assertTrue(sim_tools.rod_end_below_floor(0.4, -math.pi / 2, 1.0))

    def test_body_spec_fills_in_the_defaults(self) -> None:
        config = {"bodies": {"rod": {"type": "rod", "k": 5.0}, "ring": {"type": "roller", "shape": "ring"},
                             "odd": {"type": "roller", "inertia_factor": 0.3}}}
        rod, ring, odd = sim_tools.body_specs(config)
        self.assertEqual(rod, sim_tools.RodSpec("rod", 1.0, 0.5, 5.0))
        assert isinstance(ring, sim_tools.RollerSpec) and isinstance(odd, sim_tools.RollerSpec)
        self.assertEqual((ring.c, ring.radius, ring.slope), (1.0, 0.1, 5.0))
        self.assertEqual((odd.shape, odd.c), ("custom", 0.3))


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
