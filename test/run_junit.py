#!/usr/bin/env python3
"""Runs one test command and writes its verdict as a JUnit result file, so that catkin's run_tests (and
catkin_test_results) count a scripted test like a gtest or a rostest. The verdict follows ctest's rules:
the exit status, or with --pass-regex a match in the output (the status then does not count); a match of
--fail-regex fails. A command still running after --timeout seconds is killed with its process group and
fails. The output is passed through and kept (its tail) in the result file.

Usage: run_junit.py RESULT.xml NAME [--timeout S] [--pass-regex R] [--fail-regex R] -- COMMAND [ARG...]
Exit status: 0 when the test passed, 1 otherwise."""
import argparse
import os
import re
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from typing import List, Optional, Tuple

KEPT_OUTPUT = 20000  # characters of the output's end kept in the result file


def run(command: List[str], timeout: float) -> Tuple[Optional[int], str]:
    """The exit status (None after a timeout) and the whole output, echoed as it comes."""
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True)
    try:
        output, _ = process.communicate(timeout=timeout)
        status: Optional[int] = process.returncode
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        output, _ = process.communicate()
        status = None
    text = output.decode(errors="replace")
    sys.stdout.write(text)
    sys.stdout.flush()
    return status, text


def verdict(status: Optional[int], output: str, args: argparse.Namespace) -> Optional[str]:
    """None when the test passed, else why it failed."""
    if status is None:
        return f"timed out after {args.timeout:g} s"
    if args.fail_regex and re.search(args.fail_regex, output):
        return f"the output matches the fail regex {args.fail_regex!r}"
    if args.pass_regex:
        return None if re.search(args.pass_regex, output) else f"no match of the pass regex {args.pass_regex!r}"
    return None if status == 0 else f"exit status {status}"


def write_result(path: str, name: str, seconds: float, failure: Optional[str], output: str) -> None:
    suite = ET.Element("testsuite", name=name, tests="1", failures="0" if failure is None else "1",
                       errors="0", time=f"{seconds:.3f}")
    case = ET.SubElement(suite, "testcase", classname=name, name=name, time=f"{seconds:.3f}")
    if failure is not None:
        ET.SubElement(case, "failure", message=failure).text = failure
    ET.SubElement(suite, "system-out").text = output[-KEPT_OUTPUT:]
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    ET.ElementTree(suite).write(path, encoding="utf-8", xml_declaration=True)


def main() -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("result", help="the JUnit file to write")
    parser.add_argument("name", help="the test's name")
    parser.add_argument("--timeout", type=float, default=600.0, help="seconds before the command is killed")
    parser.add_argument("--pass-regex", help="pass when the output matches (the exit status does not count)")
    parser.add_argument("--fail-regex", help="fail when the output matches")
    argv = sys.argv[1:]
    if "--" not in argv or argv.index("--") == len(argv) - 1:
        parser.error("no command: -- COMMAND [ARG...]")
    args = parser.parse_args(argv[:argv.index("--")])
    command = argv[argv.index("--") + 1:]
    start = time.monotonic()
    status, output = run(command, args.timeout)
    failure = verdict(status, output, args)
    write_result(args.result, args.name, time.monotonic() - start, failure, output)
    if failure is not None:
        print(f"run_junit: {args.name} FAILED: {failure}", file=sys.stderr)
    return 0 if failure is None else 1


if __name__ == "__main__":
    sys.exit(main())
