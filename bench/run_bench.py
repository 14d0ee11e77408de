#!/usr/bin/python3
"""`make bench`: runs every measurement of issue 4 and prints one table (median, min, max of repeated
runs or windows) with short notes. Needs a Release build with -Drigid_body_sim_BENCHMARKS=ON whose devel/setup.bash
is sourced (rospy and the package's messages), hyperfine, and numpy.

  run_bench.py BUILD_DIR [--quick]     (--quick: shorter node runs, for trying the script out)
"""
import json
import os
import random
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time
import xmlrpc.client

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
ROWS = []   # (section, what, median, min, max, unit, target)
NOTES = []


def row(section, what, values, unit, target=""):
    values = [v for v in values if v is not None]
    if not values:
        ROWS.append((section, what, None, None, None, unit, target))
        return
    ROWS.append((section, what, statistics.median(values), min(values), max(values), unit, target))


def note(text):
    NOTES.append(text)
    print("  note: " + text, flush=True)


def say(text):
    print("bench: " + text, file=sys.stderr, flush=True)


def percentile(values, p):
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, max(0, int(round(p / 100.0 * (len(ordered) - 1)))))]


def hyperfine(commands, runs, out, warmup=2, cpu=False, failing=False):
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


# --- 1. core ------------------------------------------------------------------------------------
def core(build, out):
    say("core: Google Benchmark, 7 repetitions")
    path = os.path.join(out, "bench_core.json")
    subprocess.run([os.path.join(build, "devel/lib/rigid_body_sim/bench_core"), "--benchmark_repetitions=7",
                    "--benchmark_min_time=0.2", "--benchmark_out=" + path, "--benchmark_out_format=json"],
                   check=True, stdout=subprocess.DEVNULL)
    with open(path) as f:
        runs = [b for b in json.load(f)["benchmarks"] if b.get("run_type") == "iteration"]
    times = {}
    for b in runs:
        bodies = b.get("bodies", 1)
        times.setdefault(b["run_name"], []).append(b["cpu_time"] / bodies)
    targets = {"rodStep/euler_cromer": "<= 30", "rollerStep/rolling": "<= 15", "rollerStep/slipping": "<= 15"}
    for name, values in times.items():
        label = name.replace("rodStep/", "rod, ").replace("rollerStep/", "roller, ")
        if name.startswith("worldStep/"):
            label = "world of n = %s bodies (half rods, half rollers), per body-step" % name.split("/")[1]
        row("1 core", label, values, "ns/step (CPU)", targets.get(name, ""))
    note("core figures are CPU time per step (Google Benchmark's cpu_time): the machine is shared, and wall time "
         "per step ran 2-3x higher at the load averages seen. Debian's libbenchmark is built as DEBUG (its own "
         "warning); that slows its loop bookkeeping, not the code measured")
    note("rod: in flight (centre at least L/2 above the floor) no end can touch it, so the force model returns "
         "gravity alone without calling sincos, with the very bits the text's sums give (test_rod checks the "
         "trajectory bit for bit); before, sincos was 43 % of every step (49.5 -> 17.4 ns). In contact the step "
         "keeps the text's sincos and its three divisions by M and I, one dependent chain")
    note("roller: the sine and cosine of the incline and the accelerations of each mode are computed when the "
         "parameters change, and the core is built with -fno-semantic-interposition so that its small functions "
         "inline (before: 2 libm calls a rolling step, 6 a slipping one, and calls through the PLT; 27 -> 6 ns "
         "rolling, 67 -> 6 ns slipping, results bit-identical)")
    return times


# --- 2. the text's program ----------------------------------------------------------------------
def text_program(build, out, core_times):
    say("the text's program (numpy) against simulate, whole processes (hyperfine)")
    simulate = os.path.join(build, "devel/lib/rigid_body_sim/simulate")
    csv_dir = os.path.join(out, "rod_csv")
    python, cpp = hyperfine(["/usr/bin/python3 " + os.path.join(HERE, "text_program.py"),
                             "%s %s --out-dir %s" % (simulate, os.path.join(ROOT, "config/rod.yaml"), csv_dir)],
                            runs=10, out=out)
    row("2 text", "text's program, 10 s, whole process (python3 + numpy)", [t * 1e3 for t in python], "ms")
    row("2 text", "simulate config/rod.yaml, 10 s, whole process", [t * 1e3 for t in cpp], "ms")
    startup = hyperfine([simulate + " /nonexistent.yaml"], runs=10, out=out, failing=True)[0]
    row("2 text", "  of which simulate's start-up (a missing config: loads its libraries, refuses, exits)",
        [t * 1e3 for t in startup], "ms")
    row("2 text", "ratio, whole process (per run pairs, sorted)",
        [p / c for p, c in zip(sorted(python), sorted(cpp))], "x", ">= 50")
    result = subprocess.run(["/usr/bin/python3", os.path.join(HERE, "text_program.py"), "--repeat", "7"],
                            check=True, capture_output=True, text=True)
    stepping = json.loads(result.stdout)
    per_step_py = [s / stepping["steps"] * 1e9 for s in stepping["seconds"]]
    row("2 text", "text's program, stepping alone", per_step_py, "ns/step")
    ec = core_times["rodStep/euler_cromer"]
    ratios = [p / statistics.median(ec) for p in per_step_py]
    row("2 text", "ratio, stepping alone (vs rod Euler-Cromer above)", ratios, "x", ">= 1000")


# --- 3-5. the node --------------------------------------------------------------------------------
class Ros:
    """Its own master on a random port; one rospy subscriber in this process."""

    def __init__(self, build, out):
        self.out = out
        self.home = tempfile.mkdtemp(prefix="bench_ros_", dir=out)
        self.port = random.randint(20000, 45000)
        os.environ.pop("ROS_HOSTNAME", None)
        os.environ.update(ROS_MASTER_URI="http://127.0.0.1:%d" % self.port, ROS_IP="127.0.0.1", ROS_HOME=self.home)
        self.env = dict(os.environ)
        self.log = open(os.path.join(out, "ros.log"), "w")
        self.master = subprocess.Popen(["roscore", "-p", str(self.port)], stdout=self.log, stderr=self.log,
                                       start_new_session=True)
        import rosgraph
        deadline = time.time() + 30
        while not rosgraph.is_master_online():
            if time.time() > deadline:
                raise RuntimeError("roscore did not come up (see %s)" % self.log.name)
            time.sleep(0.2)
        import rospy
        self.rospy = rospy
        rospy.init_node("bench", anonymous=True, disable_signals=True)
        self.received = []   # (receipt wall time, header stamp, t)
        self.subscriber = None

    def subscribe(self, topic, kind):
        self.received = []
        self.subscriber = self.rospy.Subscriber(topic, kind, self._on_message, queue_size=5000, tcp_nodelay=True)

    def unsubscribe(self):
        if self.subscriber:
            self.subscriber.unregister()
            self.subscriber = None

    def _on_message(self, msg):
        self.received.append((time.time(), msg.header.stamp.to_sec(), msg.t))

    def launch(self, *args):
        return subprocess.Popen(["roslaunch", "rigid_body_sim", "sim.launch"] + list(args), stdout=self.log,
                                stderr=self.log, start_new_session=True)

    def node_pid(self, name="/sim", timeout=30):
        import rosgraph
        master = rosgraph.Master("/bench")
        deadline = time.time() + timeout
        while time.time() < deadline:
            try:
                uri = master.lookupNode(name)
                return xmlrpc.client.ServerProxy(uri).getPid("/bench")[2]
            except Exception:
                time.sleep(0.2)
        raise RuntimeError("%s did not start (see %s)" % (name, self.log.name))

    @staticmethod
    def stop(process, timeout=20):
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGINT)
            try:
                process.wait(timeout)
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()

    def close(self):
        self.unsubscribe()
        self.rospy.signal_shutdown("bench done")
        self.stop(self.master)
        self.log.close()
        shutil.rmtree(self.home, ignore_errors=True)


def cpu_seconds(pid):
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")  # utime + stime


def rss_mib(pid):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    return None


def wait_for_messages(ros, count=5, timeout=30):
    deadline = time.time() + timeout
    while len(ros.received) < count:
        if time.time() > deadline:
            raise RuntimeError("no state messages arrived")
        time.sleep(0.05)


def node_at_rate(ros, label, config, seconds, windows, nominal_gap_ms, cpu_target):
    from rigid_body_sim.msg import RodState
    say("node: %s, %d s of wall time" % (label, seconds))
    ros.subscribe("/sim/rod/state", RodState)
    process = ros.launch("config:=" + config)
    try:
        pid = ros.node_pid()
        wait_for_messages(ros)
        time.sleep(2.0)  # start-up (servers, first TF) is not the steady state
        rss_start = rss_mib(pid)
        shares, windows_received = [], []
        for _ in range(windows):
            wall0, cpu0, first = time.time(), cpu_seconds(pid), len(ros.received)
            time.sleep(seconds / windows)
            shares.append(100.0 * (cpu_seconds(pid) - cpu0) / (time.time() - wall0))
            windows_received.append(ros.received[first:])
        rss_end = rss_mib(pid)
    finally:
        ros.unsubscribe()
        ros.stop(process)
    each = "%d windows of %g s" % (windows, seconds / windows)
    row("3 node", "%s: CPU, share of one core (%s)" % (label, each), shares, "%", cpu_target)
    row("3 node", "%s: resident memory at start" % label, [rss_start], "MiB")
    row("3 node", "%s: resident memory at end" % label, [rss_end], "MiB", "= start")
    gaps = [[1e3 * (b[0] - a[0]) for a, b in zip(w, w[1:])] for w in windows_received]
    for name, pick, target in (("p50", lambda g: percentile(g, 50), "%g" % nominal_gap_ms),
                               ("p99", lambda g: percentile(g, 99), "<= %g" % (nominal_gap_ms + 2)),
                               ("max", max, "")):
        row("3 node", "%s: gap between state messages at a subscriber, %s (%s)" % (label, name, each),
            [pick(g) for g in gaps if g], "ms", target)
    # The node stamps wall_start + t: receipt - stamp is its lag behind the wall clock plus the transport.
    # The drift is how much that lag grew from the first second to the last (least-delayed message of each).
    received = [m for w in windows_received for m in w]
    lag = [(r - st) * 1e3 for r, st, _ in received]
    per_second = max(1, int(round(1000.0 / nominal_gap_ms)))
    row("3 node", "%s: drift of simulated vs wall time, first to last second" % label,
        [min(lag[-per_second:]) - min(lag[:per_second])], "ms", "<= 1")
    return rss_start, rss_end


def recording(ros, out, config_1khz, seconds):
    import rosbag
    say("recording: sim.launch record:=true at publish_rate 1000, %d s" % seconds)
    bag = os.path.join(out, "record.bag")
    for stale in (bag, bag + ".active"):
        if os.path.exists(stale):
            os.remove(stale)
    process = ros.launch("config:=" + config_1khz, "record:=true", "bag:=" + bag, "duration:=%d" % seconds)
    try:
        process.wait(seconds + 60)
    except subprocess.TimeoutExpired:
        note("the recording launch did not end by itself; stopped")
        ros.stop(process)
    deadline = time.time() + 20
    while not os.path.exists(bag) and time.time() < deadline:
        time.sleep(0.2)
    published = seconds * 1000 + 1  # t = 0, 0.001, ..., duration, per topic
    with rosbag.Bag(bag) as b:
        info = b.get_type_and_topic_info().topics
        state_topics = sorted(t for t in info if t.endswith("/state"))
        distinct = {t: set() for t in state_topics}
        for topic, msg, _ in b.read_messages(topics=state_topics):
            distinct[topic].add(int(round(msg.t * 1000)))
    lost = [published - len(distinct[t]) for t in state_topics]
    row("4 record", "state messages lost per topic (%d topics, %d published each)" % (len(state_topics), published),
        lost, "msgs", "0")
    for topic in ("/tf", "/sim/markers"):
        if topic in info:
            row("4 record", "%s messages in the bag (published: %d)" % (topic, published), [info[topic].message_count],
                "msgs", str(published))
    row("4 record", "bag size per simulated second", [os.path.getsize(bag) / seconds / 1e6], "MB/s")
    markers = info.get("/sim/markers")
    if markers and (markers.message_count < published or any(lost)):
        states = "lost up to %d state messages a topic" % max(lost) if any(lost) else "kept every state message"
        note("rosbag record kept %d of %d /sim/markers messages and %s: the MarkerArrays (trails of 400 points, "
             "at 1 kHz) make most of the bag's %.0f MB per simulated second, and rosbag's single callback queue "
             "falls behind on them when the machine is busy (load average %s); markers at a lower rate than the "
             "states would make the bag a fraction of that" %
             (markers.message_count, published, states, os.path.getsize(bag) / seconds / 1e6, load()))


def faster_than_real_time(ros, build, out, seconds):
    from rigid_body_sim.msg import RodState
    say("real_time_factor 0: node with publishing, and simulate --bag")
    ros.subscribe("/sim/rod/state", RodState)
    process = ros.launch("real_time_factor:=0")
    speeds = []
    try:
        ros.node_pid()
        wait_for_messages(ros)
        time.sleep(1.0)
        for _ in range(3):
            wall0, t0 = time.time(), ros.received[-1][2]
            time.sleep(seconds / 3.0)
            speeds.append((ros.received[-1][2] - t0) / (time.time() - wall0))
    finally:
        ros.unsubscribe()
        ros.stop(process)
    row("5 rtf 0", "node, config/demo.yaml (5 bodies), publishing at 50 Hz", speeds, "sim s / wall s")
    simulate = os.path.join(build, "devel/lib/rigid_body_sim/simulate")
    times = hyperfine(["%s %s --duration 60 --bag %s --out-dir %s" % (
        simulate, os.path.join(ROOT, "config/demo.yaml"), os.path.join(out, "simulate.bag"),
        os.path.join(out, "simulate_csv"))], runs=3, out=out, warmup=1)[0]
    row("5 rtf 0", "simulate --bag, config/demo.yaml, 60 s", [60.0 / t for t in times], "sim s / wall s")


# --- 6. sweeps ----------------------------------------------------------------------------------
def sweeps(build, out):
    say("sweeps: variants/s on 1 and 2 threads; 10,000 variants of the 10 s rod")
    simulate = os.path.join(build, "devel/lib/rigid_body_sim/simulate")
    command = "%s %s --sweep rod.theta0=0:6.283:%%d --jobs %%d --out-dir %s" % (
        simulate, os.path.join(ROOT, "config/rod.yaml"), os.path.join(out, "sweep"))
    commands = [command % (1000, 1), command % (1000, 2)]
    one, two = hyperfine(commands, runs=5, out=out, warmup=1)
    cpu_one, cpu_two = hyperfine(commands, runs=3, out=out, warmup=0, cpu=True)
    row("6 sweep", "1,000 rods x 10 s on 1 thread", [1000 / t for t in one], "variants/s")
    row("6 sweep", "1,000 rods x 10 s on 2 threads", [1000 / t for t in two], "variants/s")
    row("6 sweep", "speed-up on 2 threads (run pairs, sorted)", [a / b for a, b in zip(sorted(one), sorted(two))],
        "x", ">= 1.8")
    row("6 sweep", "CPU time per variant on 1 thread (user + sys, mean of 3 runs)", [t / 1000 * 1e3 for t in cpu_one], "ms")
    row("6 sweep", "CPU time per variant on 2 threads (user + sys, mean of 3 runs)", [t / 1000 * 1e3 for t in cpu_two], "ms")
    note("sweeps ran at load average %s on %d cores: the speed-up on 2 threads needs 2 idle cores; the CPU "
         "time per variant on 1 and 2 threads shows how much the threads slow each other" % (load(), os.cpu_count()))
    big = hyperfine([command % (10000, 0)], runs=3, out=out, warmup=0)[0]
    row("6 sweep", "10,000 rods x 10 s, every core (whole process)", big, "s", "< 5")


# --- the table ----------------------------------------------------------------------------------
def number(value):
    if value is None:
        return "-"
    if abs(value) >= 1000:
        return "{:,.0f}".format(value)
    if abs(value) >= 100:
        return "%.0f" % value
    if abs(value) >= 10:
        return "%.1f" % value
    return "%.3g" % value


def table():
    lines = ["| | what | median | min | max | unit | target |", "|---|---|---:|---:|---:|---|---|"]
    for section, what, median, low, high, unit, target in ROWS:
        lines.append("| %s | %s | %s | %s | %s | %s | %s |" % (section, what, number(median), number(low),
                                                               number(high), unit, target))
    return "\n".join(lines)


def load():
    with open("/proc/loadavg") as f:
        return " ".join(f.read().split()[:3])


def machine():
    cpu = ""
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    return "%s, %d cores, load average %s at the end" % (cpu, os.cpu_count(), load())


def main():
    build = os.path.abspath(sys.argv[1])
    quick = "--quick" in sys.argv
    out = os.path.join(build, "bench-out")
    os.makedirs(out, exist_ok=True)
    node_seconds = 12 if quick else 60
    start = time.time()
    core_times = core(build, out)
    text_program(build, out, core_times)
    sweeps(build, out)
    config_1khz = os.path.join(out, "demo_1khz.yaml")
    with open(os.path.join(ROOT, "config/demo.yaml")) as src, open(config_1khz, "w") as dst:
        dst.write(src.read().replace("publish_rate: 50.0", "publish_rate: 1000.0"))
    ros = Ros(build, out)
    try:
        demo = os.path.join(ROOT, "config/demo.yaml")
        node_at_rate(ros, "50 Hz publishing", demo, node_seconds, 6, 20.0, "<= 3")
        node_at_rate(ros, "1000 Hz publishing", config_1khz, node_seconds, 6, 1.0, "<= 15")
        recording(ros, out, config_1khz, node_seconds)
        faster_than_real_time(ros, build, out, 9)
    finally:
        ros.close()
    report = "\n".join(["", "## make bench: %s" % time.strftime("%Y-%m-%d %H:%M"), "", table(), "",
                        "Machine: " + machine() + "; all of it took %.0f s." % (time.time() - start), ""] +
                       ["- " + n for n in NOTES])
    print(report)
    with open(os.path.join(out, "bench.md"), "w") as f:
        f.write(report + "\n")


if __name__ == "__main__":
    main()
