"""rviz's own output, as roslaunch keeps it: the picture tests' "no ERROR line in rviz's log". A module of its
own, with nothing of the picture tests beside it, so that test/tools/test_scripts.py loads it by its path."""
import os
import re
from typing import List, Optional

import rospkg


def rviz_logs() -> List[str]:
    """The files of rviz's own output: roslaunch keeps them in the log folder's latest/ ($ROS_LOG_DIR, or
    $ROS_HOME/log)."""
    folder = os.path.join(rospkg.get_log_dir(), "latest")
    names = [name for name in sorted(os.listdir(folder)) if name.startswith("rviz")] if os.path.isdir(folder) else []
    return [os.path.join(folder, name) for name in names]


def output_tails(roslaunch_log: Optional[str], lines: int = 30) -> str:
    """The last lines of roslaunch's output and of rviz's own, for a failure's message: what a test that
    waited in vain saw of the launch (its master, a node that died, rviz's errors)."""
    text = ""
    for path in ([roslaunch_log] if roslaunch_log else []) + rviz_logs():
        with open(path, errors="replace") as f:
            text += f"--- the last {lines} lines of {path}:\n" + "".join(f.readlines()[-lines:])
    return text or "no output of roslaunch or rviz"


def rviz_error_lines() -> List[str]:
    """ERROR lines of rviz's own output (rviz_logs), or one line saying that there is no such output: an absent
    log is no clean one."""
    paths = rviz_logs()
    folder = os.path.join(rospkg.get_log_dir(), "latest")
    if not paths:
        return [f"no output of rviz in {folder}"]
    lines: List[str] = []
    for path in paths:
        with open(path, errors="replace") as f:
            lines += [line.strip() for line in f if re.search(r"\bERROR\b", line)]
    return lines
