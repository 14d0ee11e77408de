#!/usr/bin/python3
"""`make bench`: runs every measurement and writes one table (median, min, max of repeated runs or
windows) with short notes into docs/performance.md, between its markers, and into BUILD/bench-out/bench.md.
Needs a Release build with -Drigid_body_sim_BENCHMARKS=ON whose devel/setup.bash is sourced (rospy and the
package's messages), hyperfine, and numpy."""
import argparse
import json
import os
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from typing import IO, Any, Dict, List, Optional, Sequence, Set, Tuple

import yaml
from rigid_body_sim.sim_tools import free_port, node_pid, resident_kib, rospy_on_python39, subscribers, wait_for

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

DOC = os.path.join(ROOT, "docs", "performance.md")
BEGIN = "<!-- make bench writes from here: do not edit by hand -->"
END = "<!-- make bench writes up to here -->"
Samples = Sequence[Optional[float]]


@dataclass
class Row:
    section: str
    what: str
    values: List[float]
    unit: str
    target: str


@dataclass
class Report:
    """The table and its notes, filled by the measurements."""
    rows: List[Row] = field(default_factory=list)
    notes: List[str] = field(default_factory=list)

    def row(self, section: str, what: str, values: Samples, unit: str, target: str = "") -> None:
        self.rows.append(Row(section, what, [v for v in values if v is not None], unit, target))

    def note(self, text: str) -> None:
        self.notes.append(text)
        print("  note: " + text, flush=True)

    def table(self) -> str:
        lines = ["| | what | median | min | max | unit | target |", "|---|---|---:|---:|---:|---|---|"]
        for r in self.rows:
            median, low, high = ((statistics.median(r.values), min(r.values), max(r.values)) if r.values
                                 else (None, None, None))
            lines.append(f"| {r.section} | {r.what} | {number(median)} | {number(low)} | {number(high)} | {r.unit} "
                         f"| {r.target} |")
        return "\n".join(lines)

    def markdown(self, seconds: float) -> str:
        return "\n".join([f"Run of {time.strftime('%Y-%m-%d %H:%M')} on {machine()}; all of it took {seconds:.0f} s.",
                          "", self.table(), ""] + ["- " + n for n in self.notes])


def number(value: Optional[float]) -> str:
    if value is None:
        return "-"
    if abs(value) >= 1000:
        return f"{value:,.0f}"
    if abs(value) >= 100:
        return f"{value:.0f}"
    if abs(value) >= 10:
        return f"{value:.1f}"
    return f"{value:.3g}"


def say(text: str) -> None:
    print("bench: " + text, file=sys.stderr, flush=True)


def percentile(values: Sequence[float], p: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, max(0, int(round(p / 100.0 * (len(ordered) - 1)))))]


def hyperfine(commands: List[str], runs: int, out: str, warmup: int = 2, cpu: bool = False,
              failing: bool = False) -> List[List[float]]:
    """Times whole processes; returns each command's list of wall times (s), or CPU times with cpu=True."""
    path = os.path.join(out, "hyperfine.json")
    subprocess.run(["hyperfine", "-N", "--style", "none", "--warmup", str(warmup), "--runs", str(runs),
                    "--export-json", path] + (["-i"] if failing else []) + commands, check=True,
                   stdout=subprocess.DEVNULL)
    with open(path) as f:
        results = json.load(f)["results"]
    if cpu:  # hyperfine keeps only the mean CPU time of the runs
        return [[r["user"] + r["system"]] for r in results]
    return [result["times"] for result in results]


def simulate_exe(build: str) -> str:
    return os.path.join(build, "devel/lib/rigid_body_sim/simulate")


# --- 1. core ------------------------------------------------------------------------------------
def core(report: Report, build: str, out: str) -> Dict[str, List[float]]:
    say("core: Google Benchmark, 7 repetitions")
    path = os.path.join(out, "bench_core.json")
    subprocess.run([os.path.join(build, "devel/lib/rigid_body_sim/bench_core"), "--benchmark_repetitions=7",
                    "--benchmark_min_time=0.2", "--benchmark_out=" + path, "--benchmark_out_format=json"],
                   check=True, stdout=subprocess.DEVNULL)
    with open(path) as f:
        runs = [b for b in json.load(f)["benchmarks"] if b.get("run_type") == "iteration"]
    times: Dict[str, List[float]] = {}
    for b in runs:
        times.setdefault(b["run_name"], []).append(b["cpu_time"] / b.get("body_steps", 1))
    targets = {"rodStep/euler_cromer": "<= 30", "rollerStep/rolling": "<= 15", "rollerStep/slipping": "<= 15"}
    for name, values in times.items():
        label = name.replace("rodStep/", "rod, ").replace("rollerStep/", "roller, ")
        if name.startswith("worldStep/"):
            label = f"world of n = {name.split('/')[1]} bodies (half rods, half rollers), per body-step"
        if name.startswith("worldStepAfterSleep"):
            label = "the same n = 1000, 20 steps after 20 ms asleep (as the node steps), per body-step"
        report.row("1 core", label, values, "ns/step (CPU)", targets.get(name, ""))
    report.note("core figures are CPU time per step (Google Benchmark's cpu_time): on a shared machine wall time "
                "per step runs higher with the load. Debian's libbenchmark is built as DEBUG (its own warning); "
                "that slows its loop bookkeeping, not the code measured")
    return times


# --- 2. the text's program ----------------------------------------------------------------------
def text_program(report: Report, build: str, out: str, core_times: Dict[str, List[float]]) -> None:
    say("the text's program (numpy) against simulate, whole processes (hyperfine)")
    simulate = simulate_exe(build)
    csv_dir = os.path.join(out, "rod_csv")
    python, cpp = hyperfine(["/usr/bin/python3 " + os.path.join(HERE, "text_program.py"),
                             f"{simulate} {os.path.join(ROOT, 'config/rod.yaml')} --out-dir {csv_dir}"],
                            runs=10, out=out)
    report.row("2 text", "text's program, 10 s, whole process (python3 + numpy)", [t * 1e3 for t in python], "ms")
    report.row("2 text", "simulate config/rod.yaml, 10 s, whole process", [t * 1e3 for t in cpp], "ms")
    startup = hyperfine([simulate + " /nonexistent.yaml"], runs=10, out=out, failing=True)[0]
    report.row("2 text", "  of which simulate's start-up (a missing config: loads its libraries, refuses, exits)",
               [t * 1e3 for t in startup], "ms")
    report.row("2 text", "ratio, whole process (per run pairs, sorted)",
               [p / c for p, c in zip(sorted(python), sorted(cpp))], "x", ">= 50")
    result = subprocess.run(["/usr/bin/python3", os.path.join(HERE, "text_program.py"), "--repeat", "7"],
                            check=True, capture_output=True, text=True)
    stepping = json.loads(result.stdout)
    per_step_py = [s / stepping["steps"] * 1e9 for s in stepping["seconds"]]
    report.row("2 text", "text's program, stepping alone", per_step_py, "ns/step")
    ec = statistics.median(core_times["rodStep/euler_cromer"])
    report.row("2 text", "ratio, stepping alone (vs rod Euler-Cromer above)", [p / ec for p in per_step_py], "x",
               ">= 1000")
    python_core(report, out, [c - statistics.median(startup) for c in cpp])


def python_core(report: Report, out: str, simulate_own: List[float]) -> None:
    """The same 10 s rod from Python (rigid_body_sim.core), against simulate's own time for it (its whole
    process less its start-up) and against the text's program in the same process."""
    say("the rod from Python (rigid_body_sim.core) against simulate and the text's program")
    result = subprocess.run(["/usr/bin/python3", os.path.join(HERE, "python_core.py"), "--repeat", "7"],
                            check=True, capture_output=True, text=True)
    times = json.loads(result.stdout)
    report.row("2 text", "rigid_body_sim.core: World(rod.yaml).run(10), in Python (arrays of 501 samples)",
               [t * 1e3 for t in times["core"]], "ms")
    report.row("2 text", "ratio, Python's run / simulate's own (whole process less start-up, medians)",
               [statistics.median(times["core"]) / statistics.median(simulate_own)], "x", "<= 2")
    report.row("2 text", "ratio, text's program / Python's run, one process (per run pairs, sorted)",
               [t / c for t, c in zip(sorted(times["text"]), sorted(times["core"]))], "x", ">= 100")
    python = hyperfine(["/usr/bin/python3 " + os.path.join(HERE, "python_core.py") + " --repeat 0"], runs=5,
                       out=out)[0]
    report.row("2 text", "  the same from a shell: python3's start-up, numpy and the module imported, one run",
               [t * 1e3 for t in python], "ms")


# --- 3-5. the node --------------------------------------------------------------------------------
class Ros:
    """A master of its own on a free port; one rospy subscriber in this process."""

    def __init__(self, out: str) -> None:
        self.home = tempfile.mkdtemp(prefix="bench_ros_", dir=out)
        self.port = free_port()
        os.environ.pop("ROS_HOSTNAME", None)
        os.environ.update(ROS_MASTER_URI=f"http://127.0.0.1:{self.port}", ROS_IP="127.0.0.1", ROS_HOME=self.home)
        self.log: IO[str] = open(os.path.join(out, "ros.log"), "w")
        self.master = subprocess.Popen(["roscore", "-p", str(self.port)], stdout=self.log, stderr=self.log,
                                       start_new_session=True)
        import rosgraph
        wait_for(f"roscore (see {self.log.name})", rosgraph.is_master_online, 30.0, period=0.2)
        import rospy
        rospy_on_python39()
        self.rospy = rospy
        rospy.init_node("bench", anonymous=True, disable_signals=True)
        self.received: List[Tuple[float, float, float]] = []  # (receipt wall time, header stamp, t)
        self.subscriber: Any = None

    def subscribe(self, topic: str, kind: Any) -> None:
        self.received = []
        self.subscriber = self.rospy.Subscriber(topic, kind, self._on_message, queue_size=5000, tcp_nodelay=True)

    def unsubscribe(self) -> None:
        if self.subscriber:
            self.subscriber.unregister()
            self.subscriber = None

    def _on_message(self, msg: Any) -> None:
        self.received.append((time.time(), msg.header.stamp.to_sec(), msg.t))

    def launch(self, *args: str) -> "subprocess.Popen[bytes]":
        return subprocess.Popen(["roslaunch", "rigid_body_sim", "sim.launch"] + list(args), stdout=self.log,
                                stderr=self.log, start_new_session=True)

    def sim_pid(self) -> int:
        pid: List[int] = []

        def found() -> bool:
            try:
                pid.append(node_pid("/sim", "/bench"))
            except Exception:
                return False
            return True
        wait_for(f"/sim (see {self.log.name})", found, 30.0, period=0.2)
        return pid[0]

    def wait_for_messages(self, count: int = 5) -> None:
        wait_for("state messages", lambda: len(self.received) >= count, 30.0)

    @staticmethod
    def stop(process: "subprocess.Popen[bytes]", timeout: float = 20) -> None:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGINT)
            try:
                process.wait(timeout)
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()

    def close(self) -> None:
        self.unsubscribe()
        self.rospy.signal_shutdown("bench done")
        self.stop(self.master)
        self.log.close()
        shutil.rmtree(self.home, ignore_errors=True)


def cpu_seconds(pid: int) -> float:
    """CPU time of the process's threads, to the nanosecond (schedstat; utime + stime count 10 ms ticks, too
    coarse for a node at 1 %)."""
    total = 0
    for task in os.listdir(f"/proc/{pid}/task"):
        try:
            with open(f"/proc/{pid}/task/{task}/schedstat") as f:
                total += int(f.read().split()[0])
        except FileNotFoundError:  # a thread that ended meanwhile
            pass
    return total / 1e9


def cpu_shares(pid: int, seconds: float, windows: int) -> List[float]:
    """The process's CPU time over each of `windows` windows that together last `seconds`, in % of one core."""
    shares = []
    for _ in range(windows):
        wall0, cpu0 = time.time(), cpu_seconds(pid)
        time.sleep(seconds / windows)
        shares.append(100.0 * (cpu_seconds(pid) - cpu0) / (time.time() - wall0))
    return shares


def settle(report: Report, pid: int, what: str, window: float = 0.5, deadline: float = 30.0) -> None:
    """Until two windows of `window` s in a row give the process's CPU share within a point (or a fifth) of each
    other: its start-up, or a change of subscribers, is over and what comes next measures the steady state.
    Past the deadline a note says so, with the last two shares, and the measurement goes on."""
    end = time.monotonic() + deadline
    last, share = cpu_shares(pid, window, 1)[0], -1.0
    while time.monotonic() < end:
        share = cpu_shares(pid, window, 1)[0]
        if abs(share - last) <= max(1.0, 0.2 * last):
            return
        last = share
    report.note(f"{what}: the CPU share had not settled within {deadline:g} s ({last:.2f} then {share:.2f} % in "
                f"{window:g} s windows); measured anyway")


def unsubscribe_and_settle(report: Report, ros: Ros, node: str, topic: str, pid: int, what: str) -> None:
    """The bench's subscription ends; once the node has dropped the connection, its CPU settles."""
    ros.unsubscribe()
    wait_for(f"{node} to drop its connection on {topic}", lambda: not subscribers(node, "/bench").get(topic), 10.0)
    settle(report, pid, what)


def roscpp_floor(report: Report, ros: Ros, build: str, seconds: float, windows: int) -> None:
    """floor_node (bench/floor_node.cpp): sim_node's threads and one RodState at 50 Hz to the same subscriber,
    nothing else. What any roscpp node publishing at that rate costs on this machine."""
    from rigid_body_sim.msg import RodState
    say(f"node: roscpp's floor at 50 Hz, {seconds:g} s of wall time")
    ros.subscribe("/floor/state", RodState)
    process = subprocess.Popen([os.path.join(build, "devel/lib/rigid_body_sim/floor_node"), "__name:=floor",
                                "_rate:=50"], stdout=ros.log, stderr=ros.log, start_new_session=True)
    try:
        ros.wait_for_messages()
        settle(report, process.pid, "roscpp's floor at start-up")
        shares = cpu_shares(process.pid, seconds, windows)
        unsubscribe_and_settle(report, ros, "/floor", "/floor/state", process.pid, "roscpp's floor, unsubscribed")
        alone = cpu_shares(process.pid, seconds, windows)
    finally:
        ros.unsubscribe()
        ros.stop(process)
    each = f"{windows} windows of {seconds / windows:g} s"
    report.row("3 node", f"roscpp's floor (bench/floor_node.cpp: sim_node's threads, one RodState at 50 Hz, nothing "
               f"else): CPU, the same state subscriber ({each})", shares, "%")
    report.row("3 node", f"roscpp's floor: CPU, no subscriber at all ({each})", alone, "%")


def node_at_rate(report: Report, ros: Ros, label: str, config: str, seconds: float, windows: int,
                 nominal_gap_ms: float, cpu_target: str) -> None:
    from rigid_body_sim.msg import RodState
    say(f"node: {label}, {seconds:g} s of wall time")
    ros.subscribe("/sim/rod/state", RodState)
    process = ros.launch("config:=" + config)
    try:
        pid = ros.sim_pid()
        ros.wait_for_messages()
        settle(report, pid, f"{label} at start-up")  # start-up (servers, first TF) is not the steady state
        rss_start = resident_kib(pid) / 1024.0
        shares, windows_received = [], []
        for _ in range(windows):
            first = len(ros.received)
            shares += cpu_shares(pid, seconds / windows, 1)
            windows_received.append(ros.received[first:])
        rss_end = resident_kib(pid) / 1024.0
        unsubscribe_and_settle(report, ros, "/sim", "/sim/rod/state", pid, f"{label}, unsubscribed")
        alone = cpu_shares(pid, seconds / 2, windows // 2)
    finally:
        ros.unsubscribe()
        ros.stop(process)
    each = f"{windows} windows of {seconds / windows:g} s"
    report.row("3 node", f"{label}: CPU, share of one core, one state subscriber ({each})", shares, "%",
               cpu_target)
    report.row("3 node", f"{label}: CPU, no subscriber at all ({windows // 2} windows of {seconds / windows:g} s)",
               alone, "%")
    report.row("3 node", f"{label}: resident memory at start", [rss_start], "MiB")
    report.row("3 node", f"{label}: resident memory at end", [rss_end], "MiB", "= start")
    gaps = [[1e3 * (b[0] - a[0]) for a, b in zip(w, w[1:])] for w in windows_received]
    for name, p, target in (("p50", 50.0, f"{nominal_gap_ms:g}"), ("p99", 99.0, f"<= {nominal_gap_ms + 2:g}"),
                            ("max", 100.0, "")):
        report.row("3 node", f"{label}: gap between state messages at a subscriber, {name} ({each})",
                   [percentile(g, p) for g in gaps if g], "ms", target)
    # The node stamps wall_start + t: receipt - stamp is its lag behind the wall clock plus the transport.
    # The drift is how much that lag grew from the first second to the last (least-delayed message of each).
    lag = [(r - st) * 1e3 for w in windows_received for r, st, _ in w]
    per_second = max(1, int(round(1000.0 / nominal_gap_ms)))
    report.row("3 node", f"{label}: drift of simulated vs wall time, first to last second",
               [min(lag[-per_second:]) - min(lag[:per_second])], "ms", "<= 1")


def recording(report: Report, ros: Ros, out: str, config: str, publish_rate: float, seconds: float,
              *launch_args: str) -> None:
    import rosbag
    label = f"publish_rate {publish_rate:g}" + "".join(", " + a for a in launch_args)
    say(f"recording: sim.launch record:=true, {label}, {seconds:g} s")
    bag = os.path.join(out, "record.bag")
    for stale in (bag, bag + ".active"):
        if os.path.exists(stale):
            os.remove(stale)
    process = ros.launch("config:=" + config, "record:=true", "bag:=" + bag, f"duration:={seconds:g}", *launch_args)
    try:
        process.wait(seconds + 60)
    except subprocess.TimeoutExpired:
        report.note("the recording launch did not end by itself; stopped")
        ros.stop(process)
    wait_for("the closed bag", lambda: os.path.exists(bag), 20.0, period=0.2)
    per_second = int(round(publish_rate))
    published = int(seconds) * per_second + 1  # t = 0, 1 / publish_rate, ..., duration, per topic
    with rosbag.Bag(bag) as b:
        info = b.get_type_and_topic_info().topics
        state_topics = sorted(t for t in info if t.endswith("/state"))
        distinct: Dict[str, Set[int]] = {t: set() for t in state_topics}
        for topic, msg, _ in b.read_messages(topics=state_topics):
            distinct[topic].add(int(round(msg.t * per_second)))
    lost = [published - len(distinct[t]) for t in state_topics]
    report.row("4 record", f"{label}: state messages lost per topic ({len(state_topics)} topics, {published} "
               "published each)", lost, "msgs", "0")
    if "/tf" in info:
        report.row("4 record", f"{label}: /tf messages in the bag (published: {published})",
                   [info["/tf"].message_count], "msgs", str(published))
    for topic in ("/sim/scene", "/sim/markers"):
        report.row("4 record", f"{label}: {topic} messages in the bag",
                   [info[topic].message_count if topic in info else 0], "msgs")
    size = os.path.getsize(bag) / seconds / 1e3
    target = "<= 1500" if publish_rate >= 1000 else "<= 100"
    report.row("4 record", f"{label}: bag size per simulated second", [size], "kB/s", target)
    # The events' share of what the bag holds: their messages' bytes against everything else's.
    with rosbag.Bag(bag) as b:
        sizes: Dict[str, int] = {}
        for topic, raw, _ in b.read_messages(raw=True):
            sizes[topic] = sizes.get(topic, 0) + len(raw[1])
    events = sizes.get("/sim/events", 0)
    report.row("4 record", f"{label}: /sim/events' bytes against the rest of the bag's messages",
               [100.0 * events / max(1, sum(sizes.values()) - events)], "%", "<= 10")


def many_bodies_config(out: str, bodies: int) -> str:
    """demo.yaml's rod and sphere, bodies / 2 of each (one rod for one body)."""
    import yaml
    with open(os.path.join(ROOT, "config/demo.yaml")) as f:
        demo = yaml.safe_load(f)
    rod, sphere = demo["bodies"]["rod"], demo["bodies"]["sphere"]
    demo["bodies"] = {f"rod{i}": rod for i in range((bodies + 1) // 2)}
    demo["bodies"].update({f"sphere{i}": sphere for i in range(bodies // 2)})
    path = os.path.join(out, f"bodies_{bodies}.yaml")
    with open(path, "w") as f:
        yaml.safe_dump(demo, f)
    return path


def many_bodies(report: Report, ros: Ros, out: str, bodies: int, seconds: float, markers: bool) -> None:
    """Start-up (to the first state, to every reconfigure server), CPU and memory with no marker subscriber
    and, with `markers`, the bytes per second of /sim/markers with one."""
    from rigid_body_sim.msg import RodState
    import rosgraph
    import rospy
    say(f"node: {bodies} bodies, {seconds:g} s")
    last = f"/sim/sphere{bodies // 2 - 1}" if bodies > 1 else "/sim/rod0"
    ros.subscribe("/sim/rod0/state", RodState)
    start = time.time()
    process = ros.launch("config:=" + many_bodies_config(out, bodies))
    master = rosgraph.Master("/bench")
    label = f"{bodies} bod{'y' if bodies == 1 else 'ies'}"
    try:
        pid = ros.sim_pid()
        ros.wait_for_messages(1)
        first_state = ros.received[0][0] - start

        def servers_up() -> bool:
            try:
                master.lookupService(last + "/set_parameters")
            except Exception:
                return False
            return True
        wait_for("every reconfigure server", servers_up, 60.0, period=0.05)
        report.row("7 scale", f"{label}: start-up to the first state (roslaunch included)", [first_state], "s",
                   "< 5" if bodies >= 1000 else "")
        report.row("7 scale", f"{label}: start-up to every reconfigure server", [time.time() - start], "s")
        unsubscribe_and_settle(report, ros, "/sim", "/sim/rod0/state", pid, f"{label}, unsubscribed")
        rss_start = resident_kib(pid) / 1024.0
        report.row("7 scale", f"{label}: CPU, no subscriber at all (3 windows of {seconds / 3:g} s)",
                   cpu_shares(pid, seconds, 3), "%", "<= 5" if bodies >= 1000 else "")
        # roscpp's poll thread looks at every publication (3 a body) each time it sends a message
        ros.subscribe("/sim/rod0/state", RodState)
        ros.wait_for_messages(1)
        report.row("7 scale", f"{label}: CPU, one state subscriber (3 windows of {seconds / 6:g} s)",
                   cpu_shares(pid, seconds / 2, 3), "%")
        ros.unsubscribe()
        if markers:
            sizes: List[int] = []
            sub = rospy.Subscriber("/sim/markers", rospy.AnyMsg, lambda m: sizes.append(len(m._buff)),
                                   queue_size=1000)
            # The node builds markers only for a subscriber: from its first message on, they flow.
            wait_for("the first /sim/markers message", lambda: len(sizes) > 0, 30.0)
            settle(report, pid, f"{label}, /sim/markers subscribed")
            rates = []
            for _ in range(3):
                wall0, first = time.time(), len(sizes)
                time.sleep(seconds / 3)
                rates.append(sum(sizes[first:]) / (time.time() - wall0) / 1e3)
            sub.unregister()
            report.row("7 scale", f"{label}: /sim/markers with a subscriber (3 windows of {seconds / 3:g} s)", rates,
                       "kB/s", "<= 1000" if bodies == 100 else "")
        report.row("7 scale", f"{label}: resident memory, start -> end",
                   [resident_kib(pid) / 1024.0 - rss_start], "MiB", "~ 0")
    finally:
        ros.unsubscribe()
        ros.stop(process)


def faster_than_real_time(report: Report, ros: Ros, build: str, out: str, seconds: float) -> None:
    from rigid_body_sim.msg import RodState
    say("real_time_factor 0: node with publishing, and simulate --bag")
    ros.subscribe("/sim/rod/state", RodState)
    process = ros.launch("real_time_factor:=0")
    speeds = []
    try:
        pid = ros.sim_pid()
        ros.wait_for_messages()
        settle(report, pid, "real_time_factor 0 at start-up")
        for _ in range(3):
            wall0, t0 = time.time(), ros.received[-1][2]
            time.sleep(seconds / 3.0)
            speeds.append((ros.received[-1][2] - t0) / (time.time() - wall0))
    finally:
        ros.unsubscribe()
        ros.stop(process)
    report.row("5 rtf 0", "node, config/demo.yaml (5 bodies), publishing at 50 Hz", speeds, "sim s / wall s")
    command = (f"{simulate_exe(build)} {os.path.join(ROOT, 'config/demo.yaml')} --duration 60 "
               f"--bag {os.path.join(out, 'simulate.bag')} --out-dir {os.path.join(out, 'simulate_csv')}")
    times = hyperfine([command], runs=3, out=out, warmup=1)[0]
    report.row("5 rtf 0", "simulate --bag, config/demo.yaml, 60 s", [60.0 / t for t in times], "sim s / wall s")


# --- 6. sweeps ----------------------------------------------------------------------------------
def sweeps(report: Report, build: str, out: str) -> None:
    say("sweeps: variants/s on 1 and 2 threads; 10,000 variants of the 10 s rod")

    def command(variants: int, jobs: int) -> str:
        return (f"{simulate_exe(build)} {os.path.join(ROOT, 'config/rod.yaml')} "
                f"--sweep rod.theta0=0:6.283:{variants} --jobs {jobs} --out-dir {os.path.join(out, 'sweep')}")
    commands = [command(1000, 1), command(1000, 2)]
    one, two = hyperfine(commands, runs=5, out=out, warmup=1)
    cpu_one, cpu_two = hyperfine(commands, runs=3, out=out, warmup=0, cpu=True)
    report.row("6 sweep", "1,000 rods x 10 s on 1 thread", [1000 / t for t in one], "variants/s")
    report.row("6 sweep", "1,000 rods x 10 s on 2 threads", [1000 / t for t in two], "variants/s")
    report.row("6 sweep", "speed-up on 2 threads (run pairs, sorted)",
               [a / b for a, b in zip(sorted(one), sorted(two))], "x", ">= 1.8")
    for threads, cpu in (("1 thread", cpu_one), ("2 threads", cpu_two)):
        report.row("6 sweep", f"CPU time per variant on {threads} (user + sys, mean of 3 runs)",
                   [t / 1000 * 1e3 for t in cpu], "ms")
    report.note(f"sweeps ran at load average {load()} on {os.cpu_count()} cores: the speed-up on 2 threads needs 2 "
                "idle cores; the CPU time per variant on 1 and 2 threads shows how much the threads slow each other")
    big = hyperfine([command(10000, 0)], runs=3, out=out, warmup=0)[0]
    report.row("6 sweep", "10,000 rods x 10 s, every core (whole process)", big, "s", "< 5")


# --- the machine, and the docs -----------------------------------------------------------------------
def load() -> str:
    with open("/proc/loadavg") as f:
        return " ".join(f.read().split()[:3])


def machine() -> str:
    cpu = ""
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    return f"{cpu}, {os.cpu_count()} cores, load average {load()} at the end"


def write_with_publish_rate(source: str, target: str, publish_rate: float) -> None:
    """`source`'s config with its world key publish_rate set (whether the source gives it or not)."""
    with open(source) as f:
        config = yaml.safe_load(f)
    config["publish_rate"] = publish_rate
    with open(target, "w") as f:
        yaml.safe_dump(config, f, sort_keys=False)


def write_into_doc(path: str, text: str) -> None:
    """Replaces what stands between BEGIN and END in `path` with `text`."""
    with open(path) as f:
        doc = f.read()
    start, end = doc.find(BEGIN), doc.find(END)
    if start < 0 or end < start:
        raise RuntimeError(f"{path} has no section between '{BEGIN}' and '{END}'")
    with open(path, "w") as f:
        f.write(doc[:start + len(BEGIN)] + "\n" + text + "\n" + doc[end:])


def main() -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("build", help="the Release build folder (its devel/setup.bash sourced)")
    parser.add_argument("--quick", action="store_true", help="node runs of 12 s instead of 60, for a try-out")
    parser.add_argument("--doc", default=DOC, help="the Markdown file whose marked section gets the table")
    parser.add_argument("--node-only", action="store_true",
                        help="the node, recording and scale sections only; the doc is left as it is")
    args = parser.parse_args()
    build = os.path.abspath(args.build)
    out = os.path.join(build, "bench-out")
    os.makedirs(out, exist_ok=True)
    node_seconds = 12 if args.quick else 60
    start = time.time()
    report = Report()
    if not args.node_only:
        core_times = core(report, build, out)
        text_program(report, build, out, core_times)
        sweeps(report, build, out)
    config_1khz = os.path.join(out, "demo_1khz.yaml")
    write_with_publish_rate(os.path.join(ROOT, "config/demo.yaml"), config_1khz, 1000.0)
    ros = Ros(out)
    try:
        demo = os.path.join(ROOT, "config/demo.yaml")
        node_at_rate(report, ros, "50 Hz publishing", demo, node_seconds, 6, 20.0, "<= 0.6")
        roscpp_floor(report, ros, build, node_seconds / 2, 3)
        node_at_rate(report, ros, "1000 Hz publishing", config_1khz, node_seconds, 6, 1.0, "<= 15")
        recording(report, ros, out, demo, 50.0, 60.0, "real_time_factor:=0")
        recording(report, ros, out, demo, 50.0, 60.0, "real_time_factor:=0", "record_in_node:=true")
        recording(report, ros, out, config_1khz, 1000.0, node_seconds)
        for bodies in (1, 100, 1000):
            many_bodies(report, ros, out, bodies, node_seconds / 2, markers=bodies == 100)
        faster_than_real_time(report, ros, build, out, 9)
    finally:
        ros.close()
    text = report.markdown(time.time() - start) + ("\n\n(a --quick run: node runs of 12 s)" if args.quick else "")
    print(text)
    with open(os.path.join(out, "bench.md"), "w") as f:
        f.write(text + "\n")
    if not args.node_only:
        write_into_doc(args.doc, text)
        print(f"bench: the table is in {args.doc}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
