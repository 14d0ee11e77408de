"""A lab for every student: private worlds of the web view's pages, without ROS or a network.

A Lab is a rigid_body_sim.core.World built from a config text: from t = 0, so that its run is `simulate` of
that config bit for bit, its states and its events. A change of a key makes the new config (World.set and
World.config() on a trial World: a refusal changes nothing and is the core's one line) and starts the lab
again from t = 0 with it. A lab runs in real time at its config's rate while it runs (`advance`, given the
clock), and samples every rate / publish_rate steps, the first at t = 0, as the node publishes and simulate
samples.

A LabRoom holds the labs of one web view: one a cookie, at most `max_labs`, at most `per_address` opened
from one remote address (the loopback's exempt), each ended after `idle` s without a request and without an
attached page. Its `class_results` are each lab's outcomes (the first event of each body and kind in its run)
and the keys it varied from the config it was opened from; `curves` runs the core over a grid of a key's
values (that config, that body alone) for the same outcomes: the curve the class's points lie on. A Poll is
the teacher's question and the class's answers.

Thread use: a Lab's world is used under its `lock` alone, the room's tables under the room's. The web view
ticks the labs on its server's loop and carries out their requests on a worker thread: `LabRoom.tick` never
waits for a lock (a lab whose lock a request holds is left to the next tick, which catches it up) and stops
within its budgets of time. What the loop reads of a lab besides (its id, name, config, `t`, `paused`) are
attributes each replaced whole."""
from __future__ import annotations

import collections
import ipaddress
import json
import math
import os
import secrets
import threading
import time
from typing import Any, Callable, Deque, Dict, Iterable, List, Mapping, Optional, Sequence, Set, Tuple, Union

import yaml

from rigid_body_sim import core, description
from rigid_body_sim.web_protocol import MAX_LAB_STEPS, MAX_NAME, printable_text

MAX_LABS = 60
LABS_PER_ADDRESS = 8
IDLE = 30 * 60.0  # s without a request and without a page attached: the lab ends
MAX_EVENTS = 1_000  # of a lab's run, kept (the oldest go): some 2 MB of records at most
SAMPLES_KEPT = 500  # a lab's samples not yet sent, per body (the oldest go): a page plots the last 10 s
MAX_BEHIND = 0.5  # s of simulated time a running lab catches up at once; behind more, it slows instead
CURVE_POINTS = 25  # grid values of a curve's key, besides the class's own and the lesson's
CURVE_DURATION = 60.0  # s a grid run lasts at most, unless a lab's outcome came later
CURVE_CACHE = 20_000  # grid runs remembered
Record = Dict[str, Any]  # an event as World.events() gives it
# libyaml's parser and emitter where python3-yaml has them (Debian's has): the same documents as the pure
# Python ones, some six times faster (whose parse took most of a lab_open's or lab_set's time on the lab thread,
# holding the GIL from the web view's loop).
_YAML_LOADER: Any = yaml.CSafeLoader if yaml.__with_libyaml__ else yaml.SafeLoader
_YAML_DUMPER: Any = yaml.CSafeDumper if yaml.__with_libyaml__ else yaml.SafeDumper


def load_yaml(text: str) -> Any:
    """What yaml.safe_load(text) gives."""
    return yaml.load(text, Loader=_YAML_LOADER)


def dump_yaml(data: Any) -> str:
    """What yaml.safe_dump(data, sort_keys=False) gives."""
    return str(yaml.dump(data, Dumper=_YAML_DUMPER, sort_keys=False))


class LabRefusal(Exception):
    """A lab request that changes nothing; str() is its one line."""


def roles() -> Dict[str, Dict[str, str]]:
    """{type: {event kind: its role}}: "finish", "restart" or "" (the description's)."""
    return {name: {kind["name"]: kind["role"] for kind in t.get("event_kinds", [])}
            for name, t in description.body_types().items()}


ROLES = roles()
# Outcomes of every kind besides its instant, named by no kind: where the body was then (the state field x
# every type has: where a block came to rest, where a ball gripped) and how often it happened so far.
EXTRA_OUTCOMES: Tuple[str, ...] = ("x", "count")
# Outcomes that grow as a run goes on: no curve (a grid run has no duration of the lab's).
RUNNING_OUTCOMES = ("count",)


def clean_name(name: str) -> str:
    """The student's name trimmed; LabRefusal unless 1..MAX_NAME printable characters."""
    trimmed = printable_text(name, MAX_NAME)
    if trimmed is None:
        raise LabRefusal(f"refused: a name is 1 to {MAX_NAME} printable characters")
    return trimmed


def is_loopback(address: str) -> bool:
    try:
        ip = ipaddress.ip_address(address.split("%")[0])
    except ValueError:
        return False
    mapped = getattr(ip, "ipv4_mapped", None)
    return bool(ip.is_loopback or (mapped is not None and mapped.is_loopback))


def find_simulate() -> str:
    """The package's `simulate` as catkin finds it: lib/rigid_body_sim/ of each workspace of
    CMAKE_PREFIX_PATH (the devel or install space sourced), or ""."""
    for prefix in os.environ.get("CMAKE_PREFIX_PATH", "").split(os.pathsep):
        path = os.path.join(prefix, "lib", "rigid_body_sim", "simulate")
        if prefix and os.access(path, os.X_OK):
            return path
    return ""


def canonical(config: Union[str, Dict[str, Any]]) -> str:
    """A config as the core writes it (World.config()); LabRefusal with the core's line if it refuses it."""
    try:
        return core.World(config).config()
    except ValueError as error:
        raise LabRefusal(str(error)) from None


def lesson_values(config_text: str) -> Dict[str, float]:
    """{"body.key": value} of every lesson key of every body of a config (as the core wrote it)."""
    return lesson_values_of(load_yaml(config_text) or {})


def lesson_values_of(config: Mapping[str, Any]) -> Dict[str, float]:
    """lesson_values of a config parsed."""
    keys = description.lesson_keys()
    return {f"{name}.{key}": body[key] for name, body in (config.get("bodies") or {}).items()
            for key in keys.get(body.get("type"), []) if key in body}


def outcomes_of(records: Iterable[Record], first: Optional[Dict[Tuple[str, str], Record]] = None,
                counts: Optional[Dict[Tuple[str, str], int]] = None) -> None:
    """Adds records to `first` ((body, kind) -> its first event) and `counts` ((body, kind) -> events)."""
    for record in records:
        if ROLES.get(record["type"], {}).get(record["kind"], "restart") == "restart":
            continue
        mark = (record["body"], record["kind"])
        if first is not None:
            first.setdefault(mark, record)
        if counts is not None:
            counts[mark] = counts.get(mark, 0) + 1


def outcome_list(first: Mapping[Tuple[str, str], Record], counts: Mapping[Tuple[str, str], int]
                 ) -> List[Dict[str, Any]]:
    """[{body, kind, value_name, value, t}]: each first event's outcomes (a finish's lap_time, any other's
    instant t; the body's x then; how many of the kind so far), in time order."""
    out = []
    for (body, kind), record in sorted(first.items(), key=lambda item: (item[1]["t"], item[0])):
        role = ROLES.get(record["type"], {}).get(kind, "")
        main = ("lap_time", record["values"].get("lap_time", math.nan)) if role == "finish" else ("t", record["t"])
        values = [main] + [(extra, counts.get((body, kind), 0) if extra == "count" else record["state"].get(extra))
                           for extra in EXTRA_OUTCOMES]
        for name, value in values:
            if isinstance(value, (int, float)) and math.isfinite(value):
                out.append({"body": body, "kind": kind, "value_name": name, "value": value, "t": record["t"]})
    return out


class Lab:
    """One student's world. Every method but the constructor's bookkeeping is called with `lock` held, on one
    thread at a time."""

    def __init__(self, config: str, name: str, source: str, cookie: str, address: str, lab_id: str,
                 now: float) -> None:
        self.lock = threading.Lock()
        self.id = lab_id
        self.cookie = cookie
        self.address = address
        self.name = name
        self.source = source  # "now" or "start": what the page opened it from
        self.origin = canonical(config)  # the config it was opened from: "varied" is against it
        self.config = self.origin
        self.paused = False
        self.last_active = now
        self.attached = 0
        self.seq = 0
        self.dropped = 0  # samples that went unsent (SAMPLES_KEPT)
        self.changed = True  # its `lab` message is to be sent
        self.results_changed = True
        self._start(now)
        self.origin_values = self.values  # of the config it was opened from

    # --- the run -------------------------------------------------------------------------------------------
    def _start(self, now: float) -> None:
        """From t = 0 with its config: its samples from the first, its events afresh."""
        self.world = core.World(self.config)
        parsed = load_yaml(self.config) or {}
        # Its lesson keys' values, parsed once a run (the class's results ask for them often; a parse takes ms).
        self.values = lesson_values_of(parsed)
        self.settings: Dict[str, Dict[str, Any]] = dict(parsed.get("bodies") or {})
        self.world_settings = {key: value for key, value in parsed.items() if key != "bodies"}
        self.bodies = {name: str(body["type"]) for name, body in self.settings.items()}
        self.rate = float(parsed.get("rate", 1000.0))
        self.steps_per_sample = max(1, round(self.rate / float(parsed.get("publish_rate", 50.0))))
        self.samples: Dict[str, Deque[Dict[str, Any]]] = {
            name: collections.deque(maxlen=SAMPLES_KEPT) for name in self.world.bodies}
        self.last: Dict[str, Dict[str, Any]] = {}  # each body's last sample: a page that attaches draws it
        self.events: Deque[Record] = collections.deque(maxlen=MAX_EVENTS)
        self.new_events: List[Record] = []
        self.restarted = True  # its events are to be sent whole (lab_events all: true)
        self.first: Dict[Tuple[str, str], Record] = {}
        self.counts: Dict[Tuple[str, str], int] = {}
        self.t = 0.0
        self.sampled_t = 0.0  # its last sample's t: `simulate --duration` of it gives the run so far
        self.wall_start, self.steps_at_start = now, 0
        self._sample()
        self.changed = self.results_changed = True

    def _sample(self) -> None:
        t = self.world.t
        for name in self.world.bodies:
            kept = self.samples[name]
            self.dropped += len(kept) == kept.maxlen
            sample: Dict[str, Any] = {"t": t, **self.world.state(name)}
            kept.append(sample)
            self.last[name] = sample
        self.sampled_t = t

    def _step(self, n: int) -> None:
        """n steps, a sample at every multiple of steps_per_sample, the events they bring. Of more samples than
        SAMPLES_KEPT, those it would push out before any page got them are not taken (counted in `dropped`):
        a long lab_step costs the samples kept, not the steps' (their Python would hold the GIL from the loop)."""
        per = self.steps_per_sample
        unsent = (self.world.steps + n) // per - self.world.steps // per - SAMPLES_KEPT
        if unsent > 0:  # straight to the last sample not kept, untaken
            skipped = (self.world.steps // per + unsent) * per - self.world.steps
            self.world.step(skipped)
            n -= skipped
            self.dropped += unsent * len(self.samples)
        while n > 0:
            to_sample = self.steps_per_sample - self.world.steps % self.steps_per_sample
            chunk = min(n, to_sample)
            self.world.step(chunk)
            n -= chunk
            if chunk == to_sample:
                self._sample()
        self.t = self.world.t
        happened = self.world.events()
        if happened:
            self.events.extend(happened)
            self.new_events.extend(happened)
            del self.new_events[:-MAX_EVENTS]
            before = len(self.first), sum(self.counts.values())
            outcomes_of(happened, self.first, self.counts)
            if (len(self.first), sum(self.counts.values())) != before:
                self.results_changed = True

    def advance(self, now: float) -> None:
        """While it runs: the steps real time has brought since it started running, to the nearest sample (at
        most MAX_BEHIND s at once: a lab that fell behind slows, never bursts). Whole samples: times a frame
        apart (the web view's frame timer's schedule) then bring the same count of samples each, whatever
        steps a frame has (a step due a hair before a sample's would leave it to the next frame)."""
        if self.paused:
            return
        exact = (now - self.wall_start) * self.rate + self.steps_at_start
        due = round(exact / self.steps_per_sample) * self.steps_per_sample
        cap = self.world.steps + max(1, int(MAX_BEHIND * self.rate))
        if due > cap:
            self.wall_start, self.steps_at_start, due = now, cap, cap
        if due > self.world.steps:
            self._step(due - self.world.steps)

    def run(self, now: float) -> str:
        if self.paused:
            self.paused = False
            self.wall_start, self.steps_at_start = now, self.world.steps
            self.changed = True
        return f"lab runs from t = {self.t:g} s"

    def pause(self) -> str:
        self.paused, self.changed = True, True
        return f"lab paused at t = {self.t:g} s"

    def step(self, steps: int) -> str:
        if not self.paused:
            raise LabRefusal("refused: lab_step while the lab runs (pause it first)")
        if not 1 <= steps <= MAX_LAB_STEPS:
            raise LabRefusal(f"refused: steps is a whole number in [1, {MAX_LAB_STEPS}]")
        self._step(steps)
        self.changed = True
        return f"lab stepped to t = {self.t:g} s"

    def reset(self, now: float) -> str:
        self._start(now)
        return "lab started again from t = 0"

    def set(self, body: str, key: str, value: float, now: float) -> str:
        """The key on a trial World of its config: refused, nothing changes; else the lab starts again from
        t = 0 with the new config."""
        if self.bodies.get(body) is None:
            raise LabRefusal(f"refused: no body {body[:40]!r} in this lab")
        if key not in description.lesson_keys()[self.bodies[body]]:
            raise LabRefusal(f"refused: {self.bodies[body]} key {key[:40]!r} is not one a lesson changes")
        trial = core.World(self.config)
        try:
            trial.set(body, **{key: value})
        except ValueError as error:
            raise LabRefusal(str(error)) from None
        self.config = trial.config()
        self._start(now)
        return f"lab: {body}: {key} = {value:g}, started again from t = 0"

    # --- what it shows ------------------------------------------------------------------------------------
    def take_samples(self) -> Dict[str, List[Dict[str, Any]]]:
        """Its samples since the last call, by body ({} for none)."""
        taken = {name: list(kept) for name, kept in self.samples.items() if kept}
        for kept in self.samples.values():
            kept.clear()
        return taken

    def take_events(self) -> Tuple[bool, List[Record]]:
        """(whole, events): after a (re)start the run's whole (the page's replaced), else the new ones."""
        whole, self.restarted = self.restarted, False
        taken = list(self.events) if whole else self.new_events
        self.new_events = []
        return whole, taken

    def varied(self) -> Dict[str, float]:
        """{"body.key": value} of its lesson keys that differ from the config it was opened from."""
        return {mark: value for mark, value in self.values.items() if self.origin_values.get(mark) != value}

    def message(self, kind: str = "lab") -> Dict[str, Any]:
        return {"type": kind, "lab": self.id, "name": self.name, "config": self.config, "bodies": self.bodies,
                "settings": self.settings, "world": self.world_settings, "t": self.t, "paused": self.paused,
                "from": self.source, "states": dict(self.last)}

    def result(self) -> Dict[str, Any]:
        return {"lab": self.id, "name": self.name, "from": self.source, "varied": self.varied(),
                "outcomes": outcome_list(self.first, self.counts), "t": self.t}


class LabRoom:
    """The web view's labs: one a cookie, caps, idle expiry; `clock` gives s (monotonic; a test's own)."""

    def __init__(self, max_labs: int = MAX_LABS, per_address: int = LABS_PER_ADDRESS, idle: float = IDLE,
                 clock: Callable[[], float] = time.monotonic) -> None:
        self.max_labs = max_labs
        self.per_address = per_address
        self.idle = idle
        self.clock = clock
        self.lock = threading.Lock()
        self.labs: Dict[str, Lab] = {}  # by cookie
        self.by_id: Dict[str, Lab] = {}
        self.turn = 0  # the lab a tick begins with: those its budgets left out go first the next time

    def of(self, cookie: Optional[str]) -> Optional[Lab]:
        return self.labs.get(cookie) if cookie else None

    def open(self, cookie: str, address: str, name: str, source: str, config: Union[str, Dict[str, Any]]
             ) -> Tuple[Lab, Optional[Lab]]:
        """A new lab for the cookie (its lab before, if any, ends: returned second), or LabRefusal."""
        if not cookie:
            raise LabRefusal("refused: no lab cookie (reload the page)")
        name = clean_name(name)
        with self.lock:
            old = self.labs.get(cookie)
            count = len(self.labs) - (old is not None)
            if count >= self.max_labs:
                raise LabRefusal(f"refused: the class has {self.max_labs} labs already (the most: ~max_labs)")
            if not is_loopback(address):
                mine = sum(1 for lab in self.labs.values() if lab.address == address and lab is not old)
                if mine >= self.per_address:
                    raise LabRefusal(f"refused: {self.per_address} labs from {address} already "
                                     "(the most: ~labs_per_address)")
        now = self.clock()
        lab_id = secrets.token_hex(4)
        lab = Lab(config if isinstance(config, str) else canonical(config), name, source, cookie, address,
                  lab_id, now)  # LabRefusal: the core refused the config
        lab.attached = old.attached if old else 0
        with self.lock:
            while lab.id in self.by_id:
                lab.id = secrets.token_hex(4)
            if old is not None:
                self.by_id.pop(old.id, None)
            self.labs[cookie] = lab
            self.by_id[lab.id] = lab
        return lab, old

    def close(self, cookie: Optional[str]) -> Optional[Lab]:
        with self.lock:
            lab = self.labs.pop(cookie or "", None)
            if lab is not None:
                self.by_id.pop(lab.id, None)
        return lab

    def touch(self, lab: Lab) -> None:
        lab.last_active = self.clock()

    def attach(self, cookie: Optional[str]) -> Optional[Lab]:
        lab = self.of(cookie)
        if lab is not None:
            lab.attached += 1
            self.touch(lab)
        return lab

    def detach(self, cookie: Optional[str]) -> None:
        lab = self.of(cookie)
        if lab is not None:
            lab.attached = max(0, lab.attached - 1)
            self.touch(lab)

    def all(self) -> List[Lab]:
        with self.lock:
            return list(self.labs.values())

    def expire(self) -> List[Lab]:
        """The labs idle for `idle` s with no page attached: ended."""
        now = self.clock()
        with self.lock:
            gone = [lab for lab in self.labs.values() if lab.attached == 0 and now - lab.last_active >= self.idle]
            for lab in gone:
                del self.labs[lab.cookie]
                self.by_id.pop(lab.id, None)
        return gone

    def tick(self, news: Optional[Callable[[Lab], Any]] = None, now: Optional[float] = None,
             cpu_budget: Optional[float] = None, wall_budget: Optional[float] = None) -> List[Any]:
        """Every running lab advanced to now (the clock's, or the frame's time given) and `news` of it taken,
        under its lock; [news of each] (without `news`, the labs advanced). Never waits: a lab whose lock is
        held (a request of it, on another thread) is left out, and so are the labs still to go once the tick
        has taken `cpu_budget` s of its thread's CPU time or `wall_budget` s of wall time (the first is always
        tried); the labs left out go first at the next tick, which catches them up."""
        now = self.clock() if now is None else now
        labs = self.all()
        if labs:
            first = self.turn % len(labs)
            labs = labs[first:] + labs[:first]
        out: List[Any] = []
        cpu, wall = time.thread_time(), time.perf_counter()
        for done, lab in enumerate(labs):
            if done and ((cpu_budget is not None and time.thread_time() - cpu >= cpu_budget)
                         or (wall_budget is not None and time.perf_counter() - wall >= wall_budget)):
                self.turn = (self.turn + done) % len(labs)
                return out
            if not lab.lock.acquire(blocking=False):
                continue
            try:
                lab.advance(now)
                out.append(news(lab) if news is not None else lab)
            finally:
                lab.lock.release()
        return out

    def class_results(self) -> List[Dict[str, Any]]:
        """Each lab's result that has an outcome (a lab that found nothing yet, or since a clear, is none)."""
        results = []
        for lab in self.all():
            with lab.lock:
                lab.results_changed = False
                result = lab.result()
            if result["outcomes"]:
                results.append(result)
        return results

    def clear_results(self) -> None:
        """Every lab's outcomes forgotten (their runs go on: outcomes from now on count)."""
        for lab in self.all():
            with lab.lock:
                lab.first, lab.counts, lab.results_changed = {}, {}, True


def grid(lesson: float, seen: Sequence[float], low: Optional[float], high: Optional[float],
         points: int = CURVE_POINTS) -> List[float]:
    """The key's values of a curve: `points` evenly over the class's values and the lesson's, a tenth wider
    each side (within the key's range), and those values themselves (the class's points lie on the curve
    exactly there)."""
    values = [lesson, *seen]
    lo, hi = min(values), max(values)
    pad = 0.1 * (hi - lo) if hi > lo else 0.1 * abs(hi) or 0.1
    lo, hi = lo - pad, hi + pad
    if low is not None:
        lo = max(lo, low)
    if high is not None:
        hi = min(hi, high)
    even = [lo + (hi - lo) * i / (points - 1) for i in range(points)] if points > 1 else [lo]
    return sorted(set(even) | set(values))


class Curves:
    """The core's outcomes over a grid of one key (the others as in the lab's lesson config, that body alone),
    each grid run remembered."""

    def __init__(self) -> None:
        self.cache: Dict[Tuple[Any, ...], Dict[Tuple[str, str], float]] = {}
        self.lock = threading.Lock()

    def point(self, config: str, body: str, key: str, value: float, wanted: Set[Tuple[str, str]],
              duration: float) -> Dict[Tuple[str, str], float]:
        """{(kind, value_name): value} of the body alone with key = value, run until every wanted outcome came
        or `duration` s; {} if the core refuses the value."""
        mark = (config, body, key, value, frozenset(wanted), duration)
        with self.lock:
            if mark in self.cache:
                return self.cache[mark]
        parsed = load_yaml(config) or {}
        parsed["bodies"] = {body: {**parsed["bodies"][body], key: value}}
        found: Dict[Tuple[str, str], float] = {}
        world: Optional[core.World] = None
        try:
            world = core.World(parsed)
        except ValueError:
            pass
        first: Dict[Tuple[str, str], Record] = {}
        counts: Dict[Tuple[str, str], int] = {}
        chunk = max(1, round(1.0 / world.dt)) if world else 0
        while world is not None and world.t < duration:
            world.step(min(chunk, max(1, round((duration - world.t) / world.dt))))
            outcomes_of(world.events(), first, counts)
            found = {(o["kind"], o["value_name"]): o["value"] for o in outcome_list(first, counts)}
            if wanted <= set(found):
                break
        with self.lock:
            if len(self.cache) >= CURVE_CACHE:
                self.cache.clear()
            self.cache[mark] = found
        return found

    def compute(self, config: str, results: Sequence[Mapping[str, Any]]) -> Dict[str, Any]:
        """{"curves": {"body.key": {"body.kind.value_name": {"x": [...], "y": [...]}}}, "lesson": {"body.key":
        value}}: for every key the labs varied and every outcome of that body they had (no count: it grows
        with a run's length), from `config` (the labs' lesson config); a y the core gave no such event for:
        None."""
        lesson = lesson_values(config)
        parsed = load_yaml(config) or {}
        kinds = {name: body.get("type") for name, body in (parsed.get("bodies") or {}).items()}
        seen: Dict[str, List[float]] = collections.defaultdict(list)
        wanted: Dict[str, Set[Tuple[str, str]]] = collections.defaultdict(set)
        latest = 0.0
        for result in results:
            for mark, value in result["varied"].items():
                seen[mark].append(value)
            for outcome in result["outcomes"]:
                if outcome["value_name"] not in RUNNING_OUTCOMES:
                    wanted[outcome["body"]].add((outcome["kind"], outcome["value_name"]))
                    latest = max(latest, outcome["t"])
        duration = max(CURVE_DURATION, 2 * latest)
        curves: Dict[str, Dict[str, Dict[str, List[Any]]]] = {}
        for mark, values in sorted(seen.items()):
            body, key = mark.split(".", 1)
            if body not in kinds or mark not in lesson or not wanted[body]:
                continue
            spec = description.key(str(kinds[body]), key) or {}
            bounds = spec.get("range") or {}
            xs = grid(lesson[mark], values, bounds.get("min"), bounds.get("max"))
            points = [self.point(config, body, key, x, wanted[body], duration) for x in xs]
            curves[mark] = {f"{body}.{kind}.{name}": {"x": xs, "y": [p.get((kind, name)) for p in points]}
                            for kind, name in sorted(wanted[body])}
        return {"curves": curves, "lesson": {mark: lesson[mark] for mark in curves}}


def lesson_of(results: Sequence[Mapping[str, Any]], labs: Mapping[str, Lab]) -> Optional[str]:
    """The config most labs were opened from (the latest opened of a tie): the class's lesson."""
    origins: Dict[str, int] = collections.Counter(labs[r["lab"]].origin for r in results if r["lab"] in labs)
    return max(origins, key=lambda origin: origins[origin]) if origins else None


def class_message(results: List[Dict[str, Any]], lesson: Optional[str], labs: Mapping[str, Lab],
                  curves: Mapping[str, Any]) -> str:
    """The `class` message: each lab's results (on_curves: opened from the lesson the curves are of)."""
    for result in results:
        lab = labs.get(result["lab"])
        result["on_curves"] = bool(lab is not None and lesson is not None and lab.origin == lesson)
    return json.dumps({"type": "class", "results": results, "curves": curves.get("curves", {}),
                       "lesson": curves.get("lesson", {})}, separators=(",", ":"), allow_nan=False)


class Poll:
    """The teacher's open question and each voter's (a lab cookie's) latest answer."""

    def __init__(self) -> None:
        self.question = ""
        self.choices: Optional[List[str]] = None
        self.unit = ""
        self.open = False
        self.answers: Dict[str, Union[str, float]] = {}

    def ask(self, question: str, choices: Optional[Sequence[str]], unit: str) -> str:
        self.question, self.unit = question, unit
        self.choices = list(choices) if choices is not None else None
        self.open, self.answers = True, {}
        return "question asked"

    def answer(self, voter: str, answer: Union[str, float]) -> str:
        if not self.open:
            raise LabRefusal("refused: no open question")
        if not voter:
            raise LabRefusal("refused: no lab cookie (reload the page)")
        if self.choices is not None:
            if not isinstance(answer, str) or answer not in self.choices:
                raise LabRefusal(f"refused: the answer is one of {', '.join(self.choices)}")
        elif isinstance(answer, bool) or not isinstance(answer, (int, float)) or not math.isfinite(answer):
            raise LabRefusal("refused: the answer is a finite number")
        self.answers[voter] = answer if isinstance(answer, str) else float(answer)
        return "answer taken"

    def reveal(self) -> str:
        if not self.open:
            raise LabRefusal("refused: no open question")
        self.open = False
        return f"question closed: {len(self.answers)} answers"

    def question_message(self) -> Dict[str, Any]:
        return {"type": "question", "question": self.question, "choices": self.choices, "unit": self.unit,
                "open": self.open}

    def answers_message(self) -> Dict[str, Any]:
        """{counts: {choice: n}} for a question with choices (every choice, 0 too), else {values: sorted}."""
        message: Dict[str, Any] = {"type": "answers", "n": len(self.answers)}
        if self.choices is not None:
            message["counts"] = {c: sum(1 for a in self.answers.values() if a == c) for c in self.choices}
        else:
            message["values"] = sorted(float(a) for a in self.answers.values())
        return message
