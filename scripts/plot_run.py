#!/usr/bin/env python3
"""Plots of a rigid_body_sim run, from a bag of the node (sim.launch record:=true, or simulate --bag)
or from a folder of simulate's CSV files (simulate CONFIG --out-dir DIR).

  plot_run.py CONFIG.yaml RUN --out-dir DIR [--prefix NAME_] [--figures rod,rollers,race,energy]

RUN is a .bag file or a folder of <body>.csv files; CONFIG is the run's config (it gives each rod's
length, each roller's radius, shape and slope). Writes, for what the run holds:
  <prefix>rod.png      the path of each rod's centre with the rod drawn every 0.1 s (the text's Fig. 16.17)
  <prefix>rollers.png  per roller: x(t), v(t) and -omega R(t), slipping shaded, slip-to-roll instants marked
  <prefix>race.png     rollers that share a slope (same angle and length), first lap: who is down first
  <prefix>energy.png   energy against time of every body, rod contacts shaded
  <prefix>summary.json the numbers behind them (also printed): slip-to-roll instants, finish times,
                       critical angles, the rods' energy swing in contact
The slip-to-roll instant comes from the data alone: while a body slips its slip speed u = v + omega R
is linear in time, so the line through the last two slipping samples crosses zero at the instant."""
import argparse
import io
import json
import math
import os
import sys
from typing import Any, Callable, Dict, List, Optional, Tuple

import matplotlib
import numpy as np
from numpy.typing import NDArray

# sim_tools.py lies beside this file (in the source, and in the install space); rosrun's devel-space relay
# runs this file from elsewhere.
sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
from sim_tools import (BodySpec, Config, RodSpec, RollerSpec, body_spec, load_config, read_states,  # noqa: E402
                       rod_end_below_floor, state_fields)

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)

Array = NDArray[Any]
Columns = Dict[str, Array]  # one body's samples: column -> values
Run = Dict[str, Columns]  # body -> its samples
Summary = Dict[str, Dict[str, Any]]

ROD_EVERY = 0.1  # s between drawn rods
COLOURS = {"sphere": "tab:red", "cylinder": "tab:green", "ring": "tab:orange", "spherical_shell": "tab:purple"}


# --- reading a run ---------------------------------------------------------------------------------
def load_csv_folder(folder: str) -> Run:
    """{body: {column: array}} from simulate's <body>.csv files (their header starts with t; a sweep's
    summary does not)."""
    run: Run = {}
    for name in sorted(os.listdir(folder)):
        if not name.endswith(".csv"):
            continue
        with open(os.path.join(folder, name)) as f:
            header = f.readline().strip().split(",")
        if header[0] != "t":
            continue
        rows: Any = np.genfromtxt(os.path.join(folder, name), delimiter=",", names=True, dtype=None, encoding="utf-8")
        run[name[:-4]] = {k: np.atleast_1d(rows[k]) for k in header}
    return run


def load_bag(path: str) -> Run:
    """{body: {field: array}} from the state messages /sim/<body>/state of a bag."""
    return {name: {k: np.array([getattr(m, k) for m in msgs]) for k in state_fields(msgs[0])}
            for name, msgs in read_states(path).items()}


def load_run(path: str, config: Config) -> Run:
    """The run's bodies in the config's order."""
    run = load_bag(path) if path.endswith(".bag") else load_csv_folder(path)
    if not run:
        sys.exit(f"plot_run: no body states in {path} (a .bag with /sim/<body>/state or a folder of CSV files)")
    unknown = sorted(set(run) - set(config["bodies"]))
    if unknown:
        sys.exit(f"plot_run: bodies {', '.join(unknown)} of {path} are not in the config")
    return {name: run[name] for name in config["bodies"] if name in run}


# --- analysis --------------------------------------------------------------------------------------
Event = Dict[str, Any]


def laps(t: Array, x: Array, v: Array) -> List[Tuple[int, int]]:
    """Index ranges [start, end) between restarts: a restart is a jump of x that the speed cannot explain
    (between events the acceleration is constant, so dx = (v0 + v1) dt / 2)."""
    dx = np.diff(x)
    expected = 0.5 * (v[:-1] + v[1:]) * np.diff(t)
    jumps = np.flatnonzero(np.abs(dx - expected) > 0.05 + 0.25 * np.abs(expected)) + 1
    edges = [0, *jumps.tolist(), len(t)]
    return list(zip(edges[:-1], edges[1:]))


def slip_to_roll(data: Columns, radius: float) -> List[Event]:
    """Instants at which a slipping body starts to roll: for each mode change slipping -> rolling, the
    zero of the line through the last two slipping samples of u = v + omega R (exact: u is linear while
    slipping). With a single slipping sample, the first rolling sample's time (approximate)."""
    t, mode = data["t"], data["mode"]
    u = data["v"] + data["omega"] * radius
    found = []
    for start, end in laps(t, data["x"], data["v"]):
        for i in range(start, end - 1):
            if mode[i] != "slipping" or mode[i + 1] != "rolling":
                continue
            if i > start and mode[i - 1] == "slipping" and u[i] != u[i - 1]:
                found.append({"t": float(t[i] - u[i] * (t[i] - t[i - 1]) / (u[i] - u[i - 1])), "exact": True,
                              "last_slipping": float(t[i]), "first_rolling": float(t[i + 1])})
            else:
                found.append({"t": float(t[i + 1]), "exact": False,
                              "last_slipping": float(t[i]), "first_rolling": float(t[i + 1])})
    return found


def finish_times(data: Columns, slope: float) -> List[float]:
    """For each lap that ends off the slope: when the centre crossed x = slope (or 0 going uphill),
    from the last sample of the lap and its constant acceleration."""
    t, x, v = data["t"], data["x"], data["v"]
    times = []
    for start, end in laps(t, x, v):
        k = end - 1
        if end == len(t) or k - start < 1:
            continue  # the run ended on the slope
        a = (v[k] - v[k - 1]) / (t[k] - t[k - 1])
        target = slope if v[k] > 0 else 0.0
        # x[k] + v s + a s^2 / 2 = target, the smallest s >= 0
        roots = np.roots([0.5 * a, v[k], x[k] - target]) if abs(a) > 1e-12 else np.array([(target - x[k]) / v[k]])
        s = min((r.real for r in np.atleast_1d(roots) if abs(r.imag) < 1e-12 and r.real >= -1e-12), default=None)
        if s is not None:
            times.append(float(t[k] + s))
    return times


def critical_angle(p: RollerSpec) -> Dict[str, Any]:
    """tan(phi_c) = mu_s (1 + c) / c: the steepest slope on which the body can roll without slipping."""
    tan_c = p.tan_critical()
    return {"shape": p.shape, "c": p.c, "mu_s": p.mu_s, "tan_phi_c": tan_c, "phi_c_deg": math.degrees(math.atan(tan_c)),
            "slope_deg": math.degrees(p.angle), "rolls": p.rolls()}


def rod_contacts(data: Columns, length: float) -> Array:
    """Boolean per sample: an end below the floor."""
    return np.array([rod_end_below_floor(y, theta, length) for y, theta in zip(data["y"], data["theta"])])


def contact_runs(contact: Array) -> List[Tuple[int, int]]:
    """(start, end) index ranges of consecutive contact samples."""
    edges = np.flatnonzero(np.diff(np.concatenate([[0], contact.astype(int), [0]])))
    return list(zip(edges[::2], edges[1::2]))


def rod_energy_swing(data: Columns, length: float) -> Dict[str, Any]:
    """The largest swing of the energy inside one contact, relative to the energy just before it, and the
    energy change over the whole run."""
    e, contact = data["energy"], rod_contacts(data, length)
    swings = []
    for start, end in contact_runs(contact):
        before = e[max(start - 1, 0)]
        inside = e[max(start - 1, 0):min(end + 1, len(e))]
        swings.append({"t": float(data["t"][start]), "swing": float((inside.max() - inside.min()) / abs(before)),
                       "change": float((inside[-1] - before) / abs(before))})
    largest = max(swings, key=lambda s: s["swing"], default=None)
    return {"contacts": len(swings), "largest_swing": largest, "energy_first": float(e[0]),
            "energy_last": float(e[-1]), "energy_min": float(e.min()), "energy_max": float(e.max())}


# --- figures ---------------------------------------------------------------------------------------
Specs = Dict[str, BodySpec]


def save(fig: Any, path: str) -> None:
    """A small PNG: 80 dpi, 128 colours (plots have few), so that the README's copies stay light."""
    from PIL import Image
    buffer = io.BytesIO()
    fig.savefig(buffer, dpi=80, format="png")
    plt.close(fig)
    buffer.seek(0)
    Image.open(buffer).convert("RGB").quantize(colors=128).save(path, optimize=True)


def rods_of(run: Run, specs: Specs) -> List[Tuple[str, RodSpec]]:
    return [(name, spec) for name, spec in specs.items() if name in run and isinstance(spec, RodSpec)]


def rollers_of(run: Run, specs: Specs) -> List[Tuple[str, RollerSpec]]:
    return [(name, spec) for name, spec in specs.items() if name in run and isinstance(spec, RollerSpec)]


def plot_rods(run: Run, specs: Specs, path: str) -> None:
    rods = rods_of(run, specs)
    fig, axes = plt.subplots(len(rods), 1, figsize=(10, 3.2 * len(rods)), squeeze=False)
    for ax, (name, p) in zip(axes[:, 0], rods):
        d = run[name]
        contact = rod_contacts(d, p.length)
        step = max(1, int(round(ROD_EVERY / np.median(np.diff(d["t"])))))
        for i in range(0, len(d["t"]), step):
            half = 0.5 * p.length * np.array([math.cos(d["theta"][i]), math.sin(d["theta"][i])])
            ends = np.array([[d["x"][i], d["y"][i]] - half, [d["x"][i], d["y"][i]] + half])
            ax.plot(ends[:, 0], ends[:, 1], color="tab:red" if contact[i] else "tab:blue", lw=1.0, alpha=0.7)
        ax.plot(broken_at_restarts(d, "x", "vx"), broken_at_restarts(d, "y", "vx"), color="black", lw=0.8,
                label="centre")
        if p.floor_length > 0:
            ax.plot([0.0, p.floor_length], [0.0, 0.0], color="saddlebrown", lw=2)
        else:
            ax.axhline(0.0, color="saddlebrown", lw=2)
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_ylim(bottom=-0.3)
        ax.set_title(f"{name}: centre path, the rod every {ROD_EVERY:g} s (red: an end in the floor), "
                     f"L = {p.length:g} m, k = {p.k:g} N/m, t = 0..{d['t'][-1]:g} s", fontsize=9)
    fig.tight_layout()
    save(fig, path)


def broken_at_restarts(d: Columns, key: str, speed: str = "v") -> Array:
    """A column with NaN between laps, so that a restart is not drawn as a line back to the start (`speed`:
    the velocity along x, v for a roller, vx for a rod)."""
    parts = [d[key][start:end].astype(float) for start, end in laps(d["t"], d["x"], d[speed])]
    return np.concatenate([np.append(part, np.nan) for part in parts])[:-1]


def shade_slipping(ax: Any, t: Array, mode: Array) -> None:
    slipping = np.asarray(mode) == "slipping"
    for start, end in contact_runs(slipping):
        ax.axvspan(t[start], t[min(end, len(t) - 1)], color="0.9", lw=0)


def plot_rollers(run: Run, specs: Specs, path: str, summary: Summary) -> None:
    rollers = rollers_of(run, specs)
    fig, axes = plt.subplots(len(rollers), 1, figsize=(9, 2.4 * len(rollers)), sharex=True, squeeze=False)
    for ax, (name, p) in zip(axes[:, 0], rollers):
        d = run[name]
        shade_slipping(ax, d["t"], d["mode"])
        t, x, v, w = (broken_at_restarts(d, k) for k in ("t", "x", "v", "omega"))
        ax.plot(t, v, color="tab:blue", lw=1.2, label="v")
        ax.plot(t, -w * p.radius, color="tab:red", lw=1.2, ls="--", label="-ωR")
        ax.set_ylabel("v, -ωR (m/s)")
        ax_x = ax.twinx()
        ax_x.plot(t, x, color="0.3", lw=0.8, label="x (right axis)")
        ax_x.set_ylabel("x (m)")
        for event in summary["rollers"][name]["slip_to_roll"]:
            ax.axvline(event["t"], color="tab:green", lw=1.0)
            ax.annotate(f" rolls at\n {event['t']:.4f} s", (event["t"], 0.05), xycoords=("data", "axes fraction"),
                        fontsize=7, color="tab:green")
        crit = summary["rollers"][name]["critical_angle"]
        ax.set_title(f"{name} ({p.shape}, c = {p.c:.3g}): slope {crit['slope_deg']:.1f}°, critical angle "
                     f"{crit['phi_c_deg']:.1f}°, μs = {p.mu_s:g}, μd = {p.mu_d:g}  (grey: slipping)", fontsize=9)
        handles = ax.get_legend_handles_labels()[0] + ax_x.get_legend_handles_labels()[0]
        ax.legend(handles=handles, loc="upper left", fontsize=7, ncol=3)
    axes[-1, 0].set_xlabel("t (s)")
    fig.tight_layout()
    save(fig, path)


def slope_groups(run: Run, specs: Specs) -> List[List[Tuple[str, RollerSpec]]]:
    """Rollers that share a slope (angle and length), two or more to a group."""
    groups: Dict[Tuple[float, float], List[Tuple[str, RollerSpec]]] = {}
    for name, p in rollers_of(run, specs):
        groups.setdefault((p.angle, p.slope), []).append((name, p))
    return [group for group in groups.values() if len(group) > 1]


def plot_race(run: Run, specs: Specs, path: str, summary: Summary) -> None:
    groups = slope_groups(run, specs)
    fig, axes = plt.subplots(2, len(groups), figsize=(9, 6), sharex="col", squeeze=False)
    for col, group in enumerate(groups):
        top, bottom = axes[0, col], axes[1, col]
        for rank, (name, p) in enumerate(group):
            d = run[name]
            start, end = laps(d["t"], d["x"], d["v"])[0]
            width = 1.0 + 1.5 * (len(group) - 1 - rank)  # wider first: equal curves (two slipping shapes) both show
            colour = COLOURS.get(p.shape, "tab:gray")
            finish = summary["rollers"][name]["finish_times"]
            crit = summary["rollers"][name]["critical_angle"]
            label = (f"{name}: c = {p.c:.3g}, φc = {crit['phi_c_deg']:.1f}°, "
                     f"{'rolls' if crit['rolls'] else 'slips'}" + (f", down at {finish[0]:.3f} s" if finish else ""))
            top.plot(d["t"][start:end], d["x"][start:end], color=colour, lw=width, label=label)
            bottom.plot(d["t"][start:end], d["v"][start:end], color=colour, lw=width, label=f"{name}: v")
            bottom.plot(d["t"][start:end], -d["omega"][start:end] * p.radius, color=colour, ls="--", lw=width,
                        label=f"{name}: -ωR")
            if finish:
                top.plot(finish[0], p.slope, "o", color=colour)
        p = group[0][1]
        top.axhline(p.slope, color="saddlebrown", lw=1)
        top.set_ylabel("x along the slope (m)")
        top.set_title(f"Down the same slope: {math.degrees(p.angle):.1f}° (tan = {math.tan(p.angle):.3f}), "
                      f"{p.slope:g} m, μs = {p.mu_s:g}, μd = {p.mu_d:g}", fontsize=9)
        top.legend(fontsize=7, loc="upper left")
        bottom.set_ylabel("v, -ωR (m/s)")
        bottom.set_xlabel("t (s)")
        bottom.legend(fontsize=7, loc="upper left", ncol=2)
    fig.tight_layout()
    save(fig, path)


def zoom_on_contact(ax: Any, d: Columns, swing: Optional[Event], colour: str) -> None:
    """An inset with the energy through the contact of the largest swing."""
    if not swing:
        return
    low, high = d["energy"].min(), d["energy"].max()
    ax.set_ylim(low - 0.1 * (high - low), high + 1.4 * (high - low))  # room above the data for the inset
    inset = ax.inset_axes([0.3, 0.56, 0.3, 0.36])
    near = np.abs(d["t"] - swing["t"]) < 0.06
    inset.plot(d["t"][near], d["energy"][near], color=colour, lw=1.0, marker=".", ms=2)
    inset.set_title(f"t = {swing['t']:.2f} s: swing {100 * swing['swing']:.1f} %", fontsize=7)
    inset.tick_params(labelsize=6)


def plot_energy(run: Run, specs: Specs, path: str) -> None:
    names = list(run)
    heights = [2 if isinstance(specs[n], RodSpec) else 1 for n in names]
    fig, axes = plt.subplots(len(names), 1, figsize=(9, 1.6 * sum(heights) + 0.4), sharex=True, squeeze=False,
                             gridspec_kw={"height_ratios": heights})
    for ax, name in zip(axes[:, 0], names):
        d, p = run[name], specs[name]
        if isinstance(p, RodSpec):
            for start, end in contact_runs(rod_contacts(d, p.length)):
                ax.axvspan(d["t"][start], d["t"][min(end, len(d["t"]) - 1)], color="lightcoral", alpha=0.4, lw=0)
            colour, shaded = "tab:blue", "an end in the floor"
        else:
            shade_slipping(ax, d["t"], d["mode"])
            colour, shaded = COLOURS.get(p.shape, "tab:blue"), "slipping"
        ax.plot(d["t"], d["energy"], color=colour, lw=1.0)
        ax.set_ylabel("E (J)")
        spread = float(np.ptp(d["energy"]))
        if spread < 1e-6:  # constant to rounding: show it flat rather than magnify the rounding
            ax.set_ylim(d["energy"].mean() - 1, d["energy"].mean() + 1)
            shaded += f"; constant to {spread:.1e} J"
        ax.set_title(f"{name}: energy (shaded: {shaded})", fontsize=9)
        if isinstance(p, RodSpec):
            zoom_on_contact(ax, d, rod_energy_swing(d, p.length)["largest_swing"], colour)
    axes[-1, 0].set_xlabel("t (s)")
    fig.tight_layout()
    save(fig, path)


# --- main ------------------------------------------------------------------------------------------
def summarise(run: Run, specs: Specs) -> Summary:
    summary: Summary = {"rods": {}, "rollers": {}}
    for name, d in run.items():
        steps = np.diff(d["t"])
        gaps = int((steps > 1.5 * np.median(steps)).sum()) if len(steps) else 0
        if gaps:  # e.g. rosbag record dropping messages of a node run as fast as possible
            print(f"plot_run: warning: {name}: {gaps} gaps in the samples", file=sys.stderr)
        p = specs[name]
        if isinstance(p, RodSpec):
            summary["rods"][name] = rod_energy_swing(d, p.length)
        else:
            summary["rollers"][name] = {"critical_angle": critical_angle(p), "slip_to_roll": slip_to_roll(d, p.radius),
                                        "finish_times": finish_times(d, p.slope)}
    return summary


def print_summary(summary: Summary) -> None:
    for name, s in summary["rods"].items():
        big = s["largest_swing"]
        line = f"{name}: {s['contacts']} contacts, energy {s['energy_first']:.4f} -> {s['energy_last']:.4f} J"
        if big:
            line += f"; largest swing inside a contact {100 * big['swing']:.2f} % (at t = {big['t']:.2f} s)"
        print(line)
    for name, s in summary["rollers"].items():
        c = s["critical_angle"]
        rolls = ", ".join(f"{e['t']:.6f}" + ("" if e["exact"] else " (approx.)") for e in s["slip_to_roll"])
        print(f"{name}: {c['shape']}, tan(phi_c) = mu_s (1+c)/c = {c['tan_phi_c']:.3f} ({c['phi_c_deg']:.1f} deg) "
              f"on {c['slope_deg']:.1f} deg: {'rolls' if c['rolls'] else 'slips'}; slip-to-roll at t = "
              f"{rolls or 'never'}; off the slope at t = {', '.join(f'{t:.4f}' for t in s['finish_times']) or 'never'}")


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    parser.add_argument("config", help="the run's YAML config")
    parser.add_argument("run", help="a .bag (node or simulate --bag) or a folder of simulate's CSV files")
    parser.add_argument("--out-dir", required=True)
    parser.add_argument("--prefix", default="")
    parser.add_argument("--figures", default="rod,rollers,race,energy", help="comma-separated subset")
    args = parser.parse_args(argv)
    config = load_config(args.config)
    run = load_run(args.run, config)
    specs = {name: body_spec(config, name) for name in run}
    os.makedirs(args.out_dir, exist_ok=True)
    summary = summarise(run, specs)
    wanted = set(args.figures.split(","))
    figures: Dict[str, Tuple[bool, Callable[[str], None]]] = {
        "rod": (bool(rods_of(run, specs)), lambda path: plot_rods(run, specs, path)),
        "rollers": (bool(rollers_of(run, specs)), lambda path: plot_rollers(run, specs, path, summary)),
        "race": (bool(slope_groups(run, specs)), lambda path: plot_race(run, specs, path, summary)),
        "energy": (True, lambda path: plot_energy(run, specs, path)),
    }
    for name, (drawable, plot) in figures.items():
        if name in wanted and drawable:
            plot(os.path.join(args.out_dir, f"{args.prefix}{name}.png"))
    with open(os.path.join(args.out_dir, f"{args.prefix}summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    print_summary(summary)
    return 0


if __name__ == "__main__":
    sys.exit(main())
