#!/usr/bin/python3
"""The web view under load: what a class's pages (300, and a frozen one) cost the simulation and the web view,
and whether a page that watches still gets its frames.

sim.launch on config/demo.yaml at wall-clock pace, its own master; a rospy subscriber in this process takes
/sim/rod/state and measures the gaps between the states' arrivals (50 Hz: 20 ms apart), over one window each of:
  1. no web view (web:=false);
  2. the web view (web:=true), no page;
  3. CLIENTS pages reading every byte (bench/web_clients.py --drain, another process) and a watching page
     (web_clients.py, a process of its own) that parses every frame;
  4. the same and a frozen page: a WebSocket that finished its handshake and never reads (a receive buffer
     of 4 KiB), which the server can only drop frames for.
For each: the gaps' median, 99th percentile and maximum, sim_node's CPU and the web view's (share of one core,
the threads' schedstat), the frames the watching page received per second, the rod's states in them and the
frames the server dropped for it (sequence gaps), the bytes each of the other pages received per second, the
web view's resident memory at the window's start and end, and the frozen page's drops (from the web view's
line when it closes). Prints a Markdown table; exits 1 when the watching page got fewer than --need frames a
second in a window.

Usage: bench/web_load.py [--window S] [--clients N] [--need F]   (with the package's devel space sourced)"""
import argparse
import base64
import json
import os
import re
import socket
import statistics
import subprocess
import sys
import tempfile
import threading
import time
import urllib.request
from typing import Any, Dict, List, Optional

from rigid_body_sim.sim_tools import free_port, node_pid, resident_kib, rospy_on_python39, wait_for

from run_bench import cpu_seconds

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

rospy_on_python39()


class Launch:
    """sim.launch with or without the web view on the master at `env`'s ROS_MASTER_URI, its output kept."""

    def __init__(self, web: bool, web_port: int, env: Dict[str, str]) -> None:
        self.lines: List[str] = []
        self.process = subprocess.Popen(
            ["roslaunch", "rigid_body_sim", "sim.launch", f"web:={str(web).lower()}", f"web_port:={web_port}"],
            env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        threading.Thread(target=self.read, daemon=True).start()

    def read(self) -> None:
        assert self.process.stdout is not None
        for line in self.process.stdout:
            self.lines.append(line)

    def stop(self) -> None:
        self.process.send_signal(2)
        try:
            self.process.wait(timeout=60)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()


class Gaps:
    """Arrival times of /sim/rod/state at this process's subscriber."""

    def __init__(self) -> None:
        import rospy
        from rigid_body_sim.msg import RodState
        self.arrivals: List[float] = []
        rospy.Subscriber("/sim/rod/state", RodState, lambda _: self.arrivals.append(time.monotonic()),
                         queue_size=100)

    def since(self, index: int) -> List[float]:
        times = self.arrivals[index:]
        return [1000.0 * (b - a) for a, b in zip(times, times[1:])]


def percentile(values: List[float], p: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(p / 100.0 * len(ordered)))]


def frozen_page(port: int) -> socket.socket:
    """A WebSocket handshake, then nothing read ever again."""
    s = socket.socket()
    s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
    s.connect(("127.0.0.1", port))
    key = base64.b64encode(os.urandom(16)).decode()
    s.sendall((f"GET /ws HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
               f"Sec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\nOrigin: http://127.0.0.1:{port}\r\n\r\n")
              .encode())
    answer = b""
    while b"\r\n\r\n" not in answer:
        answer += s.recv(1)
    if b" 101 " not in answer.split(b"\r\n")[0]:
        raise RuntimeError(f"the frozen page's handshake: {answer!r}")
    return s


def window(name: str, seconds: float, gaps: Gaps, sim: int, web: Optional[int]) -> Dict[str, Any]:
    first = len(gaps.arrivals)
    sim0, web0, wall0 = cpu_seconds(sim), cpu_seconds(web) if web else 0.0, time.monotonic()
    rss0 = resident_kib(web) / 1024.0 if web else 0.0
    time.sleep(seconds)
    wall = time.monotonic() - wall0
    row: Dict[str, Any] = {"what": name, "gaps": gaps.since(first), "sim_cpu": 100.0 * (cpu_seconds(sim) - sim0) / wall,
                           "web_cpu": 100.0 * (cpu_seconds(web) - web0) / wall if web else None,
                           "rss": (rss0, resident_kib(web) / 1024.0) if web else None}
    print(f"  {name}: {len(row['gaps'])} gaps", file=sys.stderr, flush=True)
    return row


def clients(url: str, n: int, seconds: float, drain: bool = False) -> "subprocess.Popen[str]":
    process = subprocess.Popen([sys.executable, os.path.join(HERE, "web_clients.py"), url, str(n), str(seconds),
                                *(["--drain"] if drain else [])], stdout=subprocess.PIPE, text=True)
    assert process.stdout is not None
    line = process.stdout.readline()
    if not line.startswith("connected"):
        raise RuntimeError(f"web_clients.py: {line!r}")
    return process


def client_counts(process: "subprocess.Popen[str]") -> Dict[str, Any]:
    out, _ = process.communicate(timeout=120)
    counts: Dict[str, Any] = json.loads(out.strip().splitlines()[-1])
    return counts


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--window", type=float, default=10.0)
    parser.add_argument("--clients", type=int, default=300)
    parser.add_argument("--need", type=float, default=45.0, help="frames a second the watching page must get")
    args = parser.parse_args()
    home = tempfile.mkdtemp(prefix="rbs_web_load_")
    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_HOME=home, ROS_IP="127.0.0.1",
               PATH="/usr/bin:" + os.environ.get("PATH", ""))
    env.pop("ROS_HOSTNAME", None)
    os.environ.update({k: env[k] for k in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")})
    # One master for both launches: this process's subscriber stays registered with it.
    master = subprocess.Popen(["roscore", "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)
    import rospy
    rows: List[Dict[str, Any]] = []
    notes: List[str] = []
    web_port = free_port()
    try:
        wait_for("the master", lambda: subprocess.run(["rosnode", "list"], env=env, capture_output=True)
                 .returncode == 0, 60, period=0.2)
        rospy.init_node("web_load", anonymous=True, disable_signals=True)
        gaps = Gaps()
        launch = Launch(False, web_port, env)
        try:
            wait_for("states", lambda: len(gaps.arrivals) > 100, 60)
            rows.append(window("no web view", args.window, gaps, node_pid("/sim", rospy.get_name()), None))
        finally:
            launch.stop()
        launch = Launch(True, web_port, env)
        try:
            rows += with_web(launch, gaps, web_port, args, notes)
        finally:
            launch.stop()
    finally:
        rospy.signal_shutdown("done")
        master.send_signal(2)
        master.wait(timeout=60)
    print(table(rows))
    for note in notes:
        print(f"- the frozen page: `{note}`")
    rates = [r["watcher"]["frames"][0] / r["watcher"]["seconds"] for r in rows if "watcher" in r]
    if min(rates) < args.need:
        print(f"web_load: the watching page got {min(rates):.1f} frames a second, fewer than {args.need:g}")
        sys.exit(1)


def with_web(launch: Launch, gaps: Gaps, web_port: int, args: argparse.Namespace,
             notes: List[str]) -> List[Dict[str, Any]]:
    import rospy
    url = f"http://127.0.0.1:{web_port}/"

    def serving() -> bool:
        try:
            with urllib.request.urlopen(url, timeout=2) as answer:
                return bool(answer.status == 200)
        except OSError:
            return False
    wait_for("the web view", serving, 60, period=0.2)
    first = len(gaps.arrivals)
    wait_for("states again", lambda: len(gaps.arrivals) > first + 100, 60)
    sim, web = node_pid("/sim", rospy.get_name()), node_pid("/web", rospy.get_name())
    rows = [window("web view, no page", args.window, gaps, sim, web)]
    ws = f"ws://127.0.0.1:{web_port}/ws"
    # The class's pages for a little longer than the watching page counts: they are all there all along.
    pages, watcher = clients(ws, args.clients, args.window + 5, drain=True), clients(ws, 1, args.window)
    rows.append(window(f"web view, {args.clients} pages and a watching one", args.window, gaps, sim, web))
    rows[-1]["watcher"], rows[-1]["pages"] = client_counts(watcher), client_counts(pages)

    def logged(words: str) -> List[str]:
        return [line.strip() for line in list(launch.lines) if words in line]
    opened = len(logged("opened from"))
    frozen = frozen_page(web_port)
    wait_for("the frozen page in the web view's log", lambda: len(logged("opened from")) > opened, 60)
    found = re.search(r"page (\d+) opened", logged("opened from")[opened])
    assert found is not None
    number = found[1]
    pages, watcher = clients(ws, args.clients, args.window + 5, drain=True), clients(ws, 1, args.window)
    rows.append(window(f"web view, {args.clients} pages, a watching and a frozen one", args.window, gaps, sim, web))
    rows[-1]["watcher"], rows[-1]["pages"] = client_counts(watcher), client_counts(pages)
    frozen.close()
    wait_for("the frozen page's end in the web view's log", lambda: bool(logged(f"page {number} closed")), 60)
    notes += logged(f"page {number} closed")
    return rows


def table(rows: List[Dict[str, Any]]) -> str:
    lines = ["| | state gaps p50 / p99 / max (ms) | sim_node CPU | web view CPU | web view memory start -> end "
             "| watching page: frames / rod states per s, frames dropped | other pages: kB per page per s "
             "(min / max) |",
             "|---|---|---:|---:|---|---|---|"]
    for r in rows:
        g = r["gaps"]
        watcher, pages = r.get("watcher"), r.get("pages")
        watched = (f"{watcher['frames'][0] / watcher['seconds']:.1f} / {watcher['states'][0] / watcher['seconds']:.1f}"
                   f", {watcher['gaps'][0]}" if watcher else "")
        kbytes = (f"{min(pages['bytes']) / pages['seconds'] / 1000:.1f} / "
                  f"{max(pages['bytes']) / pages['seconds'] / 1000:.1f}" if pages else "")
        web = f"{r['web_cpu']:.2f} %" if r["web_cpu"] is not None else ""
        rss = f"{r['rss'][0]:.1f} -> {r['rss'][1]:.1f} MiB" if r["rss"] else ""
        lines.append(f"| {r['what']} | {statistics.median(g):.2f} / {percentile(g, 99):.2f} / {max(g):.2f} "
                     f"| {r['sim_cpu']:.2f} % | {web} | {rss} | {watched} | {kbytes} |")
    return "\n".join(lines)


if __name__ == "__main__":
    main()
