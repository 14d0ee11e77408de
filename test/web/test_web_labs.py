#!/usr/bin/env python3
"""A lab for every student, in a real browser: lesson.launch part:=slip web:=true web_control:=true (started
paused: the class's world stands still), the teacher's page and STUDENTS students' pages in one Debian headless
Chromium, each student's page in a browser context of its own (its own cookies, as a phone of its own has).

- The teacher logs in through the form at /login (the token typed in, the button clicked): no address of its
  tab's history holds the token, and once the teacher has used the page through the whole lesson and Chromium
  has ended (writing its profile), no file of its profile holds the token but its cookie store, and its History
  database (where this Chromium keeps one) holds the addresses the tab visited (the page's, the form's) and
  the token nowhere (no address, no byte of its files).
- Each student types a name, opens a lab from the lesson's start, sets the sphere's mu_d to a value of their own
  (MU_D) with the controls the page made from the description, runs it until the sphere's slip_to_roll event
  and pauses it. The event's instant is the closed form's, t = (v0 + omega0 R) / (mu_d g cos(phi) (1 + c) / c
  - g sin(phi)), to 1e-9 s.
- The teacher's view of the class, x sphere.mu_d and y the sphere's slip_to_roll instant: one point a
  student, at the student's mu_d and the instant the student's page got; the curve every point lies on is
  the closed form at each of its values; the mean and the standard deviation are the points'; the pointer on a
  point shows the student's name.
- A lab's download (the link on its page) holds config.yaml, and the files `simulate config.yaml --duration
  <the lab's t>` writes, bit for bit; every state the page got of the lab is a row of its body's CSV, in order,
  field for field, and every event the page got a row of events.csv.
- A student cannot act on another's lab: another's download is refused; a connection without a lab's cookie
  has its lab requests refused in one line, each answered with its id.
- Predict, then run: the teacher asks which rolls first (choices), students click their answers, the teacher's
  histogram counts them; then a number (with its unit), typed by students, a word refused in one line; Reveal
  closes the question on the students' pages.
- The teacher shows one student's lab: a page shows that lab's world (its mu_d); back to the class's world.
- A reload of a student's page attaches it to its lab again (the cookie). Clear forgets every result.
- Every request a page sent carried an id, and every reply names one of them. Nothing was thrown or logged as
  an error in any page.
- Screenshots of a student's lab and of the teacher's view of the class at 1600x900 and at a phone's 390x844
  go to OUT_DIR (web_lab.png, web_lab_phone.png, web_class.png, web_class_phone.png).

Usage: test_web_labs.py OUT_DIR SIMULATE   (with the package's devel space sourced)"""
import argparse
import base64
import csv
import io
import json
import math
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest
import urllib.request
import zipfile
from typing import Any, Dict, List, Optional

import websocket
from rigid_body_sim.sim_tools import INERTIA_FACTORS, free_port, load_config, wait_for, with_defaults

from browser import Browser, end
from ros_launching import Teacher, launch_reading, ros_env, teacher_login

ARGS: Any = None
DEADLINE = 60.0  # s for any one wait
ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
STUDENTS = 30
# Each student's mu_d of the sphere: all of them slip first and roll before the slope's end.
MU_D = [round(0.15 + 0.005 * i, 3) for i in range(STUDENTS)]
CHECKED_DOWNLOADS = (0, STUDENTS // 2, STUDENTS - 1)  # the students whose zips are rerun with simulate
STUDENT_SIZE = (360, 640)  # px: a phone's window a student


class Tab(Browser):
    """One target of a Browser's Chromium over its own DevTools socket: the browser itself (Target.*), or a
    page. Browser's methods (call, evaluate, wait, click, type_into, choose, resize, screenshot) work on it."""

    def __init__(self, url: str) -> None:  # pylint: disable=super-init-not-called (a Browser starts a Chromium)
        self.socket = websocket.create_connection(url, timeout=30, suppress_origin=True)
        self.next_id = 0
        self.events: List[Dict[str, Any]] = []

    def close(self) -> None:
        self.socket.close()


def open_pages(browser: Browser, url: str, count: int, size: Any) -> List[Tab]:
    """`count` pages loading `url`, each in a browser context of its own (its cookies its own), `size` px: all
    asked for first, then each one's socket opened (Chromium starts their processes side by side)."""
    with open(os.path.join(browser.profile, "DevToolsActivePort")) as written:
        port, path = written.read().split("\n")[:2]
    browser_target = Tab(f"ws://127.0.0.1:{port}{path.strip()}")
    try:
        targets = []
        for _ in range(count):
            context = browser_target.call("Target.createBrowserContext")["browserContextId"]
            targets.append(browser_target.call("Target.createTarget", url=url, browserContextId=context,
                                               width=size[0], height=size[1])["targetId"])
    finally:
        browser_target.close()
    pages = [Tab(f"ws://127.0.0.1:{port}/devtools/page/{target}") for target in targets]
    for page in pages:
        page.call("Page.enable")
        page.call("Runtime.enable")
    return pages


def act(page: Browser, script: str) -> None:
    """What a student does on the page, as the page's own elements take it (their values set, their change
    events and clicks dispatched): one call a page, where 30 pages share two cores."""
    page.evaluate(f"(() => {{ const el = (id) => document.getElementById(id); "
                  f"const choose = (id, v) => {{ el(id).value = v; el(id).dispatchEvent(new Event('change')); }}; "
                  f"{script} }})()")


def slip_to_roll_instant(b: Dict[str, Any], g: float) -> float:
    """The closed form: the instant a roller launched sliding with backspin starts to roll (docs/testing.md)."""
    phi, c, R = b["incline_angle"], INERTIA_FACTORS[b["shape"]], b["radius"]
    return (b["v0"] + b["omega0"] * R) / (b["mu_d"] * g * math.cos(phi) * (1 + c) / c - g * math.sin(phi))


def csv_value(text: str) -> Any:
    try:
        return float(text)
    except ValueError:
        return text


def key_values(text: str) -> Dict[str, Any]:
    """events.csv's values and state columns: "key=value key=value"."""
    return {k: csv_value(v) for k, v in (item.split("=", 1) for item in text.split())} if text else {}


class Labs(unittest.TestCase):
    def setUp(self) -> None:
        self.tmp = tempfile.mkdtemp(prefix="rbs_labs_")
        self.config = load_config(os.path.join(ROOT, "config", "race_slip.yaml"))
        self.gravity = float(self.config.get("gravity", 9.8))
        self.web_port = free_port()
        self.base = f"http://127.0.0.1:{self.web_port}/"
        self.log: List[str] = []
        self.launch: Optional["subprocess.Popen[str]"] = None
        self.browser: Optional[Browser] = None
        self.tabs: List[Tab] = []

    def tearDown(self) -> None:
        for tab in self.tabs:
            tab.close()
        if self.browser:
            self.browser.close()
        if self.launch:
            end(self.launch, signal.SIGINT, 60)
        shutil.rmtree(self.tmp, ignore_errors=True)

    def start(self) -> Teacher:
        """lesson.launch part:=slip with the web view (control on), paused, on ports of its own: the teacher's
        login it prints."""
        port = free_port()
        self.launch = launch_reading(
            ["-p", str(port), "rigid_body_sim", "lesson.launch", "part:=slip", "rviz:=false", "start_paused:=true",
             "web:=true", f"web_port:={self.web_port}", "web_control:=true"], ros_env(port, self.tmp), self.log)
        return teacher_login(self.log, self.web_port)

    def test_labs(self) -> None:
        started = time.monotonic()
        login = self.start()
        wait_for("the web view", lambda: self.http_status("/") == 200, DEADLINE, period=0.1)
        self.browser = teacher = Browser(1600, 900)
        teacher.resize(1600, 900, 1, False)
        teacher.log_in(login.login, login.token, DEADLINE)
        teacher.wait("the teacher's page with the class's world",
                     "window.rbs && rbs.control && rbs.world && Object.keys(rbs.world.bodies).length === 3", DEADLINE)
        self.check_tab_history(teacher, login)
        print(f"the teacher's page in {time.monotonic() - started:.1f} s", file=sys.stderr)
        students = open_pages(teacher, self.base, STUDENTS, STUDENT_SIZE)
        self.tabs.extend(students)
        names = [f"Student {i + 1:02d}" for i in range(STUDENTS)]
        for student in students:
            student.wait("a student's page with the class's world",
                         "window.rbs && rbs.world && Object.keys(rbs.world.bodies).length === 3 && "
                         "document.readyState === 'complete'", DEADLINE)
        print(f"{STUDENTS} students' pages open in {time.monotonic() - started:.1f} s", file=sys.stderr)
        self.open_labs(students, names, started)
        labs = [student.evaluate("rbs.lab.info.lab") for student in students]
        self.assertEqual(len(set(labs)), STUDENTS, "a lab each")
        self.run_labs(students)
        print(f"{STUDENTS} labs run to the sphere's slip_to_roll in {time.monotonic() - started:.1f} s",
              file=sys.stderr)
        self.check_class_view(teacher, students, names)
        for i in CHECKED_DOWNLOADS:
            self.check_download(students[i])
        self.check_not_anothers(students[0], students[1], labs[1])
        self.check_predict(teacher, students[:5])
        self.check_show_lab(teacher, students[3], students[4], labs[3], MU_D[3])
        # A reload attaches the page to its lab again (its cookie). The page's scripts run one after another:
        # view.js makes window.rbs, lab.js adds rbs.lab after it, and the wait may look in between.
        students[0].navigate(self.base)
        students[0].wait("the reloaded page at its lab", "window.rbs && rbs.lab && rbs.lab.info && rbs.lab.info.lab "
                         f"=== {json.dumps(labs[0])}", DEADLINE)
        self.assertEqual(students[0].evaluate("rbs.lab.info.settings.sphere.mu_d"), MU_D[0])
        # Clear: every result forgotten, the labs go on.
        teacher.click("class-clear")
        teacher.wait("no results", "rbs.classView.results.length === 0 && rbs.classView.points.length === 0",
                     DEADLINE)
        for page in [teacher, *students]:
            self.check_ids(page)
            self.assertEqual(page.console_errors(), [])
        self.check_tab_history(teacher, login)
        self.check_profile_history(teacher, login)
        print(f"the whole test in {time.monotonic() - started:.1f} s", file=sys.stderr)

    # --- the steps ---------------------------------------------------------------------------------------------
    def http_status(self, path: str) -> int:
        try:
            with urllib.request.urlopen(self.base.rstrip("/") + path, timeout=5) as answer:
                return int(answer.status)
        except OSError:
            return 0

    def check_tab_history(self, teacher: Browser, login: Teacher) -> None:
        """The token in no address of the tab's history: the form's, then the page's."""
        self.assertEqual(teacher.evaluate("location.search"), "")
        history = teacher.call("Page.getNavigationHistory")
        addresses = [entry["url"] for entry in history["entries"]]
        self.assertIn(login.login, addresses)
        self.assertEqual(addresses[-1], self.base)
        self.assertFalse([a for a in addresses if login.token in a or "token=" in a], addresses)
        self.assertEqual(teacher.evaluate("history.length"), len(history["entries"]))

    def check_profile_history(self, teacher: Browser, login: Teacher) -> None:
        """Chromium ended as a window's close ends it (its databases written): no file of its profile holds the
        token but its cookie store (where the login puts it, for the page's WebSocket alone), and its History
        database, where this Chromium keeps one, holds the addresses the teacher's tab visited and the token
        nowhere. (The students' pages, each in a context of its own, keep no history.)"""
        for tab in self.tabs:
            tab.close()
        self.tabs = []
        teacher.quit(DEADLINE)
        history = teacher.history()
        if history is not None:
            self.assertIn(self.base, history.urls, "the History database holds none of this lesson's addresses")
            self.assertIn(login.login, history.urls)
            self.assertFalse([u for u in history.urls if login.token in u or "token=" in u], history.urls)
            self.assertNotIn(login.token.encode(), history.raw, "the token in the profile's History database")
        files = teacher.profile_files()
        self.assertTrue(files, "an empty profile")
        holding = [name for name, data in files.items()
                   if login.token.encode() in data and os.path.basename(name) not in ("Cookies", "Cookies-journal")]
        self.assertFalse(holding, "the token in the profile's files beside its cookie store")
        kept = f"{len(history.urls)} addresses in its History ({', '.join(sorted(history.urls))})" if history \
            else "no History database (this Chromium keeps none)"
        print(f"the profile: {len(files)} files, {kept}, the token in none but its cookie store", file=sys.stderr)

    def open_labs(self, students: List[Tab], names: List[str], started: float) -> None:
        """Each student types a name and opens a lab from the lesson's start, then sets the sphere's mu_d: the
        first with the mouse and the keys, the others by the page's elements (act)."""
        first = students[0]
        first.click("lab-toggle")
        first.type_into("lab-name", names[0])
        first.choose("lab-from", "start")
        first.click("lab-open")
        for student, name in zip(students[1:], names[1:]):
            act(student, f"el('lab-toggle').click(); el('lab-name').value = {json.dumps(name)}; "
                         "choose('lab-from', 'start'); el('lab-open').click();")
        for student, name in zip(students, names):
            student.wait("the student's lab", f"rbs.lab.info && rbs.lab.info.name === {json.dumps(name)} && "
                         "rbs.showing === 'lab' && rbs.world.source === 'lab'", DEADLINE)
        print(f"{STUDENTS} labs open in {time.monotonic() - started:.1f} s", file=sys.stderr)
        first.choose("lab-body", "sphere")
        first.choose("lab-key", "mu_d")
        first.type_into("lab-value", f"{MU_D[0]}")
        first.click("lab-set")
        for student, mu in zip(students[1:], MU_D[1:]):
            act(student, f"choose('lab-body', 'sphere'); choose('lab-key', 'mu_d'); el('lab-value').value = '{mu}'; "
                         "el('lab-set').click();")
        for student, mu in zip(students, MU_D):
            # The lab's new run comes before the change's reply: the line is the reply's.
            student.wait("the lab with the student's mu_d, and the change's reply",
                         f"rbs.lab.info.settings.sphere.mu_d === {mu} && rbs.world.bodies.sphere.mu_d === {mu} && "
                         "rbs.replies.some((r) => r.ok && r.line.startsWith('lab: sphere: mu_d'))", DEADLINE)
            self.assertEqual(student.evaluate("rbs.lab.line"), student.evaluate(
                "rbs.replies.filter((r) => r.ok).map((r) => r.line).pop()"))
        print(f"{STUDENTS} labs' mu_d set in {time.monotonic() - started:.1f} s", file=sys.stderr)

    def run_labs(self, students: List[Tab]) -> None:
        """Run each lab until the sphere rolls, then pause it; the instant is the closed form's."""
        students[0].click("lab-run")
        for student in students[1:]:
            act(student, "el('lab-run').click();")
        rolled = "rbs.lab.events.some((e) => e.body === 'sphere' && e.kind === 'slip_to_roll')"
        for student in students:
            student.wait("the sphere's slip_to_roll in the lab", rolled, DEADLINE)
            act(student, "el('lab-pause').click();")
        sphere = with_defaults(self.config["bodies"]["sphere"])
        for student, mu in zip(students, MU_D):
            student.wait("the lab paused, the page at its last state",
                         "rbs.lab.info.paused && rbs.paused && rbs.lab.states.sphere.length > 0", DEADLINE)
            event = student.evaluate("rbs.lab.events.find((e) => e.body === 'sphere' && e.kind === 'slip_to_roll')")
            truth = slip_to_roll_instant(dict(sphere, mu_d=mu), self.gravity)
            self.assertAlmostEqual(event["t"], truth, delta=1e-9)

    def check_class_view(self, teacher: Browser, students: List[Tab], names: List[str]) -> None:
        """A point a student, at their mu_d and their lab's instant, on the closed form's curve."""
        teacher.click("class-toggle")
        teacher.wait("every lab's result, the sphere's slip_to_roll in each",
                     f"rbs.classView.results.length === {STUDENTS} && rbs.classView.results.every((r) => "
                     "r.outcomes.some((o) => o.body === 'sphere' && o.kind === 'slip_to_roll')) && "
                     "[...document.getElementById('class-y').options].some((o) => "
                     "o.value === 'sphere.slip_to_roll.t')",
                     DEADLINE)
        teacher.choose("class-x", "sphere.mu_d")
        teacher.choose("class-y", "sphere.slip_to_roll.t")
        self.assertEqual(teacher.evaluate("[rbs.classView.xKey, rbs.classView.yKey]"),
                         ["sphere.mu_d", "sphere.slip_to_roll.t"])
        teacher.wait("a point a student, drawn for the keys chosen",
                     "rbs.classView.pointsOf && rbs.classView.pointsOf.join() === 'sphere.mu_d,sphere.slip_to_roll.t' "
                     f"&& rbs.classView.points.length === {STUDENTS}", DEADLINE)
        view = teacher.evaluate("rbs.classView")
        sphere = with_defaults(self.config["bodies"]["sphere"])
        by_name = {p["name"]: p for p in view["points"]}
        self.assertEqual(sorted(by_name), names)
        for student, name, mu in zip(students, names, MU_D):
            instant = student.evaluate(
                "rbs.lab.events.find((e) => e.body === 'sphere' && e.kind === 'slip_to_roll').t")
            point = by_name[name]
            self.assertEqual((point["x"], point["y"]), (mu, instant),
                             (name, view["xKey"], view["yKey"], [r for r in view["results"] if r["name"] == name]))
            self.assertAlmostEqual(point["y"], slip_to_roll_instant(dict(sphere, mu_d=mu), self.gravity), delta=1e-9)
        curve = view["curve"]
        self.assertGreaterEqual(len(curve["x"]), 2, "a curve")
        checked = 0
        for x, y in zip(curve["x"], curve["y"]):
            if y is not None:
                self.assertAlmostEqual(y, slip_to_roll_instant(dict(sphere, mu_d=x), self.gravity), delta=1e-9)
                checked += 1
        self.assertGreaterEqual(checked, 2, curve)
        values = [p["y"] for p in view["points"]]
        mean = sum(values) / len(values)
        sd = math.sqrt(sum((v - mean) ** 2 for v in values) / (len(values) - 1))
        self.assertAlmostEqual(view["stats"]["mean"], mean, delta=1e-12)
        self.assertAlmostEqual(view["stats"]["sd"], sd, delta=1e-12)
        self.assertIn(f"n = {STUDENTS}", teacher.evaluate("document.getElementById('class-stats').textContent"))
        # The pointer on a point: the student's name, drawn.
        point = view["points"][7]
        box = teacher.evaluate("(() => { const r = document.getElementById('class-canvas').getBoundingClientRect();"
                               " return {x: r.x, y: r.y}; })()")
        teacher.call("Input.dispatchMouseEvent", type="mouseMoved", x=box["x"] + point["px"], y=box["y"] + point["py"])
        teacher.wait("the name of the student under the pointer",
                     f"rbs.classView.hover && rbs.classView.hover.name === {json.dumps(point['name'])} && "
                     f"rbs.texts.some((t) => t.canvas === 'class-canvas' && t.text === {json.dumps(point['name'])})",
                     DEADLINE)
        print(f"{STUDENTS} points on the closed form's curve ({checked} of its points checked): mean "
              f"{mean:.4f} s, sd {sd:.4f} s", file=sys.stderr)

    def check_download(self, student: Tab) -> None:
        """The lab's zip: its config and what simulate writes of it, bit for bit; the page's states and events
        are its rows."""
        link = student.evaluate("document.getElementById('lab-download').href")
        lab_t = student.evaluate("rbs.lab.info.t")
        data = student.evaluate(f"""fetch({json.dumps(link)}).then(async (r) => {{
            const bytes = new Uint8Array(await r.arrayBuffer()); let text = "";
            for (const b of bytes) text += String.fromCharCode(b);
            return {{status: r.status, data: btoa(text)}}; }})""")
        self.assertEqual(data["status"], 200, link)
        archive = zipfile.ZipFile(io.BytesIO(base64.b64decode(data["data"])))
        files = {name: archive.read(name) for name in archive.namelist()}
        self.assertIn("config.yaml", files)
        run = os.path.join(self.tmp, f"lab_{len(os.listdir(self.tmp))}")
        os.makedirs(run)
        with open(os.path.join(run, "config.yaml"), "wb") as out:
            out.write(files["config.yaml"])
        subprocess.run([os.path.abspath(ARGS.simulate), "config.yaml", "--duration", repr(lab_t), "--out-dir", "out"],
                       cwd=run, check=True, capture_output=True, timeout=DEADLINE)
        written = {}
        for name in os.listdir(os.path.join(run, "out")):
            with open(os.path.join(run, "out", name), "rb") as wrote:
                written[name] = wrote.read()
        self.assertEqual({n: v for n, v in files.items() if n != "config.yaml"}, written)
        states = student.evaluate("rbs.lab.states")
        self.assertEqual(student.evaluate("rbs.lab.dropped"), 0)
        for body, got in states.items():
            # Each state the page got is the CSV's row of its instant. A page that cannot keep up loses frames
            # (as a watching page does): under load it may have fewer than the CSV's rows, never another.
            rows = {float(row["t"]): row for row in csv.DictReader(io.StringIO(files[f"{body}.csv"].decode()))}
            self.assertTrue(got, body)
            self.assertLessEqual(len(got), len(rows), body)
            self.assertTrue(all(a["t"] < b["t"] for a, b in zip(got, got[1:])), f"{body}: in order, each once")
            for state in got:
                self.assertIn(state["t"], rows, body)
                row = rows[state["t"]]
                self.assertEqual({k: state[k] for k in row}, {k: csv_value(v) for k, v in row.items()}, body)
        events = student.evaluate("rbs.lab.events")
        event_rows = list(csv.DictReader(io.StringIO(files["events.csv"].decode())))
        self.assertEqual([(e["t"], e["body"], e["kind"], e["values"], e["state"]) for e in events],
                         [(float(r["t"]), r["body"], r["kind"], key_values(r["values"]), key_values(r["state"]))
                          for r in event_rows])
        print(f"lab {link}: {sorted(files)} as simulate writes them to t = {lab_t}; the page's "
              f"{sum(map(len, states.values()))} states and {len(events)} events its rows", file=sys.stderr)

    def check_not_anothers(self, student: Tab, other: Tab, others_lab: str) -> None:
        """Another's download refused; without a lab's cookie, lab requests refused in one line."""
        status = student.evaluate(f"fetch('lab/' + {json.dumps(others_lab)} + '.zip').then((r) => r.status)")
        self.assertIn(status, (403, 404))
        client = websocket.create_connection(f"ws://127.0.0.1:{self.web_port}/ws", timeout=DEADLINE,
                                             origin=f"http://127.0.0.1:{self.web_port}")
        try:
            requests: List[Dict[str, Any]] = [{"op": "lab_run"}, {"op": "lab_close"},
                                              {"op": "lab_set", "body": "sphere", "key": "mu_d", "value": 0.1}]
            for n, request in enumerate(requests):
                client.send(json.dumps(dict(request, id=900 + n)))
                while True:
                    message = json.loads(client.recv())
                    if message.get("type") == "reply":
                        break
                self.assertEqual((message["id"], message["ok"]), (900 + n, False), message)
                self.assertEqual(len(message["line"].splitlines()), 1)
        finally:
            client.close()
        self.assertEqual(other.evaluate("rbs.lab.info.settings.sphere.mu_d"), MU_D[1])
        self.assertTrue(other.evaluate("rbs.lab.info !== null"))

    def check_predict(self, teacher: Browser, students: List[Tab]) -> None:
        """A question with choices, then a number: the students' answers in the teacher's histogram."""
        teacher.type_into("ask-question", "Which one rolls first?")
        teacher.type_into("ask-choices", "sphere, cylinder, ring")
        teacher.type_into("ask-unit", "")
        teacher.click("ask")
        chosen = ["sphere", "sphere", "cylinder", "sphere", "ring"]
        for student, choice in zip(students, chosen):
            student.wait("the question", "rbs.lab.question && rbs.lab.question.open && "
                         "document.getElementById('answer-0') !== null", DEADLINE)
            student.click(f"answer-{['sphere', 'cylinder', 'ring'].index(choice)}")
        teacher.wait("every answer", f"rbs.classView.answers && rbs.classView.answers.n === {len(chosen)}", DEADLINE)
        self.assertEqual(teacher.evaluate("rbs.classView.answers.counts"), {"sphere": 3, "cylinder": 1, "ring": 1})
        bars = teacher.evaluate("[...document.querySelectorAll('#answers .bar-row')].map((r) => [r.querySelector("
                                "'.bar-label').textContent, r.querySelector('.bar-count').textContent])")
        self.assertEqual(bars, [["sphere", "3"], ["cylinder", "1"], ["ring", "1"]])
        self.take_screenshots(teacher, students[2])
        teacher.click("reveal")
        for student in students:
            student.wait("the question closed", "rbs.lab.question && !rbs.lab.question.open", DEADLINE)
        # A number, in seconds: typed, and a word refused.
        teacher.type_into("ask-question", "When does the sphere start to roll?")
        teacher.type_into("ask-choices", "")
        teacher.type_into("ask-unit", "s")
        teacher.click("ask")
        typed = ["0.8", "0.95", "1.1"]
        for student, value in zip(students, typed):
            student.wait("the number question", "rbs.lab.question && rbs.lab.question.open && "
                         "rbs.lab.question.choices === null", DEADLINE)
            student.type_into("answer-value", value)
            student.click("answer-send")
        teacher.wait("the numbers", f"rbs.classView.answers && rbs.classView.answers.n === {len(typed)}", DEADLINE)
        self.assertEqual(sorted(teacher.evaluate("rbs.classView.answers.values")), sorted(map(float, typed)))
        students[3].type_into("answer-value", "soon")
        students[3].click("answer-send")
        students[3].wait("the refusal", "rbs.lab.line && !rbs.lab.lineOk", DEADLINE)
        self.assertEqual(len(students[3].evaluate("rbs.lab.line").splitlines()), 1)
        self.assertEqual(teacher.evaluate("rbs.classView.answers.n"), len(typed))
        teacher.click("reveal")
        students[0].wait("the question closed", "!rbs.lab.question.open", DEADLINE)

    def check_show_lab(self, teacher: Browser, shown: Tab, watcher: Tab, lab: str, mu: float) -> None:
        """The teacher shows one lab: a page shows its world; back, the class's world."""
        teacher.choose("show-lab-choice", lab)
        teacher.click("show-lab")
        teacher.wait("the lab shown on the teacher's page", f"rbs.showing === 'shown' && "
                     f"rbs.world.bodies.sphere.mu_d === {mu}", DEADLINE)
        watcher.click("lab-show-class")
        watcher.wait("the lab shown on another student's page", f"rbs.showing === 'shown' && "
                     f"rbs.world.bodies.sphere.mu_d === {mu} && Object.keys(rbs.drawn).length === 3", DEADLINE)
        self.assertTrue(shown.evaluate("rbs.showing === 'lab'"), "a student in their own lab stays there")
        teacher.click("class-toggle")
        teacher.click("show-lab-back")
        teacher.wait("the class's world again", "rbs.stores.shown.world === null", DEADLINE)
        watcher.wait("the class's world again", "rbs.showing === 'class'", DEADLINE)
        watcher.click("lab-show")

    def take_screenshots(self, teacher: Browser, student: Tab) -> None:
        os.makedirs(ARGS.out_dir, exist_ok=True)
        for page, name, panel in ((student, "web_lab", None), (teacher, "web_class", "class-canvas")):
            for suffix, width, height, scale, mobile in (("", 1600, 900, 1, False), ("_phone", 390, 844, 2, True)):
                page.resize(width, height, scale, mobile)
                canvas = panel or "scene-canvas"
                page.wait(f"the page laid out at {width}x{height}",
                          f"document.getElementById('{canvas}').width === Math.round(document.getElementById("
                          f"'{canvas}').clientWidth * {scale}) && document.documentElement.clientWidth === {width}",
                          DEADLINE)
                path = os.path.join(ARGS.out_dir, f"{name}{suffix}.png")
                page.screenshot(path)
                print(f"screenshot {path}", file=sys.stderr)
        student.resize(*STUDENT_SIZE, 1, False)

    def check_ids(self, page: Browser) -> None:
        sent = page.evaluate("rbs.sent")
        ids = [r["id"] for r in sent]
        self.assertTrue(all(isinstance(i, int) for i in ids), sent)
        self.assertEqual(len(set(ids)), len(ids))
        replies = page.evaluate("rbs.replies.map((r) => r.id)")
        self.assertTrue(set(replies) <= set(ids) | {None}, (replies, ids))


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir")
    parser.add_argument("simulate")
    ARGS, rest = parser.parse_known_args()
    unittest.main(argv=[sys.argv[0]] + rest)
