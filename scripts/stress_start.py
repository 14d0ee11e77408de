#!/usr/bin/python3
"""make stress-start: starts sim_node many times under one master of its own and counts how each start ended.

Starts alternate between a refused config (the rows of test/bad_input that the parameter server can hold, in
turn) and a good one (config/demo.yaml). A refused start must exit 1 with exactly one line on stderr, the
refusal; a good start must publish a state, then exit 0 on SIGINT. Every wait is a condition with a deadline.
Prints the count of every outcome and exits 1 if any start ended otherwise; the stdout, stderr (and, with
--strace, the system calls) of those starts are kept.
"""
from __future__ import annotations

import argparse
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
from collections import Counter
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Optional

import rosgraph
import rospy
import yaml

REPO = Path(__file__).resolve().parent.parent
POLL = 0.02  # s between two looks at a condition that has no event of its own (a process's exit)

REFUSED_OK = "refused: exit 1 with its one line on stderr"
REFUSED_SILENT = "refused: silent exit (exit 1, nothing on stdout or stderr)"
REFUSED_LINES = "refused: exit 1, not exactly one line on stderr"
REFUSED_OTHER_LINE = "refused: exit 1, one line that is not the refusal"
REFUSED_CODE = "refused: an exit code other than 1"
REFUSED_TIMEOUT = "refused: no exit within the deadline"
GOOD_OK = "good: first state seen, then exit 0 on SIGINT"
GOOD_EARLY_EXIT = "good: exited before its first state"
GOOD_NO_STATE = "good: no state within the deadline"
GOOD_NO_EXIT = "good: no exit within the deadline after SIGINT"
GOOD_CODE = "good: an exit code other than 0 after SIGINT"
GOOD_STDERR = "good: exit 0, but something on stderr"
CRASHED = "crashed by a signal"
OUTCOMES = [REFUSED_OK, REFUSED_SILENT, REFUSED_LINES, REFUSED_OTHER_LINE, REFUSED_CODE, REFUSED_TIMEOUT,
            GOOD_OK, GOOD_EARLY_EXIT, GOOD_NO_STATE, GOOD_NO_EXIT, GOOD_CODE, GOOD_STDERR, CRASHED]
EXPECTED = {REFUSED_OK, GOOD_OK}


class ConfigLoader(yaml.SafeLoader):
    """The configs are read by yaml-cpp (YAML 1.2), where 1e6 is a number; PyYAML (YAML 1.1) makes it text."""


ConfigLoader.add_implicit_resolver("tag:yaml.org,2002:float",
                                   re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)[eE][-+]?\d+$"), list("-+0123456789."))


@dataclass
class RefusedRow:
    what: str
    params: Optional[dict]  # loaded into the node's private namespace; None: nothing at all


@dataclass
class Start:
    """One start of sim_node: its process and the folder of its output."""
    name: str
    folder: Path
    process: subprocess.Popen
    traced: bool

    def node_pid(self) -> int:
        """The node's own pid (under strace, the tracer's child)."""
        if not self.traced:
            return self.process.pid
        try:
            children = Path(f"/proc/{self.process.pid}/task/{self.process.pid}/children").read_text().split()
        except OSError:  # strace is gone already
            return self.process.pid
        return int(children[0]) if children else self.process.pid

    def kill(self) -> None:
        if self.process.poll() is None:
            for pid in {self.node_pid(), self.process.pid}:
                try:
                    os.kill(pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
            self.process.wait()

    def stderr_lines(self) -> list[str]:
        return [line for line in (self.folder / "stderr").read_text(errors="replace").splitlines() if line.strip()]

    def stdout(self) -> str:
        return (self.folder / "stdout").read_text(errors="replace")


def refused_rows() -> list[RefusedRow]:
    """The bad inputs sim_node meets at start-up, as test_node_bad_input_startup reads them."""
    folder = REPO / "test" / "bad_input"
    rows = []
    for entry in yaml.safe_load((folder / "configs.yaml").read_text()):
        if entry.get("node", True) and "file" not in entry:
            rows.append(RefusedRow(entry["what"], yaml.load(entry["config"], Loader=ConfigLoader)))
    for entry in yaml.safe_load((folder / "node_startup.yaml").read_text()):
        params = yaml.load(entry["params"], Loader=ConfigLoader) if "params" in entry else None
        rows.append(RefusedRow(entry["what"], params))
    return rows


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def wait_until(condition: Callable[[], bool], deadline: float) -> bool:
    """Whether condition() held before `deadline` seconds passed."""
    end = time.monotonic() + deadline
    while not condition():
        if time.monotonic() > end:
            return False
        time.sleep(POLL)
    return True


def exit_code(process: subprocess.Popen, deadline: float) -> Optional[int]:
    """The process's exit code (negative: the signal that ended it); None if it runs past the deadline."""
    try:
        return process.wait(timeout=deadline)
    except subprocess.TimeoutExpired:
        return None


class Stress:
    """The master, the driver's own rospy node, and the starts."""

    def __init__(self, args: argparse.Namespace, scratch: Path) -> None:
        self.args = args
        self.scratch = scratch
        self.exe = args.exe or str(Path(args.devel).resolve() / "lib/rigid_body_sim/sim_node")
        self.counts: Counter[str] = Counter({outcome: 0 for outcome in OUTCOMES})
        self.details: list[str] = []
        self.rows = refused_rows()
        self.good = yaml.load((REPO / args.good_config).read_text(), Loader=ConfigLoader)
        self.good_body = next(iter(self.good["bodies"]))
        self.master: Optional[subprocess.Popen] = None

    def start_master(self) -> None:
        port = free_port()
        os.environ.update(ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_HOME=str(self.scratch / "ros_home"),
                          ROS_IP="127.0.0.1")
        os.environ.pop("ROS_HOSTNAME", None)
        with open(self.scratch / "roscore.log", "wb") as log:
            roscore = subprocess.Popen(["roscore", "-p", str(port)], stdout=log, stderr=subprocess.STDOUT,
                                       stdin=subprocess.DEVNULL, start_new_session=True)
        self.master = roscore
        master = rosgraph.Master("/stress_start")
        wait_until(lambda: roscore.poll() is not None or master.is_online(), self.args.deadline * 3)
        if roscore.poll() is not None or not master.is_online():
            raise SystemExit(f"stress-start: roscore did not come up (log: {self.scratch / 'roscore.log'})")
        rospy.init_node("stress_start", disable_signals=True)

    def stop_master(self) -> None:
        if self.master and self.master.poll() is None:
            os.killpg(self.master.pid, signal.SIGINT)
            if exit_code(self.master, self.args.deadline) is None:
                os.killpg(self.master.pid, signal.SIGKILL)
                self.master.wait()

    def launch(self, name: str) -> Start:
        folder = self.scratch / name
        folder.mkdir()
        command = [self.exe, f"__name:={name}"]
        if self.args.strace:
            command = ["strace", "-f", "-ff", "-qq", "-o", str(folder / "trace")] + command
        with open(folder / "stdout", "wb") as out, open(folder / "stderr", "wb") as err:
            process = subprocess.Popen(command, stdout=out, stderr=err, stdin=subprocess.DEVNULL)
        return Start(name, folder, process, self.args.strace)

    def refused(self, index: int, row: RefusedRow) -> str:
        name = f"refused{index}"
        if row.params is not None:
            rospy.set_param(f"/{name}", row.params)
        start = self.launch(name)
        try:
            code = exit_code(start.process, self.args.deadline)
        finally:
            start.kill()
            if row.params is not None:
                rospy.delete_param(f"/{name}")
        lines = start.stderr_lines()
        if code is None:
            outcome = REFUSED_TIMEOUT
        elif code < 0:
            outcome = CRASHED
        elif code != 1:
            outcome = REFUSED_CODE
        elif not lines and not start.stdout().strip():
            outcome = REFUSED_SILENT
        elif len(lines) != 1:
            outcome = REFUSED_LINES
        elif "refused config: " not in lines[0]:
            outcome = REFUSED_OTHER_LINE
        else:
            outcome = REFUSED_OK
        return self.record(start, outcome, f"{row.what}; exit {code}")

    def good_start(self, index: int) -> str:
        name = f"good{index}"
        rospy.set_param(f"/{name}", self.good)
        seen = threading.Event()
        subscriber = rospy.Subscriber(f"/{name}/{self.good_body}/state", rospy.AnyMsg, lambda _msg: seen.set())
        start = self.launch(name)
        code: Optional[int] = None
        try:
            wait_until(lambda: seen.is_set() or start.process.poll() is not None, self.args.deadline)
            if seen.is_set():
                os.kill(start.node_pid(), signal.SIGINT)
                code = exit_code(start.process, self.args.deadline)
                outcome = (GOOD_NO_EXIT if code is None else CRASHED if code < 0 else GOOD_CODE if code != 0
                           else GOOD_STDERR if start.stderr_lines() else GOOD_OK)
            elif start.process.poll() is not None:
                code = start.process.returncode
                outcome = CRASHED if code < 0 else GOOD_EARLY_EXIT
            else:
                outcome = GOOD_NO_STATE
        finally:
            start.kill()
            subscriber.unregister()
            rospy.delete_param(f"/{name}")
        return self.record(start, outcome, f"exit {code}")

    def record(self, start: Start, outcome: str, detail: str) -> str:
        self.counts[outcome] += 1
        if outcome in EXPECTED:
            shutil.rmtree(start.folder)
        else:
            kept = Path(self.args.keep) / start.name
            shutil.rmtree(kept, ignore_errors=True)
            kept.parent.mkdir(parents=True, exist_ok=True)
            shutil.move(str(start.folder), kept)
            self.details.append(f"{start.name}: {outcome} ({detail}); output in {kept}")
        return outcome

    def run(self) -> None:
        for index in range(self.args.runs):
            if index % 2 == 0:
                self.refused(index, self.rows[(index // 2) % len(self.rows)])
            else:
                self.good_start(index)
            if (index + 1) % self.args.progress == 0:
                unexpected = sum(n for outcome, n in self.counts.items() if outcome not in EXPECTED)
                print(f"  {index + 1} starts, {unexpected} unexpected", flush=True)

    def report(self, seconds: float) -> bool:
        """Prints the table; whether every start ended as expected."""
        runs = sum(self.counts.values())
        refused = (runs + 1) // 2  # the even starts
        print(f"stress-start: {runs} starts of sim_node under one master in {seconds:.0f} s"
              f"{' (under strace)' if self.args.strace else ''}: {refused} on refused configs (the rows of "
              f"test/bad_input in turn), the others on {self.args.good_config}")
        width = max(len(outcome) for outcome in OUTCOMES)
        for outcome in OUTCOMES:
            print(f"  {outcome:<{width}}  {self.counts[outcome]:>6}")
        for line in self.details:
            print(f"  {line}")
        ok = all(outcome in EXPECTED for outcome, n in self.counts.items() if n)
        print("stress-start: " + ("every start ended as expected" if ok else "UNEXPECTED OUTCOMES (above)"))
        return ok


def parse_args() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=int(os.environ.get("STRESS_RUNS", 1000)),
                        help="starts in all, half refused, half good (default: $STRESS_RUNS or 1000)")
    parser.add_argument("--devel", default="devel", help="the devel space with lib/rigid_body_sim/sim_node")
    parser.add_argument("--exe", help="the program to start instead of the build's sim_node (to try a change)")
    parser.add_argument("--good-config", default="config/demo.yaml", help="the good config, relative to the repo")
    parser.add_argument("--deadline", type=float, default=15.0,
                        help="seconds for each wait: a refusal's exit, a first state, the exit after SIGINT")
    parser.add_argument("--keep", default="build/stress-start",
                        help="where the output of the starts that ended otherwise than expected is kept")
    parser.add_argument("--strace", action="store_true",
                        help="run every start under strace -f -ff (kept only for those that end unexpectedly)")
    parser.add_argument("--progress", type=int, default=100, help="print a line every this many starts")
    return parser.parse_args()


def main() -> int:
    args = parse_args()
    if args.strace and not shutil.which("strace"):
        raise SystemExit("stress-start: --strace needs strace (apt-get install strace)")
    scratch = Path(tempfile.mkdtemp(prefix="stress_start_"))
    stress = Stress(args, scratch)
    began = time.monotonic()
    try:
        stress.start_master()
        stress.run()
    finally:
        stress.stop_master()
    ok = stress.report(time.monotonic() - began)
    shutil.rmtree(scratch, ignore_errors=True)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
