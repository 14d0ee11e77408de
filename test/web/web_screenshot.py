#!/usr/bin/env python3
"""Screenshots of the web view as a class sees it (the page without the token: no controls), for the docs:
lesson.launch web:=true started paused, run for SECONDS of simulated time from t = 0 and paused again (so the
picture does not depend on the machine's load), the plots of PLOT_BODY; at 1600x900 (OUT_DIR/web_lesson.png)
and at a phone's 390x844 (OUT_DIR/web_lesson_phone.png); --name another name than web_lesson.

Usage: web_screenshot.py OUT_DIR [--part below] [--seconds 1.6] [--plot-body ring] [--name web_lesson]
(with the package's devel space sourced)"""
import argparse
import os
import shutil
import signal
import subprocess
import tempfile

import rospy
from std_srvs.srv import Empty
from rigid_body_sim.sim_tools import free_port, load_config, rospy_on_python39, state_message, wait_for
from rigid_body_sim.web_protocol import part_config

from browser import Browser, end

rospy_on_python39()
DEADLINE = 60.0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir")
    parser.add_argument("--part", default="below")
    parser.add_argument("--seconds", type=float, default=1.6)
    parser.add_argument("--plot-body", default="ring")
    parser.add_argument("--name", default="web_lesson")
    args = parser.parse_args()
    home = tempfile.mkdtemp(prefix="rbs_web_shot_")
    port, web_port = free_port(), free_port()
    env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_HOME=home, ROS_IP="127.0.0.1",
               PATH="/usr/bin:" + os.environ.get("PATH", ""))
    env.pop("ROS_HOSTNAME", None)
    os.environ.update({k: env[k] for k in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")})
    launch = subprocess.Popen(["roslaunch", "-p", str(port), "rigid_body_sim", "lesson.launch", f"part:={args.part}",
                               "rviz:=false", "start_paused:=true", "web:=true", f"web_port:={web_port}"],
                              env=env, stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
    browser = None
    try:
        wait_for("the master", lambda: subprocess.run(["rostopic", "list"], env=env, capture_output=True)
                 .returncode == 0, DEADLINE, period=0.2)
        rospy.init_node("web_screenshot", anonymous=True, disable_signals=True)
        root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
        config = load_config(os.path.join(root, "config", part_config(args.part)))
        kind = state_message(str(config["bodies"][args.plot_body]["type"]))
        last = [-1.0]
        rospy.Subscriber(f"/sim/{args.plot_body}/state", kind, lambda m: last.__setitem__(0, m.t))
        browser = Browser(1600, 900)
        browser.resize(1600, 900, 1, False)
        wait_for("the web view", lambda: subprocess.run(["curl", "-sf", f"http://127.0.0.1:{web_port}/"],
                                                        capture_output=True).returncode == 0, DEADLINE, period=0.2)
        browser.navigate(f"http://127.0.0.1:{web_port}/")
        # Started paused, the node sent its state at t = 0 before the web view subscribed: the bodies come with
        # the first state after Run.
        browser.wait("the bodies", "window.rbs && rbs.world && Object.keys(rbs.world.bodies).length > 0", DEADLINE)
        browser.choose("plot-body", args.plot_body)
        rospy.wait_for_service("/sim/unpause", timeout=DEADLINE)
        rospy.ServiceProxy("/sim/unpause", Empty)()
        wait_for(f"{args.seconds} s simulated", lambda: last[0] >= args.seconds, DEADLINE)
        rospy.ServiceProxy("/sim/pause", Empty)()
        browser.wait("the page at the paused state", f"rbs.paused && rbs.drawn[{args.plot_body!r}].t === "
                     "rbs.plotLast.points.energy[0]", DEADLINE)
        wait_for("the page's drawing of the last state",
                 lambda: browser is not None and browser.evaluate(f"rbs.drawn[{args.plot_body!r}].t") == last[0],
                 DEADLINE)
        os.makedirs(args.out_dir, exist_ok=True)
        for name, width, height, scale, mobile in ((f"{args.name}.png", 1600, 900, 1, False),
                                                   (f"{args.name}_phone.png", 390, 844, 2, True)):
            browser.resize(width, height, scale, mobile)
            browser.wait(f"the page laid out at {width}x{height}",
                         "document.getElementById('scene-canvas').width === Math.round(document.getElementById("
                         f"'scene-canvas').clientWidth * {scale}) && document.documentElement.clientWidth === {width}",
                         DEADLINE)
            browser.screenshot(os.path.join(args.out_dir, name))
            print(os.path.join(args.out_dir, name))
    finally:
        if browser:
            browser.close()
        end(launch, signal.SIGINT, 60)
        shutil.rmtree(home, ignore_errors=True)


if __name__ == "__main__":
    main()
