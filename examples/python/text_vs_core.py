#!/usr/bin/env python3
"""The text's two problems from Python, as a student of the text works: its bouncing-rod program beside the
package's exact core, and the incline's closed form against the core's rollers (docs/python.md).

    source devel/setup.bash                      # or install/setup.bash: rigid_body_sim.core
    python3 examples/python/text_vs_core.py      # prints the differences and times
    python3 examples/python/text_vs_core.py --figure text_vs_core.png   # and draws them

Each part below is a notebook cell as it stands.
"""
import argparse
import math
import os
import sys
import time
from typing import Dict, Optional

import numpy as np

from rigid_body_sim import core

# The text's program (section 16.3.3) is the text's loop statement for statement, with numpy in place of
# pylab: one transcription in the package, which its tests check the C++ rod against.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "test", "data"))
from text_program_reference import text_program  # noqa: E402  (the path above comes first)

THETA0 = 0.3  # the text draws theta0 at random; config/rod.yaml fixes it


def rod_cell() -> Dict[str, np.ndarray]:
    """The text's rod, its program and the package's World (Euler-Cromer, substeps: 1, the text's dt),
    sampled at every step: their difference and their times."""
    start = time.perf_counter()
    n, t, r, v, theta, omega = text_program(THETA0)
    text_seconds = time.perf_counter() - start

    world = core.World({
        "rate": 1000, "publish_rate": 50, "gravity": 9.8,
        "bodies": {"rod": {"type": "rod", "length": 1.0, "mass": 0.5, "k": 1000.0, "x0": 0.0, "y0": 4.0,
                           "vx0": 2.0, "theta0": THETA0, "integrator": "euler_cromer", "substeps": 1}},
    })
    start = time.perf_counter()
    rod = world.run(10.0, sample_rate=1000)["rod"]
    core_seconds = time.perf_counter() - start

    ours = {"x": rod["x"][:n], "y": rod["y"][:n], "theta": rod["theta"][:n]}
    theirs = {"x": r[:, 0], "y": r[:, 1], "theta": theta}
    first_3s = t < 3.0 - 1e-9
    print(f"the text's rod, theta0 = {THETA0}, {n - 1} steps of dt = 1 ms:")
    for field in ours:
        gap = np.abs(ours[field] - theirs[field])
        print(f"  {field:5s} largest |core - text| over the first 3 s {gap[first_3s].max():.1e}, "
              f"over 10 s {gap.max():.1e}")
    print(f"  time: the text's program {text_seconds * 1e3:.0f} ms, the World {core_seconds * 1e3:.2f} ms "
          f"({text_seconds / core_seconds:.0f} times faster)")
    return {"t": t, "text_y": r[:, 1], "core_y": ours["y"], "gap_y": np.abs(ours["y"] - theirs["y"])}


def incline_cell() -> Dict[str, Dict[str, np.ndarray]]:
    """A sphere, a cylinder and a ring released from rest on a 20 degree slope: rolling without slipping,
    x(t) = g sin(phi) t^2 / (2 (1 + c)) (eq. 16.69), against the World's rollers."""
    world = core.World({"bodies": {shape: {"type": "roller", "shape": shape, "incline_angle": 0.349}
                                   for shape in ("sphere", "cylinder", "ring")}})
    config = core_config(world)
    rolled = world.run(2.0, sample_rate=1000)
    out = {}
    print("rolling from rest down 0.349 rad, 2 s:")
    for shape, run in rolled.items():
        body = config["bodies"][shape]
        c, phi, g = body["inertia_factor"], body["incline_angle"], config["gravity"]
        closed = g * math.sin(phi) * run["t"] ** 2 / (2 * (1 + c))
        print(f"  {shape:8s} c = {c:<4} x(2 s) = {run['x'][-1]:.6f} m, largest |core - closed form| "
              f"{np.abs(run['x'] - closed).max():.1e} m, mode {set(run['mode'])}")
        out[shape] = {"t": run["t"], "x": run["x"], "closed": closed}
    return out


def core_config(world: core.World) -> Dict:
    import yaml
    return yaml.safe_load(world.config())


def draw(path: str, rod: Dict[str, np.ndarray], incline: Dict[str, Dict[str, np.ndarray]]) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (top, middle, bottom) = plt.subplots(3, 1, figsize=(8, 9), constrained_layout=True)
    top.plot(rod["t"], rod["text_y"], lw=2.5, color="0.7", label="the text's program (numpy)")
    top.plot(rod["t"], rod["core_y"], lw=1, color="C0", label="rigid_body_sim.core World, substeps: 1")
    top.set(xlabel="t (s)", ylabel="centre height y (m)", title="The text's rod, theta0 = 0.3")
    top.legend(loc="upper right")
    middle.plot(rod["t"], rod["gap_y"], color="C3")
    largest = rod["gap_y"].max()
    middle.set(xlabel="t (s)", ylabel="|y core - y text| (m)",
               title="Their difference: " + ("none, bit for bit" if largest == 0 else f"at most {largest:.1e} m"))
    for i, (shape, run) in enumerate(incline.items()):
        bottom.plot(run["t"], run["closed"], lw=3, color="0.8")
        bottom.plot(run["t"][::100], run["x"][::100], "o", ms=4, color=f"C{i}", label=f"{shape}: World")
    bottom.plot([], [], lw=3, color="0.8", label="closed form g sin(phi) t^2 / (2 (1 + c))")
    bottom.set(xlabel="t (s)", ylabel="x along the slope (m)", title="Rolling down 0.349 rad from rest")
    bottom.legend(loc="upper left")
    fig.savefig(path, dpi=80)
    print(f"figure: {path}")


def main(argv: Optional[list] = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--figure", help="draw the rod and the incline into this PNG")
    args = parser.parse_args(argv)
    rod = rod_cell()
    incline = incline_cell()
    if args.figure:
        draw(args.figure, rod, incline)
    return 0


if __name__ == "__main__":
    sys.exit(main())
