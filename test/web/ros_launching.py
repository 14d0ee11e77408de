"""What the web tests share to start ROS: the environment of a master of their own, that master, a
roslaunch whose lines are read as they come, and the teacher's login (the form's address and the token) that
the web view prints."""
import os
import re
import subprocess
import threading
from typing import Any, Dict, List, NamedTuple, Optional

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


class Teacher(NamedTuple):
    """What the web view prints for the teacher: its login form's address and the token to type into it."""
    login: str  # http://HOST:PORT/login
    token: str

    @property
    def base(self) -> str:
        """The page's address, http://HOST:PORT/."""
        return self.login[:-len("login")]


def teacher_in(lines: List[str], web_port: int) -> Optional[Teacher]:
    """The teacher's login the web view on `web_port` printed into `lines` (`[INFO] web view: control (keep it to
    the teacher): http://HOST:PORT/login token TOKEN`), or None."""
    pattern = re.compile(rf"web view: control \(keep it to the teacher\): (http://[^/\s]+:{web_port}/login) "
                         r"token ([A-Za-z0-9_-]{24})\s*$")
    found = [m for m in (pattern.search(line) for line in list(lines)) if m]
    return Teacher(found[0].group(1), found[0].group(2)) if found else None


def teacher_login(log: List[str], web_port: int) -> Teacher:
    """The teacher's login the web view on `web_port` printed into `log`, once it has."""
    found: List[Teacher] = []

    def printed() -> bool:
        teacher = teacher_in(log, web_port)
        found[:] = [teacher] if teacher else []
        return bool(found)
    try:
        wait_for("the web view's teacher's login in the launch's log", printed, DEADLINE)
    except TimeoutError as error:
        raise AssertionError(f"{error}; the launch's log:\n" + "".join(list(log)[-60:])) from None
    return found[0]
