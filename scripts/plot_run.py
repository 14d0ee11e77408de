#!/usr/bin/env python3
"""Plots of a rigid_body_sim run, from a bag of the node (sim.launch record:=true, or simulate --bag)
or from a folder of simulate's CSV files (simulate CONFIG --out-dir DIR), and of a sweep
(simulate CONFIG --sweep ... --out-dir DIR: its sweep.csv, or DIR).

  plot_run.py CONFIG.yaml RUN --out-dir DIR [--prefix NAME_] [--figures rod,rollers,race,energy,sweep]

RUN is a .bag file, a folder of <body>.csv files, or a sweep (a sweep.csv, or the folder holding it);
CONFIG is the run's config (it gives each rod's length, each roller's radius, shape and slope, and the
bodies' types). Writes, for what the run holds:
  <prefix>rod.png      the path of each rod's centre with the rod drawn every 0.1 s (the text's Fig. 16.17)
  <prefix>rollers.png  per roller: x(t), v(t) and -omega R(t), slipping shaded, its events marked (slip-to-roll,
                       finish, ...: a line each)
  <prefix>race.png     rollers that share a slope (same angle and length), first lap: who is down first
  <prefix>energy.png   energy against time of every body, rod contacts shaded, every event marked at its energy
  <prefix>sweep_<body>.png  for a sweep, per body with a swept key: each outcome (what the sweep adds after
                       the final state: energy drift, bounces or slip-to-roll time; and a final state
                       that is a text: the mode) against the swept keys, as lines for one key and as heat
                       maps for two (the first key across, the second up); more than two are refused
  <prefix>summary.json the numbers behind them (also printed): each body's events (instants and values), the
                       instants each figure marks, critical angles, the rods' energy swing in contact; for a
                       sweep, per outcome the values drawn, their range and where it is reached, and how often
                       each value occurs (whole numbers and texts; `empty`: variants without a value, e.g.
                       never rolling)
Every instant comes from the core's events (docs/events.md: a run's events.csv, a bag's /sim/events), none
from the samples: the marks (a slip-to-roll, a finish, a block's stop: every kind but the restarts), the laps
(cut at the events whose kind has the role restart), a rod's contacts (between contact_began and
contact_ended). Marks need no word of a body type: their kinds and roles are the description's.
The swept keys and the outcomes are read from the sweep's header (sim_tools.sweep_columns)."""
import argparse
import io
import json
import math
import os
import sys
from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Optional, Protocol, Set, Tuple

import matplotlib
import numpy as np
from rigid_body_sim import runs
from rigid_body_sim.sim_tools import (EVENT_ROLES, SWEEP_RESULT_LABELS, BlockSpec, BodySpec, Config, Event, RodSpec,
                                      RollerSpec, SweepColumns, body_spec, event_lines, face_of, is_sweep_header,
                                      key_unit, labelled, load_config, read_bag_events, read_states, role,
                                      state_fields, sweep_columns)

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)

# Arrays are np.ndarray, with no alias: bullseye has no numpy.typing (numpy 1.19), and its mypy (0.812)
# rejects an alias of np.ndarray, which is untyped there.
Columns = Dict[str, np.ndarray]  # one body's samples: column -> values
Run = Dict[str, Columns]  # body -> its samples
Events = Dict[str, List[Event]]  # body -> its events, in time order
Summary = Dict[str, Dict[str, Any]]

ROD_EVERY = 0.1  # s between drawn rods
COLOURS = {"sphere": "tab:red", "cylinder": "tab:green", "ring": "tab:orange", "spherical_shell": "tab:purple"}
# A colour and a marker per event kind, by the kind's place in its type's list (a roller's slip_to_roll green).
KIND_COLOURS = ("tab:green", "tab:purple", "tab:brown", "tab:olive", "tab:cyan", "tab:pink")
KIND_MARKERS = ("o", "s", "D", "^", "v", "P")


# --- reading a run ---------------------------------------------------------------------------------
def load_csv_folder(folder: str) -> Run:
    """{body: {column: array}} from simulate's <body>.csv files (their header starts with t; a sweep's
    summary does not; events.csv is no body's)."""
    run: Run = {}
    for name in sorted(os.listdir(folder)):
        if not name.endswith(".csv") or name == runs.EVENTS_FILE:
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


def load_events(path: str) -> List[Event]:
    """The run's events: a bag's /sim/events, or the events.csv simulate wrote beside the CSV files."""
    if path.endswith(".bag"):
        return read_bag_events(path)
    if not os.path.isfile(os.path.join(path, runs.EVENTS_FILE)):
        sys.exit(f"plot_run: no {runs.EVENTS_FILE} in {path}: its instants are the core's events (simulate "
                 f"--out-dir writes the file beside the CSV files)")
    return runs.read_events(path)


def load_run(path: str, config: Config) -> Tuple[Run, Events]:
    """The run's bodies in the config's order, and each one's events."""
    if not path.endswith(".bag") and not os.path.isdir(path):
        sys.exit(f"plot_run: {path} is not a .bag, a folder of CSV files or a sweep")
    run = load_bag(path) if path.endswith(".bag") else load_csv_folder(path)
    if not run:
        sys.exit(f"plot_run: no body states in {path} (a .bag with /sim/<body>/state or a folder of CSV files)")
    unknown = sorted(set(run) - set(config["bodies"]))
    if unknown:
        sys.exit(f"plot_run: bodies {', '.join(unknown)} of {path} are not in the config")
    events: Events = {name: [] for name in config["bodies"] if name in run}
    found = load_events(path)
    if not found:
        print(f"plot_run: warning: no events in {path}: nothing marked", file=sys.stderr)
    for event in found:
        if event["body"] in events:
            events[event["body"]].append(event)
    return {name: run[name] for name in events}, events


# --- analysis --------------------------------------------------------------------------------------
def laps(t: np.ndarray, happened: List[Event]) -> List[Tuple[int, int]]:
    """Index ranges [start, end) of the samples between the body's restarts (its events whose kind has the role
    restart); a sample at a restart's instant is the new lap's first: the state then is the restarted one."""
    cuts = np.searchsorted(t, [e["t"] for e in happened if role(e) == "restart"], side="left")
    edges = sorted({0, len(t), *map(int, cuts)})  # int per element: numpy 2's stubs and tolist()
    return [(start, end) for start, end in zip(edges[:-1], edges[1:]) if end > start]


def marked(happened: List[Event]) -> List[Event]:
    """The events a figure marks: all but the restarts, which its lines show as a break."""
    return [e for e in happened if role(e) != "restart"]


def kind_index(event: Event) -> int:
    """The kind's place in its type's list (the description's; past its end for a kind it does not declare)."""
    declared = list(EVENT_ROLES.get(event["type"], {}))
    return declared.index(event["kind"]) if event["kind"] in declared else len(declared)


def kind_style(event: Event) -> Tuple[str, str]:
    """A kind's colour and marker, the same in every figure."""
    i = kind_index(event)
    return KIND_COLOURS[i % len(KIND_COLOURS)], KIND_MARKERS[i % len(KIND_MARKERS)]


def record_marks(summary: Summary, figure: str, body: str, drawn: List[Event]) -> None:
    """The instants a figure marked, by body and kind, for summary.json."""
    kinds = summary["marks"].setdefault(figure, {}).setdefault(body, {})
    for event in drawn:
        kinds.setdefault(event["kind"], []).append(event["t"])


def events_summary(happened: List[Event]) -> Dict[str, List[Dict[str, Any]]]:
    """A body's events by kind: each one's instant and what its kind adds."""
    kinds: Dict[str, List[Dict[str, Any]]] = {}
    for event in happened:
        kinds.setdefault(event["kind"], []).append({"t": event["t"], "values": event["values"]})
    return kinds


def critical_angle(p: RollerSpec) -> Dict[str, Any]:
    """tan(phi_c) = mu_s (1 + c) / c: the steepest slope on which the body can roll without slipping (a
    figure's title and a race's labels: the verdict beside the run, no instant)."""
    tan_c = p.tan_critical()
    return {"shape": p.shape, "c": p.c, "mu_s": p.mu_s, "tan_phi_c": tan_c, "phi_c_deg": math.degrees(math.atan(tan_c)),
            "slope_deg": math.degrees(p.angle), "rolls": p.rolls()}


def spans(happened: List[Event], opens: str, closes: str, end: float) -> List[Tuple[float, float]]:
    """The intervals [from, to) while anything an `opens` event opened is still open: each is keyed by the
    event's values (a rod's end A or B), closed by a `closes` event with the same values or by a restart;
    one still open at the run's `end` ends there."""
    open_now: Set[str] = set()
    found: List[Tuple[float, float]] = []
    since = 0.0
    for event in happened:
        key = json.dumps(event["values"], sort_keys=True)
        was_open = bool(open_now)
        if event["kind"] == opens:
            open_now.add(key)
        elif event["kind"] == closes:
            open_now.discard(key)
        elif role(event) == "restart":
            open_now.clear()
        if open_now and not was_open:
            since = event["t"]
        elif was_open and not open_now:
            found.append((since, event["t"]))
    if open_now:
        found.append((since, end))
    return found


def in_spans(t: np.ndarray, intervals: List[Tuple[float, float]]) -> np.ndarray:
    """Boolean per sample: inside one of the intervals (a sample at an interval's end is outside it)."""
    inside = np.zeros(len(t), dtype=bool)
    for since, until in intervals:
        inside |= (t >= since) & (t < until)
    return inside


def span_indices(t: np.ndarray, intervals: List[Tuple[float, float]]) -> List[Tuple[int, int]]:
    """(start, end) index ranges of the samples inside each interval (empty for one between two samples)."""
    return [(int(np.searchsorted(t, since)), int(np.searchsorted(t, until))) for since, until in intervals]


# A rod's contacts: from an end's contact_began to its contact_ended (the rod's events; docs/events.md).
ROD_CONTACT = ("contact_began", "contact_ended")


def rod_contact_spans(data: Columns, happened: List[Event]) -> List[Tuple[float, float]]:
    """The intervals while an end of the rod is in its floor, from its events."""
    return spans(happened, *ROD_CONTACT, end=float(data["t"][-1]))


def rod_energy_swing(data: Columns, happened: List[Event]) -> Dict[str, Any]:
    """The largest swing of the energy inside one contact (its samples, with the one before and the one
    after), relative to the energy just before it, and the energy change over the whole run. A contact's
    instant is its contact_began's."""
    e, t = data["energy"], data["t"]
    swings = []
    intervals = rod_contact_spans(data, happened)
    for (since, _), (start, end) in zip(intervals, span_indices(t, intervals)):
        before = e[max(start - 1, 0)]
        inside = e[max(start - 1, 0):min(end + 1, len(e))]
        swings.append({"t": since, "swing": float((inside.max() - inside.min()) / abs(before)),
                       "change": float((inside[-1] - before) / abs(before))})
    largest = max(swings, key=lambda s: s["swing"], default=None)
    return {"contacts": len(swings), "largest_swing": largest, "energy_first": float(e[0]),
            "energy_last": float(e[-1]), "energy_min": float(e.min()), "energy_max": float(e.max())}


# --- figures ---------------------------------------------------------------------------------------
Specs = Dict[str, BodySpec]


@dataclass(frozen=True)
class States:
    """A run as its figures take it: each body's samples, spec and events, and the summary, to which each
    figure adds the instants it marks."""
    run: Run
    specs: Specs
    events: Events
    summary: Summary


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


def plot_rods(r: States, path: str) -> None:
    rods = rods_of(r.run, r.specs)
    fig, axes = plt.subplots(len(rods), 1, figsize=(10, 3.2 * len(rods)), squeeze=False)
    for ax, (name, p) in zip(axes[:, 0], rods):
        d, happened = r.run[name], r.events[name]
        contact = in_spans(d["t"], rod_contact_spans(d, happened))
        step = max(1, int(round(ROD_EVERY / np.median(np.diff(d["t"])))))
        for i in range(0, len(d["t"]), step):
            half = 0.5 * p.length * np.array([math.cos(d["theta"][i]), math.sin(d["theta"][i])])
            ends = np.array([[d["x"][i], d["y"][i]] - half, [d["x"][i], d["y"][i]] + half])
            ax.plot(ends[:, 0], ends[:, 1], color="tab:red" if contact[i] else "tab:blue", lw=1.0, alpha=0.7)
        ax.plot(broken_at_restarts(d, "x", happened), broken_at_restarts(d, "y", happened), color="black", lw=0.8,
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


def broken_at_restarts(d: Columns, key: str, happened: List[Event]) -> np.ndarray:
    """A column with NaN between laps, so that a restart is not drawn as a line back to the start."""
    parts = [d[key][start:end].astype(float) for start, end in laps(d["t"], happened)]
    return np.concatenate([np.append(part, np.nan) for part in parts])[:-1]


def shade_mode(ax: Any, t: np.ndarray, mode: np.ndarray, shaded: str) -> None:
    """Grey behind the samples whose mode is `shaded` (a roller's slipping, a block's sliding)."""
    inside = np.asarray(mode) == shaded
    edges = np.flatnonzero(np.diff(np.concatenate([[0], inside.astype(int), [0]])))
    for start, end in zip(edges[::2], edges[1::2]):
        ax.axvspan(t[start], t[min(int(end), len(t) - 1)], color="0.9", lw=0)


def mark_instants(ax: Any, happened: List[Event]) -> List[Event]:
    """A line at each event the figures mark, in its kind's colour, with its kind and instant beside it (each
    kind at a height of its own); the events marked."""
    drawn = marked(happened)
    for event in drawn:
        colour, _ = kind_style(event)
        ax.axvline(event["t"], color=colour, lw=1.0)
        ax.annotate(f" {event['kind'].replace('_', ' ')}\n {event['t']:.4f} s",
                    (event["t"], 0.05 + 0.22 * (kind_index(event) % 4)), xycoords=("data", "axes fraction"),
                    fontsize=7, color=colour)
    return drawn


def plot_rollers(r: States, path: str) -> None:
    rollers = rollers_of(r.run, r.specs)
    fig, axes = plt.subplots(len(rollers), 1, figsize=(9, 2.4 * len(rollers)), sharex=True, squeeze=False)
    for ax, (name, p) in zip(axes[:, 0], rollers):
        d, happened = r.run[name], r.events[name]
        shade_mode(ax, d["t"], d["mode"], "slipping")
        t, x, v, w = (broken_at_restarts(d, k, happened) for k in ("t", "x", "v", "omega"))
        ax.plot(t, v, color="tab:blue", lw=1.2, label="v")
        ax.plot(t, -w * p.radius, color="tab:red", lw=1.2, ls="--", label="-ωR")
        ax.set_ylabel("v, -ωR (m/s)")
        ax_x = ax.twinx()
        ax_x.plot(t, x, color="0.3", lw=0.8, label="x (right axis)")
        ax_x.set_ylabel("x (m)")
        record_marks(r.summary, "rollers", name, mark_instants(ax, happened))
        crit = r.summary["rollers"][name]["critical_angle"]
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


def first_finish(happened: List[Event]) -> Optional[Event]:
    """The finish of the first lap: a finish before any restart."""
    for event in happened:
        if role(event) == "restart" and event["t"] > 0.0:  # one at t = 0 (spawn, config) starts the first lap
            return None
        if role(event) == "finish":
            return event
    return None


def plot_race(r: States, path: str) -> None:
    groups = slope_groups(r.run, r.specs)
    fig, axes = plt.subplots(2, len(groups), figsize=(9, 6), sharex="col", squeeze=False)
    for col, group in enumerate(groups):
        top, bottom = axes[0, col], axes[1, col]
        for rank, (name, p) in enumerate(group):
            d = r.run[name]
            start, end = laps(d["t"], r.events[name])[0]
            width = 1.0 + 1.5 * (len(group) - 1 - rank)  # wider first: equal curves (two slipping shapes) both show
            colour = COLOURS.get(p.shape, "tab:gray")
            finish = first_finish(r.events[name])
            crit = r.summary["rollers"][name]["critical_angle"]
            place = finish["values"].get("place") if finish else None
            label = (f"{name}: c = {p.c:.3g}, φc = {crit['phi_c_deg']:.1f}°, "
                     f"{'rolls' if crit['rolls'] else 'slips'}" + (f", down at {finish['t']:.3f} s" if finish else "")
                     + (f", place {place:g}" if isinstance(place, float) else ""))
            top.plot(d["t"][start:end], d["x"][start:end], color=colour, lw=width, label=label)
            bottom.plot(d["t"][start:end], d["v"][start:end], color=colour, lw=width, label=f"{name}: v")
            bottom.plot(d["t"][start:end], -d["omega"][start:end] * p.radius, color=colour, ls="--", lw=width,
                        label=f"{name}: -ωR")
            if finish:
                top.plot(finish["t"], finish["state"]["x"], "o", color=colour)
                record_marks(r.summary, "race", name, [finish])
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


def zoom_on_contact(ax: Any, d: Columns, swing: Optional[Dict[str, Any]], colour: str) -> None:
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


def mark_energies(ax: Any, happened: List[Event]) -> List[Event]:
    """A point at each event the figures mark, at the energy of its state then, a marker per kind (named in a
    legend); the events marked."""
    drawn = marked(happened)
    for kind in dict.fromkeys(event["kind"] for event in drawn):
        these = [event for event in drawn if event["kind"] == kind]
        colour, marker = kind_style(these[0])
        ax.plot([e["t"] for e in these], [e["state"]["energy"] for e in these], ls="none", marker=marker, ms=4,
                mfc="none", color=colour, label=kind)
    if drawn:
        ax.legend(loc="upper right", fontsize=7, ncol=4)
    return drawn


def plot_energy(r: States, path: str) -> None:
    names = list(r.run)
    looks = [look_of(r.specs[n].TYPE) for n in names]
    heights = [look.energy_height for look in looks]
    fig, axes = plt.subplots(len(names), 1, figsize=(9, 1.6 * sum(heights) + 0.4), sharex=True, squeeze=False,
                             gridspec_kw={"height_ratios": heights})
    for ax, name, look in zip(axes[:, 0], names, looks):
        d, p, happened = r.run[name], r.specs[name], r.events[name]
        colour, shaded = look.shade_energy(ax, d, p, happened)
        ax.plot(d["t"], d["energy"], color=colour, lw=1.0)
        ax.set_ylabel("E (J)")
        spread = float(np.ptp(d["energy"]))
        if spread < 1e-6:  # constant to rounding: show it flat rather than magnify the rounding
            ax.set_ylim(d["energy"].mean() - 1, d["energy"].mean() + 1)
            shaded += f"; constant to {spread:.1e} J"
        record_marks(r.summary, "energy", name, mark_energies(ax, happened))
        ax.set_title(f"{name}: energy (shaded: {shaded}; marked: its events)", fontsize=9)
        look.zoom_energy(ax, d, p, happened, colour)
    axes[-1, 0].set_xlabel("t (s)")
    fig.tight_layout()
    save(fig, path)


# --- each body type's own look --------------------------------------------------------------------
def shade_rod_contacts(ax: Any, d: Columns, p: RodSpec, happened: List[Event]) -> Tuple[str, str]:
    for since, until in rod_contact_spans(d, happened):
        ax.axvspan(since, until, color="lightcoral", alpha=0.4, lw=0)
    return "tab:blue", "an end in the floor"


def zoom_on_rod_contact(ax: Any, d: Columns, p: RodSpec, happened: List[Event], colour: str) -> None:
    zoom_on_contact(ax, d, rod_energy_swing(d, happened)["largest_swing"], colour)


def rod_numbers(d: Columns, p: RodSpec, happened: List[Event]) -> Dict[str, Any]:
    return rod_energy_swing(d, happened)


def shade_roller_slipping(ax: Any, d: Columns, p: RollerSpec, happened: List[Event]) -> Tuple[str, str]:
    shade_mode(ax, d["t"], d["mode"], "slipping")
    return COLOURS.get(p.shape, "tab:blue"), "slipping"


def shade_block_sliding(ax: Any, d: Columns, p: BlockSpec, happened: List[Event]) -> Tuple[str, str]:
    shade_mode(ax, d["t"], d["mode"], "sliding")  # its energy falls while it slides
    return "tab:pink", "sliding"


def roller_numbers(d: Columns, p: RollerSpec, happened: List[Event]) -> Dict[str, Any]:
    return {"critical_angle": critical_angle(p)}


def nothing(*_: Any) -> None:
    pass


# Callables as dataclass fields typed by protocols: Debian 11's mypy (0.812) takes a field typed Callable
# for a method and calls it with the instance.
class ShadeEnergy(Protocol):
    def __call__(self, __ax: Any, __d: Any, __p: Any, __happened: List[Event]) -> Tuple[str, str]: ...


class ZoomEnergy(Protocol):
    def __call__(self, __ax: Any, __d: Any, __p: Any, __happened: List[Event], __colour: str) -> None: ...


@dataclass(frozen=True)
class TypeLook:
    """How plot_run draws and sums up the bodies of one type, beyond its events' marks (which need no row)."""
    # Shades the energy's axes (ax, columns, spec, events) and gives (the line's colour, what the shading shows).
    shade_energy: ShadeEnergy
    energy_height: int = 1  # the energy axes' share of the figure's height
    zoom_energy: ZoomEnergy = nothing  # (ax, columns, spec, events, colour): an inset after the line
    summary: Optional[Tuple[str, Callable[..., Dict[str, Any]]]] = None  # (its group, its numbers)


# Each body type's look, by its `type`.
TYPES: Dict[str, TypeLook] = {
    RodSpec.TYPE: TypeLook(shade_rod_contacts, energy_height=2, zoom_energy=zoom_on_rod_contact,
                           summary=("rods", rod_numbers)),
    RollerSpec.TYPE: TypeLook(shade_roller_slipping, summary=("rollers", roller_numbers)),
    BlockSpec.TYPE: TypeLook(shade_block_sliding),
}


def look_of(type_name: str) -> TypeLook:
    return face_of(TYPES, type_name, "look (its row in TYPES)", "scripts/plot_run.py")


# --- sweeps ----------------------------------------------------------------------------------------
# Large type: the sweep figures are shown on projectors.
PROJECTOR = {"font.size": 15, "axes.titlesize": 16, "axes.labelsize": 16, "xtick.labelsize": 14,
             "ytick.labelsize": 14, "legend.fontsize": 13, "figure.titlesize": 17}
MISSING_COLOUR = "0.75"  # heat-map cells and marks of variants without a value (slip-to-roll: never)
MISSING_LABEL = "no value"


@dataclass(frozen=True)
class Sweep:
    path: str
    columns: SweepColumns
    values: Dict[str, np.ndarray]  # column -> numbers (NaN where empty), or texts if any value is not a number

    def swept_bodies(self) -> List[str]:
        """The bodies with a swept key, in the order of the keys."""
        return list(dict.fromkeys(key.partition(".")[0] for key in self.columns.keys))

    def outcomes(self, body: str) -> List[str]:
        """What the sweep adds about the body, and its final state's texts (a roller's mode), in header order."""
        results = self.columns.results(body)
        return [field for field in self.columns.fields[body]
                if field in results or self.values[f"{body}.{field}"].dtype.kind == "U"]


def sweep_file(path: str) -> Optional[str]:
    """The sweep file RUN names (a sweep.csv, or a folder holding one), None if RUN is not a sweep."""
    candidate = path if path.endswith(".csv") else os.path.join(path, "sweep.csv")
    if not os.path.isfile(candidate):
        return None
    with open(candidate) as f:
        return candidate if is_sweep_header(f.readline().strip().split(",")) else None


def column_values(texts: List[str]) -> np.ndarray:
    """Numbers (NaN where empty), or the texts if any is not a number."""
    try:
        return np.array([float(text) if text else math.nan for text in texts])
    except ValueError:
        return np.array(texts)


def load_sweep(path: str, config: Config) -> Sweep:
    with open(path) as f:
        header = f.readline().strip().split(",")
        rows = [line.rstrip("\n").split(",") for line in f if line.strip()]
    if not rows:
        sys.exit(f"plot_run: {path} has a header and no variant")
    columns = sweep_columns(header)
    unknown = sorted(set(columns.fields) - set(config["bodies"]))
    if unknown:
        sys.exit(f"plot_run: bodies {', '.join(unknown)} of {path} are not in the config")
    if not 1 <= len(columns.keys) <= 2:
        sys.exit(f"plot_run: {path} sweeps {len(columns.keys)} keys ({', '.join(columns.keys)}); a figure shows "
                 f"one swept key (lines) or two (heat maps)")
    return Sweep(path, columns, {name: column_values([row[i] for row in rows]) for i, name in enumerate(header)})


def outcome_label(sweep: Sweep, column: str) -> str:
    field = column.partition(".")[2]
    if sweep.values[column].dtype.kind == "U":
        return f"final {field}"
    words, unit = SWEEP_RESULT_LABELS.get(field, (field.replace("_", " "), ""))
    return labelled(words, unit)


def json_number(value: Any) -> Any:
    """A number for JSON (None where the sweep has no value), or the text as it is."""
    if isinstance(value, str):
        return value
    return None if math.isnan(value) else float(value)


def at(sweep: Sweep, row: int) -> Dict[str, float]:
    """The swept keys' values of a row."""
    return {key: float(sweep.values[key][row]) for key in sweep.columns.keys}


def whole_numbers(values: np.ndarray) -> bool:
    return bool(len(values)) and bool(np.all(values == np.round(values)))


def outcome_stats(sweep: Sweep, column: str) -> Dict[str, Any]:
    """Range of a numeric outcome and where it is reached (the first such variant), the variants without a
    value; how often each value occurs for whole numbers and texts."""
    values = sweep.values[column]
    if values.dtype.kind == "U":
        texts, counts = np.unique(values, return_counts=True)
        return {"counts": {str(text): int(n) for text, n in zip(texts, counts)}}
    have = np.flatnonzero(~np.isnan(values))
    stats: Dict[str, Any] = {"empty": int(len(values) - len(have))}
    if len(have):
        low, high = have[np.argmin(values[have])], have[np.argmax(values[have])]
        stats.update(min=float(values[low]), min_at=at(sweep, low), max=float(values[high]), max_at=at(sweep, high),
                     mean=float(values[have].mean()))
    if whole_numbers(values[have]):
        numbers, counts = np.unique(values[have], return_counts=True)
        stats["counts"] = {str(int(number)): int(n) for number, n in zip(numbers, counts)}
    return stats


def line_data(sweep: Sweep, column: str) -> Tuple[np.ndarray, np.ndarray]:
    """The outcome against the one swept key, in the key's order."""
    x = sweep.values[sweep.columns.keys[0]]
    order = np.argsort(x, kind="stable")
    return x[order], sweep.values[column][order]


def grid_data(sweep: Sweep, column: str) -> Tuple[np.ndarray, np.ndarray, List[List[Any]]]:
    """The outcome on the grid of the two swept keys: the first key's values (x), the second's (y), and
    z[i][j] at (x[j], y[i]) (None where no variant has that pair, or it has no value)."""
    first, second = (sweep.values[key] for key in sweep.columns.keys)
    xs, ys = np.unique(first), np.unique(second)
    z: List[List[Any]] = [[None] * len(xs) for _ in ys]
    for row, value in enumerate(sweep.values[column]):
        z[int(np.searchsorted(ys, second[row]))][int(np.searchsorted(xs, first[row]))] = json_number(value)
    return xs, ys, z


def summarise_sweep(sweep: Sweep, config: Config) -> Dict[str, Any]:
    keys = {key: {"unit": key_unit(config, key), "values": int(len(np.unique(sweep.values[key]))),
                  "min": float(sweep.values[key].min()), "max": float(sweep.values[key].max())}
            for key in sweep.columns.keys}
    bodies: Dict[str, Any] = {}
    for body in sweep.swept_bodies():
        bodies[body] = {}
        for field in sweep.outcomes(body):
            column = f"{body}.{field}"
            if len(sweep.columns.keys) == 1:
                x, y = line_data(sweep, column)
                drawn: Dict[str, Any] = {"x": x.tolist(), "y": [json_number(v) for v in y]}
            else:
                xs, ys, z = grid_data(sweep, column)
                drawn = {"x": xs.tolist(), "y": ys.tolist(), "z": z}
            bodies[body][field] = {"label": outcome_label(sweep, column), **outcome_stats(sweep, column),
                                   "drawn": drawn}
    return {"sweep": {"file": sweep.path, "variants": len(sweep.values["variant"]),
                      "t": float(sweep.values["t"].max()), "keys": keys}, "bodies": bodies}


def key_axis(ax: Any, axis: str, key: str, unit: str, values: np.ndarray) -> None:
    """Label an axis with the key and its unit; an angle that spans half a turn or more in steps of π/2."""
    (ax.set_xlabel if axis == "x" else ax.set_ylabel)(labelled(key, unit))
    if unit == "rad" and np.ptp(values) >= math.pi:
        halves = np.arange(math.ceil(values.min() / (math.pi / 2)), math.floor(values.max() / (math.pi / 2)) + 1)
        names = {0: "0", 1: "π/2", 2: "π", -1: "-π/2", -2: "-π"}
        labels = [names.get(int(h), f"{int(h) // 2}π" if h % 2 == 0 else f"{int(h)}π/2") for h in halves]
        # Ticks, then labels: matplotlib 3.3 (bullseye) has no labels argument to set_xticks.
        (ax.set_xticks if axis == "x" else ax.set_yticks)(halves * math.pi / 2)
        (ax.set_xticklabels if axis == "x" else ax.set_yticklabels)(labels)


def draw_line(ax: Any, x: np.ndarray, y: np.ndarray, label: str) -> None:
    """One outcome against one key: points (joined when few enough to follow), texts as rows, variants
    without a value as ticks along the bottom."""
    from matplotlib.ticker import MaxNLocator

    few = len(x) <= 60
    marker = {"marker": "o", "ms": 6} if few else {"marker": ".", "ms": 8 if len(x) <= 300 else 5}
    if y.dtype.kind == "U":
        texts = sorted(set(y.tolist()))
        ax.plot(x, [texts.index(v) for v in y], ls="none", color="tab:blue", **marker)
        ax.set_yticks(range(len(texts)))  # then the labels: no labels argument in matplotlib 3.3
        ax.set_yticklabels(texts)
        ax.set_ylim(-0.5, len(texts) - 0.5)
        ax.set_ylabel(label)
        return
    ax.plot(x, y, color="tab:blue", lw=1.5 if few else 0, **marker)
    numbers = y[~np.isnan(y)]
    if whole_numbers(numbers):
        ax.yaxis.set_major_locator(MaxNLocator(integer=True))
    # Both signs: a line at zero (not np.nanmin(y, initial=0.0): numpy 1.19, bullseye's, has no `initial`).
    if (numbers < 0.0).any() and (numbers > 0.0).any():
        ax.axhline(0.0, color="0.4", lw=0.8)
    missing = np.isnan(y)
    if missing.all():
        ax.text(0.5, 0.5, f"{MISSING_LABEL} in any variant", transform=ax.transAxes, ha="center", va="center")
        ax.set_yticks([])
    elif missing.any():
        ax.plot(x[missing], np.full(missing.sum(), 0.04), ls="none", marker="|", ms=16, mew=2,
                color=MISSING_COLOUR, transform=ax.get_xaxis_transform(), label=MISSING_LABEL)
        ax.legend(loc="upper right")
    ax.set_ylabel(label)


def cell_edges(values: np.ndarray) -> np.ndarray:
    """Edges of heat-map cells centred on the values (sorted, distinct)."""
    if len(values) == 1:
        half = 0.5 * (abs(values[0]) or 1.0)
        return np.array([values[0] - half, values[0] + half])
    middles = 0.5 * (values[1:] + values[:-1])
    return np.concatenate([[2 * values[0] - middles[0]], middles, [2 * values[-1] - middles[-1]]])


def draw_heat_map(fig: Any, ax: Any, xs: np.ndarray, ys: np.ndarray, z: List[List[Any]], label: str) -> None:
    """One outcome over two keys: a colour per cell with a colour bar; texts as categories with a legend;
    cells without a value in grey."""
    from matplotlib.colors import BoundaryNorm, ListedColormap
    from matplotlib.patches import Patch

    edges = (cell_edges(xs), cell_edges(ys))
    flat = [v for row in z for v in row if v is not None]
    handles = []
    if any(isinstance(v, str) for v in flat):
        texts = sorted(set(flat))
        grid = np.ma.masked_invalid([[math.nan if v is None else texts.index(v) for v in row] for row in z])
        colours = [plt.get_cmap("tab10")(i) for i in range(len(texts))]
        ax.pcolormesh(*edges, grid, cmap=ListedColormap(colours), vmin=-0.5, vmax=len(texts) - 0.5)
        handles = [Patch(color=c, label=t) for c, t in zip(colours, texts)]
    else:
        grid = np.ma.masked_invalid([[math.nan if v is None else v for v in row] for row in z])
        numbers = np.array(flat, dtype=float)
        style: Dict[str, Any] = {"cmap": "viridis"}
        if len(numbers) and numbers.min() < 0.0 < numbers.max():  # signed: white at zero
            bound = float(np.abs(numbers).max())
            style = {"cmap": "RdBu_r", "vmin": -bound, "vmax": bound}
        elif whole_numbers(numbers) and 1 < len(np.unique(numbers)) <= 25:  # a colour per whole number
            bounds = np.arange(numbers.min() - 0.5, numbers.max() + 1.0)
            style["norm"] = BoundaryNorm(bounds, plt.get_cmap("viridis").N)
        mesh = ax.pcolormesh(*edges, grid, **style)
        bar = fig.colorbar(mesh, ax=ax)
        bar.set_label(label)
        if "norm" in style:
            bar.set_ticks(np.unique(numbers)[:: max(1, len(np.unique(numbers)) // 8)])
    ax.set_facecolor(MISSING_COLOUR)
    ax.set_title(label + (f" (grey: {MISSING_LABEL})" if np.ma.getmaskarray(grid).any() else ""))
    if handles:
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.0, 1.0))


def plot_sweep_body(sweep: Sweep, config: Config, body: str, summary: Dict[str, Any], path: str) -> None:
    """Every outcome of one body against the swept keys: stacked lines (one key) or heat maps (two)."""
    fields = list(summary["bodies"][body])
    keys = sweep.columns.keys
    variants, t = summary["sweep"]["variants"], summary["sweep"]["t"]
    with plt.rc_context(PROJECTOR):
        if len(keys) == 1:
            fig, axes = plt.subplots(len(fields), 1, figsize=(12, 3.4 * len(fields) + 1.0), sharex=True,
                                     squeeze=False)
            for ax, field in zip(axes[:, 0], fields):
                x, y = line_data(sweep, f"{body}.{field}")
                draw_line(ax, x, y, summary["bodies"][body][field]["label"])
                ax.grid(alpha=0.3)
            key_axis(axes[-1, 0], "x", keys[0], key_unit(config, keys[0]), sweep.values[keys[0]])
        else:
            columns = min(2, len(fields))
            rows = math.ceil(len(fields) / columns)
            fig, axes = plt.subplots(rows, columns, figsize=(8 * columns, 6 * rows + 0.8), squeeze=False)
            for ax, field in zip(axes.flat, fields):
                xs, ys, z = grid_data(sweep, f"{body}.{field}")
                draw_heat_map(fig, ax, xs, ys, z, summary["bodies"][body][field]["label"])
                key_axis(ax, "x", keys[0], key_unit(config, keys[0]), xs)
                key_axis(ax, "y", keys[1], key_unit(config, keys[1]), ys)
            for ax in axes.flat[len(fields):]:
                ax.set_visible(False)
        fig.suptitle(f"{body}: {variants} runs of {t:g} s, {' and '.join(keys)} swept")
        fig.tight_layout()
        save(fig, path)


def print_sweep_summary(summary: Dict[str, Any]) -> None:
    sweep = summary["sweep"]
    keys = ", ".join(f"{key} in [{k['min']:g}, {k['max']:g}] ({k['values']} values)"
                     for key, k in sweep["keys"].items())
    print(f"{sweep['file']}: {sweep['variants']} variants, t = {sweep['t']:g} s; {keys}")
    for body, outcomes in summary["bodies"].items():
        for field, o in outcomes.items():
            parts = []
            if "min" in o:
                parts.append(f"{o['min']:g} .. {o['max']:g}, mean {o['mean']:g}")
            if o.get("empty"):
                parts.append(f"{o['empty']} without a value")
            if "counts" in o:
                parts.append(", ".join(f"{value}: {n}" for value, n in o["counts"].items()))
            line = f"{body}.{field}: " + "; ".join(parts)
            print(line)


# --- main ------------------------------------------------------------------------------------------
def summarise(run: Run, specs: Specs, events: Events) -> Summary:
    summary: Summary = {look.summary[0]: {} for look in TYPES.values() if look.summary}
    summary.update(events={}, marks={})
    for name, d in run.items():
        steps = np.diff(d["t"])
        gaps = int((steps > 1.5 * np.median(steps)).sum()) if len(steps) else 0
        if gaps:  # e.g. rosbag record dropping messages of a node run as fast as possible
            print(f"plot_run: warning: {name}: {gaps} gaps in the samples", file=sys.stderr)
        p = specs[name]
        look = look_of(p.TYPE)
        if look.summary:
            group, numbers = look.summary
            summary[group][name] = numbers(d, p, events[name])
        summary["events"][name] = events_summary(events[name])
    return summary


def print_summary(summary: Summary, events: Events) -> None:
    for name, s in summary["rods"].items():
        big = s["largest_swing"]
        line = f"{name}: {s['contacts']} contacts, energy {s['energy_first']:.4f} -> {s['energy_last']:.4f} J"
        if big:
            line += f"; largest swing inside a contact {100 * big['swing']:.2f} % (at t = {big['t']:.2f} s)"
        print(line)
    for name, s in summary["rollers"].items():
        c = s["critical_angle"]
        print(f"{name}: {c['shape']}, tan(phi_c) = mu_s (1+c)/c = {c['tan_phi_c']:.3f} ({c['phi_c_deg']:.1f} deg) "
              f"on {c['slope_deg']:.1f} deg: {'rolls' if c['rolls'] else 'slips'}")
    for name, lines in event_lines(event for happened in events.values() for event in happened).items():
        for line in lines:
            print(f"{name}: {line}")


FIGURES = ("rod", "rollers", "race", "energy", "sweep")


def plot_sweep(path: str, config: Config, out_dir: str, prefix: str, wanted: Set[str]) -> None:
    sweep = load_sweep(path, config)
    summary = summarise_sweep(sweep, config)
    if "sweep" in wanted:
        for body in sweep.swept_bodies():
            plot_sweep_body(sweep, config, body, summary, os.path.join(out_dir, f"{prefix}sweep_{body}.png"))
    with open(os.path.join(out_dir, f"{prefix}summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    print_sweep_summary(summary)


def plot_states(path: str, config: Config, out_dir: str, prefix: str, wanted: Set[str]) -> None:
    run, events = load_run(path, config)
    specs = {name: body_spec(config, name) for name in run}
    summary = summarise(run, specs, events)
    r = States(run, specs, events, summary)
    figures: Dict[str, Tuple[bool, Callable[[str], None]]] = {
        "rod": (bool(rods_of(run, specs)), lambda path: plot_rods(r, path)),
        "rollers": (bool(rollers_of(run, specs)), lambda path: plot_rollers(r, path)),
        "race": (bool(slope_groups(run, specs)), lambda path: plot_race(r, path)),
        "energy": (True, lambda path: plot_energy(r, path)),
    }
    for name, (drawable, plot) in figures.items():
        if name in wanted and drawable:
            plot(os.path.join(out_dir, f"{prefix}{name}.png"))
    with open(os.path.join(out_dir, f"{prefix}summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    print_summary(summary, events)


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    parser.add_argument("config", help="the run's YAML config")
    parser.add_argument("run", help="a .bag (node or simulate --bag), a folder of simulate's CSV files, or a "
                        "sweep (its sweep.csv or its folder)")
    parser.add_argument("--out-dir", required=True)
    parser.add_argument("--prefix", default="")
    parser.add_argument("--figures", default=",".join(FIGURES), help="comma-separated subset")
    args = parser.parse_args(argv)
    wanted = set(args.figures.split(","))
    if not wanted <= set(FIGURES):
        parser.error(f"--figures: {', '.join(sorted(wanted - set(FIGURES)))} unknown (known: {', '.join(FIGURES)})")
    config = load_config(args.config)
    os.makedirs(args.out_dir, exist_ok=True)
    sweep = sweep_file(args.run)
    if sweep:
        plot_sweep(sweep, config, args.out_dir, args.prefix, wanted)
    else:
        plot_states(args.run, config, args.out_dir, args.prefix, wanted)
    return 0


if __name__ == "__main__":
    sys.exit(main())
