"""What the web tests share to start ROS: the environment of a master of their own, that master, a
roslaunch whose lines are read as they come, and the teacher's link the web view prints."""
import os
import re
import subprocess
import threading
from typing import Any, Dict, List

from rigid_body_sim.sim_tools import wait_for

DEADLINE = 60.0  # s for any one wait


def ros_env(port: int, home: str) -> Dict[str, str]:
    """The environment of a process on the master at `port` (this machine's loopback), with ROS_HOME `home`.
    PYTHONUNBUFFERED: roslaunch and the web view write their lines into a pipe, which Python would otherwise
    fill in blocks: the control link would come only when the launch ends."""
    env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_HOME=home, ROS_IP="127.0.0.1",
               PATH="/usr/bin:" + os.environ.get("PATH", ""), PYTHONUNBUFFERED="1")
    env.pop("ROS_HOSTNAME", None)
    return env


def start_master(env: Dict[str, str]) -> "subprocess.Popen[str]":
    """roscore on env's master port, once it answers."""
    port = env["ROS_MASTER_URI"].rsplit(":", 1)[1]
    master = subprocess.Popen(["roscore", "-p", port], env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL, text=True)
    wait_for("the master", lambda: subprocess.run(["rosnode", "list"], env=env, capture_output=True)
             .returncode == 0, DEADLINE, period=0.2)
    return master


def launch_reading(words: List[str], env: Dict[str, str], log: List[str]) -> "subprocess.Popen[str]":
    """roslaunch WORDS..., each line of its output appended to `log` as it comes."""
    launch = subprocess.Popen(["roslaunch", *words], env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              text=True)

    def read(out: Any) -> None:
        for line in out:
            log.append(line)
    threading.Thread(target=read, args=(launch.stdout,), daemon=True).start()
    return launch


def control_link(log: List[str], web_port: int) -> str:
    """The teacher's link (http://HOST:PORT/?token=...) the web view on `web_port` printed into `log`."""
    pattern = re.compile(rf"(http://[^/\s]+:{web_port}/\?token=[A-Za-z0-9_-]{{24}})\s*$")
    found: List[str] = []

    def printed() -> bool:
        found[:] = [m.group(1) for m in (pattern.search(line) for line in list(log)) if m]
        return bool(found)
    try:
        wait_for("the web view's control link in the launch's log", printed, DEADLINE)
    except TimeoutError as error:
        raise AssertionError(f"{error}; the launch's log:\n" + "".join(list(log)[-60:])) from None
    return found[0]
