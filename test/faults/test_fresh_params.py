#!/usr/bin/env python3
"""A launch never inherits an earlier launch's parameters: launches one after the other on one master.

- sim.launch on a refused config (a body `wobbly` with k = -5, which config/demo.yaml does not have):
  the node's one FATAL line, and the launch ends by itself (the node's exit status 1 is
  test_node_bad_input_startup's); then a plain sim.launch runs demo.yaml (nothing refused, its end at
  duration without alarm).
Every launch ends by itself with status 0 (roslaunch's, whatever its nodes did) and no REQUIRED banner.
- rod.launch (use_sim_time:=false) leaves /use_sim_time true as it was, and its node warns that no /clock
  comes; then incline.launch has exactly
  incline.yaml's bodies under /sim/bodies and publishes their states, and no rod.

Usage: test_fresh_params.py CONFIG_DIR   (with the package's devel space sourced)
"""
import argparse
import os
import shutil
import signal
import subprocess
import sys
import tempfile
from typing import Any, Dict, List, Set

import rosgraph
import yaml
from rigid_body_sim.sim_tools import free_port, load_config, wait_for


class Run:
    """roslaunch on a master of its own; its output in a file."""

    def __init__(self, work: str) -> None:
        self.work = work
        port = free_port()
        self.env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_HOME=work)
        os.environ.update(ROS_MASTER_URI=self.env["ROS_MASTER_URI"], ROS_HOME=work)
        self.core = subprocess.Popen(["roscore", "-p", str(port)], env=self.env, stdout=subprocess.DEVNULL,
                                     stderr=subprocess.DEVNULL)
        self.master = rosgraph.Master("/test")
        wait_for("roscore", self.master.is_online, 30.0, period=0.2)
        self.failures: List[str] = []

    def launch(self, args: List[str]) -> "subprocess.Popen[str]":
        return subprocess.Popen(["roslaunch", "rigid_body_sim"] + args, env=self.env, stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True)

    def expect(self, args: List[str], clean_end: bool, absent: str = "", present: str = "") -> None:
        """Runs a launch to its end, which must come by itself, with status 0 and no REQUIRED banner; a text
        that must not appear and one that must. A clean end also has no dead process."""
        process = self.launch(args)
        output, _ = process.communicate(timeout=120)
        if process.returncode != 0 or "REQUIRED" in output:
            self.failures.append(f"{' '.join(args)}: exit status {process.returncode}:\n{output[-2000:]}")
        if clean_end and "process has died [" in output:
            self.failures.append(f"{' '.join(args)}: a process died:\n{output[-2000:]}")
        if absent and absent in output:
            self.failures.append(f"{' '.join(args)}: says '{absent}':\n{output[-2000:]}")
        if present and present not in output:
            self.failures.append(f"{' '.join(args)}: does not say '{present}':\n{output[-2000:]}")

    def stop(self) -> None:
        self.core.send_signal(signal.SIGINT)
        self.core.wait(timeout=30)


def refused_config(config_dir: str, path: str) -> None:
    """config/rod.yaml with its rod renamed `wobbly` and k = -5."""
    config: Dict[str, Any] = load_config(os.path.join(config_dir, "rod.yaml"))
    wobbly = dict(config["bodies"]["rod"], k=-5.0)
    config["bodies"] = {"wobbly": wobbly}
    with open(path, "w") as out:
        yaml.safe_dump(config, out)


def state_topics(master: rosgraph.Master) -> Set[str]:
    return {topic for topic, _ in master.getPublishedTopics("/sim") if topic.endswith("/state")}


def incline_after_rod(run: Run, config_dir: str) -> None:
    # A system on simulated time: use_sim_time:=false leaves it so, and with no /clock the node says so.
    run.master.setParam("/use_sim_time", True)
    run.expect(["rod.launch", "duration:=3"], True, present="/use_sim_time is true but nothing publishes /clock")
    if run.master.getParam("/use_sim_time") is not True:
        run.failures.append("rod.launch (use_sim_time:=false) changed /use_sim_time")
    run.master.deleteParam("/use_sim_time")
    incline = load_config(os.path.join(config_dir, "incline.yaml"))
    wanted = {f"/sim/{body}/state" for body in incline["bodies"]}
    process = run.launch(["incline.launch"])
    try:
        wait_for(f"the states {sorted(wanted)}", lambda: wanted <= state_topics(run.master), 60.0, period=0.2)
        if state_topics(run.master) != wanted:
            run.failures.append(f"incline.launch after rod.launch publishes {sorted(state_topics(run.master))}")
        bodies = set(run.master.getParam("/sim/bodies"))
        if bodies != set(incline["bodies"]):
            run.failures.append(f"incline.launch after rod.launch: /sim/bodies holds {sorted(bodies)}")
    except TimeoutError as error:
        run.failures.append(str(error))
    finally:
        process.send_signal(signal.SIGINT)
        process.communicate(timeout=60)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("config_dir")
    config_dir = parser.parse_args().config_dir
    work = tempfile.mkdtemp(prefix="rbs_fresh_params_")
    run = Run(work)
    try:
        refused = os.path.join(work, "refused.yaml")
        refused_config(config_dir, refused)
        run.expect(["sim.launch", f"config:={refused}", "duration:=1"], False,
                   present="refused config: body 'wobbly', key 'k': value -5 is not allowed")
        run.expect(["sim.launch", "duration:=1"], True, absent="refused")
        incline_after_rod(run, config_dir)
    finally:
        run.stop()
    if run.failures:
        print("fresh parameters: FAILED:\n" + "\n".join(run.failures))
        sys.exit(1)
    shutil.rmtree(work)
    print("fresh parameters: ok")


if __name__ == "__main__":
    main()
