#!/usr/bin/env python3
"""The page a class reads, by its own geometry, in Debian's headless Chromium: every lesson part
(lesson.launch part:=below, above, slip, block, rod) started paused and stepped to INSTANTS (all racing; some or all
finished), the teacher's page at a phone's 390x844, a laptop's 1366x768, a projector's 1600x900 and 4K's
3840x2160, and the class's page at widths from 360 to 3840 px. At each:

- every text, on the page or drawn on a canvas (rbs.texts), is at least MIN_TEXT px (20 from 1600x900 up,
  14 below), lies whole inside its element or canvas and the screen's width, and covers no other text and
  no body;
- every body on a slope is drawn at least 20 px across and inside its panel, its slope as the configs have it and
  nearly flat and nearly upright (ANGLES, set from the teacher's page); the scene canvas fills the screen's
  height below the page's top lines (beside the plots on a wide screen);
- a race's finishers at the same time share a place, "=1st" (part:=above: all three at 1.4325 s);
- a finished racer stands still at the end of its slope, its label with its place, its time and its arrival
  speed, the page's finish instant at the closed form's and, released from rest, its speed 2 L / t;
- the plots mark the slip -> roll instants at the closed form's, and their axes carry units;
- the teacher's choice of part:=above from part:=below's page sets every body's keys, and the page names it.

Screenshots of each part at the four sizes go to OUT_DIR (web_<part>_<size>.png) to be looked at.

Usage: test_web_layout.py OUT_DIR   (with the package's devel space sourced)"""
import argparse
import json
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
import unittest
from typing import Any, Dict, List, Optional

import rospy
from rigid_body_sim.srv import Step
from rigid_body_sim.sim_tools import (INERTIA_FACTORS, free_port, load_config, rospy_on_python39, wait_for,
                                      with_defaults)
from rigid_body_sim.web_protocol import part_config

from browser import Browser, end

rospy_on_python39()
ARGS: Any = None
DEADLINE = 60.0
ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
# s of simulated time: rolling, slipping, the finishes (above: 1.43 s; below: 2.0 to 2.6 s; slip: 1.9 to 2.4 s)
# s of simulated time: all racing (slip: all slipping); below and slip: two finished, the ring racing after
# its slip -> roll; above: all three finished together at 1.4325 s
INSTANTS = (0.4, 2.2)
SIZES = {"phone": (390, 844, 3, True), "laptop": (1366, 768, 1, False), "projector": (1600, 900, 1, False),
         "4k": (3840, 2160, 1, False)}
PARTS = ("below", "above", "slip", "block", "rod")  # lesson.launch's
WIDTHS = (360, 768, 1280, 2560, 3840)
ANGLES = (0.02, 1.55)  # rad: the sphere's slope set from the teacher's page, part:=below


def min_text(width: int, height: int) -> float:
    return 20.0 if width >= 1600 and height >= 900 else 14.0


# The page's geometry, in the page: every breach of the rules as one line.
RULES = r"""((minText) => {
  const bad = [];
  const vw = document.documentElement.clientWidth;
  const pageWidth = document.documentElement.scrollWidth;
  if (pageWidth > vw) bad.push(`page ${pageWidth} px wide in ${vw}`);
  const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
  for (let n = walker.nextNode(); n; n = walker.nextNode()) {
    const el = n.parentElement;
    if (!n.textContent.trim() || !el || el.closest("[hidden]") || el.offsetParent === null) continue;
    const range = document.createRange();
    range.selectNodeContents(n);
    const r = range.getBoundingClientRect();
    const px = parseFloat(getComputedStyle(el).fontSize);
    if (px < minText) bad.push(`"${n.textContent.trim().slice(0, 30)}" at ${px} px`);
    if (r.left < -0.5 || r.right > vw + 0.5) bad.push(`"${n.textContent.trim().slice(0, 30)}" off the screen`);
    if (el.scrollWidth > el.clientWidth + 1 && getComputedStyle(el).display !== "inline") {
      bad.push(`"${n.textContent.trim().slice(0, 30)}" cut`);
    }
  }
  for (const el of document.querySelectorAll("button, select, input")) {
    if (el.offsetParent === null) continue;
    const r = el.getBoundingClientRect();
    const px = parseFloat(getComputedStyle(el).fontSize);
    if (px < minText) bad.push(`#${el.id} at ${px} px`);
    if (r.left < -0.5 || r.right > vw + 0.5) bad.push(`#${el.id} off the screen`);
  }
  const sizes = {};
  for (const c of document.querySelectorAll("canvas")) sizes[c.id] = [c.clientWidth, c.clientHeight];
  const boxes = rbs.texts;
  boxes.forEach((b, i) => {
    const [w, h] = sizes[b.canvas];
    if (b.px < minText) bad.push(`canvas "${b.text}" at ${b.px} px`);
    if (b.x < -0.5 || b.y < -0.5 || b.x + b.w > w + 0.5 || b.y + b.h > h + 0.5) {
      bad.push(`canvas "${b.text}" cut: ${Math.round(b.x)},${Math.round(b.y)} ${Math.round(b.w)}x${b.h} in ${w}x${h}`);
    }
    for (const o of boxes.slice(i + 1)) {
      if (o.canvas === b.canvas && b.x < o.x + o.w && o.x < b.x + b.w && b.y < o.y + o.h && o.y < b.y + b.h) {
        bad.push(`canvas "${b.text}" over "${o.text}"`);
      }
    }
    if (b.canvas !== "scene-canvas") return;
    for (const [name, d] of Object.entries(rbs.drawn)) {
      if (d.r === undefined) continue;
      const nx = Math.max(b.x, Math.min(d.cx, b.x + b.w));
      const ny = Math.max(b.y, Math.min(d.cy, b.y + b.h));
      if (Math.hypot(nx - d.cx, ny - d.cy) < d.r) bad.push(`canvas "${b.text}" over ${name}`);
    }
  });
  for (const [name, d] of Object.entries(rbs.drawn)) {
    if (d.r === undefined) continue;
    if (2 * d.r < 20) bad.push(`${name} ${2 * d.r} px across`);
    const p = rbs.panels[name].rect;
    if (d.cx - d.r < p.x || d.cx + d.r > p.x + p.w || d.cy - d.r < p.y || d.cy + d.r > p.y + p.h) {
      bad.push(`${name} out of its panel`);
    }
  }
  const scene = document.getElementById("scene-canvas").getBoundingClientRect();
  const room = window.innerHeight - (scene.top + window.scrollY);
  if (scene.height < room - 1.5 * minText) bad.push(`scene ${scene.height} px high in ${room}`);
  return bad;
})"""


class Layout(unittest.TestCase):
    def setUp(self) -> None:
        self.tmp = tempfile.mkdtemp(prefix="rbs_web_layout_")
        self.master: Optional["subprocess.Popen[str]"] = None
        self.launches: Dict[str, "subprocess.Popen[str]"] = {}
        self.browser: Optional[Browser] = None
        self.breaches: List[str] = []
        os.makedirs(ARGS.out_dir, exist_ok=True)

    def tearDown(self) -> None:
        if self.browser:
            self.browser.close()
        for launch in self.launches.values():  # all asked at once: their ends overlap
            launch.send_signal(signal.SIGINT)
        for launch in self.launches.values():
            end(launch, signal.SIGINT, 60)
        if self.master:
            end(self.master, signal.SIGINT, 60)
        shutil.rmtree(self.tmp, ignore_errors=True)

    def start_all(self) -> Dict[str, str]:
        """Every part at once on one master, each lesson.launch in its namespace (ns:=PART), paused at t = 0,
        with its web view: {part: the teacher's link}."""
        port = free_port()
        env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_HOME=self.tmp, ROS_IP="127.0.0.1",
                   PATH="/usr/bin:" + os.environ.get("PATH", ""), PYTHONUNBUFFERED="1")
        env.pop("ROS_HOSTNAME", None)
        os.environ.update({k: env[k] for k in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")})
        self.master = subprocess.Popen(["roscore", "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
                                       stderr=subprocess.DEVNULL, text=True)
        wait_for("the master", lambda: subprocess.run(["rosnode", "list"], env=env, capture_output=True)
                 .returncode == 0, DEADLINE, period=0.2)
        logs: Dict[str, List[str]] = {}
        patterns = {}
        for part in PARTS:
            web_port = free_port()
            logs[part] = []
            patterns[part] = re.compile(rf"(http://127\.0\.0\.1:{web_port}/\?token=[A-Za-z0-9_-]{{24}})\s*$")
            self.launches[part] = subprocess.Popen(
                ["roslaunch", "rigid_body_sim", "lesson.launch", f"part:={part}", f"ns:={part}", "rviz:=false",
                 "start_paused:=true", "web:=true", f"web_port:={web_port}", "web_control:=true"],
                env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            threading.Thread(target=self.read_log, args=(self.launches[part], logs[part]), daemon=True).start()
        links: Dict[str, str] = {}

        def printed() -> bool:
            for part in PARTS:
                found = [m.group(1) for m in (patterns[part].search(line) for line in list(logs[part])) if m]
                if found:
                    links[part] = found[0]
            return len(links) == len(PARTS)
        wait_for("every part's control link", printed, DEADLINE)
        return links

    @staticmethod
    def read_log(launch: "subprocess.Popen[str]", log: List[str]) -> None:
        assert launch.stdout is not None
        for line in launch.stdout:
            log.append(line)

    def laid_out(self, browser: Browser, width: int, height: int, scale: float) -> None:
        browser.wait(f"the page laid out at {width}x{height}",
                     "document.getElementById('scene-canvas').width === Math.round(document.getElementById("
                     f"'scene-canvas').clientWidth * {scale}) && document.documentElement.clientWidth === {width}"
                     " && new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(() => done(true))))",
                     DEADLINE)

    def check(self, browser: Browser, where: str, width: int, height: int) -> None:
        """The rules' breaches, kept to be told all at once (every part and size: the whole picture)."""
        self.breaches += [f"{where}: {line}" for line in browser.evaluate(f"{RULES}({min_text(width, height)})")]

    def test_every_part(self) -> None:
        begun = time.monotonic()
        self.browser = browser = Browser(1600, 900)
        checks = 0
        links = self.start_all()
        rospy.init_node("web_layout_test", anonymous=True, disable_signals=True)
        for part in PARTS:
            url = links[part]
            config = load_config(os.path.join(ROOT, "config", part_config(part)))
            bodies = sorted(config["bodies"])
            browser.resize(1600, 900, 1, False)
            browser.navigate(url)
            browser.wait("every body", f"window.rbs && rbs.world && Object.keys(rbs.world.bodies).length === "
                         f"{len(bodies)} && rbs.control", DEADLINE)
            rospy.wait_for_service(f"/{part}/sim/step", timeout=DEADLINE)
            step = rospy.ServiceProxy(f"/{part}/sim/step", Step)
            now = 0.0
            rate = float(config.get("rate", 1000.0))
            for instant in INSTANTS:
                answer = step(round((instant - now) * rate))
                self.assertTrue(answer.success, answer.message)
                now = answer.t
                browser.wait(f"t = {now} drawn", f"Object.keys(rbs.drawn).length === {len(bodies)} && "
                             f"Object.values(rbs.drawn).every((d) => d.t === {now!r})", DEADLINE)
                for size, (width, height, scale, mobile) in SIZES.items():
                    browser.resize(width, height, scale, mobile)
                    self.laid_out(browser, width, height, scale)
                    self.check(browser, f"part:={part} t = {now} at {size}", width, height)
                    checks += 1
                    if instant == INSTANTS[-1] or part == "slip":
                        browser.screenshot(os.path.join(ARGS.out_dir, f"web_{part}_{size}_t{instant}.png"))
                if part == "above" and instant >= 1.4325:
                    places = browser.evaluate("Object.fromEntries(Object.entries(rbs.finishes)"
                                              ".map(([b, f]) => [b, f && f.place]))")
                    self.assertEqual(places, {body: 1 for body in bodies}, "a tie shares a place")
                    shown = [t["text"] for t in browser.evaluate("rbs.texts") if t["canvas"] == "scene-canvas"]
                    for body in bodies:
                        self.assertTrue(any(t.startswith(f"{body}: =1st,") for t in shown), shown)
                self.check_finishes(browser, config)
                if part == "slip" and instant == INSTANTS[-1]:
                    self.check_slip_marks(browser, config)
            if part == "below":  # the slopes a lesson's key allows, from nearly flat to nearly upright
                for angle in ANGLES:
                    self.set_angle(browser, angle)
                    for size, (width, height, scale, mobile) in SIZES.items():
                        browser.resize(width, height, scale, mobile)
                        self.laid_out(browser, width, height, scale)
                        self.check(browser, f"part:={part} sphere at {angle} rad at {size}", width, height)
                        checks += 1
                    browser.screenshot(os.path.join(ARGS.out_dir, f"web_{part}_angle{angle}.png"))
                self.check_part_switch(browser, "above")
            for width in WIDTHS:  # the class's page, at every width
                height = max(640, round(width * 9 / 16)) if width >= 1024 else 844
                browser.resize(width, height, 1, width < 1024)
                self.laid_out(browser, width, height, 1)
                self.check(browser, f"part:={part} t = {now} at {width}x{height}", width, height)
                checks += 1
        print(f"{checks} layouts checked in {time.monotonic() - begun:.1f} s", file=sys.stderr)
        self.assertEqual(self.breaches, [], "\n".join(self.breaches))

    def set_angle(self, browser: Browser, angle: float) -> None:
        """The teacher's Set of the sphere's incline_angle, drawn (the world's keys, then its panel)."""
        browser.resize(1600, 900, 1, False)
        browser.choose("set-body", "sphere")
        browser.choose("set-key", "incline_angle")
        browser.type_into("set-value", repr(angle))
        sent = browser.evaluate("rbs.sent.length")
        browser.click("set")
        request = browser.wait("the request", f"rbs.sent[{sent}]", DEADLINE)
        reply = browser.wait("its reply", f"rbs.replies.find((r) => r.id === {request['id']})", DEADLINE)
        self.assertTrue(reply["ok"], reply)
        browser.wait(f"the slope at {angle} rad drawn", f"rbs.world.bodies.sphere.incline_angle === {angle!r} && "
                     f"rbs.panels.sphere.phi === {angle!r}", DEADLINE)

    def check_part_switch(self, browser: Browser, part: str) -> None:
        """The teacher's choice of another lesson part: every body's lesson keys as its config has them, the
        part named on the page, and a state of the new race drawn."""
        browser.resize(1600, 900, 1, False)
        self.assertEqual(browser.evaluate("document.getElementById('part').textContent"), "",
                         "the sphere's slope was changed: no part's keys")
        sent = browser.evaluate("rbs.sent.length")
        browser.choose("part-choice", part)
        request = browser.wait("the request", f"rbs.sent[{sent}]", DEADLINE)
        self.assertEqual(request["op"], "part")
        reply = browser.wait("its reply", f"rbs.replies.find((r) => r.id === {request['id']})", DEADLINE)
        self.assertTrue(reply["ok"], reply)
        browser.wait(f"part {part} on the page", f"rbs.world.part === {part!r} && "
                     f"document.getElementById('part').textContent === 'part: {part}'", DEADLINE)
        config = load_config(os.path.join(ROOT, "config", part_config(part)))
        world = browser.evaluate("rbs.world.bodies")
        for body, keys in config["bodies"].items():
            for key in ("incline_angle", "mu_s", "mu_d"):
                self.assertEqual(world[body][key], keys[key], f"{body}.{key}")
        step = rospy.ServiceProxy("/below/sim/step", Step)
        t = step(100).t
        browser.wait("the new race drawn", f"Object.values(rbs.drawn).every((d) => d.t === {t!r})", DEADLINE)
        self.check(browser, f"part:={part} from the teacher's page", 1600, 900)
        browser.screenshot(os.path.join(ARGS.out_dir, f"web_part_{part}_from_page.png"))

    def check_finishes(self, browser: Browser, config: Dict[str, Any]) -> None:
        """Every racer the node says finished (its board): drawn at rest at the end of its slope, the page's
        finish instant at the node's closed form (the first lap starts at t = 0; the board gives it to 0.1 ms),
        and its label with its arrival speed, 2 L / t for one released from rest (constant acceleration from
        rest to L in t)."""
        finishes = browser.evaluate("rbs.finishes")
        arrivals = browser.evaluate("rbs.arrivals")
        drawn = browser.evaluate("rbs.drawn")
        shown = [t["text"] for t in browser.evaluate("rbs.texts") if t["canvas"] == "scene-canvas"]
        for body, finish in finishes.items():
            if not finish:
                continue
            b = with_defaults(config["bodies"][body])
            self.assertEqual((drawn[body]["mode"], drawn[body]["v"], drawn[body]["x"]),
                             ("finished", 0.0, b["incline_length"]), f"{body} stands at the line")
            self.assertIn(body, arrivals, f"{body}: no finish instant")
            arrival = arrivals[body]
            if finish["closed_form"] is not None:  # the board's, to 0.1 ms
                self.assertAlmostEqual(arrival["t"], finish["closed_form"], delta=0.5e-4 + 1e-12,
                                       msg=f"{body}'s finish")
            if float(b.get("v0", 0.0)) == 0.0 and float(b.get("omega0", 0.0)) == 0.0:
                self.assertAlmostEqual(arrival["speed"], 2 * b["incline_length"] / arrival["t"], delta=1e-9,
                                       msg=f"{body}'s arrival speed")
            self.assertIn(f"at {arrival['speed']:.2f} m/s", " ".join(shown), f"{body}'s label")

    def check_slip_marks(self, browser: Browser, config: Dict[str, Any]) -> None:
        """Each racer's slip -> roll dot at the closed form's instant from its launch (config/race_slip.yaml:
        all three before INSTANTS[-1])."""
        g = float(config.get("gravity", 9.8))
        for body, b in config["bodies"].items():
            browser.choose("plot-body", body)
            browser.wait(f"the plots of {body}", f"rbs.plotLast.body === {json.dumps(body)}", DEADLINE)
            mark = browser.evaluate("rbs.plotLast.points.slip_to_roll")
            c, phi = INERTIA_FACTORS[b["shape"]], b["incline_angle"]
            instant = ((b["v0"] + b["omega0"] * b["radius"])
                       / (b["mu_d"] * g * math.cos(phi) * (1 + 1 / c) - g * math.sin(phi)))
            self.assertLess(instant, INSTANTS[-1])
            self.assertIsNotNone(mark, f"{body}: no slip -> roll mark")
            self.assertAlmostEqual(mark[0], instant, delta=1e-9, msg=f"{body}'s slip -> roll")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir")
    ARGS, rest = parser.parse_known_args()
    unittest.main(argv=[sys.argv[0]] + rest)
