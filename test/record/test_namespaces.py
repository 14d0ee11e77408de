#!/usr/bin/env python3
"""Two instances of sim.launch on one master, each in a namespace, with a frame prefix, each recording:
ns:=a frame_prefix:=a/ and ns:=b frame_prefix:=b/.

- A tf2 listener sees both sets of frames (a/rod, b/rod, a/rod_floor ...), none unprefixed; both instances
  place their fixed frames alike (same config), and every frame's stamps on /tf only increase (two
  instances publishing one frame would alternate between their runs).
- /use_sim_time is left unset (use_sim_time:=false).
- Each bag holds only its own instance's topics (<ns>/tf, <ns>/tf_static, <ns>/sim/markers,
  <ns>/sim/<body>/state for every body of the config), its own frames, and states from t = 0 to duration.
- playback.launch ns:=a plays bag a's transforms on /tf and /tf_static, every message of them.

Usage: test_namespaces.py CONFIG.yaml   (with the package's devel space sourced)
"""
import argparse
import os
import signal
import shutil
import subprocess
import sys
import tempfile
import unittest
from typing import IO, Any, Dict, List, Set

import rosbag
import rosgraph
import rospy
import tf2_ros
from tf2_msgs.msg import TFMessage
from rigid_body_sim.sim_tools import (Config, body_of_state_topic, free_port, load_config, play_until,
                                      rospy_on_python39, subscribe_to_the_rest, wait_for, world_value)

rospy_on_python39()

INSTANCES = ("a", "b")
DURATION = 4.0  # simulated (= wall) seconds of each run, from when its recorder has subscribed


class StampOrder:
    """Every /tf frame's stamps, checked to increase: a frame sent by two runs would go back in time."""

    def __init__(self) -> None:
        self.last: Dict[str, rospy.Time] = {}
        self.backwards: List[str] = []
        self.subscriber = rospy.Subscriber("/tf", TFMessage, self.on_tf, queue_size=1000)

    def on_tf(self, msg: TFMessage) -> None:
        for transform in msg.transforms:
            frame = transform.child_frame_id
            stamp = transform.header.stamp
            if frame in self.last and stamp <= self.last[frame]:
                self.backwards.append(f"{frame}: {self.last[frame].to_sec():.3f} then {stamp.to_sec():.3f}")
            self.last[frame] = stamp


class TwoInstances(unittest.TestCase):
    config_path = ""
    work: str
    env: Dict[str, str]
    master: "subprocess.Popen[bytes]"
    config: Config
    bodies: List[str]
    order: StampOrder
    buffer: Any
    tf_listener: Any
    logs: Dict[str, IO[str]]
    launches: Dict[str, "subprocess.Popen[bytes]"]

    @classmethod
    def setUpClass(cls) -> None:
        cls.work = tempfile.mkdtemp(prefix="rbs_namespaces_")
        port = free_port()
        cls.env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_HOME=cls.work)
        os.environ.update(ROS_MASTER_URI=cls.env["ROS_MASTER_URI"], ROS_HOME=cls.work)
        cls.master = subprocess.Popen(["roscore", "-p", str(port)], env=cls.env, stdout=subprocess.DEVNULL,
                                      stderr=subprocess.DEVNULL)
        wait_for("roscore", rosgraph.Master("/listener").is_online, 30.0, period=0.2)
        rospy.init_node("listener", anonymous=True, disable_signals=True)
        cls.config = load_config(cls.config_path)
        cls.bodies = sorted(cls.config["bodies"])
        cls.order = StampOrder()
        cls.buffer = tf2_ros.Buffer(cache_time=rospy.Duration(30))
        cls.tf_listener = tf2_ros.TransformListener(cls.buffer)
        cls.logs = {ns: open(os.path.join(cls.work, f"{ns}.log"), "w") for ns in INSTANCES}
        cls.launches = {
            ns: subprocess.Popen(["roslaunch", "rigid_body_sim", "sim.launch", f"config:={cls.config_path}",
                                  f"ns:={ns}", f"frame_prefix:={ns}/", "record:=true", f"bag:={cls.bag(ns)}",
                                  f"duration:={DURATION:g}"], env=cls.env, stdout=cls.logs[ns],
                                 stderr=subprocess.STDOUT)
            for ns in INSTANCES
        }

    @classmethod
    def tearDownClass(cls) -> None:
        for launch in cls.launches.values():
            if launch.poll() is None:
                launch.send_signal(signal.SIGINT)
                launch.wait(timeout=30)
        for log in cls.logs.values():
            log.close()
        rospy.signal_shutdown("done")
        cls.master.terminate()
        cls.master.wait(timeout=20)
        shutil.rmtree(cls.work)

    @classmethod
    def bag(cls, ns: str) -> str:
        return os.path.join(cls.work, f"{ns}.bag")

    def launch_log(self, ns: str) -> str:
        with open(os.path.join(self.work, f"{ns}.log")) as log:
            return log.read()[-3000:]

    def frames(self) -> Set[str]:
        return set(self.buffer._getFrameStrings())

    def test_1_live_frames_of_both_instances(self) -> None:
        world = world_value(self.config, "world_frame")
        wanted = {f"{ns}/{body}" for ns in INSTANCES for body in self.bodies}
        wait_for(f"the transforms of {sorted(wanted)}", lambda: wanted <= self.frames(), 60.0)
        for frame in wanted:
            self.buffer.lookup_transform(world, frame, rospy.Time(0), rospy.Duration(1.0))
        unprefixed = {frame for frame in self.frames() if frame != world and "/" not in frame}
        self.assertEqual(unprefixed, set())
        for body in self.bodies:
            fixed = [self.buffer.lookup_transform(world, f"{ns}/{body}_{kind}", rospy.Time(0))
                     for ns in INSTANCES for kind in ("floor", "slope") if f"{ns}/{body}_{kind}" in self.frames()]
            self.assertEqual(len(fixed), 2, f"{body}'s fixed frame in both instances")
            self.assertEqual(fixed[0].transform, fixed[1].transform)
        self.assertFalse(rosgraph.Master("/listener").hasParam("/use_sim_time"))

    def test_2_each_bag_holds_its_own_instance(self) -> None:
        for ns, launch in self.launches.items():
            self.assertEqual(launch.wait(timeout=120), 0, self.launch_log(ns))
        self.assertEqual(self.order.backwards, [])
        for ns in INSTANCES:
            with self.subTest(ns=ns):
                self.check_bag(ns)

    def test_3_playback_in_the_namespace(self) -> None:
        seen: Set[str] = set()
        received: Dict[str, int] = {"/tf": 0, "/tf_static": 0}

        def on_tf(topic: str, msg: TFMessage) -> None:
            received[topic] += 1
            seen.update(t.child_frame_id for t in msg.transforms)

        collect = [rospy.Subscriber(topic, TFMessage, lambda msg, topic=topic: on_tf(topic, msg), queue_size=None)
                   for topic in received]
        # The player starts once every topic has a subscriber: the transforms here, the rest dropped.
        collect += subscribe_to_the_rest(self.bag("a"), received, {"/a/tf": "/tf", "/a/tf_static": "/tf_static"})
        with rosbag.Bag(self.bag("a")) as bag:
            recorded = {"/tf": bag.get_message_count("/a/tf"), "/tf_static": bag.get_message_count("/a/tf_static")}
        try:
            # The player stays past the bag's end until every message has come (keep_alive:=true).
            play_until(self.bag("a"), f"every transform message of the bag ({recorded})", lambda: received == recorded,
                       120.0, self.env, ["ns:=a", "rate:=4"])
        finally:
            for subscriber in collect:
                subscriber.unregister()
        self.assertEqual({frame.split("/")[0] for frame in seen}, {"a"}, sorted(seen))
        self.assertLessEqual({f"a/{body}" for body in self.bodies} | {"a/rod_floor"}, seen)

    def check_bag(self, ns: str) -> None:
        world = world_value(self.config, "world_frame")
        expected = {f"/{ns}/tf", f"/{ns}/tf_static", f"/{ns}/sim/scene", f"/{ns}/sim/markers", f"/{ns}/sim/commands",
                    f"/{ns}/sim/events"}
        expected |= {f"/{ns}/sim/{body}/state" for body in self.bodies}
        topics: Set[str] = set()
        times: Dict[str, List[float]] = {}
        with rosbag.Bag(self.bag(ns)) as bag:
            for topic, msg, _ in bag.read_messages():
                topics.add(topic)
                if topic.endswith("tf") or topic.endswith("tf_static"):
                    for transform in msg.transforms:
                        self.assertEqual(transform.header.frame_id, world)
                        self.assertTrue(transform.child_frame_id.startswith(f"{ns}/"), transform.child_frame_id)
                elif topic.endswith("commands"):
                    continue  # the log of changes, for simulate --replay
                elif topic.endswith("events"):
                    self.assertIn(msg.body, self.bodies, topic)  # its own instance's bodies' events
                elif topic.endswith("markers") or topic.endswith("scene"):
                    for marker in msg.markers:
                        if marker.action == marker.ADD:
                            self.assertIn(marker.header.frame_id.split("/")[0], {world, ns}, marker.header.frame_id)
                else:
                    times.setdefault(str(body_of_state_topic(topic)), []).append(msg.t)
        self.assertEqual(topics, expected)
        for body in self.bodies:
            self.assertEqual(times[body][0], 0.0, body)
            self.assertAlmostEqual(times[body][-1], DURATION, places=9, msg=body)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("config", help="the config both instances run")
    args = parser.parse_args()
    TwoInstances.config_path = args.config
    result = unittest.main(argv=[sys.argv[0], "-v"], exit=False).result
    sys.exit(0 if result.wasSuccessful() else 1)


if __name__ == "__main__":
    main()
