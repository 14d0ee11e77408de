#!/usr/bin/env python3
"""The Simulation panel during a replay: playback.launch (rosbag play --clock, rviz/sim.rviz) of a run that
simulate --bag recorded, started paused, under Xvfb (test/pictures/rviz_screenshot.sh with
RVIZ_SCRIPT=rviz_playback.py), the panel driven with xdotool.
- rviz loads the panel with no ERROR line; it finds every body of the recording from the played state
  topics, and its status line says it shows a replay of a recording;
- Step, Reset, Spawn (its name and kind) and every body's Delete are disabled, Pause and Run are not;
- Run starts the player (it was started with --pause): the panel's t advances;
- Pause stops it: the player's /clock stands still (the same time again and again) and the panel's t with
  it, and the panel says paused; Run: /clock and the panel's t go on;
- at the end of the bag the player ends, the panel says the recording ended at its last t, and rviz stays.
Widgets are found through the panel's RBS_PANEL_LAYOUT file (rviz_panel.Panel). Exit 0 when every check
passes, 1 otherwise; writes OUT (a screenshot at the end), OUT's stem + "_paused.png" (while paused) and
OUT's stem + ".txt" (the findings)."""
import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from typing import Any, Optional

from rigid_body_sim.sim_tools import load_config

import rviz_screenshot as shot
from rviz_panel import Findings, Panel, run_launched

HERE = os.path.dirname(os.path.abspath(__file__))
PACKAGE = os.path.dirname(os.path.dirname(HERE))

DURATION = 6.0  # simulated seconds recorded
STALLED_CLOCKS = 100  # /clock messages at one time in a row: the player stands (paused, it sends 100 a second)
CHANGES = ["step", "step_count", "reset", "spawn", "spawn_name", "spawn_kind"]  # disabled in a replay


class Clock:
    """The player's /clock: the latest time and how many messages in a row carried it."""

    def __init__(self, rospy: Any) -> None:
        from rosgraph_msgs.msg import Clock as ClockMsg
        self.latest: Optional[float] = None
        self.repeats = 0
        self.subscriber = rospy.Subscriber("/clock", ClockMsg, self.on_clock, queue_size=100)

    def on_clock(self, msg: Any) -> None:
        t = msg.clock.to_sec()
        self.repeats = self.repeats + 1 if t == self.latest else 1
        self.latest = t


def panel_t(panel: Panel) -> Optional[float]:
    """The t on the panel's clock line, or None while it shows none."""
    found = re.match(r"t = ([0-9.]+) s", panel.text("clock"))
    return float(found.group(1)) if found else None


def main() -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--config", default=os.path.join(PACKAGE, "config", "demo.yaml"))
    parser.add_argument("--simulate", required=True, help="the simulate executable (records the bag)")
    parser.add_argument("--out", required=True, help="the screenshot at the end (PNG)")
    parser.add_argument("--timeout", type=float, default=180.0, help="wall seconds for everything")
    args = parser.parse_args()
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    stem = os.path.splitext(args.out)[0]
    folder = tempfile.mkdtemp(prefix="rviz_playback_")
    bag = os.path.join(folder, "run.bag")
    subprocess.run([args.simulate, args.config, "--duration", repr(DURATION), "--bag", bag,
                    "--out-dir", folder], check=True, stdout=subprocess.DEVNULL)
    layout = os.path.join(folder, "panel_layout.txt")
    os.environ["RBS_PANEL_LAYOUT"] = layout
    try:
        findings = run_launched(["playback.launch", f"bag:={bag}", "start_paused:=true"], args.out,
                                lambda launch, findings: run(args, stem, Panel(layout), launch, findings))
    finally:
        subprocess.run(["rm", "-rf", folder], check=False)
    with open(stem + ".txt", "w") as f:
        f.write("\n".join(findings.lines) + "\n")
    return 0 if findings.ok else 1


def run(args: argparse.Namespace, stem: str, panel: Panel, launch: Any, findings: Findings) -> None:
    import rosgraph
    import rospy

    start = time.monotonic()

    def left() -> float:
        return max(1.0, args.timeout - (time.monotonic() - start))

    def wait(what: str, predicate: Any, timeout: float = 20.0) -> None:
        shot.wait_while_running(what, predicate, min(timeout, left()), launch)

    bodies = list(load_config(args.config)["bodies"])
    master = rosgraph.Master("/rviz_playback_test")
    wait("the ROS master", master.is_online)
    rospy.init_node("rviz_playback_test", disable_signals=True)
    clock = Clock(rospy)

    # --- loaded, paused at the start: the bodies from the played state topics, the replay named
    wait("the panel (its layout file)", lambda: "pause" in panel.widgets(), 90.0)
    wait("a section for every body of the recording", lambda: all(f"{b}.motion" in panel.widgets() for b in bodies))
    wait("the status line to name the replay", lambda: "replay of a recording" in panel.text("status"))
    findings.check(f"the panel finds the recording's {len(bodies)} bodies; status: {panel.text('status')}", True)
    errors = shot.rviz_error_lines()
    findings.check(f"rviz loads the panel: no ERROR line in its log ({len(errors)})", not errors)
    for line in errors:
        findings.check(f"  {line[:100]}", False)
    disabled = [name for name in CHANGES + [f"{b}.delete" for b in bodies] if not panel.enabled(name)]
    findings.check(f"disabled in a replay: {', '.join(disabled)}", len(disabled) == len(CHANGES) + len(bodies))
    findings.check("  Pause and Run enabled", panel.enabled("pause") and panel.enabled("run"))
    findings.check(f"started paused (start_paused): no state yet ({panel.text('clock')})", panel_t(panel) is None)

    # --- Run: the player plays, the panel's t advances
    panel.click("run")
    wait("a t on the panel", lambda: panel_t(panel) is not None)
    first = panel_t(panel) or 0.0
    wait("the panel's t to advance by 1 s", lambda: (panel_t(panel) or 0.0) >= first + 1.0)
    findings.check(f"Run: the panel's t advances ({first:.3f} s, then {panel_t(panel):.3f} s)", True)

    # --- Pause: /clock stands, and the panel's t with it
    panel.click("pause")
    wait("the panel to say paused", lambda: panel.text("clock").endswith("paused"))
    wait(f"{STALLED_CLOCKS} /clock messages in a row at one time", lambda: clock.repeats >= STALLED_CLOCKS)
    stood = clock.latest or 0.0
    t_paused = panel_t(panel) or 0.0
    seen = clock.repeats
    wait(f"{STALLED_CLOCKS} more /clock messages", lambda: clock.repeats >= seen + STALLED_CLOCKS)
    findings.check(f"Pause: the player's /clock stands at {stood:.3f} s ({clock.repeats} messages in a row)",
                   clock.latest == stood)
    findings.check(f"  the panel's t stands with it: {panel.text('clock')}",
                   panel_t(panel) == t_paused and panel.text("clock").endswith("paused"))
    findings.check(f"  the status line: {panel.text('status')}", panel.text("status").endswith(": paused"))
    subprocess.run(["import", "-window", "root", stem + "_paused.png"], check=True)

    # --- Run: /clock and the panel's t go on
    panel.click("run")
    wait("/clock to go on", lambda: (clock.latest or 0.0) > stood + 0.5)
    wait("the panel's t to go on", lambda: (panel_t(panel) or 0.0) > t_paused + 0.5)
    findings.check(f"Run: /clock and the panel's t go on ({panel.text('clock')})",
                   not panel.text("clock").endswith("paused"))

    # --- the end of the bag: the player ends, rviz stays, the panel says so
    wait("the player to end", lambda: not node_exists(master, "/player"), DURATION + 30.0)
    wait("the panel to say the recording ended", lambda: "end of recording" in panel.text("status"))
    end_t = panel_t(panel)
    findings.check(f"the end: {panel.text('status')} ({panel.text('clock')})",
                   end_t is not None and abs(end_t - DURATION) < 1e-9
                   and panel.text("status") == f"end of recording at t = {DURATION:.3f} s")
    findings.check("  Pause and Run disabled", not panel.enabled("pause") and not panel.enabled("run"))
    findings.check("  rviz still running (roslaunch and its /rviz node)",
                   launch.poll() is None and node_exists(master, "/rviz"))


def node_exists(master: Any, name: str) -> bool:
    try:
        master.lookupNode(name)
        return True
    except Exception:  # rosgraph.MasterError: unknown node
        return False


if __name__ == "__main__":
    sys.exit(main())
