#!/usr/bin/env python3
"""The Plots tab's projector window in a real rviz (test/pictures/rviz_screenshot.sh with
RVIZ_SCRIPT=rviz_plots.py in its 1600x900 screen): sim.launch with rviz/sim.rviz on config/demo.yaml's bowler,
then on config/race_below.yaml's sphere.
- Projector view opens a window of the screen's size with every chart of the body, each at least 600 x 300 px,
  its title, axis titles and tick labels at least 14 px; the y ticks distinct numbers, none "-0";
- after a Reset (~reset) every chart's t axis starts at 0 again, its points only the states since;
- the slip-to-roll and finish marks are the node's events (~get_events) at their instants and speeds, with
  their notes (the instant since the Reset; the lap time beside the closed form's); the first slip-to-roll
  at the closed form's instant from the bowler's initial conditions (rviz_panel.py's
  closed_form_slip_to_roll) to rounding;
- Save PNG writes the charts (to RBS_PLOTS_PNG) as a PNG of the size the charts have in the window;
- in a race, each new lap starts a new line of each series, at the racer's restarts (its events: where its
  states jump back), and its finishes are marked with their places and times.
Widgets are found through the panel's RBS_PANEL_LAYOUT file. Exit 0 when every check passes, 1 otherwise;
writes OUT (the window at the end, the bowler), OUT's stem + "_race.png" (the race), OUT's stem + "_saved.png"
(Save PNG's) and OUT's stem + ".txt" (the findings). Each launch runs in a process of its own."""
import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from typing import Any, Dict, List, Tuple

from rigid_body_sim.sim_tools import load_config

import rviz_screenshot as shot
from rviz_panel import (HERE, Findings, Panel, check_marks, closed_form_slip_to_roll, event_value, finish_note,
                        run_launched, xdotool)

PACKAGE = os.path.dirname(os.path.dirname(HERE))

MIN_CHART = (600, 300)  # px, each chart in the projector window
MIN_TEXT_PX = 14
NEGATIVE_ZERO = re.compile(r"-0(\.0*)?")
PLOT_WINDOW = 10.0  # simulated s the charts keep (kPlotWindow)


class Charts:
    """The plots as the panel writes them: each chart's line and each series' last point and lines."""

    def __init__(self, panel: Panel) -> None:
        self.panel = panel

    def charts(self) -> List[Dict[str, Any]]:
        found = []
        lines = self.panel.lines()
        for i in range(3):
            line = lines.get(f"plot.chart{i}")
            if line is None:
                break
            title, axis_title, x_tick, y_tick, x_min, x_max, *ticks = line[6].split(" ") + [""]
            found.append({"size": (int(line[3]), int(line[4])), "title_px": int(title),
                          "axis_title_px": int(axis_title), "x_tick_px": int(x_tick), "y_tick_px": int(y_tick),
                          "x": (float(x_min), float(x_max)), "y_ticks": [t for t in ticks[0].split(",") if t]})
        return found

    def last(self, series: str) -> Tuple[int, float, float]:
        parts = self.panel.text(f"plot.{series}").split()
        return (int(parts[0]), float(parts[1]), float(parts[2])) if len(parts) == 3 else (0, float("nan"), 0.0)

    def lines(self, series: str) -> int:
        text = self.panel.text(f"plot.{series}.lines")
        return int(text) if text else 0


PARTS = {"bowler": "demo.yaml", "race": "race_below.yaml"}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", required=True, help="the screenshot of the bowler's window (PNG)")
    parser.add_argument("--timeout", type=float, default=120.0, help="wall seconds for each launch")
    parser.add_argument("--part", choices=["all"] + list(PARTS), default="all",
                        help="one launch (a process of its own: rospy knows one master), or both in turn")
    args = parser.parse_args()
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    stem = os.path.splitext(args.out)[0]
    if args.part == "all":
        failed = 0
        for part in PARTS:
            failed += subprocess.run([sys.executable, os.path.abspath(__file__), "--out", args.out, "--timeout",
                                      repr(args.timeout), "--part", part], check=False).returncode != 0
        with open(stem + ".txt", "w") as f:
            for part in PARTS:
                with open(f"{stem}_{part}.txt") as found:
                    f.write(f"--- {PARTS[part]}\n" + found.read())
        return 1 if failed else 0
    layout = tempfile.NamedTemporaryFile(prefix="panel_layout_", suffix=".txt", delete=False).name
    os.remove(layout)  # the panel writes it
    os.environ["RBS_PANEL_LAYOUT"] = layout
    os.environ["RBS_PLOTS_PNG"] = stem + "_saved.png"
    if args.part == "bowler" and os.path.exists(os.environ["RBS_PLOTS_PNG"]):  # the one that saves
        os.remove(os.environ["RBS_PLOTS_PNG"])
    path = os.path.join(PACKAGE, "config", PARTS[args.part])
    check = check_bowler if args.part == "bowler" else check_race
    try:
        findings = run_launched(["sim.launch", f"config:={path}", "rviz:=true"],
                                args.out if args.part == "bowler" else stem + "_race.png",
                                lambda launch, findings: check(Session(args, Panel(layout), launch),
                                                               load_config(path), findings))
    finally:
        if os.path.exists(layout):
            os.remove(layout)
    with open(f"{stem}_{args.part}.txt", "w") as f:
        f.write("\n".join(findings.lines) + "\n")
    return 0 if findings.ok else 1


class Session:
    """One launch: the panel, the node's services, the test's own states of one body, and waits that end
    with the launch."""

    def __init__(self, args: argparse.Namespace, panel: Panel, launch: Any) -> None:
        self.args, self.panel, self.launch = args, panel, launch
        self.start = time.monotonic()
        self.charts = Charts(panel)
        self.states: List[Any] = []

    def wait(self, what: str, predicate: Any, timeout: float = 20.0) -> None:
        left = max(1.0, self.args.timeout - (time.monotonic() - self.start))
        shot.wait_while_running(what, predicate, min(timeout, left), self.launch)

    def connect(self, body: str, state_type: Any) -> None:
        """The master, this test's node, its subscription to the body's states; the panel in sight."""
        import rosgraph
        import rospy
        master = rosgraph.Master("/rviz_plots_test")
        self.wait("the ROS master", master.is_online)
        rospy.init_node("rviz_plots_test", disable_signals=True)
        rospy.Subscriber(f"/sim/{body}/state", state_type, self.states.append, queue_size=1000)
        self.wait("this test to subscribe to the states",
                  shot.subscribed(master, "/rviz_plots_test", [f"/sim/{body}/state"]), 90.0)
        self.wait("the panel (its layout file)", lambda: "pause" in self.panel.widgets(), 90.0)

    def events(self, body: str) -> List[Any]:
        """The body's events of the node's run (since its start or its last reset), from ~get_events."""
        import rospy
        from rigid_body_sim.srv import GetEvents
        return [e for e in rospy.ServiceProxy("/sim/get_events", GetEvents)().events if e.body == body]

    def call(self, service: str) -> Any:
        import rospy
        from std_srvs.srv import Empty
        return rospy.ServiceProxy(f"/sim/{service}", Empty)()

    def pause(self, body_series: str) -> float:
        """~pause, then ~step 1 (refused until paused): the t where the node stands, once the panel plots it."""
        import rospy
        from rigid_body_sim.srv import Step
        step = rospy.ServiceProxy("/sim/step", Step)
        self.call("pause")
        answers: List[Any] = []

        def stepped() -> bool:  # ~step refuses while the simulation runs
            answers.append(step(1))
            return bool(answers[-1].success)
        self.wait("~step to succeed after ~pause", stepped)
        t = float(answers[-1].t)
        self.wait(f"the state at t = {t:.3f} s", lambda: any(m.t == t for m in self.states))
        self.wait("the plot at the paused t", lambda: self.charts.last(body_series)[1] == t)
        return t

    def open_window(self, body: str) -> None:
        """The Plots tab, the body chosen, then Projector view: its window at the screen's size."""
        self.panel.click("tab.Plots")
        self.wait("the Plots tab", lambda: self.panel.in_sight("plot_body"))
        self.panel.click("plot_body")
        xdotool("type", "--delay", "40", body)  # the list's keyboard search
        xdotool("key", "Return")
        self.wait(f"{body} chosen for the plots", lambda: self.panel.text("plot_body") == body)
        self.panel.click("plots_projector")
        self.wait("the projector window at the screen's size (1600 x 900)",
                  lambda: self.panel.widgets().get("plots_window", (0, 0, 0, 0, ""))[2:4] == (1600, 900))


def check_window(session: Session, findings: Findings) -> None:
    """Every chart's size and text in the projector window; its y ticks distinct numbers."""
    session.wait("every chart laid out in the window, with ticks",
                 lambda: all(c["size"][0] > 0 and c["y_ticks"] for c in session.charts.charts()))
    for i, chart in enumerate(session.charts.charts()):
        width, height = chart["size"]
        findings.check(f"chart {i}: {width} x {height} px (at least {MIN_CHART[0]} x {MIN_CHART[1]})",
                       width >= MIN_CHART[0] and height >= MIN_CHART[1])
        sizes = {key: chart[key] for key in ("title_px", "axis_title_px", "x_tick_px", "y_tick_px")}
        findings.check(f"  text at least {MIN_TEXT_PX} px: {sizes}", min(sizes.values()) >= MIN_TEXT_PX)
        ticks = chart["y_ticks"]
        findings.check(f"  y ticks distinct numbers, none -0: {ticks}",
                       len(ticks) >= 3 and len(set(ticks)) == len(ticks)
                       and all(not NEGATIVE_ZERO.fullmatch(t) for t in ticks) and all(is_number(t) for t in ticks))


def is_number(text: str) -> bool:
    try:
        float(text)
        return True
    except ValueError:
        return False


def check_bowler(session: Session, config: Dict[str, Any], findings: Findings) -> None:
    from rigid_body_sim.msg import RollerState
    session.connect("bowler", RollerState)
    errors = shot.rviz_error_lines()
    findings.check(f"rviz loads the panel: no ERROR line in its log ({len(errors)})", not errors)
    session.open_window("bowler")
    check_window(session, findings)
    # The window scrolled on (the node's t past 12 s), then a Reset: the axis starts at 0 again.
    session.wait("the t axis past 12 s", lambda: session.charts.charts()[0]["x"][1] > 12, 30.0)
    before = [c["x"] for c in session.charts.charts()]
    t_reset = session.pause("friction")
    session.call("reset")
    session.call("unpause")
    session.wait("the slip-to-roll mark after the Reset", lambda: session.charts.last("slip_to_roll")[1] > t_reset)
    # Its lap's end, 1.2 s after it: the picture shows both phases and the finish.
    session.wait("the finish mark after the Reset", lambda: session.charts.last("finished")[1] > t_reset)
    t_end = session.pause("friction")
    after = [c["x"] for c in session.charts.charts()]
    since = t_end - t_reset
    findings.check(f"Reset at t = {t_reset:.3f} s: every t axis from {before} to {after} ({since:.3f} s since)",
                   all(x[0] > 0 for x in before) and all(x == (0.0, 10.0) for x in after) and since < 10)
    states = [m for m in session.states if t_reset < m.t <= t_end]
    counts = {series: session.charts.last(series)[0] for series in ("v", "minus_omega_r", "friction", "energy")}
    findings.check(f"  each series holds the {len(states)} states since the Reset, none before: {counts}",
                   all(count == len(states) for count in counts.values()))
    run = session.events("bowler")  # since the Reset
    slips = [e for e in run if e.kind == "slip_to_roll"]
    finishes = [e for e in run if e.kind == "finished"]
    if slips and finishes:
        session.wait("the marks up to the node's last events", lambda: session.charts.last("slip_to_roll")[1]
                     >= slips[-1].t and session.charts.last("finished")[1] >= finishes[-1].t)
        check_marks(session.panel, "slip_to_roll", slips,
                    [f"slip \u2192 roll at {e.t - t_reset:.3f} s" for e in slips], findings)
        closed = closed_form_slip_to_roll(config["bodies"]["bowler"], float(config["gravity"]))
        first = slips[0].t - t_reset
        findings.check(f"  the first {first:.9f} s after the Reset: the closed form's {closed:.9f} s to rounding "
                       f"(1e-9 s)", abs(first - closed) <= 1e-9)
        check_marks(session.panel, "finished", finishes, [finish_note(e) for e in finishes], findings)
    else:
        findings.check(f"a slip-to-roll and a finish since the Reset ({len(slips)}, {len(finishes)})", False)
    check_window(session, findings)  # the ticks of a slipping-then-rolling run
    # Save PNG: the charts as the window shows them.
    path = os.environ["RBS_PLOTS_PNG"]
    session.panel.click("plots_save")
    session.wait("the saved note", lambda: session.panel.text("plots_saved").startswith("saved "))
    window = session.panel.widgets()["plots_window"]
    height, width = shot.read_png(path).shape[:2]
    findings.check(f"Save PNG: {session.panel.text('plots_saved')}; the window {window[2]} x {window[3]} px",
                   (width, height) == (window[2], window[3]) == (1600, 900))


def check_race(session: Session, config: Dict[str, Any], findings: Findings) -> None:
    from rigid_body_sim.msg import RollerState
    session.connect("sphere", RollerState)
    session.open_window("sphere")
    check_window(session, findings)
    session.wait("a new lap on the charts", lambda: session.charts.lines("v") >= 2, 40.0)
    t_end = session.pause("v")
    count = session.charts.last("v")[0]
    plotted = [m for m in session.states if m.t <= t_end][-count:]
    run = session.events("sphere")
    restarts = [e.t for e in run if e.kind == "lap_restarted" and plotted[0].t < e.t <= t_end]
    jumps = sum(1 for a, b in zip(plotted, plotted[1:]) if b.x < a.x - 1.0)
    lines = {series: session.charts.lines(series) for series in ("v", "minus_omega_r", "friction", "energy")}
    findings.check(f"race: {len(restarts)} restarts {restarts} among the {count} states plotted up to t = "
                   f"{t_end:.3f} s ({jumps} jumps back); lines drawn {lines}",
                   bool(restarts) and jumps == len(restarts) and all(n == 1 + len(restarts) for n in lines.values()))
    finishes = [e for e in run if e.kind == "finished" and e.t >= t_end - PLOT_WINDOW]
    if finishes:
        session.wait("the finish marks up to the node's last", lambda: session.charts.last("finished")[1]
                     >= finishes[-1].t)
        check_marks(session.panel, "finished", finishes, [finish_note(e) for e in finishes], findings)
        place = event_value(finishes[-1].values, "place")
        findings.check(f"  a racer's finish gives its place: {place}", place is not None)
    else:
        findings.check("a finish of the sphere in the window", False)
    findings.check(f"  the t axis counts from the start: {session.charts.charts()[0]['x']}",
                   session.charts.charts()[0]["x"][1] >= t_end - 0.1)


if __name__ == "__main__":
    sys.exit(main())
