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

Then the labs (--labs N, 0 for none): sim.launch web:=true on config/race_below.yaml (a lesson part: a lab
opens from its start), the subscriber on /sim/sphere/state, N pages (web_clients.py --labs: a cookie each from
GET /), a probe page (web_clients.py --probe: a pause without the token every 50 ms, refused at once by the
server's loop) and a watching page, over one window each of:
  5. the N pages and the probe, no lab;
  6. the same, each of the N pages with a lab of its own, running (lab_open from the start).
For each, besides the above: the class's frames each lab page got per second, its own lab's frames and
samples per body per second and the frames the server dropped for it, the refused requests' reply times;
the web view's resident memory before the labs, once they opened and at the window's end (per lab), and its
lines about slow lab ticks. Exits 1 too when a lab page got fewer than --need frames a second of its lab or
of the class, when the refused requests' 99th percentile reached --reply-ms, or when the state gaps' median
with the labs differs from without by more than --gap-ms.

Usage: bench/web_load.py [--window S] [--clients N] [--need F] [--labs N] [--reply-ms MS] [--gap-ms MS]
                         [--labs-only] [--raw FILE]   (with the package's devel space sourced)"""
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

from rigid_body_sim.sim_tools import (body_type, free_port, load_config, node_pid, resident_kib, rospy_on_python39,
                                      state_message, wait_for)

from run_bench import cpu_seconds

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

rospy_on_python39()


class Launch:
    """sim.launch with or without the web view on the master at `env`'s ROS_MASTER_URI, its output kept."""

    def __init__(self, web: bool, web_port: int, env: Dict[str, str], config: str = "") -> None:
        self.lines: List[str] = []
        self.process = subprocess.Popen(
            ["roslaunch", "rigid_body_sim", "sim.launch", f"web:={str(web).lower()}", f"web_port:={web_port}",
             *([f"config:={config}"] if config else [])],
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
    """Arrival times of a body's states (/sim/<body>/state) at this process's subscriber."""

    def __init__(self, config: str, body: str) -> None:
        import rospy
        self.arrivals: List[float] = []
        message = state_message(body_type(load_config(config), body))  # its type's state message
        rospy.Subscriber(f"/sim/{body}/state", message, lambda _: self.arrivals.append(time.monotonic()),
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


def clients(url: str, n: int, seconds: float, drain: bool = False, body: str = "rod") -> "subprocess.Popen[str]":
    process = subprocess.Popen([sys.executable, os.path.join(HERE, "web_clients.py"), url, str(n), str(seconds),
                                *(["--drain"] if drain else ["--body", body])], stdout=subprocess.PIPE, text=True)
    assert process.stdout is not None
    line = process.stdout.readline()
    if not line.startswith("connected"):
        raise RuntimeError(f"web_clients.py: {line!r}")
    return process


def client_counts(process: "subprocess.Popen[str]") -> Dict[str, Any]:
    out, _ = process.communicate(timeout=120)
    counts: Dict[str, Any] = json.loads(out.strip().splitlines()[-1])
    return counts


class Pages:
    """A web_clients.py --labs or --probe process: its pages stay open; commands on its stdin."""

    def __init__(self, url: str, n: int, mode: str) -> None:
        self.process = subprocess.Popen([sys.executable, os.path.join(HERE, "web_clients.py"), url, str(n), mode],
                                        stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
        self.expect("connected")

    def expect(self, word: str) -> str:
        assert self.process.stdout is not None
        line = self.process.stdout.readline()
        if not line.startswith(word):
            raise RuntimeError(f"web_clients.py: {line!r} (not {word})")
        return line

    def command(self, line: str) -> None:
        assert self.process.stdin is not None
        self.process.stdin.write(line + "\n")
        self.process.stdin.flush()

    def counts(self) -> Dict[str, Any]:
        counted: Dict[str, Any] = json.loads(self.expect("{"))
        return counted

    def end(self) -> None:
        assert self.process.stdin is not None
        self.process.stdin.close()
        try:
            self.process.wait(timeout=30)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--window", type=float, default=10.0)
    parser.add_argument("--clients", type=int, default=300)
    parser.add_argument("--need", type=float, default=45.0, help="frames a second the watching page must get")
    parser.add_argument("--labs", type=int, default=60, help="pages with a lab each (0: no labs' windows)")
    parser.add_argument("--reply-ms", type=float, default=100.0,
                        help="a refused request's reply within this (99th percentile) while the labs run")
    parser.add_argument("--gap-ms", type=float, default=1.0,
                        help="the state gaps' median with the labs within this of without")
    parser.add_argument("--labs-only", action="store_true", help="the labs' windows alone")
    parser.add_argument("--raw", default="", help="write every window's measurements here (JSON)")
    args = parser.parse_args()
    home = tempfile.mkdtemp(prefix="rbs_web_load_")
    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_HOME=home, ROS_IP="127.0.0.1",
               PATH="/usr/bin:" + os.environ.get("PATH", ""))
    env.pop("ROS_HOSTNAME", None)
    os.environ.update({k: env[k] for k in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")})
    import rospy  # before the master starts: an interpreter without rospy leaves no master behind
    # One master for both launches: this process's subscriber stays registered with it.
    master = subprocess.Popen(["roscore", "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)
    rows: List[Dict[str, Any]] = []
    notes: List[str] = []
    web_port = free_port()
    try:
        wait_for("the master", lambda: subprocess.run(["rosnode", "list"], env=env, capture_output=True)
                 .returncode == 0, 60, period=0.2)
        rospy.init_node("web_load", anonymous=True, disable_signals=True)
        if not args.labs_only:
            gaps = Gaps(os.path.join(ROOT, "config", "demo.yaml"), "rod")
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
        if args.labs:
            launch = Launch(True, web_port, env, os.path.join(ROOT, "config", "race_below.yaml"))
            try:
                lab_rows = with_labs(launch, Gaps(os.path.join(ROOT, "config", "race_below.yaml"), "sphere"), web_port,
                                     args)
            finally:
                launch.stop()
    finally:
        rospy.signal_shutdown("done")
        master.send_signal(2)
        master.wait(timeout=60)
    missed: List[str] = []
    if args.raw:
        with open(args.raw, "w") as out:
            json.dump(rows + (lab_rows if args.labs else []), out)
    if rows:
        print(table(rows))
        for note in notes:
            print(f"- the frozen page: `{note}`")
    if args.labs:
        print()
        print(labs_table(lab_rows, args.need))
        print()
        print(labs_notes(lab_rows))
        rows += lab_rows
        missed += labs_missed(lab_rows, args)
    rates = [r["watcher"]["frames"][0] / r["watcher"]["seconds"] for r in rows if "watcher" in r]
    if rates and min(rates) < args.need:
        missed.append(f"the watching page got {min(rates):.1f} frames a second, fewer than {args.need:g}")
    for line in missed:
        print(f"web_load: {line}")
    if missed:
        sys.exit(1)


def wait_serving(web_port: int) -> None:
    """Until the web view answers its page."""
    url = f"http://127.0.0.1:{web_port}/"

    def serving() -> bool:
        try:
            with urllib.request.urlopen(url, timeout=2) as answer:
                return bool(answer.status == 200)
        except OSError:
            return False
    wait_for("the web view", serving, 60, period=0.2)


def with_web(launch: Launch, gaps: Gaps, web_port: int, args: argparse.Namespace,
             notes: List[str]) -> List[Dict[str, Any]]:
    import rospy
    wait_serving(web_port)
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


def with_labs(launch: Launch, gaps: Gaps, web_port: int, args: argparse.Namespace) -> List[Dict[str, Any]]:
    """Windows 5 and 6: the lab pages and the probe without labs, then with a lab each."""
    import rospy
    wait_serving(web_port)
    wait_for("the sphere's states", lambda: len(gaps.arrivals) > 100, 60)
    sim, web = node_pid("/sim", rospy.get_name()), node_pid("/web", rospy.get_name())
    ws = f"ws://127.0.0.1:{web_port}/ws"
    lab_pages, probe = Pages(ws, args.labs, "--labs"), Pages(ws, 1, "--probe")
    rows: List[Dict[str, Any]] = []
    before = opened = 0
    try:
        for name in (f"race, {args.labs} pages, a probe and a watching one, no lab",
                     f"race, the same, each of the {args.labs} pages with its lab"):
            if rows:
                before = resident_kib(web)
                lab_pages.command("open")
                lab_pages.expect("opened")
                opened = resident_kib(web)
            watcher = clients(ws, 1, args.window, body="sphere")
            lab_pages.command(f"count {args.window}")
            probe.command(f"count {args.window}")
            rows.append(window(name, args.window, gaps, sim, web))
            rows[-1].update(watcher=client_counts(watcher), lab_pages=lab_pages.counts(), probe=probe.counts())
        rows[-1]["memory_kib"] = (before, opened, resident_kib(web))
        rows[-1]["labs"] = args.labs
        rows[-1]["slow_ticks"] = [line.strip() for line in list(launch.lines) if "labs took" in line]
    finally:
        lab_pages.end()
        probe.end()
    return rows


def labs_table(rows: List[Dict[str, Any]], need: float) -> str:
    lines = ["| | state gaps p50 / p99 / max (ms) | sim_node CPU | web view CPU | web view memory start -> end "
             "| watching page: frames / sphere states per s, frames dropped "
             "| lab pages: the class's frames per s (min / median), dropped (max) "
             "| own lab: frames per s (min / median), labs under NEED; samples per body per s (min); frames "
             "dropped (max) "
             "| refused request's reply p50 / p99 / max (ms) |",
             "|---|---|---:|---:|---|---|---|---|---|"]
    lines[0] = lines[0].replace("NEED", f"{need:g}")
    for r in rows:
        g, w, p, probe = r["gaps"], r["watcher"], r["lab_pages"], r["probe"]
        s = p["seconds"]
        frames = [n / s for n in p["frames"]]
        own = [n / s for n in p["lab_frames"]]
        samples = [n / max(1, b) / s for n, b in zip(p["lab_samples"], p["bodies"])]
        times = probe["reply_ms"]
        under = sum(1 for rate in own if rate < need)
        lab = (f"{min(own):.1f} / {statistics.median(own):.1f}, {under}; {min(samples):.1f}; {max(p['lab_gaps'])}"
               if max(own) > 0 else "")
        lines.append(f"| {r['what']} | {statistics.median(g):.2f} / {percentile(g, 99):.2f} / {max(g):.2f} "
                     f"| {r['sim_cpu']:.2f} % | {r['web_cpu']:.2f} % | {r['rss'][0]:.1f} -> {r['rss'][1]:.1f} MiB "
                     f"| {w['frames'][0] / w['seconds']:.1f} / {w['states'][0] / w['seconds']:.1f}, {w['gaps'][0]} "
                     f"| {min(frames):.1f} / {statistics.median(frames):.1f}, {max(p['frame_gaps'])} | {lab} "
                     f"| {statistics.median(times):.1f} / {percentile(times, 99):.1f} / {max(times):.1f} |")
    return "\n".join(lines)


def labs_notes(rows: List[Dict[str, Any]]) -> str:
    before, opened, end = rows[-1]["memory_kib"]
    n = rows[-1]["labs"]
    lines = [f"- the web view's resident memory: {before / 1024:.1f} MiB before the labs, {opened / 1024:.1f} "
             f"MiB once {n} had opened, {end / 1024:.1f} MiB at the window's end: {(opened - before) / n:.0f} kB "
             f"a lab opened, {(end - before) / n:.0f} kB a lab at the end"]
    lines += [f"- `{line}`" for line in rows[-1]["slow_ticks"]]
    return "\n".join(lines)


def labs_missed(rows: List[Dict[str, Any]], args: argparse.Namespace) -> List[str]:
    missed = []
    for r in rows:
        p = r["lab_pages"]
        least = min(p["frames"]) / p["seconds"]
        if least < args.need:
            missed.append(f"{r['what']}: a lab page got {least:.1f} of the class's frames a second, fewer than "
                          f"{args.need:g}")
    p = rows[-1]["lab_pages"]
    least = min(p["lab_frames"]) / p["seconds"]
    if least < args.need:
        missed.append(f"a lab page got {least:.1f} frames a second of its lab, fewer than {args.need:g}")
    late = percentile(rows[-1]["probe"]["reply_ms"], 99)
    if late >= args.reply_ms:
        missed.append(f"a refused request's reply took {late:.1f} ms (99th percentile) with the labs, not under "
                      f"{args.reply_ms:g}")
    shift = statistics.median(rows[-1]["gaps"]) - statistics.median(rows[0]["gaps"])
    if abs(shift) > args.gap_ms:
        missed.append(f"the state gaps' median moved {shift:+.2f} ms with the labs, more than {args.gap_ms:g}")
    return missed


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
