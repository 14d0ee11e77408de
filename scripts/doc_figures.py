#!/usr/bin/env python3
"""The figures the docs state about runs, computed from the runs they describe.

    doc_figures.py SIMULATE [--write] [--work DIR]

runs `simulate` on the documented configs (demo.yaml and incline.yaml for 10 s sampled at 1 kHz, the sweep
of the text's random theta0 over 1001 rods of 10 s, the lesson's race below the critical angles until its
sphere is down), computes every figure listed in FIGURES from them (an instant, and the state then, from the
core's events in the run's events.csv; a swing from the samples, with plot_run.py's own analysis) or from the
closed forms the docs state as such, and compares each with the text of its doc.
Without --write it prints one line per figure that differs and exits 1 (the `doc_figures` test); with
--write it puts the computed figures into the docs (`make figures`). A figure that is no longer found in
its doc fails as well: a reworded sentence must be reworded here too.
"""
import argparse
import math
import os
import re
import subprocess
import sys
import tempfile
from typing import Any, Callable, Dict, List, NamedTuple, Tuple

import numpy as np
from rigid_body_sim import runs as run_files
from rigid_body_sim.sim_tools import Event, RodSpec, RollerSpec, body_spec, load_config, role

from plot_run import laps, load_csv_folder, rod_energy_swing

PACKAGE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
THETA0_RODS = 1001  # theta0 = i 2 pi / 1000: theta0 + pi and pi - theta0 are on the grid too
RACE_SECONDS = 2.1  # race_below.yaml's sphere is down at 2.04 s (docs/rviz.md); the other parts' bags need 0.02 s
Runs = Dict[str, Any]


class Figure(NamedTuple):  # not a dataclass: Debian 11's mypy takes a Callable field of one for a method
    doc: str  # relative to the package
    pattern: str  # a regular expression whose groups are the figures
    values: Callable[[Runs], List[str]]  # the figures as the doc writes them, one per group


def run_simulate(simulate: str, args: List[str]) -> None:
    done = subprocess.run([simulate, *args], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        sys.exit(f"doc_figures: simulate {' '.join(args)} failed: {done.stderr.strip()}")


def runs(simulate: str, work: str) -> Runs:
    """The documented runs: their CSV columns, their events, the specs of their bodies, the sweep's rows."""
    out: Runs = {}
    for name, duration in (("demo", 10), ("incline", 10)):
        folder = os.path.join(work, name)
        config = os.path.join(PACKAGE, "config", name + ".yaml")
        run_simulate(simulate, [config, "--duration", str(duration), "--sample-rate", "1000", "--out-dir", folder])
        out[name] = load_csv_folder(folder)
        out[name + "_events"] = run_files.read_events(folder)
        loaded = load_config(config)
        out[name + "_specs"] = {body: body_spec(loaded, body) for body in loaded["bodies"]}
    folder = os.path.join(work, "theta0")
    run_simulate(simulate, [os.path.join(PACKAGE, "config", "rod.yaml"), "--sweep",
                            f"rod.theta0=0:{2 * math.pi!r}:{THETA0_RODS}", "--duration", "10", "--out-dir", folder])
    out["sweep"] = np.genfromtxt(os.path.join(folder, "sweep.csv"), delimiter=",", names=True)
    for part in ("above", "below", "slip"):
        bag = os.path.join(work, f"race_{part}.bag")
        seconds = str(RACE_SECONDS if part == "below" else 0.02)
        run_simulate(simulate, [os.path.join(PACKAGE, "config", f"race_{part}.yaml"), "--duration", seconds,
                                "--out-dir", os.path.join(work, f"race_{part}"), "--bag", bag])
        out[f"lanes_{part}"] = lane_ys(bag)
    out["race_below_events"] = run_files.read_events(os.path.join(work, "race_below"))
    return out


def first_event(r: Runs, run: str, body: str, kind: str = "", of_role: str = "") -> Event:
    """The first event of a body in a run, of a kind or of a role (a finish: its type's kind with that role)."""
    for event in r[run + "_events"]:
        if event["body"] == body and (not kind or event["kind"] == kind) and (not of_role or role(event) == of_role):
            return event
    sys.exit(f"doc_figures: the {run} run has no {kind or of_role} event of {body}")


def lane_ys(bag: str) -> List[float]:
    """The world y of each slope's frame as the bag's /tf_static gives it (the scene's lanes), nearest first."""
    import rosbag  # ROS's, from Debian: imported here so that the rest runs without it
    ys = {}
    with rosbag.Bag(bag) as opened:
        for _, message, _ in opened.read_messages(topics=["/tf_static"]):
            for transform in message.transforms:
                if transform.child_frame_id.endswith("_slope"):
                    ys[transform.child_frame_id] = transform.transform.translation.y
    return sorted(ys.values())


def lane_spacing(r: Runs, part: str) -> str:
    """The lanes' spacing of a race (its three slopes alike: one spacing), in the doc's "%.1f"."""
    gaps = np.diff(r[f"lanes_{part}"])
    assert len(gaps) == 2 and abs(gaps[0] - gaps[1]) < 1e-9, gaps
    return f"{gaps[0]:.1f}"


# --- the closed forms of section 16.3.2 -----------------------------------------------------------------
G = 9.8


def spec(r: Runs, config: str, body: str) -> Any:
    return r[config + "_specs"][body]


def rolling_acceleration(p: RollerSpec) -> float:
    return G * math.sin(p.angle) / (1 + p.c)


def sliding_acceleration(p: RollerSpec) -> float:
    return G * (math.sin(p.angle) - p.mu_d * math.cos(p.angle))


def acceleration(p: RollerSpec) -> float:
    return rolling_acceleration(p) if p.rolls() else sliding_acceleration(p)


def degrees(radians: float) -> str:
    return f"{math.degrees(radians):.1f}"


def race_row(r: Runs, body: str) -> List[str]:
    """tan(phi_c), phi_c, the acceleration (closed forms) and the time down the slope (the run's first finish)."""
    p = spec(r, "incline", body)
    return [f"{p.tan_critical():.2f}", degrees(math.atan(p.tan_critical())), f"{acceleration(p):.3f}",
            f"{first_event(r, 'incline', body, of_role='finish')['t']:.4f}"]


# --- measured on the runs -------------------------------------------------------------------------------
def energy_lost_on_first_lap(r: Runs, body: str) -> str:
    """From the start to the first finish: the energy of the state at that instant (the event's)."""
    finish = first_event(r, "demo", body, of_role="finish")
    return f"{r['demo'][body]['energy'][0] - finish['state']['energy']:.3f}"


def bound(value: float) -> str:
    """The smallest power of ten at or above |value|: 1e-12."""
    return f"1e{math.ceil(math.log10(abs(value)))}" if value else "0"


def sphere_energy_bound(r: Runs) -> List[str]:
    e = r["demo"]["sphere"]["energy"]
    return [bound(float(np.max(np.abs(e - e[0]))))]


def bowler_slip(r: Runs) -> List[str]:
    """The energy the bowler loses while it slips: from the start to its state at its first slip_to_roll."""
    start = float(r["demo"]["bowler"]["energy"][0])
    at_roll = float(first_event(r, "demo", "bowler", "slip_to_roll")["state"]["energy"])
    return [f"{start - at_roll:.2f}", f"{start:.3f}", f"{at_roll:.3f}"]


def bowler_slip_speed(r: Runs) -> Tuple[float, float]:
    """The closed form of the bowler's slip (docs/physics.md states it): u0 = v0 + omega0 R from its config and
    du/dt = g sin(phi) - mu_d g cos(phi) (1 + c)/c."""
    p = spec(r, "demo", "bowler")
    config = load_config(os.path.join(PACKAGE, "config", "demo.yaml"))["bodies"]["bowler"]
    u0 = config["v0"] + config["omega0"] * p.radius
    return u0, G * math.sin(p.angle) - p.mu_d * G * math.cos(p.angle) * (1 + p.c) / p.c


def bowler_closed_form(r: Runs) -> List[str]:
    u0, du_dt = bowler_slip_speed(r)
    return [f"{u0:g}", f"{abs(du_dt):.4f}"]


def bowler_rolls_at(r: Runs, decimals: int = 3) -> str:
    """The closed form's slip-to-roll instant of the demo's bowler, u0 / |du/dt|, as the panel's note gives it:
    the docs state the closed form itself, the truth the core's instant is checked against, so it stays a
    formula."""
    u0, du_dt = bowler_slip_speed(r)
    return f"{u0 / abs(du_dt):.{decimals}f}"


def rod_events(r: Runs) -> List[Event]:
    return [event for event in r["demo_events"] if event["body"] == "rod"]


def rod_first_lap(r: Runs) -> Dict[str, np.ndarray]:
    """The demo rod's samples until it leaves its floor and restarts (its first restart event; the whole run:
    it bounces in place)."""
    d = r["demo"]["rod"]
    start, end = laps(d["t"], rod_events(r))[0]
    return {column: values[start:end] for column, values in d.items()}


def rod_swing(r: Runs) -> Dict[str, Any]:
    """The energy's swings inside the contacts of the rod's first lap, and its change over that lap."""
    assert isinstance(spec(r, "demo", "rod"), RodSpec)
    lap = rod_first_lap(r)
    return rod_energy_swing(lap, [event for event in rod_events(r) if event["t"] <= lap["t"][-1]])


def free_flight_loss_rate(r: Runs) -> str:
    """J/s lost in the rod's first free fall: from its start to the sample before its first contact_began."""
    d = r["demo"]["rod"]
    first_contact = int(np.searchsorted(d["t"], first_event(r, "demo", "rod", "contact_began")["t"]))
    t, e = d["t"][:first_contact], d["energy"][:first_contact]
    return f"{(e[0] - e[-1]) / (t[-1] - t[0]):.3f}"


def rod_start_energy() -> float:
    """M g y0 + M v0^2 / 2 of the text's rod (config/rod.yaml), whatever its theta0 (no end below the floor)."""
    rod = load_config(os.path.join(PACKAGE, "config", "rod.yaml"))["bodies"]["rod"]
    return float(rod["mass"] * G * rod["y0"] + 0.5 * rod["mass"] * (rod["vx0"] ** 2 + rod["vy0"] ** 2))


def sweep_figures(r: Runs) -> Dict[str, str]:
    """What docs/sweeps.md says of the theta0 sweep."""
    s = r["sweep"]
    bounces = s["rodbounces"].astype(int)
    drift = s["rodenergy_drift"]
    n = len(bounces)
    i = np.arange(n)
    flat = [0, n // 2, n - 1]  # theta0 = 0, pi, 2 pi
    tilted = np.delete(bounces, flat)
    in_band = np.mean((tilted >= 8) & (tilted <= 13))
    half = (n - 1) // 2  # theta0 + pi is i + 500 on the grid, pi - theta0 is 500 - i (both mod 1000)
    shifted = bounces[(i + half) % (n - 1)]
    mirrored = bounces[(half - i) % (n - 1)]
    e0 = rod_start_energy()
    return {"flat": str(int(bounces[0])) if len(set(bounces[flat])) == 1 else "?",
            "fewest": str(int(tilted.min())), "most": str(int(tilted.max())), "band": f"{100 * in_band:.0f}",
            "shift": str(int(np.sum(shifted != bounces))), "mirror": str(int(np.sum(mirrored != bounces))),
            "start": f"{e0:g}", "near": f"{100 * np.mean(np.abs(drift) <= 0.1):.0f}", "low": f"{drift.min():.2f}",
            "low_percent": f"{100 * drift.min() / e0:.1f}"}


def race_board(r: Runs) -> List[str]:
    """What the sphere's board says at the end of the lesson's race below the critical angles: its place, its
    lap time and the closed form's time, the values of its finished event."""
    values = first_event(r, "race_below", "sphere", of_role="finish")["values"]
    place = int(values["place"])
    suffix = "th" if 10 <= place % 100 <= 20 else {1: "st", 2: "nd", 3: "rd"}.get(place % 10, "th")
    return [f"{place}{suffix}", f"{values['lap_time']:.4f}", f"{values['closed_form']:.4f}"]


def settle_of_screenshot(_: Runs) -> List[str]:
    """The simulated seconds that `make screenshot` steps before the demo's picture (the script's default)."""
    with open(os.path.join(PACKAGE, "test", "pictures", "rviz_screenshot.py")) as f:
        found = re.search(r'"--settle", type=float, default=([0-9.]+)', f.read())
    assert found, "rviz_screenshot.py has no --settle default"
    return [f"{float(found.group(1)):g}"]


FIGURES = [
    Figure("docs/physics.md", r"stepped to (\S+) s after the reset", settle_of_screenshot),
    Figure("docs/physics.md", r"u = v \+ ωR = 0, at t = (\S+) s \(green line\)",
           lambda r: [f"{first_event(r, 'demo', 'bowler', 'slip_to_roll')['t']:.6f}"]),
    Figure("docs/physics.md", r"bottom, t = (\S+) s\)",
           lambda r: [f"{first_event(r, 'demo', 'bowler', of_role='finish')['t']:.4f}"]),
    Figure("docs/physics.md", r"u0 / \|du/dt\| = (\S+) / (\S+) s", bowler_closed_form),
    Figure("docs/rviz.md", r"\((\S+) s after a Reset for `demo.yaml`'s\s+bowler",
           lambda r: [f"{first_event(r, 'demo', 'bowler', 'slip_to_roll')['t']:.6f}"]),
    Figure("docs/rviz.md", r"`slip → roll at (\S+) s`",
           lambda r: [f"{first_event(r, 'demo', 'bowler', 'slip_to_roll')['t']:.3f}"]),
    Figure("docs/rviz.md", r"`finished in (\S+) s \(closed form (\S+) s\)`",
           lambda r: [f"{first_event(r, 'demo', 'bowler', of_role='finish')['values'][value]:.4f}"
                      for value in ("lap_time", "closed_form")]),
    Figure("docs/rviz.md", r"in a race its place first, `(\S+) in (\S+) s \(closed form (\S+) s\)`", race_board),
    Figure("docs/testing.md", r"note with its place \(`(\S+) in (\S+) s \(closed form (\S+) s\)`\)", race_board),
    Figure("docs/testing.md", r"is at the closed form's instant after the Reset\s+\((\S+) s\) and its v then",
           lambda r: [bowler_rolls_at(r)]),
    Figure("docs/testing.md", r"\(1 \+ c\)/c − g sin φ\) = (\S+) s", lambda r: [bowler_rolls_at(r, 6)]),
    Figure("docs/physics.md", r"33\.0°, tan φ = (\S+),",
           lambda r: [f"{math.tan(spec(r, 'incline', 'sphere').angle):.3f}"]),
    Figure("docs/physics.md", r"\| sphere \| 2/5 \| 3\.5 μs = (\S+) \| (\S+)° \| rolls \| g sin φ/\(1\+c\) = (\S+) \| "
           r"(\S+) s \|", lambda r: race_row(r, "sphere")),
    Figure("docs/physics.md", r"\| cylinder \| 1/2 \| 3 μs = (\S+) \| (\S+)° \| slips \| g \(sin φ − μd cos φ\) = "
           r"(\S+) \| (\S+) s \|", lambda r: race_row(r, "cylinder")),
    Figure("docs/physics.md", r"\| ring \| 1 \| 2 μs = (\S+) \| (\S+)° \| slips \| g \(sin φ − μd cos φ\) = (\S+) \| "
           r"(\S+) s \|", lambda r: race_row(r, "ring")),
    Figure("docs/physics.md", r"Sliding friction μd N = (\S+) N holds them back less than the (\S+) N of static",
           lambda r: [f"{(p := spec(r, 'incline', 'cylinder')).mu_d * p.mass * G * math.cos(p.angle):.2f}",
                      f"{(q := spec(r, 'incline', 'sphere')).mass * G * math.sin(q.angle) * q.c / (1 + q.c):.2f}"]),
    Figure("docs/physics.md", r"(\S+) rad/s² for the cylinder and (\S+) rad/s² for the ring",
           lambda r: [f"{(p := spec(r, 'incline', b)).mu_d * G * math.cos(p.angle) / (p.c * p.radius):.1f}"
                      for b in ("cylinder", "ring")]),
    Figure("docs/physics.md", r"The sphere's energy is constant to within (\S+) J", sphere_energy_bound),
    Figure("docs/physics.md", r"sliding friction, (\S+) J and (\S+) J by the bottom",
           lambda r: [energy_lost_on_first_lap(r, b) for b in ("cylinder", "ring")]),
    Figure("docs/physics.md", r"The bowling ball loses (\S+) J while it slips \((\S+) → (\S+) J\)", bowler_slip),
    Figure("docs/physics.md", r"½ M g² dt² = (\S+) J per step",
           lambda r: [f"{0.5 * spec(r, 'demo', 'rod').mass * G ** 2 * 1e-6:.1e}".replace("e-05", "e-5")]),
    Figure("docs/physics.md", r"\((\S+) J/s, as measured\)", lambda r: [free_flight_loss_rate(r)]),
    Figure("docs/physics.md", r"by up to (\S+) % \(t = (\S+) s, inset\)",
           lambda r: [f"{100 * rod_swing(r)['largest_swing']['swing']:.2f}",
                      f"{rod_swing(r)['largest_swing']['t']:.2f}"]),
    Figure("docs/physics.md", r"stays bounded at ω_c dt = (\S+)\.",
           lambda r: [f"{math.sqrt(4 * (p := spec(r, 'demo', 'rod')).k / p.mass) * 1e-3:.3f}"]),
    Figure("docs/physics.md",
           r"Over the (\S+) contacts of the run's (\S+) s, E goes from (\S+) to (\S+) J\s+\((\S+) %\)",
           lambda r: [str(rod_swing(r)["contacts"]), f"{rod_first_lap(r)['t'][-1]:.2f}",
                      f"{rod_swing(r)['energy_first']:.4f}",
                      f"{rod_swing(r)['energy_last']:.4f}",
                      f"{100 * (rod_swing(r)['energy_last'] / rod_swing(r)['energy_first'] - 1):.2f}"
                      .replace("-", "−")]),
    Figure("docs/rviz.md", r"`sphere: (\S+), (\S+) s` over `\(closed form (\S+) s\)`", race_board),
    Figure("docs/rviz.md", r"\((\S+) m at 38°, (\S+) m at 20°, (\S+) m at 5\.7°\)",
           lambda r: [lane_spacing(r, part) for part in ("above", "below", "slip")]),
    Figure("docs/sweeps.md", r"lands on both ends at once\s+and bounces (\S+) times",
           lambda r: [sweep_figures(r)["flat"]]),
    Figure("docs/sweeps.md", r"(\S+) to (\S+) bounces \(8 to 13 for (\S+) %\)",
           lambda r: [sweep_figures(r)[k] for k in ("fewest", "most", "band")]),
    Figure("docs/sweeps.md", r"all but (\S+) of the 1001 rods bounce as often as at θ0 \+ π, all but (\S+) as at",
           lambda r: [sweep_figures(r)[k] for k in ("shift", "mirror")]),
    Figure("docs/sweeps.md", r"within ±0\.1 J of (\S+) J for (\S+) %",
           lambda r: [sweep_figures(r)[k] for k in ("start", "near")]),
    Figure("docs/sweeps.md", r"it reaches (\S+) J \((\S+) %\)",
           lambda r: [sweep_figures(r)["low"].replace("-", "−"), sweep_figures(r)["low_percent"].replace("-", "−")]),
]


def check(r: Runs, write: bool) -> List[str]:
    """One line per figure that differs (or is not found); with `write`, the docs get the computed ones."""
    problems: List[str] = []
    texts: Dict[str, str] = {}
    for figure in FIGURES:
        path = os.path.join(PACKAGE, figure.doc)
        text = texts.setdefault(figure.doc, open(path).read())
        found = re.search(figure.pattern, text)
        if not found:
            problems.append(f"{figure.doc}: no text matches /{figure.pattern}/")
            continue
        values = figure.values(r)
        for group, value in enumerate(values, start=1):
            if found.group(group) != value:
                problems.append(f"{figure.doc}: /{figure.pattern}/ says {found.group(group)}, the run gives {value}")
        if write:
            pieces, last = [], found.start()
            for group, value in enumerate(values, start=1):
                pieces += [text[last:found.start(group)], value]
                last = found.end(group)
            texts[figure.doc] = text[:found.start()] + "".join(pieces) + text[last:]
    if write:
        for doc, text in texts.items():
            with open(os.path.join(PACKAGE, doc), "w") as f:
                f.write(text)
    return problems


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("simulate", help="the simulate executable")
    parser.add_argument("--write", action="store_true", help="put the computed figures into the docs")
    parser.add_argument("--work", help="where the runs go (default: a temporary folder)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as temporary:
        problems = check(runs(args.simulate, args.work or temporary), args.write)
    for line in problems:
        print(f"doc_figures: {line}")
    print(f"doc_figures: {len(FIGURES)} statements, {len(problems)} differ" + (" (written)" if args.write else ""))
    return 1 if problems and not args.write else 0


if __name__ == "__main__":
    sys.exit(main())
