#!/usr/bin/python3
"""The text's bouncing-rod program, headless: the baseline that `make bench` times against `simulate`.

The program itself is test/data/text_program_reference.py's text_program(): the text's loop statement
for statement with numpy in place of pylab, its plotting removed (one transcription, shared with the
test that checks the C++ rod against it). As in the text, theta0 is drawn at random, for its 10 s.

  text_program.py                 one run, as the text does (what hyperfine times as a whole process)
  text_program.py --repeat N      N runs; prints the seconds each spent in the program (its stepping)
"""
import json
import os
import sys
import time

from numpy import pi, random

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "test", "data"))
from text_program_reference import text_program  # noqa: E402  (the path above comes first)


def main():
    repeat = int(sys.argv[2]) if len(sys.argv) == 3 and sys.argv[1] == "--repeat" else 0
    seconds = []
    for _ in range(max(repeat, 1)):
        theta0 = 2 * pi * random.rand(1)[0]  # the text: theta[0] = 2*pi*random.rand(1)
        start = time.perf_counter()
        n = text_program(theta0)[0]
        seconds.append(time.perf_counter() - start)
    if repeat:
        print(json.dumps({"steps": n - 1, "seconds": seconds}))


if __name__ == "__main__":
    main()
