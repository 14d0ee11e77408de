#!/usr/bin/env python3
"""The web view's requests, frames and events (rigid_body_sim.web_protocol), without ROS or a network: every
well-formed request parses to what it says; every malformed, oversized, unexpected or uncontrolled one is refused
with one line, of its own kind; a full frame queue drops its oldest frame and counts it; frames and events carry
the doubles exactly; the run's events the server keeps are each there once, in time order, from the run's start
(a reset), with what the node's get_events answered and what came on the topic after it was asked, and each
body's last finish and restart however old.

Usage: test_web_protocol.py"""
import json
import math
import unittest
from typing import Any, Dict, List, Tuple

from rigid_body_sim import description
from rigid_body_sim.web_protocol import (EVENTS_KEPT, LAB_OPS, LESSON_KEYS, MAX_LAB_STEPS, MAX_REQUEST_BYTES,
                                         MAX_STEPS, EventLog, FrameQueue, Refusal, Request, event_roles,
                                         events_message, frame_message, lab_events_message, lab_frame_message,
                                         parse_request)

BODIES = {"rod": "rod", "sphere": "roller"}
LAB_BODIES = {"ring": "roller", "crate": "block"}  # a page's own lab's


def parse(message: object, control: bool = True, lab: object = LAB_BODIES) -> Request:
    text = message if isinstance(message, (str, bytes)) else json.dumps(message)
    return parse_request(text, control, BODIES, (), lab if isinstance(lab, dict) else None)


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

    def refused(self, message: object, kind: str, control: bool = True, lab: object = LAB_BODIES) -> str:
        with self.assertRaises(Refusal) as caught:
            parse(message, control, lab)
        self.assertEqual(caught.exception.kind, kind, str(caught.exception))
        # Its reply names the request: the id, where the message had a well-formed one.
        given = message.get("id") if isinstance(message, dict) else None
        if isinstance(message, str) and len(message.encode()) <= MAX_REQUEST_BYTES:  # an oversized one is not read
            try:
                decoded = json.loads(message, parse_constant=lambda name: math.nan)
                given = decoded.get("id") if isinstance(decoded, dict) else None
            except (ValueError, RecursionError):
                pass
        whole = isinstance(given, int) and not isinstance(given, bool) and 0 <= given < 2**53
        self.assertEqual(caught.exception.id, given if whole else None, message)
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

    def test_lab_ops(self) -> None:
        # Any page: its own lab's ops and its answer; the teacher's page: the class's.
        for control in (False, True):
            self.assertEqual(parse({"op": "lab_open", "id": 1, "from": "now", "name": "  Ada L.  "}, control, None),
                             Request("lab_open", 1, source="now", name="Ada L."))
            self.assertEqual(parse({"op": "lab_open", "id": 2, "from": "start", "name": "x" * 40}, control),
                             Request("lab_open", 2, source="start", name="x" * 40))
            for op in LAB_OPS:
                if op not in ("lab_step", "lab_set"):
                    self.assertEqual(parse({"op": op, "id": 3}, control), Request(op, 3))
            self.assertEqual(parse({"op": "lab_step", "id": 4, "steps": MAX_LAB_STEPS}, control),
                             Request("lab_step", 4, steps=MAX_LAB_STEPS))
            self.assertEqual(parse({"op": "lab_set", "id": 5, "body": "crate", "key": "mu_d", "value": 0.25},
                                   control), Request("lab_set", 5, body="crate", key="mu_d", value=0.25))
            self.assertEqual(parse({"op": "answer", "id": 6, "answer": " ring "}, control, None),
                             Request("answer", 6, answer="ring"))
            self.assertEqual(parse({"op": "answer", "id": 7, "answer": 2}, control), Request("answer", 7, answer=2.0))
        self.assertEqual(parse({"op": "ask", "id": 8, "question": "Which first?", "choices": ["ring", "crate"],
                                "unit": ""}), Request("ask", 8, question="Which first?", choices=("ring", "crate")))
        self.assertEqual(parse({"op": "ask", "id": 9, "question": "Its lap time?", "choices": None, "unit": "s"}),
                         Request("ask", 9, question="Its lap time?", unit="s"))
        self.assertEqual(parse({"op": "reveal", "id": 10}), Request("reveal", 10))
        self.assertEqual(parse({"op": "show_lab", "id": 11, "lab": "0a1b2c3d"}),
                         Request("show_lab", 11, lab="0a1b2c3d"))
        self.assertEqual(parse({"op": "show_lab", "id": 12, "lab": None}), Request("show_lab", 12))
        self.assertEqual(parse({"op": "class_clear", "id": 13}), Request("class_clear", 13))

    def test_lab_ops_refused(self) -> None:
        for op in LAB_OPS:
            extra: Dict[str, Any] = {"steps": 1} if op == "lab_step" else (
                {"body": "ring", "key": "mu_d", "value": 1} if op == "lab_set" else {})
            self.refused({"op": op, "id": 1, **extra}, "no lab", lab=None)
        for name in ("", "   ", "x" * 41, "a\tb", "a\nb", 7, None):
            self.refused({"op": "lab_open", "id": 1, "from": "now", "name": name}, "name")
        for source in ("later", "", None, 1):
            self.refused({"op": "lab_open", "id": 1, "from": source, "name": "Ada"}, "from")
        self.refused({"op": "lab_open", "id": 1, "name": "Ada"}, "keys")
        for steps in (0, MAX_LAB_STEPS + 1, 2.5, True):
            self.refused({"op": "lab_step", "id": 1, "steps": steps}, "steps")
        self.refused({"op": "lab_set", "id": 1, "body": "rod", "key": "k", "value": 1}, "body")  # the class's, not its
        self.refused({"op": "lab_set", "id": 1, "body": "crate", "key": "omega0", "value": 1}, "key")
        self.refused('{"op": "lab_set", "id": 1, "body": "ring", "key": "mu_d", "value": NaN}', "value")
        for answer in (None, True, [1], "", "x" * 41, 1e400):
            self.refused({"op": "answer", "id": 1, "answer": answer}, "answer")
        self.refused('{"op": "answer", "id": 1, "answer": Infinity}', "answer")
        teachers: List[Tuple[str, Dict[str, Any]]] = [
            ("ask", {"question": "Q?", "choices": None, "unit": ""}), ("reveal", {}), ("show_lab", {"lab": None}),
            ("class_clear", {})]
        for op, extra in teachers:
            self.refused({"op": op, "id": 1, **extra}, "control", control=False)
        for question in ("", "q" * 201, None):
            self.refused({"op": "ask", "id": 1, "question": question, "choices": None, "unit": ""}, "question")
        for choices in (["one"], ["a", "a"], ["a", ""], [f"c{n}" for n in range(9)], "a,b", [1, 2]):
            self.refused({"op": "ask", "id": 1, "question": "Q?", "choices": choices, "unit": ""}, "choices")
        self.refused({"op": "ask", "id": 1, "question": "Q?", "choices": None, "unit": "u" * 21}, "unit")
        for lab in ("../x", "ABC", 5, ""):
            self.refused({"op": "show_lab", "id": 1, "lab": lab}, "lab")

    def test_every_refusal_names_its_request(self) -> None:
        # However early a request is refused, its reply carries its id, where it had a well-formed one.
        self.refused({"op": "launch", "id": 41}, "op")
        self.refused({"op": "pause", "id": 42, "extra": 0}, "keys")
        self.refused({"op": "step", "id": 43, "steps": 0}, "steps")
        self.refused({"op": "pause", "id": 44}, "control", control=False)
        self.refused({"op": "pause", "id": 1.5, "x": 1}, "keys")  # no whole id: null


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

    def test_lab_messages(self) -> None:
        state = {"t": 0.1 + 0.2, "x": 1 / 3, "mode": "rolling"}
        self.assertEqual(json.loads(lab_frame_message("ab12", 3, {"ring": [state]})),
                         {"type": "lab_frame", "lab": "ab12", "seq": 3, "states": {"ring": [state]}})
        record = {"t": 1.5, "body": "ring", "type": "roller", "kind": "finished",
                  "values": {"lap_time": 1.5, "closed_form": math.nan}, "state": {"x": 5.0}}
        sent = json.loads(lab_events_message("ab12", [record], True))
        self.assertEqual((sent["type"], sent["lab"], sent["all"]), ("lab_events", "ab12", True))
        self.assertIsNone(sent["events"][0]["values"]["closed_form"])


ROLES = event_roles(description.body_types())


def event(t: float, body: str, kind: str, **values: Any) -> Dict[str, Any]:
    """A roller's event as rigid_body_sim.runs.event_record gives it."""
    return {"t": t, "body": body, "type": "roller", "kind": kind, "values": values,
            "state": {"x": 0.0, "v": 0.0, "theta": 0.0, "omega": 0.0, "mode": "rolling", "friction": 0.0,
                      "normal": 9.2, "energy": 0.0}}


def kinds(log: EventLog) -> List[Any]:
    return [(r["t"], r["body"], r["kind"]) for r in log.records()]


class Events(unittest.TestCase):
    def test_roles_are_the_descriptions(self) -> None:
        # The page and the server read roles, never kinds' names: each type that races has a finish and a restart.
        for name, kinds_of in ROLES.items():
            self.assertIn("restart", kinds_of.values(), name)
            if description.body_types()[name]["races"]:
                self.assertIn("finish", kinds_of.values(), name)
        self.assertEqual(ROLES["roller"]["finished"], "finish")
        self.assertEqual(ROLES["roller"]["lap_restarted"], "restart")
        self.assertEqual(ROLES["roller"]["slip_to_roll"], "")

    def test_messages_carry_the_doubles_exactly(self) -> None:
        finished = event(0.1 + 0.2, "sphere", "finished", speed=1 / 3, lap_time=2.0439, closed_form=math.nan,
                         place=1.0)
        sent = json.loads(events_message([finished], False))
        self.assertEqual((sent["type"], sent["all"]), ("events", False))
        self.assertEqual(sent["events"][0]["t"].hex(), (0.1 + 0.2).hex())
        self.assertEqual(sent["events"][0]["values"]["speed"].hex(), (1 / 3).hex())
        self.assertIsNone(sent["events"][0]["values"]["closed_form"], "JSON has no NaN: null")
        self.assertEqual(sent["events"][0]["state"], finished["state"])
        self.assertEqual(json.loads(events_message([], True)), {"type": "events", "all": True, "events": []})

    def test_each_once_in_time_order(self) -> None:
        log = EventLog(ROLES)
        self.assertTrue(log.add(event(1.0, "ring", "slip_to_roll")))
        self.assertTrue(log.add(event(0.5, "sphere", "slip_to_roll")))  # two topics: not always in order
        self.assertFalse(log.add(event(1.0, "ring", "slip_to_roll")))
        self.assertTrue(log.add(event(1.0, "ring", "slip_to_roll", end="A")))  # other values: another event
        self.assertEqual(kinds(log), [(0.5, "sphere", "slip_to_roll"), (1.0, "ring", "slip_to_roll"),
                                      (1.0, "ring", "slip_to_roll")])

    def test_a_reset_begins_a_run(self) -> None:
        log = EventLog(ROLES)
        log.add(event(1.0, "ring", "slip_to_roll"))
        log.add(event(2.0, "ring", "finished", lap_time=2.0, speed=3.0))
        log.add(event(3.0, "ring", "lap_restarted", cause="race"))  # a lap: the run goes on
        self.assertEqual(len(log.records()), 3)
        log.add(event(4.0, "sphere", "slip_to_roll"))  # in the step that ended at the reset: the run before
        log.add(event(4.0, "ring", "lap_restarted", cause="reset"))
        log.add(event(4.0, "sphere", "lap_restarted", cause="reset"))
        self.assertFalse(log.add(event(3.5, "sphere", "slip_to_roll")), "from before the reset, come late")
        self.assertEqual(kinds(log), [(4.0, "ring", "lap_restarted"), (4.0, "sphere", "lap_restarted")])

    def test_get_events_and_the_topic(self) -> None:
        log = EventLog(ROLES)
        log.add(event(1.0, "ring", "slip_to_roll"))  # a run the node forgot (it restarted)
        since = log.arrivals  # the fetch asks now
        log.add(event(5.0, "ring", "slip_to_roll"))  # on the topic while it asked: in the answer too
        log.add(event(6.0, "ring", "finished", lap_time=6.0, speed=2.0))  # after the answer
        log.replace([event(3.0, "sphere", "slip_to_roll"), event(5.0, "ring", "slip_to_roll")], since)
        self.assertEqual(kinds(log), [(3.0, "sphere", "slip_to_roll"), (5.0, "ring", "slip_to_roll"),
                                      (6.0, "ring", "finished")])

    def test_old_events_but_the_last_finish_and_restart(self) -> None:
        log = EventLog(ROLES)
        log.add(event(0.0, "ring", "lap_restarted", cause="race"))
        log.add(event(1.0, "ring", "slip_to_roll"))
        log.add(event(2.0, "ring", "finished", lap_time=2.0, speed=3.0))
        log.add(event(3.0, "sphere", "lap_restarted", cause="race"))
        log.add(event(4.0, "sphere", "slip_to_roll"))
        log.add(event(4.5, "sphere", "lap_restarted", cause="race"))
        log.add(event(5.0 + EVENTS_KEPT, "sphere", "slip_to_roll"))
        # The ring waits at its finish (a race not over): its finish and its lap's start stay; of the sphere's,
        # its last restart before the cutoff (where its plots' axis counts from) and the recent.
        self.assertEqual(kinds(log), [(0.0, "ring", "lap_restarted"), (2.0, "ring", "finished"),
                                      (4.5, "sphere", "lap_restarted"), (5.0 + EVENTS_KEPT, "sphere", "slip_to_roll")])


if __name__ == "__main__":
    unittest.main()
