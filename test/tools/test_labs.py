#!/usr/bin/env python3
"""The web view's labs (rigid_body_sim.labs) without ROS or a network, against the truth:
- a lab run in real time (an injected clock), paused and stepped by any count, equals a core.World of its
  config run as long and `simulate` of its config, bit for bit: every sample (t, each state field) and event;
  after a change of a key it starts again from t = 0 and equals simulate of its new config;
- a tick waits for no lab (one whose lock a request holds is left out) and keeps to its budgets of CPU and wall
  time (one lab a tick with none), the labs it left out going first and caught up at the next: the run still
  equals simulate;
- a step of more samples than a lab keeps: its last ones, simulate's, and every event;
- ticks at the frame timer's times (a frame apart) bring a lab one sample each, whatever its phase against them;
- a refused change answers the core's one line (World.set's ValueError) and changes nothing;
- the caps: one lab a cookie, ~max_labs, ~labs_per_address (the loopback exempt), names 1..40 printable;
- a lab ends after its idle time with no page attached (the injected clock), never while one is;
- the class's outcomes against the closed forms: each roller's slip -> roll instant against
  t = (v0 + omega0 R) / (mu_d g cos(phi) (1 + c) / c - g sin(phi)), its lap time against the finish event's
  closed_form; the curve over a key's grid passes through each lab's point exactly and follows the closed form;
- the poll: choices counted, numbers listed, one answer a voter, refusals;
- the lab requests' pacing (web_protocol.Pacer, as the web view runs it on its lab thread): a page that asks for
  long lab_steps over and over, its requests sent at once, gets them one at a time, in order, each after
  a rest of three times the one before it on the thread (LAB_THREAD_SHARE of it); another page's request waits
  for none of that rest; a key at rest with nothing asked is forgotten; and after every request of any page
  the thread rests as long as it took (LAB_THREAD_TOTAL_SHARE of it): 8 pages asking for long steps together
  take no more than that share, and 30 pages' requests at once run in the order they came, each one rest after
  the one before, all within their time over the share;
- libyaml's loader and dumper (labs.load_yaml, dump_yaml) give the pure Python ones' documents and text.
Usage: test_labs.py [SIMULATE_EXE]   (with the package's devel or install space sourced; without the argument,
simulate is found as catkin finds it)"""
import asyncio
import concurrent.futures
import math
import os
import subprocess
import sys
import tempfile
import time
import unittest
from typing import Any, Callable, Dict, List, Tuple, cast

import numpy
import yaml

import rigid_body_sim.core as core
from rigid_body_sim import labs, runs
from rigid_body_sim.web_protocol import LAB_THREAD_SHARE, LAB_THREAD_TOTAL_SHARE, MAX_LAB_STEPS, Pacer

HERE = os.path.dirname(os.path.abspath(__file__))
CONFIG_DIR = os.path.join(HERE, "..", "..", "config")
SIMULATE = sys.argv.pop(1) if len(sys.argv) > 1 and not sys.argv[1].startswith("-") else labs.find_simulate()


def config_text(name: str) -> str:
    with open(os.path.join(CONFIG_DIR, name)) as file:
        return file.read()


class Clock:
    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


class Collected:
    """What a lab's page gets: its samples and events, as the page keeps them (a restart replaces)."""

    def __init__(self) -> None:
        self.samples: Dict[str, List[Dict[str, Any]]] = {}
        self.events: List[Dict[str, Any]] = []

    def take(self, lab: labs.Lab) -> None:
        whole, events = lab.take_events()
        if whole:
            self.samples, self.events = {}, []
        self.events += events
        for body, states in lab.take_samples().items():
            self.samples.setdefault(body, []).extend(states)


def simulate_run(config: str, duration: float) -> Tuple[Dict[str, Dict[str, numpy.ndarray]], List[Dict[str, Any]]]:
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "config.yaml")
        with open(path, "w") as file:
            file.write(config)
        subprocess.run([SIMULATE, path, "--duration", repr(duration), "--out-dir", folder], check=True,
                       capture_output=True)
        return runs.read_run(folder), runs.read_events(folder)


class Runs(unittest.TestCase):
    def assert_run_is_simulate(self, lab: labs.Lab, got: Collected) -> None:
        duration = lab.sampled_t
        theirs, their_events = simulate_run(lab.config, duration)
        mine, my_events = core.World(lab.config).run(duration, events=True)
        self.assertEqual(sorted(theirs), sorted(got.samples))
        for body, states in got.samples.items():
            for field, column in theirs[body].items():
                values = [state[field] for state in states]
                self.assertEqual(len(values), len(column), (body, field))
                if column.dtype.kind == "f":
                    self.assertEqual([v.hex() for v in values], [float(c).hex() for c in column], (body, field))
                    self.assertEqual([v.hex() for v in values], [float(c).hex() for c in mine[body][field]])
                else:
                    self.assertEqual(values, list(column), (body, field))
        kept = [e for e in got.events if e["t"] <= duration]
        self.assertEqual(kept, their_events)
        self.assertEqual(kept, my_events)
        self.assertTrue(kept, "a run with events")

    def test_real_time_paused_stepped_and_changed(self) -> None:
        clock = Clock()
        room = labs.LabRoom(clock=clock)
        lab, _ = room.open("cookie", "10.0.0.5", "Ada", "start", config_text("race_slip.yaml"))
        got = Collected()
        for _ in range(130):  # 2.6 s in frames of 20 ms
            clock.now += 0.02
            room.tick()
            got.take(lab)
        self.assertAlmostEqual(lab.t, 2.6, delta=0.0011)
        lab.pause()
        clock.now += 5.0
        room.tick()
        self.assertAlmostEqual(lab.t, 2.6, delta=0.0011, msg="paused: no steps")
        lab.step(333)  # not a whole number of samples: the next ones fall where simulate's do
        got.take(lab)
        lab.run(clock.now)
        for _ in range(20):
            clock.now += 0.05
            room.tick()
            got.take(lab)
        self.assert_run_is_simulate(lab, got)
        # A change: from t = 0 with the new config, which is World.set's, and simulate's run of it.
        line = lab.set("ring", "mu_d", 0.25, clock.now)
        self.assertIn("mu_d = 0.25", line)
        self.assertEqual(lab.t, 0.0)
        trial = core.World(config_text("race_slip.yaml"))
        trial.set("ring", mu_d=0.25)
        self.assertEqual(lab.config, trial.config())
        self.assertEqual(lab.varied(), {"ring.mu_d": 0.25})
        got.take(lab)
        lab.pause()
        lab.step(2500)
        got.take(lab)
        self.assert_run_is_simulate(lab, got)

    def test_a_tick_waits_for_no_lab_and_keeps_to_its_budgets(self) -> None:
        clock = Clock()
        room = labs.LabRoom(clock=clock)
        opened = [room.open(f"c{n}", "10.0.0.5", f"s{n}", "start", config_text("race_slip.yaml"))[0]
                  for n in range(3)]
        held = opened[1]
        got = Collected()
        got.take(held)
        clock.now += 0.02
        with held.lock:  # a request of it under way: the tick leaves it out, waiting for nothing
            self.assertEqual(room.tick(lambda lab: lab.id), [opened[0].id, opened[2].id])
        self.assertEqual((opened[0].t, held.t), (0.02, 0.0))
        got.take(held)
        clock.now += 0.02
        room.tick()
        self.assertEqual([lab.t for lab in opened], [0.04] * 3, "caught up at the next tick")
        got.take(held)
        # No time left: one lab a tick, each in turn, each caught up when its turn comes.
        clock.now += 0.02
        turns = [room.tick(lambda lab: lab.id, cpu_budget=0.0) for _ in range(3)]
        self.assertEqual(sorted(id for ids in turns for id in ids), sorted(lab.id for lab in opened))
        self.assertEqual([len(ids) for ids in turns], [1, 1, 1])
        self.assertEqual([lab.t for lab in opened], [0.06] * 3)
        got.take(held)
        for _ in range(150):  # 3 s: past its slip -> roll
            clock.now += 0.02
            room.tick(wall_budget=0.0)
            got.take(held)
        self.assert_run_is_simulate(held, got)

    def test_frames_a_frame_apart_bring_one_sample_each(self) -> None:
        # The web view's frame timer: frame k at start + k / 50 s. Labs opened at every phase of a sample
        # against it (one at a frame's very time) each get one sample a frame, never none then two.
        start, period = 1234.5678, 1.0 / 50.0
        phases = [n / 15 for n in range(15)]
        clock = Clock()
        room = labs.LabRoom(clock=clock)
        opened = []
        for n, phase in enumerate(phases):
            clock.now = start + phase * period
            opened.append(room.open(f"c{n}", "127.0.0.1", f"s{n}", "start", config_text("race_below.yaml"))[0])
            opened[-1].take_samples()
        room.tick(lambda lab: lab.take_samples(), now=start + period)  # the first: one, or none yet
        for k in range(2, 501):
            counts = room.tick(lambda lab: {len(states) for states in lab.take_samples().values()},
                               now=start + k * period)
            self.assertEqual(counts, [{1}] * len(opened), f"frame {k}")
        for lab, phase in zip(opened, phases):  # real time, to the nearest sample
            self.assertLessEqual(abs(lab.t - (10.0 - phase * period)), period / 2)

    def test_a_long_step_keeps_the_last_samples(self) -> None:
        # More samples than a lab keeps: the last SAMPLES_KEPT, simulate's bit for bit, and every event.
        room = labs.LabRoom(clock=Clock())
        lab, _ = room.open("cookie", "10.0.0.5", "Ada", "start", config_text("race_slip.yaml"))
        lab.pause()
        got = Collected()
        got.take(lab)
        steps = 3 * labs.SAMPLES_KEPT * lab.steps_per_sample + 7
        lab.step(steps)
        self.assertEqual(lab.world.steps, steps)
        got.take(lab)
        theirs, their_events = simulate_run(lab.config, lab.sampled_t)
        for body, states in got.samples.items():
            self.assertEqual(len(states), labs.SAMPLES_KEPT + 1, body)  # and t = 0's, taken before
            for field, column in theirs[body].items():
                values = [state[field] for state in states[1:]]
                tail = list(column[-labs.SAMPLES_KEPT:])
                if column.dtype.kind == "f":
                    self.assertEqual([v.hex() for v in values], [float(c).hex() for c in tail], (body, field))
                else:
                    self.assertEqual(values, tail, (body, field))
        kept = [e for e in got.events if e["t"] <= lab.sampled_t]
        self.assertEqual(kept, their_events)
        self.assertTrue(kept, "a run with events")

    def test_a_refused_change_changes_nothing(self) -> None:
        clock = Clock()
        room = labs.LabRoom(clock=clock)
        lab, _ = room.open("cookie", "10.0.0.5", "Ada", "now", config_text("race_slip.yaml"))
        lab.pause()
        lab.step(700)
        before = (lab.config, lab.t, lab.world.steps, lab.world.state("sphere"), lab.varied())
        for key, value in (("mu_d", -1.0), ("incline_angle", 2.0), ("mu_s", math.inf)):
            with self.assertRaises(ValueError) as core_says:
                core.World(lab.config).set("sphere", **{key: value})
            with self.assertRaises(labs.LabRefusal) as refused:
                lab.set("sphere", key, value, clock.now)
            line = str(refused.exception)
            self.assertEqual(line, str(core_says.exception))
            self.assertNotIn("\n", line)
            self.assertIn("'sphere'", line)
            self.assertIn(f"'{key}'", line)
            self.assertEqual((lab.config, lab.t, lab.world.steps, lab.world.state("sphere"), lab.varied()), before)
        with self.assertRaises(labs.LabRefusal):
            lab.set("hoop", "mu_d", 0.1, clock.now)
        with self.assertRaises(labs.LabRefusal):
            lab.set("sphere", "radius", 0.2, clock.now)  # not a lesson key
        lab.run(clock.now)
        with self.assertRaises(labs.LabRefusal):
            lab.step(10)  # running: no step
        self.assertEqual(lab.t, before[1])


class Room(unittest.TestCase):
    def test_caps(self) -> None:
        room = labs.LabRoom(max_labs=4, per_address=2, clock=Clock())
        text = config_text("rod.yaml")
        first, _ = room.open("a1", "10.0.0.7", "  Ann  ", "now", text)
        self.assertEqual(first.name, "Ann")
        room.open("a2", "10.0.0.7", "Ann again", "now", text)
        with self.assertRaisesRegex(labs.LabRefusal, r"^refused: 2 labs from 10\.0\.0\.7 already"):
            room.open("a3", "10.0.0.7", "Ann thrice", "now", text)
        # The same cookie: its lab replaced, never a second one.
        again, old = room.open("a1", "10.0.0.7", "Ann", "now", text)
        self.assertIs(old, first)
        self.assertEqual(len(room.labs), 2)
        self.assertIsNone(room.by_id.get(first.id))
        self.assertIs(room.by_id[again.id], again)
        self.assertNotEqual(again.id, again.cookie)
        # The loopback is exempt from the address's cap, not from the class's.
        room.open("l1", "127.0.0.1", "Teacher", "now", text)
        room.open("l2", "::ffff:127.0.0.1", "Teacher 2", "now", text)
        with self.assertRaisesRegex(labs.LabRefusal, r"^refused: the class has 4 labs already"):
            room.open("l3", "::1", "Teacher 3", "now", text)
        room.close("l2")
        room.open("l3", "::1", "Teacher 3", "now", text)
        for name in ("", "   ", "x" * 41, "tab\there", "new\nline"):
            with self.assertRaisesRegex(labs.LabRefusal, "^refused: a name is 1 to 40 printable characters$"):
                room.open("n1", "10.0.0.9", name, "now", text)
        self.assertEqual(labs.clean_name(" " + "x" * 40 + " "), "x" * 40)
        with self.assertRaisesRegex(labs.LabRefusal, "^refused: no lab cookie"):
            room.open("", "10.0.0.9", "Ann", "now", text)
        broken = yaml.safe_load(text)
        broken["bodies"]["rod"]["k"] = -5
        with self.assertRaises(ValueError) as core_says:
            core.World(broken)
        room.close("l3")
        with self.assertRaises(labs.LabRefusal) as refused:
            room.open("n1", "10.0.0.9", "Ann", "now", broken)
        self.assertEqual(str(refused.exception), str(core_says.exception))
        self.assertNotIn("n1", room.labs)

    def test_idle_expiry(self) -> None:
        clock = Clock()
        room = labs.LabRoom(idle=labs.IDLE, clock=clock)
        text = config_text("rod.yaml")
        watched, _ = room.open("w", "10.0.0.1", "Watched", "now", text)
        left, _ = room.open("l", "10.0.0.2", "Left", "now", text)
        room.attach("w")
        clock.now += labs.IDLE - 1
        self.assertEqual(room.expire(), [])
        room.touch(left)  # a request
        clock.now += labs.IDLE - 1
        self.assertEqual(room.expire(), [])
        clock.now += 1
        self.assertEqual(room.expire(), [left])
        clock.now += 10 * labs.IDLE
        self.assertEqual(room.expire(), [], "a lab with its page attached stays")
        room.detach("w")
        clock.now += labs.IDLE - 1
        self.assertEqual(room.expire(), [])
        clock.now += 1
        self.assertEqual(room.expire(), [watched])
        self.assertEqual((room.labs, room.by_id), ({}, {}))


def slip_to_roll_time(body: Dict[str, Any], g: float) -> float:
    """The closed form of a roller's slip -> roll instant, launched with backspin."""
    c, phi = body["inertia_factor"], body["incline_angle"]
    return ((body["v0"] + body["omega0"] * body["radius"])
            / (body["mu_d"] * g * math.cos(phi) * (1 + c) / c - g * math.sin(phi)))


def slip_to_roll_place(body: Dict[str, Any], g: float) -> float:
    """Where it grips: x0 + v0 t + a t^2 / 2 at that instant, a = g sin(phi) - mu_d g cos(phi) while it slips."""
    t, phi = slip_to_roll_time(body, g), body["incline_angle"]
    return body.get("x0", 0.0) + body["v0"] * t + 0.5 * (g * math.sin(phi) - body["mu_d"] * g * math.cos(phi)) * t * t


class Class(unittest.TestCase):
    def test_outcomes_and_curves_against_the_closed_forms(self) -> None:
        clock = Clock()
        room = labs.LabRoom(clock=clock)
        lesson = config_text("race_slip.yaml")
        opened = []
        for n, mu_d in enumerate((None, 0.15, 0.25, 0.12)):
            lab, _ = room.open(f"c{n}", f"10.0.0.{n}", f"student {n}", "start", lesson)
            if mu_d is not None:
                lab.set("sphere", "mu_d", mu_d, clock.now)
            lab.pause()
            lab.step(4000)
            opened.append(lab)
        results = room.class_results()
        self.assertEqual([r["varied"] for r in results],
                         [{}, {"sphere.mu_d": 0.15}, {"sphere.mu_d": 0.25}, {"sphere.mu_d": 0.12}])
        for lab, result in zip(opened, results):
            config = yaml.safe_load(lab.config)
            outcomes = {(o["body"], o["kind"], o["value_name"]): o for o in result["outcomes"]}
            for name, body in config["bodies"].items():
                slip = outcomes[(name, "slip_to_roll", "t")]["value"]
                self.assertAlmostEqual(slip, slip_to_roll_time(body, config["gravity"]), delta=1e-9 * slip, msg=name)
                finish = [e for e in lab.events if e["body"] == name and e["kind"] == "finished"][0]
                lap = outcomes[(name, "finished", "lap_time")]["value"]
                self.assertEqual(lap, finish["values"]["lap_time"])
                self.assertAlmostEqual(lap, finish["values"]["closed_form"], delta=1e-9 * lap, msg=name)
        by_id = dict(room.by_id)
        base = labs.lesson_of(results, by_id) or ""
        self.assertEqual(base, opened[0].origin)
        computed = labs.Curves().compute(base, results)
        self.assertEqual(computed["lesson"], {"sphere.mu_d": 0.2})
        self.assertEqual(set(computed["curves"]), {"sphere.mu_d"})
        curves = computed["curves"]["sphere.mu_d"]
        self.assertEqual(set(curves), {"sphere.slip_to_roll.t", "sphere.slip_to_roll.x", "sphere.finished.lap_time",
                                       "sphere.finished.x"})
        slip = curves["sphere.slip_to_roll.t"]
        xs, ys = slip["x"], slip["y"]
        self.assertEqual(xs, sorted(xs))
        self.assertGreaterEqual(len(xs), labs.CURVE_POINTS)
        # Each lab's point is on the curve, bit for bit: the same core, the same config, that body alone.
        for lab, result in zip(opened, results):
            x = result["varied"].get("sphere.mu_d", 0.2)
            mine = {(o["kind"], o["value_name"]): o["value"] for o in result["outcomes"] if o["body"] == "sphere"}
            self.assertEqual(ys[xs.index(x)], mine[("slip_to_roll", "t")], x)
            lap = curves["sphere.finished.lap_time"]
            self.assertEqual(lap["y"][lap["x"].index(x)], mine[("finished", "lap_time")], x)
            place = curves["sphere.slip_to_roll.x"]
            self.assertEqual(place["y"][place["x"].index(x)], mine[("slip_to_roll", "x")], x)
        # And everywhere on the grid, the closed form (a value the core refuses has no point: None).
        sphere = yaml.safe_load(base)["bodies"]["sphere"]
        checked = 0
        for x, y in zip(xs, ys):
            if y is None:
                with self.assertRaises(ValueError):
                    core.World(base).set("sphere", mu_d=x)
                continue
            self.assertAlmostEqual(y, slip_to_roll_time({**sphere, "mu_d": x}, 9.8), delta=1e-9 * y, msg=x)
            where = curves["sphere.slip_to_roll.x"]["y"][xs.index(x)]
            self.assertAlmostEqual(where, slip_to_roll_place({**sphere, "mu_d": x}, 9.8), delta=1e-9, msg=x)
            checked += 1
        self.assertGreater(checked, labs.CURVE_POINTS // 2)
        # Cleared: outcomes forgotten, the labs go on.
        room.clear_results()
        self.assertEqual(room.class_results(), [], "a lab without an outcome is no result")
        self.assertEqual(len(room.labs), 4)

    def test_block_comes_to_rest(self) -> None:
        """A block's came_to_rest: its instant and where it stopped, against the closed form of a block
        launched up... or down a slope it cannot slide down: v0 / (g (mu_d cos(phi) - sin(phi)))."""
        config = {"rate": 1000, "publish_rate": 50, "bodies": {"block": {
            "type": "block", "incline_angle": 0.1, "mu_s": 0.5, "mu_d": 0.4, "v0": 2.0, "incline_length": 10.0}}}
        room = labs.LabRoom(clock=Clock())
        lab, _ = room.open("c", "10.0.0.1", "Bo", "now", config)
        lab.pause()
        lab.step(3000)
        result = room.class_results()[0]
        outcomes = {(o["kind"], o["value_name"]): o["value"] for o in result["outcomes"]}
        g, phi = 9.8, 0.1
        decel = g * (0.4 * math.cos(phi) - math.sin(phi))
        self.assertAlmostEqual(outcomes[("came_to_rest", "t")], 2.0 / decel, delta=1e-9)
        self.assertAlmostEqual(outcomes[("came_to_rest", "x")], 2.0 ** 2 / (2 * decel), delta=1e-9)


class Polls(unittest.TestCase):
    def test_poll(self) -> None:
        poll = labs.Poll()
        with self.assertRaisesRegex(labs.LabRefusal, "^refused: no open question$"):
            poll.answer("a", "sphere")
        poll.ask("Which finishes first?", ["sphere", "ring"], "")
        self.assertEqual(poll.question_message(), {"type": "question", "question": "Which finishes first?",
                                                   "choices": ["sphere", "ring"], "unit": "", "open": True})
        poll.answer("a", "ring")
        poll.answer("a", "sphere")  # a voter's latest answer counts
        poll.answer("b", "sphere")
        with self.assertRaisesRegex(labs.LabRefusal, "^refused: the answer is one of sphere, ring$"):
            poll.answer("c", "cube")
        with self.assertRaisesRegex(labs.LabRefusal, "^refused: no lab cookie"):
            poll.answer("", "ring")
        self.assertEqual(poll.answers_message(), {"type": "answers", "n": 2, "counts": {"sphere": 2, "ring": 0}})
        poll.reveal()
        self.assertFalse(poll.question_message()["open"])
        with self.assertRaises(labs.LabRefusal):
            poll.answer("c", "ring")
        poll.ask("The sphere's lap time?", None, "s")
        self.assertEqual(poll.answers_message(), {"type": "answers", "n": 0, "values": []})
        poll.answer("a", 1.9)
        poll.answer("b", 2)
        for bad in ("two", math.nan, math.inf, True):
            with self.assertRaises(labs.LabRefusal):
                poll.answer("c", cast(Any, bad))  # True: a bool, which JSON's true would be
        self.assertEqual(poll.answers_message(), {"type": "answers", "n": 2, "values": [1.9, 2.0]})


class Timed:
    """Works on the pacer's thread, each's start and end (perf_counter s) as it ran, by key, in their order."""

    def __init__(self) -> None:
        self.runs: List[Tuple[str, float, float]] = []

    def work(self, key: str, body: Callable[[], Any]) -> Callable[[], None]:
        def timed() -> None:
            started = time.perf_counter()
            body()
            self.runs.append((key, started, time.perf_counter()))
        return timed

    def of(self, key: str) -> List[Tuple[float, float]]:
        return [(start, end) for k, start, end in self.runs if k == key]


class Pacing(unittest.TestCase):
    REST = (1.0 - LAB_THREAD_SHARE) / LAB_THREAD_SHARE  # a key's rest per second of its work
    THREAD_REST = (1.0 - LAB_THREAD_TOTAL_SHARE) / LAB_THREAD_TOTAL_SHARE  # the thread's, of any key's work
    # s the loop takes at most to start the next work once a rest is over (the work's future, the lock, the
    # timer: some 0.1 ms on an idle machine; 10 ms on a loaded one of 2 cores).
    HANDOFF = 0.01
    # Steps of a long request: a tenth of the most a lab_step may ask, some ms of a lab's work (the shares do not
    # depend on its length; the full count made the suite outlast its minute under AddressSanitizer).
    LONG_STEPS = MAX_LAB_STEPS // 10

    def assert_rested(self, runs: List[Tuple[float, float]], rest: float = REST) -> None:
        """Each work began once `rest` times the one before it had passed since its end."""
        for (start, end), (after, _) in zip(runs, runs[1:]):
            self.assertGreaterEqual(after - end, rest * (end - start), (start, end, after))

    @staticmethod
    def pacer(thread: concurrent.futures.Executor) -> Pacer:
        return Pacer(thread, LAB_THREAD_SHARE, LAB_THREAD_TOTAL_SHARE)  # as the web view paces its lab thread

    @staticmethod
    def long_step(lab: labs.Lab) -> Callable[[], None]:
        def step() -> None:  # a lab_step request's work: the steps, then the samples its frame takes
            with lab.lock:
                lab.step(Pacing.LONG_STEPS)
                lab.take_samples()
        return step

    def test_a_page_asking_for_long_steps_keeps_to_its_share(self) -> None:
        room = labs.LabRoom(clock=Clock())
        spammer, _ = room.open("spammer", "10.0.0.5", "Ada", "start", config_text("race_slip.yaml"))
        spammer.pause()
        timed = Timed()
        thread = concurrent.futures.ThreadPoolExecutor(max_workers=1)

        async def spam(pacer: Pacer, rounds: int) -> None:
            for _ in range(rounds):  # a page's most pending requests at once, again and again
                await asyncio.gather(*(pacer.run("spammer", timed.work("spammer", self.long_step(spammer)))
                                       for _ in range(8)))
        try:
            asyncio.run(spam(self.pacer(thread), 3))
        finally:
            thread.shutdown()
        runs = timed.of("spammer")
        self.assertEqual(len(runs), 24)
        self.assertEqual(spammer.world.steps, 24 * self.LONG_STEPS, "each request carried out once")
        self.assertTrue(all(end <= after for (_, end), (after, _) in zip(runs, runs[1:])), "one at a time")
        self.assert_rested(runs)
        busy = sum(end - start for start, end in runs)
        span = runs[-1][1] + self.REST * (runs[-1][1] - runs[-1][0]) - runs[0][0]  # to the end of the last rest
        self.assertLessEqual(busy, LAB_THREAD_SHARE * span + 1e-9)
        print(f"lab_step {self.LONG_STEPS} x 24 at once: {1000 * busy / len(runs):.1f} ms each on the thread, "
              f"{busy / span:.3f} of it over {span:.2f} s", file=sys.stderr)

    def test_pages_asking_for_long_steps_together_keep_to_the_total_share(self) -> None:
        room = labs.LabRoom(clock=Clock())
        spammers = [room.open(f"spammer {i}", "127.0.0.1", f"Ada {i}", "start", config_text("race_slip.yaml"))[0]
                    for i in range(8)]
        for lab in spammers:
            lab.pause()
        timed = Timed()
        thread = concurrent.futures.ThreadPoolExecutor(max_workers=1)

        async def spam(pacer: Pacer) -> None:  # every page its 3 requests at once, all pages together
            await asyncio.gather(*(pacer.run(lab.cookie, timed.work(lab.cookie, self.long_step(lab)))
                                   for _ in range(3) for lab in spammers))
        try:
            asyncio.run(spam(self.pacer(thread)))
        finally:
            thread.shutdown()
        runs = [(start, end) for _, start, end in timed.runs]
        self.assertEqual(len(runs), 24)
        for lab in spammers:
            self.assertEqual(lab.world.steps, 3 * self.LONG_STEPS, "each request carried out once")
            self.assert_rested(timed.of(lab.cookie))
        self.assertTrue(all(end <= after for (_, end), (after, _) in zip(runs, runs[1:])), "one at a time")
        self.assert_rested(runs, self.THREAD_REST)
        # Each work and the thread's rest after it, back to back at best: the busy share is at most the total
        # share, up to the sums' rounding.
        busy = sum(end - start for start, end in runs)
        span = runs[-1][1] + self.THREAD_REST * (runs[-1][1] - runs[-1][0]) - runs[0][0]
        self.assertLessEqual(busy, LAB_THREAD_TOTAL_SHARE * span + 1e-9)
        print(f"8 pages' lab_step {self.LONG_STEPS} x 3 at once: {1000 * busy / len(runs):.1f} ms each on the "
              f"thread, {busy / span:.3f} of it over {span:.2f} s", file=sys.stderr)

    def test_other_pages_wait_for_no_rest_but_their_own(self) -> None:
        timed = Timed()
        thread = concurrent.futures.ThreadPoolExecutor(max_workers=1)
        took = 0.2  # s of a long request's work: its page rests three times that, on the loop
        asked: Dict[str, float] = {}

        async def lesson(pacer: Pacer) -> None:
            await pacer.run("long", timed.work("long", lambda: time.sleep(took)))
            asked["student"] = time.perf_counter()  # in the long page's rest
            await asyncio.gather(pacer.run("long", timed.work("long", lambda: time.sleep(took))),
                                 pacer.run("student", timed.work("student", lambda: None)))
        pacer = self.pacer(thread)
        try:
            asyncio.run(lesson(pacer))
        finally:
            thread.shutdown()
        (start, end), after = timed.of("long")[0], timed.of("long")[1][0]
        student = timed.of("student")[0][0]
        self.assertGreaterEqual(after - end, self.REST * (end - start))
        self.assertLess(student, end + self.REST * (end - start), "the student's request waited for another's rest")
        self.assertLess(student, after)
        # Every key at rest with nothing asked is forgotten once another's request ends, its rest over.
        self.assertTrue(pacer.keys, "no page's rest under way")
        time.sleep(max(0.0, max(turns.rests_until for turns in pacer.keys.values()) - time.perf_counter()))
        thread = concurrent.futures.ThreadPoolExecutor(max_workers=1)
        try:
            pacer.executor = thread
            asyncio.run(pacer.run("last", lambda: None))
        finally:
            thread.shutdown()
        self.assertEqual(set(pacer.keys) - {"last"}, set())
        print(f"a student's request {1000 * (student - asked['student']):.1f} ms after it was asked, in another's "
              f"rest of {1000 * self.REST * (end - start):.0f} ms", file=sys.stderr)

    def test_a_class_at_once_is_served_in_order_within_the_total_share(self) -> None:
        timed = Timed()
        thread = concurrent.futures.ThreadPoolExecutor(max_workers=1)
        took = 0.02  # s of a lab_open's work
        asked: List[float] = []

        async def lesson(pacer: Pacer) -> None:
            asked.append(time.perf_counter())
            await asyncio.gather(*(pacer.run(f"page {i}", timed.work(f"page {i}", lambda: time.sleep(took)))
                                   for i in range(30)))
            await asyncio.gather(*(pacer.run(f"page {i}", timed.work(f"page {i}", lambda: None)) for i in range(3)))
        try:
            asyncio.run(lesson(self.pacer(thread)))
        finally:
            thread.shutdown()
        first = timed.runs[:30]
        self.assertEqual([key for key, _, _ in first], [f"page {i}" for i in range(30)], "not in the order asked")
        self.assert_rested([(start, end) for _, start, end in first], self.THREAD_REST)
        for i in range(3):
            self.assert_rested(timed.of(f"page {i}"))
        # Each work after the one before it and the thread's rest, but for the loop's hand-offs.
        works = [end - start for _, start, end in first]
        bound = sum(works) + self.THREAD_REST * sum(works[:-1]) + len(works) * self.HANDOFF
        self.assertLessEqual(first[-1][2] - asked[0], bound)
        print(f"30 pages' requests of {1000 * took:.0f} ms at once, served in {first[-1][2] - asked[0]:.2f} s "
              f"(at most {bound:.2f} s)", file=sys.stderr)


class Yaml(unittest.TestCase):
    def test_the_fast_loader_and_dumper_give_the_pure_ones_documents(self) -> None:
        for name in sorted(os.listdir(CONFIG_DIR)):
            text = config_text(name)
            for config in (text, core.World(text).config()):
                parsed = yaml.load(config, Loader=yaml.SafeLoader)
                self.assertEqual(repr(labs.load_yaml(config)), repr(parsed), name)  # repr: -0.0 too
                self.assertEqual(labs.dump_yaml(parsed), yaml.dump(parsed, Dumper=yaml.SafeDumper, sort_keys=False),
                                 name)


if __name__ == "__main__":
    if not SIMULATE:
        sys.exit("test_labs: simulate not found: give its path, or source the devel space")
    unittest.main()
