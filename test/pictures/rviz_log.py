"""rviz's own output, as roslaunch keeps it: the picture tests' "no ERROR line in rviz's log". A module of its
own, with nothing of the picture tests beside it, so that test/tools/test_scripts.py loads it by its path."""
import os
import re
from typing import List

import rospkg


def rviz_error_lines() -> List[str]:
    """ERROR lines of rviz's own output (roslaunch keeps it in the log folder's latest/: $ROS_LOG_DIR, or
    $ROS_HOME/log), or one line saying that there is no such output: an absent log is no clean one."""
    folder = os.path.join(rospkg.get_log_dir(), "latest")
    names = [name for name in sorted(os.listdir(folder)) if name.startswith("rviz")] if os.path.isdir(folder) else []
    if not names:
        return [f"no output of rviz in {folder}"]
    lines: List[str] = []
    for name in names:
        with open(os.path.join(folder, name), errors="replace") as f:
            lines += [line.strip() for line in f if re.search(r"\bERROR\b", line)]
    return lines
