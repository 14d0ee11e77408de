"""What the web view's server and its pages say to each other, without ROS or a network: the requests a page
may send (each checked whole before anything is done with it), the frames the server sends, and the bounded
queue of frames each page has.

A request is one JSON object of at most MAX_REQUEST_BYTES, {"op": ..., "id": N, ...} with exactly the keys
of its op:
  {"op": "pause" | "run" | "reset", "id": N}
  {"op": "step", "id": N, "steps": S}                    S a whole number in [1, MAX_STEPS]
  {"op": "set", "id": N, "body": B, "key": K, "value": V} B a body the view knows, K one of LESSON_KEYS of its
                                                           type, V a finite number
  {"op": "view", "id": N, "plot_body": B}                B a body the view knows: the body every page that
                                                           follows the teacher plots
  {"op": "part", "id": N, "part": P}                     P a lesson part the world's bodies can take
                                                           (lesson.launch's, config/): its keys, then a reset
Every reply names the request it answers by its id.
Anything else is refused with one line (Refusal) and goes no further: the node's services and reconfigure
servers see only well-formed requests from pages that hold the token, and judge the values themselves."""
from __future__ import annotations

import collections
import json
import math
import re
from dataclasses import dataclass
from typing import Any, Collection, Deque, Dict, List, Mapping, Optional, Set, Tuple, Union

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
OPS: Dict[str, Set[str]] = {"pause": set(), "run": set(), "reset": set(), "step": {"steps"},
                            "set": {"body", "key", "value"}, "view": {"plot_body"}, "part": {"part"}}


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

    def __init__(self, kind: str, line: str) -> None:
        super().__init__(line)
        self.kind = kind


@dataclass(frozen=True)
class Request:
    op: str
    id: int
    steps: int = 0
    body: str = ""
    key: str = ""
    value: float = 0.0


def _whole(value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def parse_request(text: Any, control: bool, bodies: Mapping[str, str], parts: Collection[str] = ()) -> Request:
    """The request in `text` (a WebSocket message), or Refusal. `control`: the page holds the token;
    `bodies`: {name: its type} of the world the view knows; `parts`: the lesson parts it can take."""
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
    op = message.get("op")
    if not isinstance(op, str) or op not in OPS:
        raise Refusal("op", f"refused: unknown op {str(op)[:40]!r}")
    expected = {"op", "id"} | OPS[op]
    if set(message) != expected:
        raise Refusal("keys", f"refused: {op} takes exactly {', '.join(sorted(expected))}")
    if not _whole(message["id"]) or not 0 <= message["id"] < 2**53:
        raise Refusal("id", "refused: id is a whole number in [0, 2^53)")
    if not control:
        raise Refusal("control", "refused: this page only shows (control needs the link with the token)")
    request = Request(op, message["id"])
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
    if op == "step":
        steps = message["steps"]
        if not _whole(steps) or not 1 <= steps <= MAX_STEPS:
            raise Refusal("steps", f"refused: steps is a whole number in [1, {MAX_STEPS}]")
        return Request(op, request.id, steps=steps)
    if op == "set":
        body, key, value = message["body"], message["key"], message["value"]
        if not isinstance(body, str) or body not in bodies:
            raise Refusal("body", f"refused: no body {str(body)[:40]!r}")
        if not isinstance(key, str) or key not in LESSON_KEYS[bodies[body]]:
            raise Refusal("key", f"refused: {bodies[body]} key {str(key)[:40]!r} is not one a lesson changes "
                                 f"({', '.join(LESSON_KEYS[bodies[body]])})")
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
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


# The node's label of a racer over the line (a race: `race: true`): its place and time beside the closed
# form's, as the node computes them (src/ros/scene.cpp; test_scene holds the form).
# A word on a shared place ("=1st", "1st (tie)") is let through: the times say who ties.
FINISH_LABEL = re.compile(r"^([A-Za-z][A-Za-z0-9_]*): =?(\d+)(?:st|nd|rd|th)\b[^,]*, ([0-9.]+) s"
                          r"(?: \(closed form ([0-9.]+) s\))?$")


def finish_of_label(text: str) -> Tuple[str, Optional[Dict[str, Any]]]:
    """(body, {"place", "time", "closed_form"}) from a node's board (its lines joined by a space), or (body,
    None) for a board that is no finish. closed_form is None when the node gives none."""
    text = " ".join(text.split("\n"))
    found = FINISH_LABEL.match(text)
    if not found:
        return text.split(":", 1)[0], None
    closed = found.group(4)
    return found.group(1), {"place": int(found.group(2)), "time": float(found.group(3)),
                            "closed_form": float(closed) if closed else None}


def tied_places(finishes: Mapping[str, Optional[Dict[str, Any]]]) -> Dict[str, Optional[Dict[str, Any]]]:
    """The finishes with racers that the node's label shows at the same time sharing the best of their
    places (a tie, to the label's 0.1 ms, is one place: the node's own places, where it ties them, agree)."""
    best: Dict[float, int] = {}
    for finish in finishes.values():
        if finish:
            best[finish["time"]] = min(best.get(finish["time"], finish["place"]), finish["place"])
    return {body: {**finish, "place": best[finish["time"]]} if finish else None
            for body, finish in finishes.items()}


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
