#!/usr/bin/env python3
"""The sphere of config/slope.yaml against a closed form, through the node's events: it rolls from rest,
x = a t^2 / 2 with a = g sin(phi) / (1 + 2/5), so its centre passes the end of its slope at t = sqrt(2 L / a);
the node's `finished` event carries that instant, to rounding. sim.launch start_paused:=true holds the node
at t = 0 until the test, subscribed to ~events, unpauses it."""
import math
import unittest

import rospy
import rostest
from rigid_body_sim.testing import SimNode, value


class FinishTest(unittest.TestCase):
    def test_finish_time_against_closed_form(self) -> None:
        sim = SimNode()
        events = sim.events()  # subscribed before the node moves: no event missed
        sim.unpause()
        finished = events.wait_for("finished", "sphere", deadline=30.0)
        phi, g = sim.body_param("sphere", "incline_angle"), sim.param("gravity")
        length = sim.body_param("sphere", "incline_length")
        expected = math.sqrt(2.0 * length / (g * math.sin(phi) / 1.4))
        self.assertAlmostEqual(finished.t, expected, delta=1e-9, msg=f"finished at {finished.t!r} s")
        self.assertEqual(value(finished, "lap_time"), finished.t)  # its first lap started at t = 0
        self.assertEqual(value(finished, "x"), length)  # the state at that instant: on the line


if __name__ == "__main__":
    rospy.init_node("finish_test")
    rostest.rosrun("sim_fixture_example", "finish_test", FinishTest)
