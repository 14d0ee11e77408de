#!/usr/bin/env python3
"""The Python test helpers another package uses (rigid_body_sim.testing) on sim.launch held at t = 0: each
does what it says, and each failure says what it saw (a wait on a paused node, a refused step or
reconfigure, a parameter the config leaves out). Its C++ twin: test_node_fixture.cpp."""
import unittest

import rospy
import rostest
import yaml
from rigid_body_sim.msg import RollerState
from rigid_body_sim.srv import Spawn
from rigid_body_sim.testing import SimNode


class Fixture(unittest.TestCase):
    def test_every_helper_and_what_its_failures_say(self) -> None:
        with open(rospy.get_param("~config")) as f:
            config = yaml.safe_load(f)
        sim, impatient = SimNode(), SimNode(deadline=0.5)
        rod = sim.states("rod")

        # Parameters as the launch loaded them; a key the config leaves out is named, every key in config().
        self.assertEqual(sim.param("gravity"), config["gravity"])
        self.assertEqual(sim.body_param("rod", "type"), "rod")
        with self.assertRaisesRegex(AssertionError, "no parameter /sim/bodies/rod/substeps"):
            sim.body_param("rod", "substeps")
        self.assertEqual(sim.config()["bodies"]["rod"]["substeps"], "auto")

        # Held at t = 0: a wait for a later state fails on its deadline, saying so.
        with self.assertRaisesRegex(AssertionError, "is paused"):
            rod.wait_for(0.1, deadline=0.5)
        with self.assertRaisesRegex(AssertionError, "refused"):
            impatient.step(0)
        t = sim.step(100)
        self.assertEqual(rod.wait_for(t).t, t)

        # A key through the reconfigure server: taken, or refused saying what the server shows instead.
        self.assertEqual(sim.set("rod", k=2000.0)["k"], 2000.0)
        with self.assertRaisesRegex(AssertionError, r"refused .*it shows \{'k': 2000.0\}"):
            sim.set("rod", k=-5.0)
        with self.assertRaisesRegex(AssertionError, "don't know parameter: stiffness"):
            sim.set("rod", stiffness=1.0)

        # Reset keeps time going; unpause runs on, pause holds.
        sim.reset()
        sim.unpause()
        self.assertGreater(rod.wait_for(t + 0.2).t, t)
        sim.pause()

        # A spawned body is not on the parameter server: its states by the message type given.
        answer = rospy.ServiceProxy("/sim/spawn", Spawn)("hoop", "{type: roller, shape: ring}")
        self.assertTrue(answer.success, answer.message)
        with self.assertRaisesRegex(AssertionError, "no parameter /sim/bodies/hoop/type"):
            sim.states("hoop")
        hoop = sim.states("hoop", message=RollerState)
        t = sim.step(100)
        self.assertEqual(hoop.wait_for(t).t, t)


if __name__ == "__main__":
    rospy.init_node("test_fixture")
    # mypy, given test/, takes the folder test/rostest/ for ROS's rostest module (and an ignore comment is
    # needed by one mypy, unused for another): the function looked up by name
    getattr(rostest, "rosrun")("rigid_body_sim", "test_fixture", Fixture)
