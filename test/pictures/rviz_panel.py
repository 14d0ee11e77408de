#!/usr/bin/env python3
"""The Simulation panel (rigid_body_sim/SimPanel) in a real rviz, driven with xdotool: sim.launch with
rviz/sim.rviz on config/demo.yaml, under Xvfb (test/pictures/rviz_screenshot.sh with RVIZ_SCRIPT=rviz_panel.py).
- rviz loads the panel with no plugin error, and it shows a section for every body;
- every number shows its unit (sim_tools.KEY_UNITS), an angle also in degrees (radians * 180 / pi); a
  roller's section its critical angle atan(mu_s (1 + c) / c) and whether its slope is above it;
- Pause stops simulated time (~step now succeeds; no later state; the node's ~paused says so and the panel's
  clock says paused); Run starts it again and the clock gives the real-time factor;
- Reset, a rod k typed into the rod's section and Step with a typed count: the server shows k, and the rod
  after the steps is, field for field, simulate's rod (config/demo.yaml's rod with that k) at that time;
- a refused k (-5) snaps back to the value that runs, the node logs one WARN line, and the panel shows the
  refusal (its words in the panel's text, its colour in the picture); a change accepted while paused says
  it shows at the next Step or Run, until it does; after Step the clock says paused (no real-time factor
  from a ~step's states), and each energy shown is the documented formula with its zero, from the state;
- the mouse wheel over a field without focus scrolls the sections (their scroll position) and changes
  nothing: the field, the node's world and its servers keep the value;
- Spawn with a typed name and a chosen shape adds that body to the node's world (~get_config) and its
  section to the panel; a spawn under a taken name is refused and adds nothing; the new body's Delete
  takes it out of the world and its section out of the panel; a block spawned from the same list shows its
  motion and its critical angle atan(mu_s) with its verdict;
- the Plots tab: the last point of each series is the test's own state; after a Reset the bowler's
  slip-to-roll and finish marks are the node's events (~get_events), at their instants and speeds, with
  their notes (the instant since the Reset; the lap time and the closed form's), the first slip-to-roll at
  the closed form's instant to rounding; its lines part at its restarts.
Widgets are found through the panel's RBS_PANEL_LAYOUT file. Exit 0 when every check passes, 1 otherwise;
writes OUT (a screenshot at the end) and OUT's stem + ".txt" (the findings)."""
import argparse
import csv
import math
import os
import re
import subprocess
import sys
import tempfile
import time
from typing import Any, Callable, Dict, List, Tuple

import numpy as np
import yaml
from rigid_body_sim.sim_tools import KEY_UNITS, body_type, free_port, load_config, state_fields, wait_for

import rviz_screenshot as shot
from rviz_log import output_tails

HERE = os.path.dirname(os.path.abspath(__file__))
PACKAGE = os.path.dirname(os.path.dirname(HERE))

REFUSAL_COLOUR = (230, 90, 60)  # the panel's refusal text (kRefusalStyle, body_section.h)
TYPED_K = 2000.0
STEPS = 1500  # 1.5 s: the rod reaches the floor, and k matters
SHAPE_C = {"sphere": 2 / 5, "cylinder": 1 / 2, "ring": 1.0, "spherical_shell": 2 / 3}  # the text's I / (M R^2)
PAUSED_NOTE = "the mode and energy above follow it at the next Step or Run"
ROD_ZERO = "(potential 0 with its centre at floor level)"
ROLLER_ZERO = "(potential 0 with its centre at the slope's top)"
Widget = Tuple[int, int, int, int, str]  # x, y, width, height (the part in sight), text


class Panel:
    """The panel's widgets, read from its layout file, and xdotool's hands on them."""

    def __init__(self, layout_file: str) -> None:
        self.layout_file = layout_file

    def lines(self) -> Dict[str, List[str]]:
        """Each widget's line: name, x, y, width, height, enabled (1 or 0), text."""
        found: Dict[str, List[str]] = {}
        try:
            with open(self.layout_file, encoding="utf-8") as f:
                for line in f:
                    parts = line.rstrip("\n").split(" ", 6)
                    if len(parts) >= 6:
                        found[parts[0]] = parts + [""] * (7 - len(parts))
        except FileNotFoundError:
            pass
        return found

    def widgets(self) -> Dict[str, Widget]:
        return {name: (int(p[1]), int(p[2]), int(p[3]), int(p[4]), p[6]) for name, p in self.lines().items()}

    def enabled(self, name: str) -> bool:
        return self.lines().get(name, ["", "", "", "", "", "0"])[5] == "1"

    def text(self, name: str) -> str:
        return self.widgets().get(name, (0, 0, 0, 0, ""))[4]

    def in_sight(self, name: str) -> bool:
        w = self.widgets().get(name)
        return w is not None and w[2] >= 10 and w[3] >= 10

    def writes(self) -> int:
        """How many times the panel has written its layout (it does at every clock tick)."""
        text = self.text("layout.written")
        return int(text) if text else 0

    def fresh(self, timeout: float = 20.0) -> Dict[str, Widget]:
        """The widgets as laid out after this call began: the panel wrote its layout twice since, so a change
        made before (a longer status line pushing the sections down) is in the places read."""
        after = self.writes() + 2
        wait_for("the panel to write its layout anew", lambda: self.writes() >= after, timeout)
        return self.widgets()

    def click(self, name: str) -> None:
        x, y, w, h, _ = self.fresh()[name]
        if w < 10 or h < 10:
            raise RuntimeError(f"{name} is not in sight to be clicked ({w} x {h} px)")
        xdotool("mousemove", str(x + w // 2), str(y + h // 2), "click", "1")

    def type_into(self, name: str, text: str) -> None:
        """Clicks a field, replaces its text and presses Enter (the edit is done)."""
        self.click(name)
        xdotool("key", "ctrl+a")
        xdotool("type", "--delay", "40", "--", text)
        xdotool("key", "Return")

    def scroll_to(self, name: str, timeout: float) -> None:
        """Turns the mouse wheel over the sections' left margin (no field there) until `name` is in sight:
        up while it is above them, else down."""
        x, y, _, h, _ = self.fresh()["sections"]
        end = time.monotonic() + timeout
        while not self.in_sight(name):
            before = self.text("sections")  # the scroll position
            above = self.widgets()[name][1] < y  # as laid out after the last turn
            xdotool("mousemove", str(x + 3), str(y + h // 2), "click", "4" if above else "5")
            try:
                wait_for("the sections to move", lambda: self.text("sections") != before,
                         max(0.1, end - time.monotonic()))
            except TimeoutError:
                raise TimeoutError(f"{name} not in sight at the end of the panel's scrolling") from None


def xdotool(*args: str) -> None:
    subprocess.run(["xdotool", *args], check=True)


class Findings:
    def __init__(self) -> None:
        self.lines: List[str] = []
        self.ok = True

    def check(self, what: str, ok: bool) -> bool:
        self.lines.append(f"{'ok  ' if ok else 'FAIL'} {what}")
        self.ok = self.ok and ok
        print(self.lines[-1], flush=True)
        return ok


def simulated_rod(simulate: str, config_path: str, k: float, duration: float) -> Dict[str, float]:
    """simulate's rod (the config's rod alone, with k) at `duration`: its CSV's last row."""
    config = load_config(config_path)
    rod = dict(config["bodies"]["rod"], k=k)
    world = {key: value for key, value in config.items() if key != "bodies"}
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "rod.yaml")
        with open(path, "w") as f:
            yaml.safe_dump(dict(world, bodies={"rod": rod}), f)
        subprocess.run([simulate, path, "--duration", repr(duration), "--out-dir", folder], check=True,
                       stdout=subprocess.DEVNULL)
        with open(os.path.join(folder, "rod.csv")) as f:
            rows = list(csv.DictReader(f))
    return {key: float(value) for key, value in rows[-1].items()}


def run_launched(launch_args: List[str], out: str, run_it: Callable[[Any, Findings], None]) -> Findings:
    """roslaunch of this package's `launch_args` on a master of its own (its log beside the picture `out`),
    then run_it(launch, findings); whatever happened, the screenshot `out` and the launch stopped."""
    port = free_port()
    os.environ["ROS_MASTER_URI"] = f"http://127.0.0.1:{port}"
    findings = Findings()
    with open(os.path.splitext(out)[0] + "_roslaunch.log", "w") as log:
        launch = subprocess.Popen(["roslaunch", "-p", str(port), "rigid_body_sim"] + launch_args, stdout=log,
                                  stderr=subprocess.STDOUT)
        try:
            run_it(launch, findings)
        except (TimeoutError, RuntimeError) as error:
            log.flush()
            findings.check(f"no time-out: {error}\n{output_tails(log.name)}", False)
        finally:
            if os.environ.get("DISPLAY"):
                subprocess.run(["import", "-window", "root", out], check=False)
            launch.send_signal(2)
            try:
                launch.wait(timeout=20)
            except subprocess.TimeoutExpired:
                launch.kill()
    return findings


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--config", default=os.path.join(PACKAGE, "config", "demo.yaml"))
    parser.add_argument("--simulate", required=True, help="the simulate executable (the reference)")
    parser.add_argument("--out", required=True, help="the screenshot at the end (PNG)")
    parser.add_argument("--timeout", type=float, default=180.0, help="wall seconds for everything")
    args = parser.parse_args()
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    stem = os.path.splitext(args.out)[0]
    layout = tempfile.NamedTemporaryFile(prefix="panel_layout_", suffix=".txt", delete=False).name
    os.remove(layout)  # the panel writes it
    os.environ["RBS_PANEL_LAYOUT"] = layout
    try:
        findings = run_launched(["sim.launch", f"config:={args.config}", "rviz:=true"], args.out,
                                lambda launch, findings: run(args, Panel(layout), launch, findings))
    finally:
        if os.path.exists(layout):
            os.remove(layout)
    with open(stem + ".txt", "w") as f:
        f.write("\n".join(findings.lines) + "\n")
    return 0 if findings.ok else 1


def run(args: argparse.Namespace, panel: Panel, launch: Any, findings: Findings) -> None:
    import rosgraph
    import rospy
    from dynamic_reconfigure.msg import Config as ReconfigureConfig
    from rigid_body_sim.msg import RodState, RollerState
    from std_msgs.msg import Bool
    from rigid_body_sim.srv import GetConfig, GetEvents, Step
    from rosgraph_msgs.msg import Log

    start = time.monotonic()

    def left() -> float:
        return max(1.0, args.timeout - (time.monotonic() - start))

    def wait(what: str, predicate: Any, timeout: float = 20.0) -> None:
        shot.wait_while_running(what, predicate, min(timeout, left()), launch)

    config = load_config(args.config)
    master = rosgraph.Master("/rviz_panel_test")
    wait("the ROS master", master.is_online)
    rospy.init_node("rviz_panel_test", disable_signals=True)
    rods: List[Any] = []
    server_k: List[float] = []
    warnings: List[str] = []
    bowlers: List[Any] = []  # the roller whose energy has every term: launched spinning, off the slope's top
    paused_topic: List[bool] = []
    updates: Dict[str, int] = {name: 0 for name in config["bodies"]}  # parameter_updates per body
    rospy.Subscriber("/sim/rod/state", RodState, rods.append, queue_size=1000)
    rospy.Subscriber("/sim/bowler/state", RollerState, bowlers.append, queue_size=1000)
    rospy.Subscriber("/sim/paused", Bool, lambda m: paused_topic.append(m.data), queue_size=10)
    for name in config["bodies"]:
        rospy.Subscriber(f"/sim/{name}/parameter_updates", ReconfigureConfig,
                         lambda _, name=name: updates.__setitem__(name, updates[name] + 1), queue_size=10)
    rospy.Subscriber("/sim/rod/parameter_updates", ReconfigureConfig,
                     lambda c: server_k.extend(p.value for p in c.doubles if p.name == "k"), queue_size=10)
    rospy.Subscriber("/rosout", Log, lambda m: warnings.append(m.msg)
                     if m.name == "/sim" and m.level == Log.WARN else None, queue_size=100)
    # What the paused node publishes once (a step's state, ~paused) reaches a subscription made before it.
    wait("this test to subscribe to the states and ~paused", shot.subscribed(
        master, "/rviz_panel_test", ["/sim/rod/state", "/sim/bowler/state", "/sim/paused"]), 90.0)
    step_service = rospy.ServiceProxy("/sim/step", Step)
    get_config = rospy.ServiceProxy("/sim/get_config", GetConfig)

    def world_bodies() -> Dict[str, Any]:
        return dict(yaml.safe_load(get_config().yaml)["bodies"])

    # --- loaded: every body's section, no plugin error
    wait("the panel (its layout file)", lambda: "pause" in panel.widgets(), 90.0)
    wait("a section for every body", lambda: all(f"{name}.motion" in panel.widgets() for name in config["bodies"]))
    wait("states on the panel's clock", lambda: panel.text("clock").startswith("t = ") and "?" not in
         panel.text("clock"))
    errors = shot.rviz_error_lines()
    findings.check(f"rviz loads the panel: no ERROR line in its log ({len(errors)})", not errors)
    for line in errors:
        findings.check(f"  {line[:100]}", False)
    # A field is made when the server's descriptions come and filled when its config comes: check once filled.
    node_bodies = world_bodies()
    wait("every number's field showing the node's value",
         lambda: shows_world(panel.widgets(), config, node_bodies))
    check_units(panel.widgets(), config, findings)
    sideways = panel.text("sections").split()[-1]
    findings.check(f"  the sections fit the panel's width, units in sight (sideways scroll: {sideways})",
                   sideways == "0")
    for name, body in world_bodies().items():
        if body["type"] == "roller":
            wait(f"{name}'s critical angle", lambda name=name: panel.text(f"{name}.critical") != "")
            check_critical(panel.text(f"{name}.critical"), name, body, findings)

    # --- Pause: ~step now succeeds (it refuses while running), no state after it, the clock stopped
    probe: List[Any] = []

    def paused() -> bool:  # ~step refuses while the simulation runs
        probe.append(step_service(1))
        return bool(probe[-1].success)
    panel.click("pause")
    wait("~step to succeed after Pause", paused)
    t_paused = probe[-1].t
    wait(f"the state at t = {t_paused:.3f} s (~step publishes where it ends)",
         lambda: any(m.t == t_paused for m in rods))
    wait("the panel's clock paused at that time", lambda: panel.text("clock") == f"t = {t_paused:.3f} s paused")
    latest = max(m.t for m in rods)
    findings.check(f"Pause: no state after t = {t_paused:.3f} s (latest {latest:.3f} s); the panel shows it",
                   latest == t_paused)
    findings.check(f"  the node's ~paused says so ({paused_topic[-1:]}), and the clock: {panel.text('clock')}",
                   paused_topic[-1:] == [True])

    # --- Run: time goes on
    panel.click("run")
    wait("states after Run", lambda: max(m.t for m in rods) > t_paused + 0.5)
    wait("the real-time factor on the clock", lambda: "real-time factor" in panel.text("clock"))
    findings.check(f"Run: simulated time goes on; ~paused {paused_topic[-1:]}; the clock: {panel.text('clock')}",
                   paused_topic[-1:] == [False])

    # --- Pause, Reset, type k for the rod and a step count, Step: the rod is simulate's with that k
    panel.click("pause")
    wait("~step to succeed after the second Pause", paused)
    panel.click("reset")
    wait("Reset done", lambda: panel.text("status") == "reset")
    panel.scroll_to("rod.k", 20.0)
    panel.type_into("rod.k", "2000")
    wait("the rod's server to show k = 2000", lambda: bool(server_k) and server_k[-1] == TYPED_K)
    wait("the panel to show k = 2000", lambda: panel.text("rod.k") == "2000")
    findings.check("k typed in the panel: the rod's server shows 2000", True)
    wait("the paused note in the rod's section", lambda: PAUSED_NOTE in panel.text("rod.message"))
    findings.check(f"  paused: the section says when it shows: {panel.text('rod.message')}",
                   panel.text("rod.message") == f"paused: k = 2000 is set; {PAUSED_NOTE}")
    panel.type_into("step_count", str(STEPS))
    wait("the step count", lambda: panel.text("step_count") == str(STEPS))
    t_reset = probe[-1].t
    panel.click("step")
    t_end = t_reset + STEPS / config["rate"]
    wait("the state after Step", lambda: any(abs(m.t - t_end) < 1e-9 for m in rods))
    got = next(m for m in rods if abs(m.t - t_end) < 1e-9)
    want = simulated_rod(args.simulate, args.config, TYPED_K, STEPS / config["rate"])
    other = simulated_rod(args.simulate, args.config, float(config["bodies"]["rod"]["k"]), STEPS / config["rate"])
    fields = [f for f in state_fields(got) if f != "t"]
    same = [f for f in fields if getattr(got, f) == want[f]]
    findings.check(f"Step {STEPS} after k = 2000: the rod equals simulate's ({len(same)} of {len(fields)} fields)",
                   len(same) == len(fields))
    findings.check("  and k mattered (simulate with the old k differs)", any(other[f] != want[f] for f in fields))
    wait("the panel to report the steps", lambda: f"after {STEPS} steps" in panel.text("status"))
    findings.check(f"Step: the panel says so ({panel.text('status')})", True)
    wait("the panel's clock at the end of the steps", lambda: panel.text("clock").startswith(f"t = {t_end:.3f} s"))
    findings.check(f"  its clock says paused, no real-time factor from the steps: {panel.text('clock')}",
                   panel.text("clock") == f"t = {t_end:.3f} s paused")
    wait("the paused note to go with the state after Step", lambda: PAUSED_NOTE not in panel.text("rod.message"))
    findings.check("  the paused note went with the first state after the change", True)
    bowler = next(m for m in bowlers if abs(m.t - t_end) < 1e-9)
    wait("the bowler's state at the end of the steps", lambda: f"{bowler.energy:.3f} J" in panel.text("bowler.motion"))
    check_energy(panel.text("rod.motion"), rod_energy(got, config, TYPED_K), ROD_ZERO, "rod", findings)
    check_energy(panel.text("bowler.motion"), roller_energy(bowler, world_bodies()["bowler"], config["gravity"]),
                 ROLLER_ZERO, "bowler", findings)

    # --- refused: k = -5 snaps back, one WARN line, the refusal shown
    before = len(warnings)
    panel.type_into("rod.k", "-5")
    wait("the node's WARN line", lambda: len(warnings) > before)
    wait("the panel to show the refusal", lambda: "'k'" in panel.text("rod.message") and "'k'" in panel.text("status"))
    wait("the panel's k back at 2000", lambda: panel.text("rod.k") == "2000")
    findings.check(f"refused k = -5: the node logged one WARN line ({len(warnings) - before})",
                   len(warnings) - before == 1 and "value -5" in warnings[-1])
    findings.check(f"  the server still shows k = {server_k[-1]:g}", server_k[-1] == TYPED_K)
    findings.check(f"  the panel shows: {panel.text('rod.message')[:90]}", "refused" in panel.text("rod.message"))
    findings.check(f"  and in its status line: {panel.text('status')[:80]}", "'k'" in panel.text("status"))
    findings.check("  the picture shows it", refusal_in_picture(args.out, panel.widgets()["status"]))

    # --- the mouse wheel over a field that has no focus (rod.k has it): the sections scroll, nothing changes
    name, key = field_in_sight(panel.widgets(), config, "rod.k")
    widgets = panel.widgets()
    was, position, sent = widgets[f"{name}.{key}"][4], scrolled(widgets), dict(updates)
    x, y, w, h, _ = widgets[f"{name}.{key}"]
    xdotool("mousemove", str(x + w // 2), str(y + h // 2), "click", "4" if position > 0 else "5")
    wait("the sections to scroll under the wheel", lambda: scrolled(panel.widgets()) != position)
    after = panel.widgets()
    findings.check(f"the wheel over {name}.{key} (no focus) scrolled the sections ({position} -> "
                   f"{after['sections'][4]}); the field still shows {after[f'{name}.{key}'][4]} ({was} before)",
                   after[f"{name}.{key}"][4] == was)
    in_world = float(world_bodies()[name][key])
    findings.check(f"  the node's world keeps {name}.{key} = {in_world:g}; no reconfigure ({updates == sent})",
                   in_world == float(was) and updates == sent)

    def spawn(typed: str, kind: str, name: str) -> Dict[str, Any]:
        """Spawn of `kind`, chosen by typing into the list (its keyboard search), named `name`: the body in
        the node's world afterwards."""
        panel.click("spawn_kind")
        xdotool("type", "--delay", "40", typed)
        xdotool("key", "Return")
        wait(f"{kind} chosen", lambda: panel.text("spawn_kind") == kind)
        panel.type_into("spawn_name", name)
        panel.click("spawn")
        wait(f"the panel to report the spawn of {name}", lambda: f"spawned '{name}'" in panel.text("status"))
        return dict(world_bodies().get(name, {}))

    # --- Run; Spawn a spherical shell named wheel (last in name order: its section comes at the bottom), a refused
    # spawn, then the wheel's Delete
    panel.click("run")
    wait("Run done", lambda: panel.text("status") == "running")
    wheel = spawn("spherical", "spherical_shell", "wheel")  # the list's search: sphere, then spherical_shell
    findings.check(f"Spawn: the node's world has a spherical_shell roller named wheel ({wheel})",
                   wheel.get("type") == "roller" and wheel.get("shape") == "spherical_shell")
    wait("the wheel's section", lambda: "wheel.motion" in panel.widgets())
    panel.scroll_to("wheel.delete", 20.0)
    wait("the wheel's state in its section", lambda: "E = " in panel.text("wheel.motion"))
    findings.check(f"  its section shows it: {panel.text('wheel.motion')[:60]}", True)
    check_critical(panel.text("wheel.critical"), "wheel", world_bodies()["wheel"], findings)
    findings.check(f"  the sections still fit sideways ({panel.text('sections')})",
                   panel.text("sections").endswith(" 0"))
    before = len(world_bodies())
    panel.type_into("spawn_name", "rod")
    panel.click("spawn")
    wait("the refused spawn in the status line", lambda: "'rod'" in panel.text("status")
         and "spawned" not in panel.text("status"))
    findings.check(f"a spawn under a taken name is refused: {panel.text('status')[:80]}",
                   len(world_bodies()) == before)
    panel.scroll_to("wheel.delete", 20.0)  # the refusal's lines in the status push the sections down
    panel.click("wheel.delete")
    wait("the panel to report the delete", lambda: panel.text("status") == "deleted 'wheel'")
    findings.check("Delete: wheel is out of the node's world", "wheel" not in world_bodies())
    wait("the wheel's section to go", lambda: not any(name.startswith("wheel.") for name in panel.widgets()))
    findings.check("  and its section out of the panel", True)
    # A block, the third type, from the same list: its section with its motion and its critical angle.
    crate = spawn("block", "block", "crate")
    findings.check(f"Spawn: the node's world has a block named crate ({crate})", crate.get("type") == "block")
    wait("the crate's state in its section", lambda: "E = " in panel.text("crate.motion"))
    findings.check(f"  its section shows it: {panel.text('crate.motion')[:60]}", True)
    wait("the crate's critical angle", lambda: panel.text("crate.critical") != "")
    check_critical(panel.text("crate.critical"), "crate", crate, findings)
    panel.scroll_to("crate.delete", 20.0)
    panel.click("crate.delete")
    wait("the panel to report the crate's delete", lambda: panel.text("status") == "deleted 'crate'")

    # --- the Plots tab: the rod's ends after a Step, then the bowler from a Reset to past its slip-to-roll
    get_events = rospy.ServiceProxy("/sim/get_events", GetEvents)
    check_plots(Plots(panel, wait, paused, probe, rods, bowlers, lambda: list(get_events().events)), config,
                world_bodies()["bowler"], findings)


class Plots:
    """The Plots tab's series as the panel writes them ("plot.<series>": count, then the last t and value),
    the test's own states, the node's events of the run (~get_events), and the waits and clicks of run()."""

    def __init__(self, panel: Panel, wait: Callable[..., None], paused: Callable[[], bool], probe: List[Any],
                 rods: List[Any], bowlers: List[Any], events: Callable[[], List[Any]]) -> None:
        self.panel, self.wait, self.paused, self.probe = panel, wait, paused, probe
        self.rods, self.bowlers, self.events = rods, bowlers, events

    def last(self, series: str) -> Tuple[int, float, float]:
        parts = self.panel.text(f"plot.{series}").split()
        return (int(parts[0]), float(parts[1]), float(parts[2])) if len(parts) == 3 else (0, math.nan, math.nan)

    def choose(self, body: str) -> None:
        self.panel.click("plot_body")
        xdotool("type", "--delay", "40", body)  # the list's keyboard search
        xdotool("key", "Return")
        self.wait(f"{body} chosen for the plots", lambda: self.panel.text("plot_body") == body)

    def pause(self) -> float:
        """Pause; the t where the node stands (~step 1 succeeds once paused, and publishes where it ends)."""
        self.panel.click("pause")
        self.wait("~step to succeed after Pause", self.paused)
        t = float(self.probe[-1].t)
        self.wait(f"the bowler's state at t = {t:.3f} s", lambda: any(m.t == t for m in self.bowlers))
        return t


def check_plots(plots: Plots, config: Dict[str, Any], bowler: Dict[str, Any], findings: Findings) -> None:
    """The last point of each series is the test's own state at that t, with the same values; after a Reset
    the bowler's marks are its events (the node's ~get_events), the first slip-to-roll at the closed form's
    instant."""
    panel = plots.panel
    panel.click("tab.Plots")
    plots.wait("the Plots tab", lambda: panel.in_sight("plot_body"))
    plots.choose("rod")
    panel.click("step")  # pauses, then the step count of before (STEPS)
    plots.wait("the rod's ends on the plot", lambda: plots.last("y_end_minus")[0] > 0
               and plots.last("y_end_minus")[1] == max(m.t for m in plots.rods))
    rod = next(m for m in plots.rods if m.t == plots.last("energy")[1])
    half = 0.5 * float(config["bodies"]["rod"]["length"])
    kinetic = rod_kinetic(rod, config["bodies"]["rod"])
    want = {"energy": rod.energy, "y_end_plus": rod.y + half * math.sin(rod.theta),
            "y_end_minus": rod.y - half * math.sin(rod.theta), "kinetic": kinetic, "potential": rod.energy - kinetic}
    got = {series: plots.last(series) for series in want}
    findings.check(f"Plots, rod at t = {rod.t:.3f} s: the last points are its state's {got}",
                   all(got[s][1] == rod.t and same(s, got[s][2], want[s]) for s in want))

    plots.choose("bowler")
    t_reset = plots.pause()
    panel.click("reset")
    plots.wait("Reset done", lambda: panel.text("status") == "reset")
    panel.click("run")
    # The marks of the laps before the Reset go with it: wait for those after it.
    plots.wait("the slip-to-roll mark after the Reset", lambda: plots.last("slip_to_roll")[1] > t_reset)
    plots.wait("the finish mark after the Reset", lambda: plots.last("finished")[1] > t_reset)
    t_end = plots.pause()
    plots.wait("the plot at the paused t", lambda: plots.last("friction")[1] == t_end)
    states = [m for m in plots.bowlers if t_reset < m.t <= t_end]
    end = states[-1]
    radius = float(bowler["radius"])
    kinetic = roller_kinetic(end, bowler)
    want = {"energy": end.energy, "v": end.v, "minus_omega_r": -end.omega * radius, "friction": end.friction,
            "kinetic": kinetic, "potential": end.energy - kinetic}
    got = {series: plots.last(series) for series in want}
    findings.check(f"Plots, bowler: {len(states)} states since the Reset at t = {t_reset:.3f} s; each series "
                   f"has them all, and its last point is the state's at t = {t_end:.3f} s: {got}",
                   all(got[s][0] == len(states) and got[s][1] == t_end and same(s, got[s][2], want[s]) for s in want))

    # The node's events since the Reset (its run, paused at t_end): the marks are theirs.
    run = [e for e in plots.events() if e.body == "bowler"]
    resets = [e.t for e in run if e.kind == "lap_restarted" and event_value(e.values, "cause") == "reset"]
    findings.check(f"  the node's run begins with the bowler's restart of cause reset at t = {t_reset:.3f} s "
                   f"({resets})", resets == [t_reset])
    closed = closed_form_slip_to_roll(bowler, float(config["gravity"]))
    slips = [e for e in run if e.kind == "slip_to_roll"]
    finishes = [e for e in run if e.kind == "finished"]
    if not (slips and finishes):
        findings.check(f"  a slip-to-roll and a finish since the Reset ({len(slips)}, {len(finishes)})", False)
        return
    plots.wait("the panel's marks up to the node's last events", lambda: plots.last("slip_to_roll")[1] >= slips[-1].t
               and plots.last("finished")[1] >= finishes[-1].t)
    check_marks(plots.panel, "slip_to_roll", slips, [f"slip \u2192 roll at {e.t - t_reset:.3f} s" for e in slips],
                findings)
    first = slips[0].t - t_reset
    findings.check(f"  the first slip-to-roll {first:.9f} s after the Reset: the closed form's {closed:.9f} s to "
                   f"rounding (1e-9 s)", abs(first - closed) <= 1e-9)
    check_marks(plots.panel, "finished", finishes, [finish_note(e) for e in finishes], findings)
    lap, closed_lap = event_value(finishes[0].values, "lap_time"), event_value(finishes[0].values, "closed_form")
    findings.check(f"  the first finish after the Reset: lap time {lap!r} s, its closed form {closed_lap!r} s, to "
                   f"rounding (1e-9 s)", closed_lap is not None and abs(lap - closed_lap) <= 1e-9)
    # Its lines part where it restarts (off the end of its lane): one more line per restart among the states.
    restarts = [e.t for e in run if e.kind == "lap_restarted" and states[0].t < e.t <= t_end]
    lines = {series: plots.panel.text(f"plot.{series}.lines") for series in ("v", "friction", "energy")}
    findings.check(f"  its lines part at its restarts {restarts}: lines drawn {lines}",
                   all(n == str(1 + len(restarts)) for n in lines.values()))


def event_value(fields: List[Any], name: str) -> Any:
    """The number (or the text, for a text) of an event's field named `name`; None if it has none."""
    for field in fields:
        if field.name == name:
            return field.text if field.text else field.number
    return None


def ordinal(place: int) -> str:
    """1st, 2nd, 3rd, 4th ... 11th, 12th, 13th ... 21st."""
    teen = place % 100 // 10 == 1
    return f"{place}" + ("th" if teen else {1: "st", 2: "nd", 3: "rd"}.get(place % 10, "th"))


def finish_note(event: Any) -> str:
    """A finish's note from its values: its place in a race, its lap time, then its closed form's."""
    place, lap = event_value(event.values, "place"), event_value(event.values, "lap_time")
    closed = event_value(event.values, "closed_form")
    note = (ordinal(int(place)) if place is not None else "finished") + f" in {lap:.4f} s"
    return note + (f" (closed form {closed:.4f} s)" if closed is not None else "")


def check_marks(panel: Panel, series: str, events: List[Any], notes: List[str], findings: Findings) -> None:
    """A track of marks as the panel writes it: as many as `events`, the last at the last one's instant and
    speed (its state's v, to the bit), its note the last of `notes`."""
    parts = panel.text(f"plot.{series}").split()
    count, t, v = (int(parts[0]), float(parts[1]), float(parts[2])) if len(parts) == 3 else (0, math.nan, math.nan)
    note = panel.text(f"plot.{series}.note")
    last = events[-1]
    want_v = event_value(last.state, "v")
    findings.check(f"  {series} marks: {count}, the last at t = {t!r} s, v = {v!r} m/s, {note!r}; the node's "
                   f"events: {len(events)}, the last at {last.t!r} s, v = {want_v!r} m/s, {notes[-1]!r}",
                   count == len(events) and t == last.t and v == want_v and note == notes[-1])


def same(series: str, plotted: float, want: float) -> bool:
    """Equal to the bit (the layout file writes numbers in full) for what the plot takes from the state; for
    the kinetic and potential energies (the core's, from the state and the body's parameters) to the last
    bits of a sum formed in another order (this test's, in Python)."""
    if series in ("kinetic", "potential"):
        return abs(plotted - want) <= 1e-12 * max(1.0, abs(want))
    return plotted == want


def closed_form_slip_to_roll(body: Dict[str, Any], g: float) -> float:
    """Launched sliding with backspin: u = v + omega R falls at g sin(phi) - mu_d g cos(phi) (1 + c)/c
    (test_plot_run.py's)."""
    c, phi = SHAPE_C[body["shape"]], float(body["incline_angle"])
    u0 = float(body["v0"]) + float(body["omega0"]) * float(body["radius"])
    return u0 / -(g * math.sin(phi) - float(body["mu_d"]) * g * math.cos(phi) * (1 + c) / c)


def scrolled(widgets: Dict[str, Widget]) -> int:
    """The sections' vertical scroll position, from their layout line ("vertical sideways-range")."""
    return int(widgets["sections"][4].split()[0])


def shows_world(widgets: Dict[str, Widget], config: Dict[str, Any], in_world: Dict[str, Any]) -> bool:
    """Whether every number's field is there and shows the node's value of it (the panel writes numbers
    shortest round-trip: the same double)."""
    for name in config["bodies"]:
        for key in KEY_UNITS[body_type(config, name)]:
            field = widgets.get(f"{name}.{key}")
            try:
                if field is None or float(field[4]) != float(in_world[name][key]):
                    return False
            except ValueError:
                return False
    return True


def check_units(widgets: Dict[str, Widget], config: Dict[str, Any], findings: Findings) -> None:
    """Every number's unit is sim_tools.KEY_UNITS's (the .cfg files'); an angle's degrees are its radians'."""
    for name in config["bodies"]:
        wrong, angles = [], []
        for key, unit in KEY_UNITS[body_type(config, name)].items():
            shown = widgets.get(f"{name}.{key}.unit", (0, 0, 0, 0, ""))[4]
            if shown != unit:
                wrong.append(f"{key}: {shown!r}, not {unit!r}")
            if unit == "rad":
                radians = float(widgets[f"{name}.{key}"][4])
                degrees = widgets.get(f"{name}.{key}.degrees", (0, 0, 0, 0, "?"))[4]
                angles.append(f"{key} {radians:g} rad = {degrees}")
                if not degrees.endswith("\u00b0") or abs(float(degrees[:-1]) - math.degrees(radians)) > 0.005:
                    wrong.append(f"{key} in degrees: {degrees}")
        findings.check(f"{name}: every number's unit as KEY_UNITS; {', '.join(angles)} {wrong or ''}", not wrong)


def check_critical(shown: str, name: str, body: Dict[str, Any], findings: Findings) -> None:
    """A roller's critical angle and verdict against the closed form tan(phi_c) = mu_s (1 + c) / c; a
    block's against tan(phi_c) = mu_s."""
    mu_s, slope = float(body["mu_s"]), float(body["incline_angle"])
    at = f"{math.degrees(slope):.1f}\u00b0"
    if body["type"] == "block":
        tan_c, holds, slides = mu_s, f"stays put at rest (slope {at})", f"slides from rest (slope {at} above it)"
    else:
        c = SHAPE_C[body["shape"]]
        tan_c = mu_s * (1 + c) / c
        holds, slides = f"can roll without slipping (slope {at})", f"slips (slope {at} above it)"
    want = (f"critical angle {math.degrees(math.atan(tan_c)):.1f}\u00b0 for \u03bcs {mu_s:g}: "
            + (holds if math.tan(slope) <= tan_c else slides))
    findings.check(f"{name} ({body.get('shape', body['type'])}): {shown}", shown == want)
    if shown != want:
        findings.check(f"  the closed form says: {want}", False)


def check_energy(shown: str, want: float, zero: str, name: str, findings: Findings) -> None:
    """The energy a section shows is the documented formula (whose zero it names) at the same state."""
    found = re.search(r"E = (-?[0-9.]+) J ", shown)
    ok = found is not None and abs(float(found.group(1)) - want) <= 0.0005 + 1e-9 and shown.endswith(zero)
    findings.check(f"{name}: {shown}; the formula with that zero gives {want:.4f} J", ok)


def rod_kinetic(state: Any, rod: Dict[str, Any]) -> float:
    """1/2 M v^2 + 1/2 (M L^2 / 12) omega^2."""
    mass, length = float(rod["mass"]), float(rod["length"])
    return 0.5 * mass * (state.vx ** 2 + state.vy ** 2) + 0.5 * mass * length ** 2 / 12 * state.omega ** 2


def rod_energy(state: Any, config: Dict[str, Any], k: float) -> float:
    """The kinetic + M g y + 1/2 k y_end^2 for each end below the floor (y = 0)."""
    rod, g = config["bodies"]["rod"], float(config["gravity"])
    mass, length = float(rod["mass"]), float(rod["length"])
    energy = rod_kinetic(state, rod) + mass * g * state.y
    for end in (1, -1):
        y_end = state.y + end * 0.5 * length * math.sin(state.theta)
        energy += 0.5 * k * y_end ** 2 if y_end < 0 else 0.0
    return energy


def roller_kinetic(state: Any, body: Dict[str, Any]) -> float:
    """1/2 M V^2 + 1/2 c M R^2 omega^2."""
    mass, radius, c = float(body["mass"]), float(body["radius"]), SHAPE_C[body["shape"]]
    return 0.5 * mass * state.v ** 2 + 0.5 * c * mass * radius ** 2 * state.omega ** 2


def roller_energy(state: Any, body: Dict[str, Any], g: float) -> float:
    """The kinetic - M g X sin(phi), X from the top of the slope."""
    mass = float(body["mass"])
    return roller_kinetic(state, body) - mass * g * state.x * math.sin(float(body["incline_angle"]))


def field_in_sight(widgets: Dict[str, Widget], config: Dict[str, Any], focused: str) -> Tuple[str, str]:
    """A number's field wholly in sight, other than the focused one: a ring's first if one is."""
    names = sorted(config["bodies"], key=lambda name: config["bodies"][name].get("shape") != "ring")
    for name in names:
        for key in KEY_UNITS[body_type(config, name)]:
            field = widgets.get(f"{name}.{key}")
            if f"{name}.{key}" != focused and field is not None and field[2] >= 20 and field[3] >= 15:
                return name, key
    raise RuntimeError("no number's field in sight for the wheel")


def refusal_in_picture(path: str, message: Widget) -> bool:
    """The refusal's colour in the message's place on a screenshot (rviz draws it a frame later: looked for
    until there, 10 s at most)."""
    x, y, w, h, _ = message
    found: List[int] = [0]

    def drawn() -> bool:
        subprocess.run(["import", "-window", "root", path], check=True)
        region = shot.read_png(path)[y:y + h, x:x + w].astype(int)
        found[0] = int((np.abs(region - REFUSAL_COLOUR).max(axis=-1) <= 40).sum())
        return found[0] >= 20
    try:
        wait_for("the refusal's colour", drawn, 10.0, 0.5)
    except TimeoutError:
        pass
    print(f"refusal colour: {found[0]} px", flush=True)
    return found[0] >= 20


if __name__ == "__main__":
    sys.exit(main())
