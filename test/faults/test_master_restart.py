#!/usr/bin/env python3
"""A master that restarts: sim.launch respawn:=true under a roscore of its own; the roscore is stopped and
started again on the same port. roscpp cannot register a running node again, so the node must notice
that the new master does not know it, log one line and exit with status 3; roslaunch then respawns it,
and the new node is registered with the new master, on its parameters (which the old node put back), and
publishes its states again.

Usage: test_master_restart.py CONFIG.yaml   (with the package's devel space sourced)
"""
import argparse
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from typing import List

import rosgraph
from rigid_body_sim.sim_tools import free_port, node_pid, wait_for

FORGOT_LINE = "no longer knows this node"
EXIT_STATUS = 3


def knows(master: rosgraph.Master, node: str) -> bool:
    """Whether the master answers and lists the node."""
    try:
        master.lookupNode(node)
        return True
    except (rosgraph.MasterError, OSError):
        return False


def one_state(env: "dict[str, str]", topic: str) -> bool:
    """Whether a fresh subscriber receives one message on the topic within 10 s."""
    try:
        echo = subprocess.run(["rostopic", "echo", "-n", "1", topic], env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.DEVNULL, text=True, timeout=10)
    except subprocess.TimeoutExpired:
        return False
    return echo.returncode == 0 and "t:" in echo.stdout


def start_roscore(port: int, env: "dict[str, str]") -> "subprocess.Popen[bytes]":
    core = subprocess.Popen(["roscore", "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    wait_for("roscore", rosgraph.Master("/test").is_online, 30.0, period=0.2)
    return core


def stop(process: "subprocess.Popen[bytes]") -> None:
    if process.poll() is None:
        process.send_signal(signal.SIGINT)
        process.wait(timeout=30)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("config")
    config = parser.parse_args().config
    work = tempfile.mkdtemp(prefix="rbs_master_restart_")
    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_HOME=work)
    os.environ.update(ROS_MASTER_URI=env["ROS_MASTER_URI"], ROS_HOME=work)
    log_path = os.path.join(work, "launch.log")
    failures: List[str] = []
    core = start_roscore(port, env)
    with open(log_path, "w") as log:
        launch = subprocess.Popen(["roslaunch", "rigid_body_sim", "sim.launch", f"config:={config}",
                                   "respawn:=true"], env=env, stdout=log, stderr=subprocess.STDOUT)
    try:
        wait_for("the first state", lambda: one_state(env, "/sim/rod/state"), 60.0, period=0.5)
        first_pid = node_pid("/sim", "/test")
        stop(core)
        core = start_roscore(port, env)
        restarted = time.monotonic()
        wait_for("the respawned node on the new master", lambda: knows(rosgraph.Master("/test"), "/sim"), 30.0)
        registered = time.monotonic() - restarted
        wait_for("a state from the respawned node", lambda: one_state(env, "/sim/rod/state"), 30.0, period=0.5)
        if node_pid("/sim", "/test") == first_pid:
            failures.append("the node on the new master is the old process")
        print(f"master restarted: the node was registered again after {registered:.1f} s")
    except TimeoutError as error:
        failures.append(str(error))
    finally:
        stop(launch)
        stop(core)
    with open(log_path) as log:
        output = log.read()
    if output.count(FORGOT_LINE) != 1:
        failures.append(f"'{FORGOT_LINE}' logged {output.count(FORGOT_LINE)} times, not once")
    if f"exit code {EXIT_STATUS}" not in output:
        failures.append(f"roslaunch did not see exit code {EXIT_STATUS}")
    if failures:
        print("master restart: FAILED:\n  " + "\n  ".join(failures) + "\n--- roslaunch:\n" + output[-4000:])
        sys.exit(1)
    shutil.rmtree(work)
    print("master restart: ok")


if __name__ == "__main__":
    main()
