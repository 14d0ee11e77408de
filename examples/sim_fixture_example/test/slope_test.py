#!/usr/bin/env python3
"""The sphere of config/slope.yaml against a closed form: its x at the first state at or after ~t (1 s).
~claim: rolling, x = 5/14 g sin(phi) t^2 (a sphere rolling without slipping: true for this config);
sliding, x = 1/2 g sin(phi) t^2 (a block sliding without friction: false). sim.launch start_paused:=true
holds the node at t = 0 until the test, subscribed, unpauses it."""
import math
import unittest

import rospy
import rostest
from rigid_body_sim.testing import SimNode

ACCELERATION_FACTOR = {"rolling": 5.0 / 7.0, "sliding": 1.0}


class SlopeTest(unittest.TestCase):
    def test_x_against_closed_form(self) -> None:
        claim, t = rospy.get_param("~claim"), rospy.get_param("~t", 1.0)
        sim = SimNode()
        sphere = sim.states("sphere")
        sim.unpause()
        state = sphere.wait_for(t)  # fails on its deadline if the simulation ends or dies first
        phi, g = sim.body_param("sphere", "incline_angle"), sim.param("gravity")
        expected = 0.5 * ACCELERATION_FACTOR[claim] * g * math.sin(phi) * state.t ** 2
        # The node integrates the closed form between events: equal to rounding.
        self.assertAlmostEqual(state.x, expected, delta=1e-9 * max(1.0, abs(expected)),
                               msg=f"{claim}: x({state.t:g} s) = {state.x!r} m, the closed form {expected!r} m")


if __name__ == "__main__":
    rospy.init_node("slope_test")
    rostest.rosrun("sim_fixture_example", "slope_test", SlopeTest)
