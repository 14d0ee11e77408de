#!/usr/bin/env python3
"""scripts/plot_run.py on a short simulate run of config/demo.yaml, read from the CSV files and from the
bag of the same run, and on a bag recorded from sim_node through sim.launch: it writes every figure; every
instant it marks is an event of the run's events.csv (or the bag's /sim/events), each one it should mark is
marked, and those instants agree with the closed forms of docs/DESIGN.md and with the CSV's own modes; a folder
without events.csv is refused. On sweeps of one
key (the rod's θ0) and of two (the bowler's v0 and omega0): a figure for each swept body and none for the
others, and the values it draws and reports are the sweep.csv's, variant for variant.
Needs RBS_SIMULATE (the simulate executable) and RBS_DEVEL (the devel space, for sim.launch)."""
import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest
from collections import Counter
from typing import Any, Dict, List, Optional, Set

from rigid_body_sim import runs
from rigid_body_sim.sim_tools import free_port, load_config, read_bag_events, role

HERE = os.path.dirname(os.path.abspath(__file__))
PACKAGE = os.path.dirname(os.path.dirname(HERE))

PLOT = os.path.join(PACKAGE, "scripts", "plot_run.py")
CONFIG = os.path.join(PACKAGE, "config", "demo.yaml")
ROD_CONFIG = os.path.join(PACKAGE, "config", "rod.yaml")
PNG = b"\x89PNG\r\n\x1a\n"
FIGURES = ("rod.png", "rollers.png", "race.png", "energy.png")
# A figure's share of ink (pixels darker than 0.9 in every channel) beyond its frame: an empty axes with
# ticks, labels and a title, at the rod figure's size, has 2.25 %; the demo's figures 4 to 8 %.
MIN_INK = 0.03
# The closed forms' values, written out as the text gives them (independently of plot_run's own).
G = 9.8
C = {"sphere": 0.4, "cylinder": 0.5, "ring": 1.0}
Body = Dict[str, Any]


def closed_form_slip_to_roll(b: Body) -> float:
    """Launched sliding with backspin: u = v + omega R falls at g sin(phi) - mu_d g cos(phi) (1 + c)/c."""
    c, phi = C[b["shape"]], b["incline_angle"]
    u0 = b["v0"] + b["omega0"] * b["radius"]
    return u0 / -(G * math.sin(phi) - b["mu_d"] * G * math.cos(phi) * (1 + c) / c)


def closed_form_down(b: Body) -> float:
    """From rest: rolling, a = g sin(phi)/(1 + c); slipping, a = g (sin(phi) - mu_d cos(phi))."""
    c, phi = C[b["shape"]], b["incline_angle"]
    rolls = math.tan(phi) <= b["mu_s"] * (1 + c) / c
    a = G * math.sin(phi) / (1 + c) if rolls else G * (math.sin(phi) - b["mu_d"] * math.cos(phi))
    return math.sqrt(2 * b["incline_length"] / a)


class PlotRunTest(unittest.TestCase):
    tmp: "tempfile.TemporaryDirectory[str]"
    run_dir: str
    summaries: Dict[str, Any]
    bodies: Dict[str, Body]
    events: List[Dict[str, Any]]

    @classmethod
    def setUpClass(cls) -> None:
        cls.tmp = tempfile.TemporaryDirectory()
        cls.run_dir = os.path.join(cls.tmp.name, "run")
        bag = os.path.join(cls.tmp.name, "run.bag")
        subprocess.run([os.environ["RBS_SIMULATE"], CONFIG, "--duration", "6", "--out-dir", cls.run_dir,
                        "--bag", bag], check=True, stdout=subprocess.DEVNULL)
        cls.summaries = {}
        for source, path in (("csv", cls.run_dir), ("bag", bag)):
            out = os.path.join(cls.tmp.name, source)
            subprocess.run([sys.executable, PLOT, CONFIG, path, "--out-dir", out], check=True,
                           stdout=subprocess.DEVNULL)
            with open(os.path.join(out, "summary.json")) as f:
                cls.summaries[source] = json.load(f)
        cls.bodies = load_config(CONFIG)["bodies"]
        cls.events = runs.read_events(cls.run_dir)

    @classmethod
    def tearDownClass(cls) -> None:
        cls.tmp.cleanup()

    def csv_rows(self, name: str) -> List[Dict[str, str]]:
        with open(os.path.join(self.run_dir, name + ".csv")) as f:
            return list(csv.DictReader(f))

    def test_every_figure_is_a_png_of_some_substance(self) -> None:
        import matplotlib.image
        for source in ("csv", "bag"):
            for figure in FIGURES:
                path = os.path.join(self.tmp.name, source, figure)
                with open(path, "rb") as f:
                    self.assertEqual(f.read(8), PNG, path)
                ink = (matplotlib.image.imread(path)[..., :3].min(axis=2) < 0.9).mean()
                self.assertGreater(ink, MIN_INK, path)

    def instants(self, body: str, kind: str) -> List[float]:
        return [e["t"] for e in self.events if e["body"] == body and e["kind"] == kind]

    def test_each_figure_marks_the_events_instants(self) -> None:
        """The rollers' and the energy figure mark every event but the restarts, at its instant, to the bit;
        the race its racers' first finish."""
        marks = self.summaries["csv"]["marks"]
        for figure, bodies in (("rollers", ("sphere", "cylinder", "ring", "bowler")), ("energy", self.bodies)):
            expected: Dict[str, Dict[str, List[float]]] = {}
            for e in self.events:
                if e["body"] in bodies and role(e) != "restart":
                    expected.setdefault(e["body"], {}).setdefault(e["kind"], []).append(e["t"])
            self.assertEqual(marks[figure], expected, figure)
        self.assertEqual(set(marks["energy"]), set(self.bodies))  # every body has a mark in 6 s: none is missed
        self.assertEqual(marks["race"], {name: {"finished": self.instants(name, "finished")[:1]}
                                         for name in ("sphere", "cylinder", "ring")})
        self.assertIn("slip_to_roll", marks["rollers"]["bowler"])
        self.assertIn("contact_began", marks["energy"]["rod"])

    def test_the_summary_has_every_event(self) -> None:
        summary = self.summaries["csv"]["events"]
        self.assertEqual(sum(len(happened) for kinds in summary.values() for happened in kinds.values()),
                         len(self.events))
        for e in self.events:
            self.assertIn({"t": e["t"], "values": e["values"]}, summary[e["body"]][e["kind"]])

    def test_slip_to_roll_instant_is_the_closed_form(self) -> None:
        marked = self.summaries["csv"]["marks"]["rollers"]["bowler"]["slip_to_roll"]
        self.assertGreaterEqual(len(marked), 1)
        self.assertAlmostEqual(marked[0], closed_form_slip_to_roll(self.bodies["bowler"]), delta=1e-9)

    def test_slip_to_roll_instant_lies_at_the_csv_mode_change(self) -> None:
        rows = self.csv_rows("bowler")
        change = next(i for i in range(1, len(rows))
                      if rows[i - 1]["mode"] == "slipping" and rows[i]["mode"] == "rolling")
        marked = self.summaries["csv"]["marks"]["rollers"]["bowler"]["slip_to_roll"][0]
        self.assertLess(float(rows[change - 1]["t"]), marked)
        self.assertLessEqual(marked, float(rows[change]["t"]))

    def test_race_times_are_the_closed_forms(self) -> None:
        for name in ("sphere", "cylinder", "ring"):
            finish = self.summaries["csv"]["marks"]["race"][name]["finished"]
            self.assertEqual(len(finish), 1, name)
            self.assertAlmostEqual(finish[0], closed_form_down(self.bodies[name]), delta=1e-9, msg=name)

    def test_laps_are_cut_at_the_restarts(self) -> None:
        """The x the race draws for its first lap stops before the first restart; the rollers' curves break
        there (NaN) and nowhere else."""
        sys.path.insert(0, os.path.dirname(PLOT))  # the figures' own cutting, on the CSV's samples
        import plot_run
        data = plot_run.load_csv_folder(self.run_dir)
        for name in ("sphere", "bowler"):
            happened = [e for e in self.events if e["body"] == name]
            restarts = [e["t"] for e in happened if role(e) == "restart"]
            self.assertGreater(len(restarts), 0, name)
            t = data[name]["t"]
            starts = [int(start) for start, _ in plot_run.laps(t, happened)]
            self.assertEqual([float(t[i]) for i in starts[1:]], [min(t[t >= r]) for r in restarts], name)
            broken = plot_run.broken_at_restarts(data[name], "x", happened)
            self.assertEqual(sum(1 for x in broken if math.isnan(x)), len(restarts), name)

    def test_critical_angle_verdict_matches_the_run(self) -> None:
        # The verdict comes from tan(phi_c) = mu_s (1 + c)/c; the modes from the simulation itself.
        for name in ("sphere", "cylinder", "ring"):
            rolls = self.summaries["csv"]["rollers"][name]["critical_angle"]["rolls"]
            modes = {row["mode"] for row in self.csv_rows(name)}
            self.assertEqual(modes, {"rolling"} if rolls else {"slipping"}, name)

    def test_rod_energy_starts_at_its_closed_form_and_swings_in_contact(self) -> None:
        rod = self.bodies["rod"]
        summary = self.summaries["csv"]["rods"]["rod"]
        expected = rod["mass"] * G * rod["y0"] + 0.5 * rod["mass"] * rod["vx0"] ** 2
        self.assertAlmostEqual(summary["energy_first"], expected, delta=1e-9)
        self.assertGreater(summary["contacts"], 0)

    def test_rod_contacts_are_its_events(self) -> None:
        """A contact lasts from an end's contact_began while either end is in the floor: counted here from
        events.csv, each begins at a contact_began."""
        ends: Set[str] = set()
        begins: List[float] = []
        for e in self.events:
            if e["body"] == "rod" and e["kind"] in ("contact_began", "contact_ended"):
                if not ends:
                    begins.append(e["t"])
                (ends.add if e["kind"] == "contact_began" else ends.discard)(e["values"]["end"])
        summary = self.summaries["csv"]["rods"]["rod"]
        self.assertEqual(summary["contacts"], len(begins))
        self.assertIn(summary["largest_swing"]["t"], begins)

    def test_rod_energy_swing_is_the_figure_docs_physics_states(self) -> None:
        # docs/physics.md: "by up to X % (t = T s, inset)", from `make pictures`' run of demo.yaml: 10 s with
        # every step sampled (a coarser sampling misses the peaks).
        with open(os.path.join(PACKAGE, "docs", "physics.md")) as f:
            stated = re.search(r"by up to (\S+) % \(t = (\S+) s, inset\)", f.read())
        assert stated is not None, "docs/physics.md states no largest swing"
        run_dir, out = os.path.join(self.tmp.name, "every_step"), os.path.join(self.tmp.name, "every_step_plot")
        subprocess.run([os.environ["RBS_SIMULATE"], CONFIG, "--duration", "10", "--sample-rate", "1000",
                        "--out-dir", run_dir], check=True, stdout=subprocess.DEVNULL)
        subprocess.run([sys.executable, PLOT, CONFIG, run_dir, "--out-dir", out, "--figures", "rod"], check=True,
                       stdout=subprocess.DEVNULL)
        with open(os.path.join(out, "summary.json")) as f:
            largest = json.load(f)["rods"]["rod"]["largest_swing"]
        self.assertEqual(f"{100 * largest['swing']:.2f}", stated.group(1))  # as the docs round it
        self.assertEqual(f"{largest['t']:.2f}", stated.group(2))

    def test_bag_and_csv_give_the_same_numbers(self) -> None:
        self.assertEqual(json.dumps(self.summaries["bag"], sort_keys=True),
                         json.dumps(self.summaries["csv"], sort_keys=True))

    def test_a_folder_without_states_is_refused_in_one_line(self) -> None:
        with tempfile.TemporaryDirectory() as empty:
            result = subprocess.run([sys.executable, PLOT, CONFIG, empty, "--out-dir", empty],
                                    capture_output=True, text=True)
        self.assertNotEqual(result.returncode, 0)
        self.assertEqual(len(result.stderr.strip().splitlines()), 1, result.stderr)

    def test_a_folder_without_events_is_refused_in_one_line(self) -> None:
        """Its instants are the core's events: without them it marks nothing rather than guess."""
        with tempfile.TemporaryDirectory() as tmp:
            states = os.path.join(tmp, "states")
            shutil.copytree(self.run_dir, states)
            os.remove(os.path.join(states, runs.EVENTS_FILE))
            result = subprocess.run([sys.executable, PLOT, CONFIG, states, "--out-dir", os.path.join(tmp, "out")],
                                    capture_output=True, text=True)
        self.assertNotEqual(result.returncode, 0)
        self.assertEqual(len(result.stderr.strip().splitlines()), 1, result.stderr)
        self.assertIn(runs.EVENTS_FILE, result.stderr)


def sweep(config: str, out: str, *sweeps: str) -> List[Dict[str, str]]:
    """Runs simulate's sweep into `out` and returns sweep.csv's rows."""
    subprocess.run([os.environ["RBS_SIMULATE"], config, "--duration", "4", "--out-dir", out,
                    *(f"--sweep={s}" for s in sweeps)], check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "sweep.csv")) as f:
        return list(csv.DictReader(f))


def plot(config: str, run: str, out: str) -> Dict[str, Any]:
    """plot_run on a run; its summary.json."""
    subprocess.run([sys.executable, PLOT, config, run, "--out-dir", out], check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "summary.json")) as f:
        summary: Dict[str, Any] = json.load(f)
    return summary


def value(text: str) -> Optional[float]:
    """A sweep's number as plot_run reports it: None where the CSV has none."""
    return float(text) if text else None


class SweepTest(unittest.TestCase):
    """One key: 64 rods over θ0 in [0, 2π] (the text's random θ0), read from sweep.csv itself. Two keys:
    the bowler's v0 x omega0 in demo.yaml (five bodies, one swept), read from the sweep's folder."""
    tmp: "tempfile.TemporaryDirectory[str]"
    rods: List[Dict[str, str]]
    bowlers: List[Dict[str, str]]
    one: Dict[str, Any]
    two: Dict[str, Any]

    @classmethod
    def setUpClass(cls) -> None:
        cls.tmp = tempfile.TemporaryDirectory()
        folder = cls.tmp.name
        cls.rods = sweep(ROD_CONFIG, os.path.join(folder, "theta0"), "rod.theta0=0:6.283185307179586:64")
        cls.one = plot(ROD_CONFIG, os.path.join(folder, "theta0", "sweep.csv"), os.path.join(folder, "one"))
        cls.bowlers = sweep(CONFIG, os.path.join(folder, "spin"), "bowler.v0=0:6:7", "bowler.omega0=-40:40:9")
        cls.two = plot(CONFIG, os.path.join(folder, "spin"), os.path.join(folder, "two"))

    @classmethod
    def tearDownClass(cls) -> None:
        cls.tmp.cleanup()

    def test_a_figure_per_swept_body(self) -> None:
        for out, body in (("one", "rod"), ("two", "bowler")):
            folder = os.path.join(self.tmp.name, out)
            self.assertEqual(sorted(os.listdir(folder)), ["summary.json", f"sweep_{body}.png"])
            with open(os.path.join(folder, f"sweep_{body}.png"), "rb") as f:
                self.assertEqual(f.read(8), PNG, out)
            self.assertGreater(os.path.getsize(os.path.join(folder, f"sweep_{body}.png")), 10000, out)

    def test_the_outcomes_are_the_sweeps_added_columns_and_texts(self) -> None:
        self.assertEqual(list(self.one["bodies"]), ["rod"])
        self.assertEqual(list(self.one["bodies"]["rod"]), ["energy_drift", "bounces"])
        self.assertEqual(list(self.two["bodies"]), ["bowler"])
        self.assertEqual(list(self.two["bodies"]["bowler"]), ["mode", "energy_drift", "slip_to_roll"])

    def test_bounces_per_theta0_are_the_csvs(self) -> None:
        bounces = self.one["bodies"]["rod"]["bounces"]
        self.assertEqual(bounces["drawn"]["x"], [float(row["rod.theta0"]) for row in self.rods])
        self.assertEqual(bounces["drawn"]["y"], [float(row["rod.bounces"]) for row in self.rods])
        counts = Counter(row["rod.bounces"] for row in self.rods)
        self.assertEqual(bounces["counts"], {n: counts[n] for n in sorted(counts, key=int)})
        fewest = min(self.rods, key=lambda row: int(row["rod.bounces"]))
        self.assertEqual((bounces["min"], bounces["min_at"]),
                         (float(fewest["rod.bounces"]), {"rod.theta0": float(fewest["rod.theta0"])}))

    def test_energy_drift_per_theta0_is_the_csvs(self) -> None:
        drift = self.one["bodies"]["rod"]["energy_drift"]
        column = [float(row["rod.energy_drift"]) for row in self.rods]
        self.assertEqual(drift["drawn"]["y"], column)
        self.assertEqual((drift["min"], drift["max"], drift["empty"]), (min(column), max(column), 0))
        self.assertAlmostEqual(drift["mean"], sum(column) / len(column), delta=1e-12)
        self.assertEqual(self.one["sweep"]["keys"]["rod.theta0"]["unit"], "rad")

    def test_the_heat_maps_cells_are_the_csvs_variants(self) -> None:
        v0s = sorted({float(row["bowler.v0"]) for row in self.bowlers})
        omegas = sorted({float(row["bowler.omega0"]) for row in self.bowlers})
        outcomes = self.two["bodies"]["bowler"]
        for field in ("mode", "energy_drift", "slip_to_roll"):
            drawn = outcomes[field]["drawn"]
            self.assertEqual((drawn["x"], drawn["y"]), (v0s, omegas), field)
            for row in self.bowlers:
                cell = drawn["z"][omegas.index(float(row["bowler.omega0"]))][v0s.index(float(row["bowler.v0"]))]
                text = row[f"bowler.{field}"]
                self.assertEqual(cell, text if field == "mode" else value(text), (field, row["variant"]))

    def test_the_two_key_counts_are_the_csvs(self) -> None:
        outcomes = self.two["bodies"]["bowler"]
        modes = Counter(row["bowler.mode"] for row in self.bowlers)
        self.assertEqual(outcomes["mode"]["counts"], dict(sorted(modes.items())))
        never = sum(1 for row in self.bowlers if not row["bowler.slip_to_roll"])
        self.assertGreater(never, 0)  # the heat map's grey cells are exercised
        self.assertEqual(outcomes["slip_to_roll"]["empty"], never)
        times = [float(r["bowler.slip_to_roll"]) for r in self.bowlers if r["bowler.slip_to_roll"]]
        self.assertEqual((outcomes["slip_to_roll"]["min"], outcomes["slip_to_roll"]["max"]), (min(times), max(times)))
        self.assertEqual(self.two["sweep"]["variants"], len(self.bowlers))
        self.assertEqual({k: v["unit"] for k, v in self.two["sweep"]["keys"].items()},
                         {"bowler.v0": "m/s", "bowler.omega0": "rad/s"})

    def test_three_swept_keys_are_refused_in_one_line(self) -> None:
        folder = os.path.join(self.tmp.name, "three")
        sweep(CONFIG, folder, "bowler.v0=0:1:2", "bowler.omega0=0:1:2", "rod.k=100:200:2")
        out = os.path.join(self.tmp.name, "three_plots")
        result = subprocess.run([sys.executable, PLOT, CONFIG, folder, "--out-dir", out], capture_output=True,
                                text=True)
        self.assertEqual(result.returncode, 1)
        self.assertEqual(len(result.stderr.strip().splitlines()), 1, result.stderr)
        self.assertIn("bowler.v0, bowler.omega0, rod.k", result.stderr)
        self.assertFalse(os.path.exists(out) and os.listdir(out), "nothing written")


class NodeBagTest(unittest.TestCase):
    def test_a_bag_recorded_from_the_node(self) -> None:
        port = free_port()
        with tempfile.TemporaryDirectory() as tmp:
            bag = os.path.join(tmp, "node.bag")
            env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_IP="127.0.0.1", ROS_HOME=tmp,
                       PATH="/usr/bin:" + os.environ.get("PATH", ""))
            env.pop("ROS_HOSTNAME", None)
            launch = (f'source "{os.environ["RBS_DEVEL"]}/setup.bash" && roslaunch -p {port} rigid_body_sim '
                      f'sim.launch config:={CONFIG} duration:=2 record:=true bag:={bag}')
            subprocess.run(["bash", "-c", launch], env=env, timeout=120, check=True, stdout=subprocess.DEVNULL)
            out = os.path.join(tmp, "plots")
            subprocess.run([sys.executable, PLOT, CONFIG, bag, "--out-dir", out], check=True, stdout=subprocess.DEVNULL)
            for figure in FIGURES:
                self.assertTrue(os.path.isfile(os.path.join(out, figure)), figure)
            with open(os.path.join(out, "summary.json")) as f:
                marked = json.load(f)["marks"]["rollers"]["bowler"]["slip_to_roll"]
            recorded = [e["t"] for e in read_bag_events(bag) if e["body"] == "bowler" and e["kind"] == "slip_to_roll"]
        bowler = load_config(CONFIG)["bodies"]["bowler"]
        # The marks are the node's events, recorded with their instants: no sample is needed for them.
        self.assertEqual(marked, recorded)
        self.assertAlmostEqual(marked[0], closed_form_slip_to_roll(bowler), delta=1e-9)


if __name__ == "__main__":
    unittest.main()
