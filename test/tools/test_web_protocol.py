#!/usr/bin/env python3
"""The web view's requests and frames (rigid_body_sim.web_protocol), without ROS or a network: every well-formed
request parses to what it says; every malformed, oversized, unexpected or uncontrolled one is refused with
one line, of its own kind; a full frame queue drops its oldest frame and counts it; frames carry the doubles
exactly.

Usage: test_web_protocol.py"""
import json
import unittest
from typing import Any, Dict, Optional

from rigid_body_sim.web_protocol import (LESSON_KEYS, MAX_REQUEST_BYTES, MAX_STEPS, FrameQueue, Refusal, Request,
                                         finish_of_label, frame_message, parse_request, tied_places)

BODIES = {"rod": "rod", "sphere": "roller"}


def parse(message: object, control: bool = True) -> Request:
    return parse_request(message if isinstance(message, (str, bytes)) else json.dumps(message), control, BODIES)


class Requests(unittest.TestCase):
    def test_well_formed(self) -> None:
        self.assertEqual(parse({"op": "pause", "id": 1}), Request("pause", 1))
        self.assertEqual(parse({"op": "run", "id": 2}), Request("run", 2))
        self.assertEqual(parse({"op": "reset", "id": 3}), Request("reset", 3))
        self.assertEqual(parse({"op": "step", "id": 4, "steps": 250}), Request("step", 4, steps=250))
        self.assertEqual(parse({"op": "set", "id": 5, "body": "rod", "key": "k", "value": 2000}),
                         Request("set", 5, body="rod", key="k", value=2000.0))
        self.assertEqual(parse({"op": "view", "id": 6, "plot_body": "sphere"}), Request("view", 6, body="sphere"))
        self.assertEqual(parse_request(json.dumps({"op": "part", "id": 7, "part": "above"}), True, BODIES, ("above",)),
                         Request("part", 7, key="above"))
        for kind, keys in LESSON_KEYS.items():
            body = "rod" if kind == "rod" else "sphere"
            for key in keys:
                self.assertEqual(parse({"op": "set", "id": 0, "body": body, "key": key, "value": -0.5}).key, key)

    def refused(self, message: object, kind: str, control: bool = True) -> str:
        with self.assertRaises(Refusal) as caught:
            parse(message, control)
        self.assertEqual(caught.exception.kind, kind, str(caught.exception))
        line = str(caught.exception)
        self.assertTrue(line.startswith("refused") and "\n" not in line and len(line) < 200, line)
        return line

    def test_refused(self) -> None:
        self.refused(b'{"op": "pause", "id": 1}', "binary")
        self.refused(json.dumps({"op": "pause", "id": 1, "pad": "x" * MAX_REQUEST_BYTES}), "size")
        self.refused("{not json", "json")
        self.refused("[" * (MAX_REQUEST_BYTES - 1), "json")
        self.refused("[" * 200 + "]" * 200, "shape")
        self.refused("NaN", "shape")
        self.refused([1, 2], "shape")
        self.refused({"op": "launch", "id": 1}, "op")
        self.refused({"op": ["pause"], "id": 1}, "op")
        self.refused({"id": 1}, "op")
        self.refused({"op": "pause"}, "keys")
        self.refused({"op": "pause", "id": 1, "extra": 0}, "keys")
        self.refused({"op": "step", "id": 1}, "keys")
        self.refused({"op": "set", "id": 1, "body": "rod", "key": "k"}, "keys")
        self.refused({"op": "pause", "id": -1}, "id")
        self.refused({"op": "pause", "id": 1.5}, "id")
        self.refused({"op": "pause", "id": True}, "id")
        self.refused({"op": "pause", "id": 2**53}, "id")
        for steps in (0, -3, 2.5, "10", True, MAX_STEPS + 1, None):
            self.refused({"op": "step", "id": 1, "steps": steps}, "steps")
        self.refused({"op": "set", "id": 1, "body": "hoop", "key": "k", "value": 1}, "body")
        self.refused({"op": "view", "id": 1, "plot_body": "hoop"}, "body")
        self.refused({"op": "view", "id": 1, "plot_body": None}, "body")
        self.refused({"op": "part", "id": 1, "part": "above"}, "part")  # no part for these bodies
        self.refused({"op": "set", "id": 1, "body": ["rod"], "key": "k", "value": 1}, "body")
        self.refused({"op": "set", "id": 1, "body": "rod", "key": "mu_s", "value": 1}, "key")
        self.refused({"op": "set", "id": 1, "body": "sphere", "key": "k", "value": 1}, "key")
        self.refused({"op": "set", "id": 1, "body": "rod", "key": "integrator", "value": 1}, "key")
        for value in ("2000", True, None, [1], {"v": 1}, 1e400):
            self.refused({"op": "set", "id": 1, "body": "rod", "key": "k", "value": value}, "value")
        self.refused('{"op": "set", "id": 1, "body": "rod", "key": "k", "value": NaN}', "value")
        self.refused('{"op": "set", "id": 1, "body": "rod", "key": "k", "value": -Infinity}', "value")

    def test_a_page_without_the_token_only_shows(self) -> None:
        for message in ({"op": "pause", "id": 1}, {"op": "step", "id": 1, "steps": 5},
                        {"op": "set", "id": 1, "body": "rod", "key": "k", "value": 2000}):
            self.refused(message, "control", control=False)
        # a malformed request is refused for what it is, whoever sends it
        self.refused({"op": "pause"}, "keys", control=False)


class Frames(unittest.TestCase):
    def test_full_queue_drops_the_oldest(self) -> None:
        queue = FrameQueue(3)
        for n in range(5):
            queue.offer(str(n))
        self.assertEqual(queue.dropped, 2)
        self.assertEqual([queue.take(), queue.take(), queue.take(), queue.take()], ["2", "3", "4", None])
        queue.offer("5")
        self.assertEqual((queue.take(), queue.dropped), ("5", 2))

    def test_frames_carry_the_doubles_exactly(self) -> None:
        state = {"t": 0.1 + 0.2, "x": 1 / 3, "v": -2.5e-300, "mode": "rolling"}
        frame = json.loads(frame_message(7, {"sphere": [state]}))
        self.assertEqual(frame, {"type": "frame", "seq": 7, "states": {"sphere": [state]}})
        self.assertEqual(frame["states"]["sphere"][0]["t"].hex(), (0.1 + 0.2).hex())
        with self.assertRaises(ValueError):
            frame_message(8, {"sphere": [{"t": float("nan")}]})


class FinishLabels(unittest.TestCase):
    """The node's boards of a race, as test_scene holds the form of a finished racer's."""

    def test_a_finished_racer_gives_its_place_and_times(self) -> None:
        self.assertEqual(finish_of_label("sphere: 1st, 2.0439 s\n(closed form 2.0438 s)"),
                         ("sphere", {"place": 1, "time": 2.0439, "closed_form": 2.0438}))
        self.assertEqual(finish_of_label("ring_2: 12th, 10.5000 s"),
                         ("ring_2", {"place": 12, "time": 10.5, "closed_form": None}))
        for tied in ("ring: =1st, 1.4325 s\n(closed form 1.4325 s)",
                     "ring: 1st (tie), 1.4325 s\n(closed form 1.4325 s)"):
            self.assertEqual(finish_of_label(tied), ("ring", {"place": 1, "time": 1.4325, "closed_form": 1.4325}))

    def test_racers_at_the_same_time_share_a_place(self) -> None:
        # part:=above: all three down at 1.4325 s, whatever places the node's labels give them
        finishes: Dict[str, Optional[Dict[str, Any]]] = {
            name: {"place": place, "time": 1.4325, "closed_form": 1.4325}
            for name, place in (("cylinder", 1), ("ring", 2), ("sphere", 3))}
        finishes["late"] = {"place": 4, "time": 1.5, "closed_form": None}
        finishes["racing"] = None
        places = {body: f and f["place"] for body, f in tied_places(finishes).items()}
        self.assertEqual(places, {"cylinder": 1, "ring": 1, "sphere": 1, "late": 4, "racing": None})

    def test_any_other_label_is_no_finish(self) -> None:
        for text in ("ring: rolling\ncritical angle 21.8 deg", "rod:\nE = 20.600 J", "ring: rolling\nE = 0.000 J"):
            self.assertEqual(finish_of_label(text), (text.split(":")[0], None))


if __name__ == "__main__":
    unittest.main()
