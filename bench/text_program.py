#!/usr/bin/python3
"""The text's bouncing-rod program, headless: the baseline that `make bench` times against `simulate`.

The program itself is test/data/text_program_reference.py's text_program(): the text's loop statement
for statement with numpy in place of pylab, its plotting removed (one transcription, shared with the
test that checks the C++ rod against it). As in the text, theta0 is drawn at random, for its 10 s.

  text_program.py                 one run, as the text does (what hyperfine times as a whole process)
  text_program.py --repeat N      N runs; prints the seconds each spent in the program (its stepping)
"""
import argparse
import importlib.abc
import importlib.util
import json
import os
import sys
import time
from typing import Any

from numpy import pi, random


def load_text_program() -> Any:
    """test/data's text_program(), loaded from its file: the test data is no package, and this one transcription
    of the text is the test's reference as well as the bench's program."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "test", "data", "text_program_reference.py")
    spec = importlib.util.spec_from_file_location("text_program_reference", path)
    # isinstance, not `is not None`: bullseye's typeshed types spec.loader as a protocol without exec_module.
    assert spec is not None and isinstance(spec.loader, importlib.abc.Loader)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return getattr(module, "text_program")  # getattr: Debian 11's mypy knows no attribute of a module made here


text_program = load_text_program()


def main() -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--repeat", type=int, default=0, help="runs, each timed; 0: one run, untimed")
    args = parser.parse_args()
    seconds = []
    steps = 0
    for _ in range(max(args.repeat, 1)):
        theta0 = 2 * pi * random.rand(1)[0]  # the text: theta[0] = 2*pi*random.rand(1)
        start = time.perf_counter()
        steps = text_program(theta0)[0] - 1
        seconds.append(time.perf_counter() - start)
    if args.repeat:
        print(json.dumps({"steps": steps, "seconds": seconds}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
