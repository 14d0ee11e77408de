#!/usr/bin/env python3
"""The sphere of config/slope.yaml against a closed form: its x at the first state at or after ~t.

The fixture (sim.launch start_paused:=true) waits at t = 0: this test subscribes, calls ~unpause and waits
for the state at ~t, each wait for at most ~deadline wall seconds. ~claim says what it asserts:
  rolling   x = 5/14 g sin(phi) t^2 (a solid sphere rolling without slipping: true for this config)
  sliding   x = 1/2 g sin(phi) t^2  (a block sliding without friction: false)
A simulation that ends (sim.launch duration) or dies before ~t fails the test on its deadline.
"""
import math
import unittest
from typing import Callable, List

import rospy
import rostest
from rigid_body_sim.msg import RollerState
from std_srvs.srv import Empty

PACKAGE = "sim_fixture_example"
ACCELERATION_FACTOR = {"rolling": 5.0 / 7.0, "sliding": 1.0}


class SlopeTest(unittest.TestCase):
    def setUp(self) -> None:
        self.states: List[RollerState] = []
        self.subscriber = rospy.Subscriber("/sim/sphere/state", RollerState, self.states.append, queue_size=1000)

    def wait_for(self, what: str, condition: Callable[[], bool], deadline: float) -> None:
        end = rospy.Time.now().to_sec() + deadline
        while not condition():
            if rospy.Time.now().to_sec() > end or rospy.is_shutdown():
                self.fail(f"no {what} within {deadline} s")
            rospy.sleep(0.01)

    def wait_for_state(self, t: float, deadline: float) -> RollerState:
        """The first state at or after t; fails the test, saying what it saw, if none comes in time."""
        end = rospy.Time.now().to_sec() + deadline
        while rospy.Time.now().to_sec() < end and not rospy.is_shutdown():
            for state in list(self.states):
                if state.t >= t - 1e-9:
                    return state
            rospy.sleep(0.01)
        last = f"the last at t = {self.states[-1].t:.3f} s" if self.states else "none at all"
        self.fail(f"no state at t >= {t} s within {deadline} s ({last}): the simulation ended or died early")

    def test_x_against_closed_form(self) -> None:
        claim = rospy.get_param("~claim")
        t = rospy.get_param("~t", 1.0)
        deadline = rospy.get_param("~deadline", 10.0)
        # start_paused: nothing moves until this test is subscribed and unpauses.
        rospy.wait_for_service("/sim/unpause", deadline)
        self.wait_for("a connection to /sim/sphere/state", lambda: self.subscriber.get_num_connections() > 0,
                      deadline)
        rospy.ServiceProxy("/sim/unpause", Empty)()
        state = self.wait_for_state(t, deadline)
        phi = rospy.get_param("/sim/bodies/sphere/incline_angle")
        g = rospy.get_param("/sim/gravity")
        expected = 0.5 * ACCELERATION_FACTOR[claim] * g * math.sin(phi) * state.t ** 2
        # The node integrates the closed form between events: equal to rounding.
        self.assertAlmostEqual(state.x, expected, delta=1e-9 * max(1.0, abs(expected)),
                               msg=f"{claim}: x({state.t:g} s) = {state.x!r} m, the closed form {expected!r} m")


if __name__ == "__main__":
    rospy.init_node("slope_test")
    rostest.rosrun(PACKAGE, "slope_test", SlopeTest)
