"""What the web view's server and its pages say to each other, without ROS or a network: the requests a page
may send (each checked whole before anything is done with it), the messages the server sends, the bounded
queue of frames each page has, the run's events the server keeps for a page that opens late, and the pacing
of each page's lab requests, and of all of them, on the lab thread (Pacer).

A request is one JSON object of at most MAX_REQUEST_BYTES, {"op": ..., "id": N, ...} with exactly the keys
of its op. The teacher's page (the token's cookie) alone may send:
  {"op": "pause" | "run" | "reset", "id": N}
  {"op": "step", "id": N, "steps": S}                    S a whole number in [1, MAX_STEPS]
  {"op": "set", "id": N, "body": B, "key": K, "value": V} B a body the view knows, K one of LESSON_KEYS of its
                                                           type, V a finite number
  {"op": "view", "id": N, "plot_body": B}                B a body the view knows: the body every page that
                                                           follows the teacher plots
  {"op": "part", "id": N, "part": P}                     P a lesson part the world's bodies can take
                                                           (lesson.launch's, config/): its keys, then a reset
  {"op": "ask", "id": N, "question": Q, "choices": [C, ...] | null, "unit": U}
                                                         pose a question to every page: Q 1..MAX_QUESTION
                                                           printable characters; choices 2..MAX_CHOICES different
                                                           texts of 1..MAX_NAME (which finishes first...), or null
                                                           for a number (a time...) in unit U (0..MAX_UNIT)
  {"op": "reveal", "id": N}                              close the question: every page gets the answers
  {"op": "show_lab", "id": N, "lab": L | null}           every page shows lab L's world (null: the class's again)
  {"op": "class_clear", "id": N}                         forget every lab's outcomes (the labs go on)
Every page may send, about its own lab (the one of its `rbs_lab` cookie, which GET / gives: HttpOnly,
SameSite=Strict, a random secret; a reload re-attaches the page to its lab):
  {"op": "lab_open", "id": N, "from": "now" | "start", "name": S}
                                                         a lab of the class's world as it runs now (the keys the
                                                           teacher changed included) or of its lesson part's config
                                                           file, from t = 0; S the student's name, trimmed, 1..40
                                                           printable characters. The cookie's lab before ends.
  {"op": "lab_run" | "lab_pause" | "lab_reset" | "lab_close", "id": N}
                                                         run in real time, pause, start again from t = 0, end it
  {"op": "lab_step", "id": N, "steps": S}                S whole in [1, MAX_LAB_STEPS], paused only
  {"op": "lab_set", "id": N, "body": B, "key": K, "value": V}
                                                         B a body of its lab, K one of LESSON_KEYS of its type, V a
                                                           finite number: the lab's new config (the core's World.set
                                                           on a trial World; a refusal is the core's one line and
                                                           changes nothing), from t = 0
  {"op": "answer", "id": N, "answer": A}                 A one of the open question's choices, or a finite number;
                                                           a page's latest answer counts (one a cookie)
A lab op from a page without a lab is refused ("no lab"); a lab is opened at most ~max_labs in all and
~labs_per_address from one remote address (the loopback exempt), and ends after 30 minutes without a request
and without a page attached.
Every reply names the request it answers by its id; a refusal too, once the message was a JSON object with a
whole "id" in [0, 2^53) (else "id": null).
Anything else is refused with one line (Refusal) and goes no further: the node's services and reconfigure
servers see only well-formed requests from pages that hold the token, and judge the values themselves; a lab's
core judges its.

The server's messages, each a JSON object with its "type":
  hello    {control, node, frame_rate, description (body_types.json), view, [addresses]}: first, once
  world    {source, paused, settings, bodies, parts, part}: the followed world, whenever it changes
  frame    {seq, states: {body: [state, ...]}}: every state since the last frame (frame_message)
  events   {all, events: [record, ...]}: the node's events (rigid_body_sim/Event on <node>/events, each as
           rigid_body_sim.runs.event_record gives it: {t, body, type, kind, values, state}), oldest first;
           all: true, the run's events the server keeps (EventLog: after hello, and when it read the node's
           <node>/get_events again), which replace what the page had; all: false, new ones (events_message)
  view     {plot_body}: the teacher's choice for every following page
  paused   {paused}
  reply    {id, ok, line}: the answer to a request
  line     {line}: the node's WARN line, to the teacher's page alone
The labs' (rigid_body_sim.labs):
  lab      {lab (its public id), name, config (YAML text: runs unchanged in simulate, the node and the core),
           bodies: {body: type}, settings: {body: every key, as the config has them}, world: {rate,
           publish_rate, gravity, world_frame, race}, t, paused, from, states: {body: its last sample}}: the
           page's own lab, at attach and open and after each of its requests (a paused lab is drawn from states)
  lab_frame  {lab, seq, states: {body: [state, ...]}}: its samples since its last frame (every rate /
           publish_rate steps, t = k / publish_rate, the first at t = 0; at most 500 a body, the newest), to its
           pages, or to every page while it is shown
  lab_events {lab, all, events: [record, ...]}: its events (as World.events() gives them; a value that is not
           finite as null); all: true after each (re)start and at attach (its run's last 1000: replace)
  lab_closed {lab, line}: it ended (lab_close, a new lab_open, 30 idle minutes)
  shown_lab  {the fields of `lab`} | {lab: null}: the lab the teacher shows (again when it changes; its
           lab_frame and lab_events then go to every page)
  class    {results: [{lab, name, from, varied: {"body.key": value}, outcomes: [{body, kind, value_name,
           value, t}], t, on_curves}], curves: {"body.key": {"body.kind.value_name": {x: [...], y: [... |
           null]}}}, lesson: {"body.key": value}}: to the teacher's pages, at most every second when results
           change. outcomes: each (body, kind) first event of the run (finished: lap_time; any other kind: t;
           came_to_rest: x too; contact_began: count so far too); varied: its lesson keys that differ from the
           config it was opened from. curves: for each varied key and each outcome of that body (no count),
           the core run over a grid of the key (the lesson config, that body alone; the labs' own values among
           the grid's: their points lie on it exactly); y null where the core gave no such event or refused the
           value. lesson: the config most labs were opened from (on_curves: a lab opened from it).
  question {question, choices, unit, open}: to every page (at ask, at reveal with open: false, at hello)
  answers  {n, counts: {choice: n} | values: [sorted numbers]}: to the teacher's pages at each answer; to every
           page at reveal
HTTP: GET /lab/<lab id>.zip (that lab's cookie only; else 404): config.yaml and the files `simulate
config.yaml --duration <its last sample's t> --out-dir` writes (one CSV a body, events.csv): its run so far."""
from __future__ import annotations

import asyncio
import collections
import concurrent.futures
import json
import math
import re
import time
from dataclasses import dataclass
from typing import (Any, Callable, Collection, Deque, Dict, List, Mapping, Optional, Sequence, Set, Tuple, TypeVar,
                    Union)

from rigid_body_sim import description

MAX_REQUEST_BYTES = 1024
# The ~step service's own bound is 600 s of steps: this only keeps a number from being absurd on the wire.
MAX_STEPS = 10_000_000
# The keys a lesson changes, by body type (the slope, friction, the floor's spring and the initial
# conditions): the core's description marks them.
LESSON_KEYS: Dict[str, Tuple[str, ...]] = {kind: tuple(keys) for kind, keys in description.lesson_keys().items()}
# lesson.launch's parts that are no race: each one's config is config/<part>.yaml (its `config` argument says
# the same); every other part's is config/race_<part>.yaml.
SOLO_PARTS: Tuple[str, ...] = ("rod",)
# A lab's (rigid_body_sim.labs): a lab_step's most steps, a student's name's most characters.
MAX_LAB_STEPS = 100_000
MAX_NAME = 40
MAX_QUESTION = 200  # characters of a question
MAX_CHOICES = 8
MAX_UNIT = 20
OPS: Dict[str, Set[str]] = {"pause": set(), "run": set(), "reset": set(), "step": {"steps"},
                            "set": {"body", "key", "value"}, "view": {"plot_body"}, "part": {"part"},
                            "lab_open": {"from", "name"}, "lab_run": set(), "lab_pause": set(), "lab_reset": set(),
                            "lab_close": set(), "lab_step": {"steps"}, "lab_set": {"body", "key", "value"},
                            "answer": {"answer"}, "ask": {"question", "choices", "unit"}, "reveal": set(),
                            "show_lab": {"lab"}, "class_clear": set()}
# The ops any page may send (about its own lab, or its answer); the rest need the token.
PAGE_OPS = ("lab_open", "lab_run", "lab_pause", "lab_reset", "lab_close", "lab_step", "lab_set", "answer")
# The ops of a page's lab: refused where the page has none (but lab_open).
LAB_OPS = ("lab_run", "lab_pause", "lab_reset", "lab_close", "lab_step", "lab_set")


def part_config(part: str) -> str:
    """The file name under config/ of a lesson part's config, as lesson.launch picks it."""
    return f"{part}.yaml" if part in SOLO_PARTS else f"race_{part}.yaml"


def part_of_config(file_name: str) -> Optional[str]:
    """The lesson part whose config `file_name` (under config/) is, or None."""
    found = re.fullmatch(r"race_(\w+)\.yaml|(\w+)\.yaml", file_name)
    part = found and (found.group(1) or found.group(2))
    return part if part and part_config(part) == file_name else None


class Refusal(Exception):
    """A request that goes no further; str() is the one line the page and the log show. `kind` groups
    refusals of one sort, so that each is logged once per page."""

    def __init__(self, kind: str, line: str, request_id: Optional[int] = None) -> None:
        super().__init__(line)
        self.kind = kind
        self.id = request_id  # the request's id, when it had a well-formed one: its reply names it


@dataclass(frozen=True)
class Request:
    op: str
    id: int
    steps: int = 0
    body: str = ""
    key: str = ""
    value: float = 0.0
    name: str = ""  # lab_open: the student's name, trimmed
    source: str = ""  # lab_open: "now" or "start"
    answer: Union[str, float, None] = None
    question: str = ""
    choices: Optional[Tuple[str, ...]] = None  # ask: None for a number's question
    unit: str = ""
    lab: Optional[str] = None  # show_lab: None for none


def _whole(value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def printable_text(value: Any, most: int, least: int = 1) -> Optional[str]:
    """`value` trimmed if it is a text of `least`..`most` printable characters, else None."""
    if not isinstance(value, str):
        return None
    trimmed = value.strip()
    return trimmed if least <= len(trimmed) <= most and trimmed.isprintable() else None


def _finite_number(value: Any) -> bool:
    return not isinstance(value, bool) and isinstance(value, (int, float)) and math.isfinite(value)


def parse_request(text: Any, control: bool, bodies: Mapping[str, str], parts: Collection[str] = (),
                  lab_bodies: Optional[Mapping[str, str]] = None) -> Request:
    """The request in `text` (a WebSocket message), or Refusal (with the request's id when it had a
    well-formed one). `control`: the page holds the token; `bodies`: {name: its type} of the world the view
    knows; `parts`: the lesson parts it can take; `lab_bodies`: {name: its type} of the page's own lab, None
    where it has none."""
    if not isinstance(text, str):
        raise Refusal("binary", "refused: a binary message (requests are JSON text)")
    if len(text.encode()) > MAX_REQUEST_BYTES:
        raise Refusal("size", f"refused: a message of more than {MAX_REQUEST_BYTES} bytes")
    try:
        message = json.loads(text, parse_constant=lambda name: math.nan)
    except (ValueError, RecursionError):  # RecursionError: nesting deeper than Python's stack allows
        raise Refusal("json", "refused: not JSON") from None
    if not isinstance(message, dict):
        raise Refusal("shape", "refused: a request is a JSON object")
    given: Any = message.get("id")
    request_id = given if _whole(given) and 0 <= given < 2**53 else None
    try:
        return _parse(message, control, bodies, parts, lab_bodies)
    except Refusal as refusal:
        refusal.id = request_id
        raise


def _parse(message: Dict[str, Any], control: bool, bodies: Mapping[str, str], parts: Collection[str],
           lab_bodies: Optional[Mapping[str, str]]) -> Request:
    op = message.get("op")
    if not isinstance(op, str) or op not in OPS:
        raise Refusal("op", f"refused: unknown op {str(op)[:40]!r}")
    expected = {"op", "id"} | OPS[op]
    if set(message) != expected:
        raise Refusal("keys", f"refused: {op} takes exactly {', '.join(sorted(expected))}")
    if not _whole(message["id"]) or not 0 <= message["id"] < 2**53:
        raise Refusal("id", "refused: id is a whole number in [0, 2^53)")
    if not control and op not in PAGE_OPS:
        raise Refusal("control", "refused: this page only shows (control needs the token, typed in at /login)")
    request = Request(op, message["id"])
    if op in LAB_OPS and lab_bodies is None:
        raise Refusal("no lab", "refused: this page has no lab (open one first)")
    if op == "lab_open":
        source, name = message["from"], printable_text(message["name"], MAX_NAME)
        if source not in ("now", "start"):
            raise Refusal("from", "refused: a lab opens from \"now\" (the class's world as it runs) or \"start\" "
                                  "(its lesson part's config)")
        if name is None:
            raise Refusal("name", f"refused: a name is 1 to {MAX_NAME} printable characters")
        return Request(op, request.id, source=source, name=name)
    if op == "answer":
        answer = message["answer"]
        if isinstance(answer, str):
            text = printable_text(answer, MAX_NAME)
            if text is None:
                raise Refusal("answer", f"refused: an answer is a choice (1 to {MAX_NAME} printable characters) "
                                        "or a finite number")
            return Request(op, request.id, answer=text)
        if not _finite_number(answer):
            raise Refusal("answer", "refused: an answer is a choice or a finite number")
        return Request(op, request.id, answer=float(answer))
    if op == "ask":
        question, unit, choices = message["question"], message["unit"], message["choices"]
        question = printable_text(question, MAX_QUESTION)
        if question is None:
            raise Refusal("question", f"refused: a question is 1 to {MAX_QUESTION} printable characters")
        unit = printable_text(unit, MAX_UNIT, least=0)
        if unit is None:
            raise Refusal("unit", f"refused: a unit is at most {MAX_UNIT} printable characters")
        if choices is not None:
            texts = [printable_text(c, MAX_NAME) for c in choices] if isinstance(choices, list) else [None]
            if not 2 <= len(texts) <= MAX_CHOICES or None in texts or len(set(texts)) != len(texts):
                raise Refusal("choices", f"refused: choices are null (a number's question) or 2 to {MAX_CHOICES} "
                                         f"different texts of 1 to {MAX_NAME} printable characters")
            return Request(op, request.id, question=question, unit=unit,
                           choices=tuple(str(t) for t in texts))
        return Request(op, request.id, question=question, unit=unit)
    if op == "show_lab":
        lab = message["lab"]
        if lab is not None and (not isinstance(lab, str) or not re.fullmatch(r"[0-9a-f]{1,40}", lab)):
            raise Refusal("lab", f"refused: no lab {str(lab)[:40]!r}")
        return Request(op, request.id, lab=lab)
    if op == "part":
        part = message["part"]
        if not isinstance(part, str) or part not in parts:
            raise Refusal("part", f"refused: no lesson part {str(part)[:40]!r} for these bodies "
                                  f"({', '.join(sorted(parts)) or 'none'})")
        return Request(op, request.id, key=part)
    if op == "view":
        body = message["plot_body"]
        if not isinstance(body, str) or body not in bodies:
            raise Refusal("body", f"refused: no body {str(body)[:40]!r}")
        return Request(op, request.id, body=body)
    if op in ("step", "lab_step"):
        steps, most = message["steps"], MAX_STEPS if op == "step" else MAX_LAB_STEPS
        if not _whole(steps) or not 1 <= steps <= most:
            raise Refusal("steps", f"refused: steps is a whole number in [1, {most}]")
        return Request(op, request.id, steps=steps)
    if op in ("set", "lab_set"):
        known = bodies if op == "set" else lab_bodies or {}
        body, key, value = message["body"], message["key"], message["value"]
        if not isinstance(body, str) or body not in known:
            raise Refusal("body", f"refused: no body {str(body)[:40]!r}{' in this lab' if op == 'lab_set' else ''}")
        if not isinstance(key, str) or key not in LESSON_KEYS[known[body]]:
            raise Refusal("key", f"refused: {known[body]} key {str(key)[:40]!r} is not one a lesson changes "
                                 f"({', '.join(LESSON_KEYS[known[body]])})")
        if not _finite_number(value):
            raise Refusal("value", f"refused: {key} is a finite number")
        return Request(op, request.id, body=body, key=key, value=float(value))
    return request


class FrameQueue:
    """A page's frames not yet written: at most `bound`; a frame offered to a full queue pushes the oldest
    out (a page that cannot keep up sees the latest state, with gaps), counted in `dropped`."""

    def __init__(self, bound: int) -> None:
        self.frames: Deque[Union[str, bytes]] = collections.deque(maxlen=bound)
        self.dropped = 0

    def offer(self, frame: Union[str, bytes]) -> None:
        if len(self.frames) == self.frames.maxlen:
            self.dropped += 1
        self.frames.append(frame)

    def take(self) -> Optional[Union[str, bytes]]:
        return self.frames.popleft() if self.frames else None


def frame_message(seq: int, states: Mapping[str, List[Dict[str, Any]]]) -> str:
    """One frame: every state that came for each body since the last frame, in order, each with the state
    message's fields (numbers in shortest round-trip form: JSON.parse gives the very doubles)."""
    return json.dumps({"type": "frame", "seq": seq, "states": states}, separators=(",", ":"), allow_nan=False)


# A restart's causes that begin a new run (the node's <node>/get_events forgets what came before it): what
# came before goes from the plots and from the events a page gets.
RUN_STARTS: Tuple[str, ...] = ("reset", "config")
# s of events before the newest that the server keeps for a page that opens late: more than its plots' 10 s.
EVENTS_KEPT = 30.0
Record = Dict[str, Any]  # an event as rigid_body_sim.runs.event_record gives it


def event_roles(types: Mapping[str, Any]) -> Dict[str, Dict[str, str]]:
    """{type: {event kind: its role}} from the description's types: "finish", "restart" or ""."""
    return {name: {kind["name"]: kind["role"] for kind in t.get("event_kinds", [])} for name, t in types.items()}


def _finite(fields: Mapping[str, Any]) -> Dict[str, Any]:
    return {k: None if isinstance(v, float) and not math.isfinite(v) else v for k, v in fields.items()}


def events_message(records: Sequence[Mapping[str, Any]], whole: bool) -> str:
    """One events message (`whole`: the run's events the server keeps, which replace a page's), numbers in
    shortest round-trip form, a value that is not finite as null (JSON has no NaN)."""
    events = [{**r, "values": _finite(r["values"]), "state": _finite(r["state"])} for r in records]
    return json.dumps({"type": "events", "all": whole, "events": events}, separators=(",", ":"), allow_nan=False)


def lab_frame_message(lab: str, seq: int, states: Mapping[str, List[Dict[str, Any]]]) -> str:
    """A lab's frame: its samples since its last, as frame_message's."""
    return json.dumps({"type": "lab_frame", "lab": lab, "seq": seq, "states": states}, separators=(",", ":"),
                      allow_nan=False)


def lab_events_message(lab: str, records: Sequence[Mapping[str, Any]], whole: bool) -> str:
    """A lab's events, as events_message's (`whole`: its run's, which replace the page's)."""
    events = [{**r, "values": _finite(r["values"]), "state": _finite(r["state"])} for r in records]
    return json.dumps({"type": "lab_events", "lab": lab, "all": whole, "events": events}, separators=(",", ":"),
                      allow_nan=False)


class EventLog:
    """The run's events the server keeps for its pages, oldest first, each once (<node>/get_events and the
    topic may both bring one). A restart that begins a run (RUN_STARTS) drops what came before it; of what is
    more than `kept` s older than the newest, each body's last finish and last restart stay (a racer that
    waits shows its finish; a plot's time axis counts from its lap's start)."""

    def __init__(self, roles: Mapping[str, Mapping[str, str]], kept: float = EVENTS_KEPT) -> None:
        self.roles = roles
        self.kept = kept
        self.events: List[Tuple[int, Record]] = []  # (its arrival, the record), in time order
        self.keys: Set[Tuple[Any, ...]] = set()
        self.arrivals = 0  # records that came on the topic so far: a fetch notes it before it asks (replace)
        self.run_start = -math.inf

    @staticmethod
    def key(record: Mapping[str, Any]) -> Tuple[Any, ...]:
        return (record["t"], record["body"], record["kind"], json.dumps(record["values"], sort_keys=True))

    def role(self, record: Mapping[str, Any]) -> str:
        return self.roles.get(record["type"], {}).get(record["kind"], "")

    def starts_run(self, record: Mapping[str, Any]) -> bool:
        return self.role(record) == "restart" and record["values"].get("cause") in RUN_STARTS

    def add(self, record: Record) -> bool:
        """A record from the topic; False if it was there already, or belongs to a run before this one."""
        self.arrivals += 1
        return self._insert(self.arrivals, record)

    def replace(self, records: Sequence[Record], since: int) -> None:
        """The run's events as <node>/get_events answered, asked when `since` records had come on the topic:
        those that came after stay (the answer may lack them), the rest go (a run the node forgot)."""
        later = [(arrival, record) for arrival, record in self.events if arrival > since]
        self.clear()
        for record in records:
            self._insert(0, record)
        for arrival, record in later:
            self._insert(arrival, record)

    def clear(self) -> None:
        self.events, self.keys, self.run_start = [], set(), -math.inf

    def records(self) -> List[Record]:
        return [record for _, record in self.events]

    def _insert(self, arrival: int, record: Record) -> bool:
        key = self.key(record)
        if key in self.keys or record["t"] < self.run_start:
            return False
        self.keys.add(key)
        self.events.append((arrival, record))
        if len(self.events) > 1 and self.events[-2][1]["t"] > record["t"]:  # two topics' order: seldom
            self.events.sort(key=lambda pair: pair[1]["t"])
        if self.starts_run(record) and record["t"] > self.run_start:
            self.run_start = record["t"]
            # At its instant too, what came before it is of the run before (the step that ended at the reset).
            self.events = [(a, r) for a, r in self.events if r["t"] > self.run_start or r is record]
        self._trim()
        return True

    def _trim(self) -> None:
        cutoff = self.events[-1][1]["t"] - self.kept
        if self.events[0][1]["t"] >= cutoff:
            return
        last: Set[Tuple[str, str]] = set()  # (body, role) kept from before the cutoff
        kept: List[Tuple[int, Record]] = []
        for arrival, record in reversed(self.events):
            mark = (record["body"], self.role(record))
            if record["t"] >= cutoff or (mark[1] and mark not in last):
                kept.append((arrival, record))
                if record["t"] < cutoff:
                    last.add(mark)
        self.events = kept[::-1]
        self.keys = {self.key(record) for _, record in self.events}


def websocket_text_frame(text: str) -> bytes:
    """One unmasked, uncompressed WebSocket text frame (RFC 6455 5.2), as a server sends it: built once for
    every page that gets the same message."""
    payload = text.encode()
    n = len(payload)
    if n < 126:
        head = bytes((0x81, n))
    elif n < 1 << 16:
        head = bytes((0x81, 126)) + n.to_bytes(2, "big")
    else:
        head = bytes((0x81, 127)) + n.to_bytes(8, "big")
    return head + payload


T = TypeVar("T")
# Of the web view's lab thread's time, what one page's lab requests take at most (after each, that page's next
# waits three times as long, on the loop; other pages' wait for none of it): their Python holds the GIL from the
# loop, which waits for it at every page's write (a page asking for long steps over and over would take most of
# every page's frames).
LAB_THREAD_SHARE = 0.25
# Of the lab thread's time, what all pages' lab requests take together at most (after each, no page's next
# starts until the thread has rested (1 - total) / total times as long, on the loop): a class's pages, each
# within LAB_THREAD_SHARE, would still fill the thread, its Python holding the GIL from the loop for most of
# every frame; half leaves the loop the GIL between requests as long as their Python holds it.
LAB_THREAD_TOTAL_SHARE = 0.5


class _Turns:
    """A key's (or the whole thread's) works: one at a time, in order (the lock), and when its rest after the last
    one ends."""

    def __init__(self) -> None:
        self.lock = asyncio.Lock()
        self.users = 0  # its works waiting or under way
        self.rests_until = 0.0  # perf_counter s


class Pacer:
    """One worker thread's time shared among keys (the web view's lab thread among its pages' lab cookies): a
    key's works run one at a time, in order, each once the key has rested after its previous one that one's
    time on the thread (its start to its end) times (1 - share) / share, so that no key takes more than `share`
    of the thread, however long its works take on a busy machine; and each once the thread has rested after
    the last work of any key its time times (1 - total) / total, so that all keys together take no more than
    `total` of it. The rests are awaited on the loop (asyncio.sleep), never on the thread: another key's work
    waits for none of a key's rest, and the works whose key's rest is over take the thread in the order they
    came to it (a fair lock: none starves)."""

    def __init__(self, executor: concurrent.futures.Executor, share: float, total: float = 1.0) -> None:
        for name, value in (("share", share), ("total", total)):
            if not 0.0 < value <= 1.0:
                raise ValueError(f"{name} {value} not in (0, 1]")
        self.executor = executor
        self.rest_per_second = (1.0 - share) / share
        self.thread_rest_per_second = (1.0 - total) / total
        self.keys: Dict[str, _Turns] = {}
        # Every key's works, in the order their key's rest ended; made on the loop (Python 3.9's asyncio.Lock
        # takes the loop it is made on).
        self.thread: Optional[_Turns] = None

    async def run(self, key: str, work: Callable[[], T], starting: Optional[Callable[[], Any]] = None) -> T:
        """work() on the executor in the key's turn, once its rest and the thread's are over; starting() on the
        loop just before work goes to the executor."""
        turns = self.keys.get(key)
        if turns is None:
            turns = self.keys[key] = _Turns()
        thread = self.thread = self.thread or _Turns()
        turns.users += 1
        try:
            async with turns.lock:
                await self._rest(turns)
                async with thread.lock:
                    await self._rest(thread)
                    if starting is not None:
                        starting()
                    timing: List[float] = []

                    def timed() -> T:
                        timing.append(time.perf_counter())
                        try:
                            return work()
                        finally:
                            timing.append(time.perf_counter())
                    try:
                        return await asyncio.get_running_loop().run_in_executor(self.executor, timed)
                    finally:
                        if len(timing) == 2:
                            started, ended = timing
                            turns.rests_until = ended + (ended - started) * self.rest_per_second
                            thread.rests_until = ended + (ended - started) * self.thread_rest_per_second
        finally:
            turns.users -= 1
            now = time.perf_counter()
            for name in [name for name, t in self.keys.items() if not t.users and t.rests_until <= now]:
                del self.keys[name]

    @staticmethod
    async def _rest(turns: _Turns) -> None:
        rest = turns.rests_until - time.perf_counter()
        while rest > 0:  # the loop's timer may wake a hair early
            await asyncio.sleep(rest)
            rest = turns.rests_until - time.perf_counter()
