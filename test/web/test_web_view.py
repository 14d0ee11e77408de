#!/usr/bin/env python3
"""The web view in a real browser: sim.launch web:=true web_control:=true on config/demo.yaml (a rod and four
rollers), its page loaded in Debian's headless Chromium over the DevTools protocol.

- The log prints the teacher's login form's address and a random token; the token typed into that form (keys
  and clicks) gives the page the controls, as a cookie its script cannot read, never in an address (the tab's
  history holds none with it), and the page stays the teacher's on a reload; a page opened without it (its
  cookie cleared) shows no controls and plots the teacher's body.
- Pause clicked: the node's ~paused says true; the page's drawn state of every body is the last state the test
  received from the node, field for field, exactly; each body is drawn where the page's own view puts that
  state (a roller on its slope, r above it; a rod's centre and ends); each plot's last point is that state
  (v, -omega R, the total energy and a rod's end heights exactly; the kinetic and potential energies to 1e-12).
- Reset, then Pause 1.5 s later: the node's events (~events, as ~get_events answers) start with every body's
  restart of cause "reset" at the reset's instant, and the page holds them all, each once; the bowler, launched
  sliding with backspin, is marked at each of its slip_to_roll events' instants and speeds since the reset,
  the first at the closed form's, each between its last slipping and first rolling state; the plots' time axis
  starts at 0 at the reset; every body's plot holds every state since the reset, once, while a page that reads
  nothing is open too. A second web view started then reads the run's events from ~get_events: the first page
  it serves gets them all.
- Step (a count of 100 typed in) moves every body to the node's state 0.1 s on.
- A lesson's key: k = 2000 typed for the rod reaches the node (~get_config); k = -5 is refused, the page's line
  is the node's own WARN line from /rosout, and k stays 2000.
- A WebSocket client without the token: its requests, malformed, oversized and unexpected messages are each
  refused in one line, the world unchanged (no command on ~commands), each kind logged once in the launch's log;
  another Origin, or another Host (DNS rebinding), gets no connection and no page.
- Screenshots at 1600x900 and at a phone's 390x844 (a scale of 3): the page shows every body.
- Run: ~paused says false again; Step then is refused, and the page shows the node's own line. The page
  without the token shows the world and no control; opened at an address with the very token (?token=) it gives
  no control and says that the token goes in the form at /login; with a wrong token's cookie (a login from before
  a restart) it says that the token is not this view's; the form refuses a wrong token in one line, logged
  without it. Nothing was thrown or logged as an error in the page, and it asked nothing of any server but its
  own.

And playback.launch web:=true of a bag `simulate` wrote, started paused: the page's Run and Pause drive the player
(its pause_playback); the page finds the recording's bodies and their keys (the played config), draws the played
states exactly, plots them, and refuses Step in one line; at the recording's end it keeps the last frame and
says so.

And web.launch web_host:=0.0.0.0 alone (test_network), over raw HTTP: the login form (its password field, its
XSRF cookie and field), the token POSTed answered 303 with the control cookie, a POST without the XSRF field, a
wrong or an empty token refused (403, no cookie), a body over 4 KiB 413, an address with ?token= no control;
the class's addresses and QR code, the Host check on every address, 414 and 431, half-sent and idle
connections closed, the token in no log file and not on /rosout.

Each click's answer is the reply that names its request's id.

Usage: test_web_view.py CONFIG.yaml OUT_DIR SIMULATE WebView.test_node | WebView.test_replay | WebView.test_network
(with the package's devel space sourced; OUT_DIR gets the screenshots; one test a process: rospy joins one master)"""
import argparse
import html
import http.client
import json
import math
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
import unittest
import urllib.error
import urllib.parse
import urllib.request
from typing import Any, Dict, List, NamedTuple, Optional

import rospy
import websocket
import yaml
from rigid_body_sim.msg import Command, Event
from rigid_body_sim.runs import event_record, read_bag_events
from rigid_body_sim.srv import GetConfig, GetEvents
from rosgraph_msgs.msg import Log
from std_msgs.msg import Bool
from rigid_body_sim.sim_tools import (free_port, load_config, rospy_on_python39, state_message, wait_for,
                                      with_defaults)

from browser import Browser, end
from ros_launching import Teacher, launch_reading, ros_env, teacher_login

rospy_on_python39()
ARGS: Any = None
DEADLINE = 60.0  # s for any one wait
ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


class Listener:
    """What the node publishes, as the test receives it."""

    def __init__(self, bodies: Dict[str, str]) -> None:
        self.lock = threading.Lock()
        self.states: Dict[str, List[Any]] = {body: [] for body in bodies}
        self.paused: Optional[bool] = None
        self.commands: List[Command] = []
        self.events: List[Dict[str, Any]] = []
        self.warnings: List[str] = []
        for body, kind in bodies.items():
            rospy.Subscriber(f"/sim/{body}/state", state_message(kind),
                             lambda m, b=body: self.on_state(b, m), queue_size=1000)
        rospy.Subscriber("/sim/paused", Bool, self.on_paused)
        rospy.Subscriber("/sim/commands", Command, self.on_command, queue_size=1000)
        rospy.Subscriber("/sim/events", Event, lambda m: self.events.append(event_record(m)), queue_size=1000)
        rospy.Subscriber("/rosout", Log, self.on_log, queue_size=1000)

    def on_state(self, body: str, msg: Any) -> None:
        with self.lock:
            self.states[body].append(msg)

    def on_paused(self, msg: Bool) -> None:
        self.paused = msg.data

    def on_command(self, msg: Command) -> None:
        self.commands.append(msg)

    def on_log(self, msg: Log) -> None:
        if msg.name == "/sim" and msg.level >= Log.WARN:
            self.warnings.append(msg.msg)

    def last(self, body: str) -> Any:
        with self.lock:
            return self.states[body][-1] if self.states[body] else None


def event_key(e: Dict[str, Any]) -> Any:
    """An event, comparable and sortable: its instant, body, kind, values and state."""
    return (e["t"], e["body"], e["kind"], sorted(e["values"].items()), sorted(e["state"].items()))


class Answer(NamedTuple):
    status: int
    headers: Dict[str, str]
    body: bytes
    cookies: List[str]  # its Set-Cookie headers


def fields(msg: Any) -> Dict[str, Any]:
    return {f: getattr(msg, f) for f in msg.__slots__ if f != "header"}


Checker = Any  # the test case: its assertions


def _rod_place(t: Checker, b: Dict[str, Any], s: Dict[str, Any], d: Dict[str, Any], view: Dict[str, float]) -> None:
    """Its centre and end A at their heights above the floor, x along it."""
    scale, ox, oy = view["scale"], view["ox"], view["oy"]
    t.assertAlmostEqual(d["cx"], ox + s["x"] * scale, delta=1e-6)
    t.assertAlmostEqual(d["cy"], oy - s["y"] * scale, delta=1e-6)
    half = 0.5 * b["length"]
    t.assertAlmostEqual(d["ax"], ox + (s["x"] + half * math.cos(s["theta"])) * scale, delta=1e-6)
    t.assertAlmostEqual(d["ay"], oy - (s["y"] + half * math.sin(s["theta"])) * scale, delta=1e-6)


def _slope_place(half: float, spoke: bool, t: Checker, b: Dict[str, Any], s: Dict[str, Any], d: Dict[str, Any],
                 view: Dict[str, float]) -> None:
    """Its centre `half` (to scale, or 10 px: the page's smallest, 20 px across, said on its panel) above its
    slope at x along it; a spoke at its rotation theta about the slope's z."""
    scale, ox, oy = view["scale"], view["ox"], view["oy"]
    phi = b["incline_angle"]
    r = max(half * scale, 10.0)
    t.assertAlmostEqual(d["r"], r, delta=1e-9)
    t.assertAlmostEqual(d["cx"], ox + s["x"] * math.cos(phi) * scale + r * math.sin(phi), delta=1e-6)
    t.assertAlmostEqual(d["cy"], oy + s["x"] * math.sin(phi) * scale - r * math.cos(phi), delta=1e-6)
    if spoke:
        angle = math.atan2(-(d["sy"] - d["cy"]), d["sx"] - d["cx"])  # the spoke's angle on the screen
        t.assertAlmostEqual(math.remainder(angle - (s["theta"] - phi), 2 * math.pi), 0.0, delta=1e-9)


class TypeChecks(NamedTuple):
    """What the page draws and plots of one body type (web/types.js's entry), as this test expects it."""
    place: Any  # (test, body, state, drawn, view): where it is drawn
    motion: Any  # (body, state) -> {the motion plot's key: its last value}
    kinetic: Any  # (body, state) -> its kinetic energy (J)


# The one place of these tests that names a body type.
TYPE_CHECKS: Dict[str, TypeChecks] = {
    "rod": TypeChecks(
        _rod_place,
        lambda b, s: {"end_a": s["y"] + 0.5 * b["length"] * math.sin(s["theta"]),
                      "end_b": s["y"] - 0.5 * b["length"] * math.sin(s["theta"])},
        lambda b, s: (0.5 * b["mass"] * (s["vx"] ** 2 + s["vy"] ** 2)
                      + 0.5 * (b["mass"] * b["length"] ** 2 / 12) * s["omega"] ** 2)),
    "roller": TypeChecks(
        lambda t, b, s, d, view: _slope_place(b["radius"], True, t, b, s, d, view),
        lambda b, s: {"v": s["v"], "minus_omega_r": -s["omega"] * b["radius"]},
        lambda b, s: (0.5 * b["mass"] * s["v"] ** 2
                      + 0.5 * b["inertia_factor"] * b["mass"] * b["radius"] ** 2 * s["omega"] ** 2)),
    "block": TypeChecks(
        lambda t, b, s, d, view: _slope_place(0.5 * b["size"], False, t, b, s, d, view),
        lambda b, s: {"v": s["v"]},
        lambda b, s: 0.5 * b["mass"] * s["v"] ** 2),
}


class WebView(unittest.TestCase):
    def setUp(self) -> None:
        self.tmp = tempfile.mkdtemp(prefix="rbs_web_")
        self.config = load_config(ARGS.config)
        self.kinds = {name: str(b["type"]) for name, b in self.config["bodies"].items()}
        self.bodies = {name: with_defaults(b) for name, b in self.config["bodies"].items()}
        self.web_port = free_port()
        self.log: List[str] = []
        self.launch: Optional["subprocess.Popen[str]"] = None
        self.browser: Optional[Browser] = None

    def start(self, *words: str) -> None:
        """roslaunch rigid_body_sim WORDS... with the web view (control on) on a port of its own, and a master
        of its own; this process joins that master (one test per process: rospy joins one master)."""
        port = free_port()
        env = ros_env(port, self.tmp)
        os.environ.update({k: env[k] for k in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")})
        self.launch = launch_reading(
            ["-p", str(port), "rigid_body_sim", *words, *(["web:=true"] if words[0] != "web.launch" else []),
             f"web_port:={self.web_port}", "web_control:=true"], env, self.log)

    def tearDown(self) -> None:
        if self.browser:
            self.browser.close()
        if self.launch:
            end(self.launch, signal.SIGINT, 60)
        shutil.rmtree(self.tmp, ignore_errors=True)

    def log_lines(self, words: str) -> List[str]:
        return [line for line in list(self.log) if words in line]

    def teacher(self) -> Teacher:
        return teacher_login(self.log, self.web_port)

    def test_node(self) -> None:
        """The page follows and drives sim_node (the module's docstring)."""
        self.start("sim.launch", f"config:={ARGS.config}")
        teacher = self.teacher()
        rospy.init_node("web_view_test", anonymous=True, disable_signals=True)
        node = Listener(self.kinds)
        wait_for("a state of every body", lambda: all(node.last(b) for b in self.kinds), DEADLINE)
        self.browser = browser = Browser(1600, 900)
        browser.resize(1600, 900, 1, False)
        browser.call("Network.enable")
        browser.log_in(teacher.login, teacher.token, DEADLINE)
        browser.wait("every body drawn", "window.rbs && rbs.world && Object.keys(rbs.world.bodies).length === "
                     f"{len(self.kinds)} && Object.keys(rbs.drawn).length === {len(self.kinds)}", DEADLINE)
        self.assertEqual(browser.evaluate("location.href"), teacher.base)
        addresses = [entry["url"] for entry in browser.call("Page.getNavigationHistory")["entries"]]
        self.assertEqual(addresses[-2:], [teacher.login, teacher.base])
        self.assertFalse([a for a in addresses if teacher.token in a or "token=" in a], addresses)
        self.assertTrue(browser.evaluate("rbs.control && !document.getElementById('controls').hidden"))

        # Reset, then Pause after 1.5 s: the bowler slips, then rolls (0.57 s after its launch). Meanwhile a page
        # that reads nothing is open: the browser's page gets every state all the same.
        frozen = websocket.create_connection(f"ws://127.0.0.1:{self.web_port}/ws", timeout=DEADLINE,
                                             origin=f"http://127.0.0.1:{self.web_port}",
                                             sockopt=((socket.SOL_SOCKET, socket.SO_RCVBUF, 4096),))
        browser.click("reset")
        wait_for("the reset on ~commands", lambda: any(c.kind == "reset" for c in node.commands), DEADLINE)
        reset_t = next(c.t for c in node.commands if c.kind == "reset")
        wait_for("1.5 s after the reset", lambda: node.last("rod").t >= reset_t + 1.5, DEADLINE)
        browser.click("pause")
        wait_for("~paused true", lambda: node.paused is True, DEADLINE)
        self.check_drawn_is_the_node(browser, node)
        self.check_plots(browser, node)
        truth = self.check_events(browser, node, reset_t)
        self.check_slip_to_roll(browser, node, reset_t, truth)
        self.check_late_view(truth)
        for body in self.kinds:
            with node.lock:
                sent = [m.t for m in node.states[body] if m.t > reset_t]
            self.assertEqual(browser.evaluate(f"rbs.times({json.dumps(body)})"), sent, f"{body}: states plotted")
        frozen.close()
        print(f"every state since the reset plotted once ({len(sent)} a body), a frozen page open", file=sys.stderr)

        # Step 100 (typed): every body where the node's next state is.
        before = node.last("rod").t
        browser.type_into("steps", "100")
        browser.click("step")
        wait_for("the state after the step", lambda: node.last("rod").t > before, DEADLINE)
        self.assertAlmostEqual(node.last("rod").t, before + 0.1, delta=1e-9)
        self.check_drawn_is_the_node(browser, node)

        self.check_keys(browser, node)
        self.check_refusals(node)
        self.assertNotIn("only shows", browser.evaluate("rbs.line"), "another page's refusal shown here")
        self.take_screenshots(browser)

        run = self.click_and_answer(browser, "run")
        self.assertTrue(run["ok"], run)
        wait_for("~paused false after Run", lambda: node.paused is False, DEADLINE)
        # Step while running: the node refuses it, and the page shows the node's line (the reply to Step's
        # own id: Run's may come later than Step is clicked).
        warnings = len(node.warnings)
        reply = self.click_and_answer(browser, "step")
        wait_for("the node's WARN line about ~step", lambda: len(node.warnings) > warnings, DEADLINE)
        self.assertFalse(reply["ok"])
        self.assertEqual([reply["line"]], node.warnings[warnings:])
        self.assertTrue(reply["line"].startswith("~step refused"), reply)
        # A reload keeps the teacher's page a teacher's page (its cookie), the token nowhere in its address.
        browser.navigate(teacher.base)
        browser.wait("the teacher's page again", "window.rbs && rbs.control === true", DEADLINE)
        self.assertIsNotNone(browser.centre("controls"))
        self.assertEqual(browser.evaluate("document.cookie"), "", "the page's script reads the token")
        # The class's page (no token, no cookie): the world, and no control in sight.
        browser.call("Network.clearBrowserCookies")
        browser.navigate(teacher.base)
        browser.wait("the class's page", f"window.rbs && Object.keys(rbs.drawn).length === {len(self.kinds)}",
                     DEADLINE)
        self.assertFalse(browser.evaluate("rbs.control"))
        self.assertEqual(browser.evaluate("document.getElementById('plot-body').value"), "bowler",
                         "the class plots the teacher's body")
        # A student's own choice stands until the teacher chooses again.
        browser.choose("plot-body", "rod")
        teachers = websocket.create_connection(f"ws://127.0.0.1:{self.web_port}/ws", timeout=DEADLINE,
                                               origin=f"http://127.0.0.1:{self.web_port}",
                                               cookie=f"rbs_control={teacher.token}")
        self.assertTrue(self.read_until(teachers, "hello")["control"])
        teachers.send(json.dumps({"op": "view", "id": 1, "plot_body": "bowler"}))
        self.assertEqual(self.read_until(teachers, "reply"),
                         {"type": "reply", "id": 1, "ok": True, "line": "the class plots bowler"})
        teachers.close()
        browser.wait("the teacher's new choice on the class's page",
                     "document.getElementById('plot-body').value === 'bowler' && rbs.plotLast.body === 'bowler'",
                     DEADLINE)
        for control in ("controls", "pause", "run", "step", "reset", "set"):
            self.assertIsNone(browser.centre(control), f"#{control} shown on the class's page")
        self.check_no_control(browser, teacher)
        self.assertEqual(browser.console_errors(), [])
        # Nothing from the internet: every request the page made went to its own server.
        asked = {e["params"]["request"]["url"] for e in browser.events if e["method"] == "Network.requestWillBeSent"}
        own = f"http://127.0.0.1:{self.web_port}/"
        self.assertEqual({u for u in asked if not u.startswith(own)}, set())
        files = {own + name for name in ("types.js", "view.js", "view.css")}
        self.assertTrue(files <= {u.split("?")[0] for u in asked}, asked)

    def test_replay(self) -> None:
        """playback.launch of a bag simulate wrote: the page finds the bodies from the played state topics,
        their keys from the played config, runs and pauses the player, draws what it plays, and refuses any
        change."""
        bag = os.path.join(self.tmp, "run.bag")
        subprocess.run([ARGS.simulate, ARGS.config, "--duration", "20", "--bag", bag, "--out-dir", self.tmp],
                       check=True, timeout=120, stdout=subprocess.DEVNULL)
        self.start("playback.launch", f"bag:={bag}", "rviz:=false", "start_paused:=true")
        teacher = self.teacher()
        rospy.init_node("web_view_test", anonymous=True, disable_signals=True)
        node = Listener(self.kinds)
        self.browser = browser = Browser(1600, 900)
        browser.log_in(teacher.login, teacher.token, DEADLINE)
        browser.wait("the recording's bodies", "window.rbs && rbs.world && rbs.world.source === 'replay' && "
                     f"Object.keys(rbs.world.bodies).length === {len(self.kinds)}", DEADLINE)
        # The page's Run and Pause drive the player (its pause_playback), as rviz's panel does.
        self.assertEqual(self.click_and_answer(browser, "run"),
                         {"type": "reply", "id": 1, "ok": True, "line": "/player: Playback is now resumed"})
        wait_for("2 s of the recording", lambda: node.last("rod") is not None and node.last("rod").t >= 2.0,
                 DEADLINE)
        self.assertEqual(self.click_and_answer(browser, "pause")["line"], "/player: Playback is now paused")
        world = browser.evaluate("rbs.world.bodies")  # from the config the player played at t = 0
        for body, keys in self.config["bodies"].items():
            for key, value in keys.items():
                self.assertEqual(world[body][key], value, f"{body}.{key}: the played config's")
        self.check_drawn_is_the_node(browser, node)
        self.check_plots(browser, node)
        self.check_replayed_marks(browser, node, bag)
        self.assertEqual(browser.evaluate("document.getElementById('status').textContent"),
                         "replay of a recording, paused")
        self.assertEqual(self.click_and_answer(browser, "step")["line"],
                         "refused: a recording cannot be changed, only paused and run (no node serves /sim/pause)")
        # Its end: the last frame stays, and says so.
        drawn = browser.evaluate("rbs.drawn")
        self.click_and_answer(browser, "run")
        browser.wait("the end of the recording", "document.getElementById('status').textContent === "
                     "'end of recording: its last frame'", DEADLINE)
        self.assertEqual(browser.evaluate("Object.keys(rbs.drawn).sort()"), sorted(drawn))
        self.assertGreater(browser.evaluate("rbs.drawn.rod.t"), drawn["rod"]["t"])
        self.assertEqual(browser.console_errors(), [])

    def test_network(self) -> None:
        """web.launch web_host:=0.0.0.0 web_control:=true, no simulation: the class's addresses, the Host
        check, the answers to overlong and half-sent requests, and the token kept off every log."""
        self.start("web.launch", "web_host:=0.0.0.0")
        token = self.teacher().token
        rospy.init_node("web_view_test", anonymous=True, disable_signals=True)
        rosout: List[str] = []
        rospy.Subscriber("/rosout", Log, lambda m: rosout.append(m.msg), queue_size=1000)
        addresses = self.addresses()
        self.assertTrue(addresses, "no address but the loopback's on this machine")
        urls = [f"http://[{a}]:{self.web_port}/" if ":" in a else f"http://{a}:{self.web_port}/" for a in addresses]
        cookie = self.check_login(token)
        teacher = websocket.create_connection(f"ws://127.0.0.1:{self.web_port}/ws", timeout=DEADLINE,
                                              origin=f"http://127.0.0.1:{self.web_port}",
                                              cookie=cookie.split(";")[0])
        hello = self.read_until(teacher, "hello")
        self.assertTrue(hello["control"])
        self.assertEqual(sorted(hello["addresses"]), sorted(urls))
        teacher.close()
        qr = self.http("GET", "/qr.svg")
        self.assertEqual((qr.status, qr.headers["Content-Type"]), (200, "image/svg+xml"))
        self.assertIn(b"<svg", qr.body)
        # Host: this machine's names and addresses, nothing else (DNS rebinding), even on every address.
        own = [u.split("/")[2].rsplit(":", 1)[0] for u in urls]
        for host in [socket.gethostname(), "localhost", "127.0.0.1", "127.0.1.1", *own]:
            self.assertEqual(self.http("GET", "/", host=f"{host}:{self.web_port}").status, 200, host)
        for host in ("evil.example", f"evil.example:{self.web_port}", f"{addresses[0]}.evil.example:{self.web_port}",
                     f"127.0.0.1.evil.example:{self.web_port}", "127.0.0.1:1"):
            self.assertEqual(self.http("GET", "/", host=host).status, 403, host)
        # Overlong: answered, not dropped.
        self.assertEqual(self.http("GET", "/?" + "a" * (1 << 20)).status, 414)
        self.assertEqual(self.http("GET", "/", headers={"X-Big": "b" * 100_000}).status, 431)
        # Half-sent and idle connections: closed by the server within its 10 s, whatever their pace.
        started = time.monotonic()
        slow = [socket.create_connection(("127.0.0.1", self.web_port), timeout=DEADLINE) for _ in range(20)]
        idle = socket.create_connection(("127.0.0.1", self.web_port), timeout=DEADLINE)
        for s in slow:
            s.sendall(b"GET / HTTP/1.1\r\nHost: 127.0.0.1\r\n")
        deadline = time.monotonic() + 30
        for s in slow + [idle]:
            s.settimeout(max(0.1, deadline - time.monotonic()))
            try:
                while True:
                    s.sendall(b"X")  # one byte more of a header that never ends
                    if s.recv(1) == b"":
                        break
            except (ConnectionError, socket.timeout):
                pass
            s.close()
        closed_after = time.monotonic() - started
        self.assertLess(closed_after, 15.0)
        # The token: on the launch's terminal, nowhere in a log file or on /rosout.
        wait_for("/rosout's lines", lambda: bool(rosout), DEADLINE)
        self.assertFalse([line for line in rosout if token in line])
        logs = [os.path.join(d, f) for d, _, files in os.walk(self.tmp) for f in files]
        self.assertTrue(logs)
        for path in logs:
            with open(path, errors="replace") as written:
                self.assertNotIn(token, written.read(), path)
        print(f"addresses {addresses}; half-sent and idle connections closed after {closed_after:.1f} s",
              file=sys.stderr)

    def check_login(self, token: str) -> str:
        """The teacher's login over raw HTTP: the form; the token POSTed with its XSRF field answered 303 to the
        page with the control cookie (HttpOnly, for /ws alone); without that field, wrong, empty or too long
        refused, no cookie given; an address with the token gives none either. The control cookie."""
        page = self.http("GET", f"/?token={token}")
        self.assertEqual(page.status, 200)
        self.assertFalse([c for c in page.cookies if c.startswith("rbs_control=")], page.cookies)
        form = self.http("GET", "/login")
        self.assertEqual(form.status, 200)
        self.assertEqual(form.headers["Cache-Control"], "no-store")
        text = form.body.decode()
        field = re.search(r"<input [^>]*name=\"token\"[^>]*>", text)
        assert field is not None, text
        for attribute in ('type="password"', 'autocomplete="off"'):
            self.assertIn(attribute, field.group(0))
        hidden = re.search(r'name="_xsrf" value="([^"]+)"', text)
        assert hidden is not None, text
        xsrf_cookie = next(c for c in form.cookies if c.startswith("_xsrf="))
        for attribute in ("HttpOnly", "Path=/login", "SameSite=Strict"):
            self.assertIn(attribute.lower(), xsrf_cookie.lower())
        headers = {"Content-Type": "application/x-www-form-urlencoded", "Cookie": xsrf_cookie.split(";")[0]}

        def post(fields: Dict[str, str]) -> Answer:
            return self.http("POST", "/login", headers=headers, body=urllib.parse.urlencode(fields).encode())
        refusals = {"no XSRF field": ({"token": token}, ""),
                    "a wrong token": ({"_xsrf": hidden.group(1), "token": "x" * 24},
                                      "refused control: not this web view's token"),
                    "no token": ({"_xsrf": hidden.group(1), "token": ""}, "refused control: no token given")}
        began = time.monotonic()
        for case, (fields, line) in refusals.items():
            answer = post(fields)
            self.assertEqual(answer.status, 403, case)
            self.assertFalse([c for c in answer.cookies if c.startswith("rbs_control=")], case)
            refusal = re.search(r'<p id="refusal"[^>]*>([^<]*)</p>', answer.body.decode())
            if line:  # the form again, with its one line
                assert refusal is not None, answer.body
                self.assertTrue(html.unescape(refusal.group(1)).startswith(line), refusal.group(1))
                self.assertIn('name="token"', answer.body.decode())
            else:
                self.assertIsNone(refusal, case)
        refused_within = time.monotonic() - began
        # A body announced over 4 KiB: answered at its head, before any of it is read.
        answer = self.http("POST", "/login", headers=dict(headers, **{"Content-Length": str(4097)}))
        self.assertEqual(answer.status, 413)
        logged = "web view: login from 127.0.0.1: refused control"
        wait_for("the refused login's line in the log", lambda: bool(self.log_lines(logged)), DEADLINE)
        if refused_within < 10.0:  # the web view's LOGIN_LOG_PERIOD
            self.assertEqual(len(self.log_lines(logged)), 1, "a login refused again within 10 s: counted, not logged")
        answer = post({"_xsrf": hidden.group(1), "token": token})
        self.assertEqual((answer.status, answer.headers["Location"]), (303, "/"))
        cookie = next(c for c in answer.cookies if c.startswith("rbs_control="))
        self.assertRegex(cookie, rf"^rbs_control={token};")
        for attribute in ("HttpOnly", "Path=/ws", "SameSite=Strict"):
            self.assertIn(attribute.lower(), cookie.lower())
        print(f"login: {len(refusals)} POSTs refused, the token's answered 303 with the control cookie",
              file=sys.stderr)
        return cookie

    def check_no_control(self, browser: Browser, teacher: Teacher) -> None:
        """Without the token's cookie: an address with the very token gives no control and the page says where
        the token goes; a wrong token's cookie (a login from before a restart) says that it is not this view's;
        the form refuses a wrong token in one line, logged without it."""
        browser.navigate(f"{teacher.base}?token={teacher.token}")
        browser.wait("the page's line about the login form", "window.rbs && rbs.line.includes('/login') && "
                     "rbs.world !== null", DEADLINE)
        self.assertEqual(browser.evaluate("location.search"), "")
        self.assertFalse(browser.evaluate("rbs.control"))
        self.assertIsNone(browser.centre("controls"))
        browser.call("Network.setCookie", name="rbs_control", value="x" * 24, url=f"{teacher.base}ws", httpOnly=True,
                     sameSite="Strict")
        browser.navigate(teacher.base)
        browser.wait("the page's line about the token", "window.rbs && rbs.line.includes(\"token is not this "
                     "view's\")", DEADLINE)
        self.assertFalse(browser.evaluate("rbs.control"))
        self.assertIsNone(browser.centre("controls"))
        self.assertEqual(len(self.log_lines("refused control: this browser's token is not this view's")), 1)
        browser.call("Network.clearBrowserCookies")
        browser.load(teacher.login, "the login form", DEADLINE)
        browser.type_into("token", "y" * 24)
        browser.submit("login-submit", DEADLINE)
        refusal = browser.evaluate("document.getElementById('refusal').textContent")
        self.assertEqual(refusal, "refused control: not this web view's token (a new one at each start: see its "
                                  "terminal)")
        self.assertEqual(browser.evaluate("location.pathname"), "/login")
        self.assertIsNotNone(browser.centre("token"), "the form again")
        logged = "web view: login from 127.0.0.1: refused control: not this web view's token"
        wait_for("the refused login's line in the log", lambda: bool(self.log_lines(logged)), DEADLINE)
        self.assertEqual(len(self.log_lines(logged)), 1)
        self.assertFalse([line for line in self.log_lines("login from") if "y" * 24 in line])
        print("no control from an address with the token, a stale cookie or a wrong token in the form",
              file=sys.stderr)

    def http(self, method: str, path: str, host: Optional[str] = None,
             headers: Optional[Dict[str, str]] = None, body: Optional[bytes] = None) -> Answer:
        connection = http.client.HTTPConnection("127.0.0.1", self.web_port, timeout=DEADLINE)
        connection.putrequest(method, path, skip_host=True)
        connection.putheader("Host", host or f"127.0.0.1:{self.web_port}")
        for name, value in (headers or {}).items():
            connection.putheader(name, value)
        if body is not None:
            connection.putheader("Content-Length", str(len(body)))
        connection.endheaders(body)
        answer = connection.getresponse()
        cookies: List[str] = list(answer.msg.get_all("Set-Cookie") or ())
        return Answer(answer.status, dict(answer.getheaders()), answer.read(), cookies)

    @staticmethod
    def addresses() -> List[str]:
        """This machine's addresses a student can use (all but the loopback's and IPv6's link-local ones), as
        `hostname -I` lists them."""
        return subprocess.run(["hostname", "-I"], capture_output=True, text=True, check=True).stdout.split()

    @staticmethod
    def click_and_answer(browser: Browser, button: str) -> Dict[str, Any]:
        """Clicks a button and waits for the reply to its own request (by the id the page gave it)."""
        sent = browser.evaluate("rbs.sent.length")
        browser.click(button)
        request = browser.wait(f"the request of {button}", f"rbs.sent.length > {sent} && rbs.sent[{sent}]", DEADLINE)
        reply: Dict[str, Any] = browser.wait(f"the answer to {button}",
                                             f"rbs.replies.find((r) => r.id === {request['id']})", DEADLINE)
        return reply

    def check_drawn_is_the_node(self, browser: Browser, node: Listener) -> None:
        """Once the page has drawn the last state the test received of every body (paused: none comes after)."""
        seen: Dict[str, Any] = {}

        def caught_up() -> bool:
            seen["drawn"] = browser.evaluate("rbs.drawn")
            return all(seen["drawn"].get(b, {}).get("t") == node.last(b).t for b in self.kinds)
        wait_for("the page's drawing of the node's last states", caught_up, DEADLINE)
        last = {body: fields(node.last(body)) for body in self.kinds}
        drawn = seen["drawn"]
        panels = browser.evaluate("rbs.panels")
        for body, state in last.items():
            for field, value in state.items():
                self.assertEqual(drawn[body][field], value, f"{body}.{field} drawn")
            self.check_place(body, state, drawn[body], panels[body])
        print(f"drawn as the node's states at t = {last['rod']['t']}", file=sys.stderr)

    def check_place(self, body: str, s: Dict[str, Any], d: Dict[str, Any], view: Dict[str, float]) -> None:
        """Where the page drew it: its view's metres to pixels (side view: downhill and up the screen)."""
        TYPE_CHECKS[self.kinds[body]].place(self, self.bodies[body], s, d, view)

    def check_plots(self, browser: Browser, node: Listener) -> None:
        for body in sorted(self.kinds):
            browser.choose("plot-body", body)
            browser.wait(f"the plots of {body}", f"rbs.plotLast.body === {json.dumps(body)}", DEADLINE)
            points = browser.evaluate("rbs.plotLast.points")
            s = fields(node.last(body))
            b = self.bodies[body]
            for key in points:
                self.assertEqual(points[key][0], s["t"], f"{body}: {key}'s last point is at t = {points[key][0]}")
            self.assertEqual(points["energy"][1], s["energy"])
            checks = TYPE_CHECKS[self.kinds[body]]
            for key, value in checks.motion(b, s).items():
                self.assertEqual(points[key][1], value, f"{body}: {key}")
            kinetic = checks.kinetic(b, s)
            self.assertAlmostEqual(points["kinetic"][1], kinetic, delta=1e-12 * max(1.0, abs(kinetic)))
            potential = s["energy"] - kinetic
            self.assertAlmostEqual(points["potential"][1], potential, delta=1e-12 * max(1.0, abs(s["energy"])))
        print(f"plots' last points: the states of {sorted(self.kinds)}", file=sys.stderr)

    def check_events(self, browser: Browser, node: Listener, reset_t: float) -> List[Dict[str, Any]]:
        """The run's events as ~get_events answers (paused: all there are): every body's restart of cause
        "reset" at the reset's instant first, then nothing older; the same on ~events; the page holds each of
        them once. The run's events, oldest first."""
        answer = rospy.ServiceProxy("/sim/get_events", GetEvents)()
        truth = [event_record(m) for m in answer.events]
        firsts = truth[:len(self.kinds)]
        self.assertEqual(sorted(e["body"] for e in firsts), sorted(self.kinds), firsts)
        for e in firsts:
            self.assertEqual((e["t"], e["values"]["cause"]), (reset_t, "reset"), e)
        self.assertTrue(all(e["t"] >= reset_t for e in truth))

        # By order, not instant: an event of the step that ended at the reset is at reset_t too, in the run before.
        def since_reset() -> List[Dict[str, Any]]:
            events = list(node.events)
            first = next((i for i, e in enumerate(events) if e["values"].get("cause") == "reset"), len(events))
            return events[first:]
        wait_for("every event since the reset on ~events",
                 lambda: sorted(map(event_key, since_reset())) == sorted(map(event_key, truth)), DEADLINE)
        on_page: List[Dict[str, Any]] = []

        def page_has_them() -> bool:
            on_page[:] = [e for es in browser.evaluate("rbs.events").values() for e in es]
            return sorted(map(event_key, on_page)) == sorted(map(event_key, truth))
        try:
            wait_for("the page's events: the node's", page_has_them, DEADLINE)
        except TimeoutError:
            self.assertEqual(sorted(map(event_key, on_page)), sorted(map(event_key, truth)))
        # The plots count from the reset: 0 there (the bowler's, as every body's).
        browser.choose("plot-body", "bowler")
        browser.wait("the bowler's plots", "rbs.plotLast.body === 'bowler'", DEADLINE)
        plot = browser.evaluate("rbs.plotLast")
        self.assertEqual((plot["t0"], plot["origins"], plot["axis"]), (reset_t, [reset_t], "t since reset (s)"))
        self.assertEqual(plot["ticks"][0], [reset_t, "0"])
        print(f"{len(truth)} events since the reset, on the page as the node has them; the plots count from the "
              f"reset: ticks {[label for _, label in plot['ticks']]}", file=sys.stderr)
        return truth

    def check_slip_to_roll(self, browser: Browser, node: Listener, reset_t: float,
                           truth: List[Dict[str, Any]]) -> None:
        """The bowler's slip -> roll dots since the reset: one at each of its slip_to_roll events, at its instant
        and its v then, each between the last slipping and the first rolling state the node sent around it;
        the first at the closed form's instant after the reset (docs/testing.md) and its v then. Under load the
        pause may come after more than one."""
        browser.choose("plot-body", "bowler")
        browser.wait("the bowler's plots", "rbs.plotLast.body === 'bowler'", DEADLINE)
        gripped = [e for e in truth if e["body"] == "bowler" and e["kind"] == "slip_to_roll"]
        marks = browser.evaluate("rbs.plotLast.marks")
        self.assertEqual([(m["t"], m["v"]) for m in marks], [(e["t"], e["state"]["v"]) for e in gripped])
        self.assertEqual({m["name"] for m in marks}, {"slip \u2192 roll"})
        with node.lock:
            after = [m for m in node.states["bowler"] if m.t > reset_t]
        pairs = [(a, b) for a, b in zip(after, after[1:]) if a.mode == "slipping" and b.mode == "rolling"]
        self.assertEqual(len(gripped), len(pairs), ([e["t"] for e in gripped], [(a.t, b.t) for a, b in pairs]))
        self.assertGreater(len(pairs), 0)
        for mark, (slipping, rolling) in zip(marks, pairs):
            self.assertTrue(slipping.t < mark["t"] <= rolling.t, (slipping.t, mark, rolling.t))
        b = self.bodies["bowler"]
        g, phi, c, R = float(self.config.get("gravity", 9.8)), b["incline_angle"], b["inertia_factor"], b["radius"]
        rate = b["mu_d"] * g * math.cos(phi) * (1 + c) / c - g * math.sin(phi)  # -du/dt, u = v + omega R > 0
        slowing = g * math.sin(phi) - b["mu_d"] * g * math.cos(phi)  # dv/dt
        instant = (b["v0"] + b["omega0"] * R) / rate
        self.assertAlmostEqual(marks[0]["t"], reset_t + instant, delta=1e-9)
        self.assertAlmostEqual(marks[0]["v"], b["v0"] + slowing * instant, delta=1e-9)
        print(f"slip -> roll marked at t = {[m['t'] for m in marks]} ({marks[0]['t'] - reset_t:.4f} s after the "
              "reset), the node's events", file=sys.stderr)

    def check_replayed_marks(self, browser: Browser, node: Listener, bag: str) -> None:
        """In a replay, the recording's events as the player plays them: the bowler's slip -> roll dots at the
        bag's slip_to_roll events (their instants and speeds) of the plots' window, up to the state drawn."""
        last = node.last("bowler").t
        recorded = [(e["t"], e["state"]["v"]) for e in read_bag_events(bag)
                    if e["body"] == "bowler" and e["kind"] == "slip_to_roll" and max(0.0, last - 10) <= e["t"] <= last]
        self.assertTrue(recorded, "no slip -> roll of the bowler in the recording's first seconds")
        browser.choose("plot-body", "bowler")
        shown: List[Any] = []

        def marked() -> bool:
            plot = browser.evaluate("rbs.plotLast")
            shown[:] = [(m["t"], m["v"]) for m in plot["marks"] if m["t"] <= last] if plot["body"] == "bowler" else []
            return shown == recorded
        try:
            wait_for("the recording's slip -> roll marks", marked, DEADLINE)
        except TimeoutError:
            self.assertEqual(shown, recorded)
        print(f"replay: slip -> roll marked at the recording's events, t = {[t for t, _ in shown]}", file=sys.stderr)

    def check_late_view(self, truth: List[Dict[str, Any]]) -> None:
        """A web view started now, long after the node: it reads the run's events from ~get_events, and its
        page gets them all (the node is paused: no other comes)."""
        port = free_port()
        log = os.path.join(self.tmp, "web_late.log")
        with open(log, "w") as out:
            # The script itself: rosrun finds two of it (the source's and the devel space's relay).
            late = subprocess.Popen([sys.executable, os.path.join(ROOT, "scripts", "web_view.py"), "__name:=web_late",
                                     f"_port:={port}", "_node:=/sim", f"_web_root:={os.path.join(ROOT, 'web')}"],
                                    env=dict(os.environ, PATH="/usr/bin:" + os.environ.get("PATH", "")),
                                    stdout=out, stderr=subprocess.STDOUT)
        try:
            def listening() -> bool:
                if late.poll() is not None:
                    with open(log) as written:
                        raise AssertionError(f"the late web view ended: {written.read()}")
                try:
                    socket.create_connection(("127.0.0.1", port), timeout=1.0).close()
                    return True
                except OSError:
                    return False
            wait_for("the late web view listening", listening, DEADLINE)
            client = websocket.create_connection(f"ws://127.0.0.1:{port}/ws", timeout=DEADLINE,
                                                 origin=f"http://127.0.0.1:{port}")
            deadline = time.monotonic() + DEADLINE
            got: List[Dict[str, Any]] = []
            while sorted(map(event_key, got)) != sorted(map(event_key, truth)):
                self.assertLess(time.monotonic(), deadline, f"the late view's events: {len(got)} of {len(truth)}")
                message = self.read_until(client, "events")
                got = message["events"] if message["all"] else got + message["events"]
            client.close()
        finally:
            end(late, signal.SIGINT, 60)
        print(f"a web view started late: its page got the run's {len(truth)} events", file=sys.stderr)

    def rod_k(self) -> float:
        config = yaml.safe_load(rospy.ServiceProxy("/sim/get_config", GetConfig)().yaml)
        return float(config["bodies"]["rod"]["k"])

    def set_key(self, browser: Browser, body: str, key: str, value: str) -> Dict[str, Any]:
        browser.choose("set-body", body)
        browser.choose("set-key", key)
        browser.type_into("set-value", value)
        return self.click_and_answer(browser, "set")

    def check_keys(self, browser: Browser, node: Listener) -> None:
        reply = self.set_key(browser, "rod", "k", "2000")
        self.assertTrue(reply["ok"], reply)
        self.assertEqual(self.rod_k(), 2000.0)
        warnings = len(node.warnings)
        reply = self.set_key(browser, "rod", "k", "-5")
        self.assertFalse(reply["ok"], reply)
        wait_for("the node's WARN line", lambda: len(node.warnings) > warnings, DEADLINE)
        self.assertEqual(node.warnings[warnings:], [reply["line"]])
        self.assertIn("'rod'", reply["line"])
        self.assertEqual(browser.evaluate("document.getElementById('line').textContent"), reply["line"])
        self.assertEqual(browser.evaluate("document.getElementById('line').className"), "refused")
        self.assertEqual(self.rod_k(), 2000.0)
        self.assertEqual(browser.evaluate("document.getElementById('set-value').value"), "2000",
                         "the field shows the value that runs after a refusal")
        print(f"k = 2000 set; k = -5 refused with the node's line: {reply['line']}", file=sys.stderr)

    def check_refusals(self, node: Listener) -> None:
        """A client without the token, and malformed messages: one line each, nothing reaches the node."""
        commands = len(node.commands)
        paused = node.paused
        client = websocket.create_connection(f"ws://127.0.0.1:{self.web_port}/ws", timeout=DEADLINE,
                                             origin=f"http://127.0.0.1:{self.web_port}")
        hello = self.read_until(client, "hello")
        self.assertFalse(hello["control"])
        self.assertEqual(hello["view"], {"plot_body": "bowler"}, "the teacher's last choice, for the class")
        self.assertNotIn("addresses", hello)
        cases = [('{"op": "pause", "id": 1}', "refused: this page only shows"),
                 ('{"op": "set", "id": 2, "body": "rod", "key": "k", "value": 1}', "refused: this page only shows"),
                 ("{not json", "refused: not JSON"),
                 ('{"op": "pause", "id": 3}' + " " * 1100, "refused: a message of more than 1024 bytes"),
                 ('{"op": "shutdown", "id": 4}', "refused: unknown op 'shutdown'"),
                 ("{not json either", "refused: not JSON")]
        for text, line in cases:
            client.send(text)
            reply = self.read_until(client, "reply")
            self.assertFalse(reply["ok"])
            self.assertTrue(reply["line"].startswith(line), reply)
        client.send("x" * (64 * 1024 + 1))  # beyond tornado's limit: the connection is closed
        with self.assertRaises((websocket.WebSocketConnectionClosedException, ConnectionError)):
            for _ in range(10000):
                client.recv()
        client.close()
        # a foreign page's script (another Origin) gets no connection at all
        with self.assertRaises(websocket.WebSocketBadStatusException):
            websocket.create_connection(f"ws://127.0.0.1:{self.web_port}/ws", timeout=DEADLINE,
                                        origin="http://example.invalid")
        # nor does a site whose name was pointed at 127.0.0.1 (DNS rebinding: same origin, foreign host)
        rebound = f"rebound.invalid:{self.web_port}"
        with self.assertRaises(websocket.WebSocketBadStatusException):
            websocket.create_connection(f"ws://127.0.0.1:{self.web_port}/ws", timeout=DEADLINE, host=rebound,
                                        origin=f"http://{rebound}")
        with self.assertRaises(urllib.error.HTTPError) as refused:
            urllib.request.urlopen(urllib.request.Request(f"http://127.0.0.1:{self.web_port}/",
                                                          headers={"Host": rebound}), timeout=DEADLINE)
        self.assertEqual(refused.exception.code, 403)
        wait_for("the refusals in the log", lambda: len(self.log_lines("bytes (connection closed)")) == 1, DEADLINE)
        self.assertEqual(len(self.log_lines("refused: not JSON")), 1, "logged once per page")
        self.assertEqual(len(self.log_lines("refused: this page only shows")), 1)
        self.assertEqual(len(node.commands), commands, "a refused request reached the node")
        self.assertEqual(node.paused, paused)
        print(f"{len(cases) + 1} refused messages, each kind logged once; no command reached the node",
              file=sys.stderr)

    @staticmethod
    def read_until(client: Any, kind: str) -> Dict[str, Any]:
        deadline = time.monotonic() + DEADLINE
        while time.monotonic() < deadline:
            message: Dict[str, Any] = json.loads(client.recv())
            if message["type"] == kind:
                return message
        raise TimeoutError(f"no {kind} message")

    def take_screenshots(self, browser: Browser) -> None:
        os.makedirs(ARGS.out_dir, exist_ok=True)
        for name, width, height, scale, mobile in (("web.png", 1600, 900, 1, False),
                                                   ("web_phone.png", 390, 844, 3, True)):
            browser.choose("plot-body", "bowler")
            browser.resize(width, height, scale, mobile)
            browser.wait(f"the page laid out at {width}x{height}",
                         f"document.getElementById('scene-canvas').width === "
                         f"Math.round(document.getElementById('scene-canvas').clientWidth * {scale}) && "
                         f"document.documentElement.clientWidth === {width}", DEADLINE)
            drawn = browser.evaluate("Object.keys(rbs.drawn).length")
            self.assertEqual(drawn, len(self.kinds))
            path = os.path.join(ARGS.out_dir, name)
            browser.screenshot(path)
            print(f"screenshot {path}", file=sys.stderr)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("config")
    parser.add_argument("out_dir")
    parser.add_argument("simulate")
    ARGS, rest = parser.parse_known_args()
    unittest.main(argv=[sys.argv[0]] + rest)
