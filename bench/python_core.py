#!/usr/bin/python3
"""The text's rod from Python, in one process: rigid_body_sim.core's World (config/rod.yaml, the text's values
and dt, 10 s sampled as simulate samples it) against the text's own numpy program, each run N times.
Prints {"core": [s, ...], "text": [s, ...], "steps": n} as JSON (make bench's rows; run alone, the ratio too).

  python_core.py [--repeat N]      (the package's devel or install space sourced)
  python_core.py --repeat 0        one run of the World, untimed (what hyperfine times as a whole process)
"""
import argparse
import json
import os
import sys
import time

import rigid_body_sim.core as core  # a compiled module; mypy reads its stub, rigid_body_sim/core.pyi

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "test", "data"))
from text_program_reference import text_program  # noqa: E402  (the path above comes first)

ROD = os.path.join(HERE, "..", "config", "rod.yaml")


def main() -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7,
                        help="runs of each, each timed; 0: one run of the World, untimed")
    args = parser.parse_args()
    with open(ROD) as f:
        config = f.read()
    core.World(config).run(10.0)  # numpy's import and the module's first call, outside the timing
    if args.repeat == 0:
        return 0
    core_seconds, text_seconds = [], []
    for _ in range(args.repeat):
        start = time.perf_counter()
        core.World(config).run(10.0)  # a world from the config's text, its 10 s, the arrays
        core_seconds.append(time.perf_counter() - start)
    steps = 0
    for _ in range(args.repeat):
        start = time.perf_counter()
        steps = text_program(0.3)[0] - 1  # rod.yaml's theta0
        text_seconds.append(time.perf_counter() - start)
    print(json.dumps({"core": core_seconds, "text": text_seconds, "steps": steps}))
    core_best, text_best = min(core_seconds), min(text_seconds)
    print(f"core {core_best * 1e3:.3f} ms, text's program {text_best * 1e3:.1f} ms: {text_best / core_best:.0f} x",
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
