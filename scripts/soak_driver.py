#!/usr/bin/env python3
"""Drives the soak: holds sim_node paused and advances it one simulated second at a time with ~step,
reconfiguring k (rods), mu (rollers) and the initial conditions of every body at random (seeded) at each
whole second, so that a seed replays the same run step for step. Measures the energy drift of each body
between reconfigures, message counts and the node's resident memory; prints a report."""
import argparse
import math
import random
import sys
import threading
import time
from typing import Any, Callable, Dict, List, Optional, Tuple

import rospy
from dynamic_reconfigure.client import Client
from rigid_body_sim.sim_tools import (BlockSpec, BodySpec, RodSpec, RollerSpec, SlopeSpec, body_specs, face_of,
                                      load_config, node_pid, resident_kib, state_message, state_numbers, subscribers,
                                      wait_for, world_value)
from rigid_body_sim.srv import Step


class Body:
    """The received states of one body and its energy drift inside each segment: between two reconfigures,
    and for a body on a slope also between two laps (it restarts where it leaves the slope). A rod's energy
    swings inside a contact (Euler-Cromer); a roller's is conserved while it rolls and only falls while it
    slips, a block's only falls while it slides."""

    def __init__(self, spec: BodySpec, dt: float) -> None:
        self.spec, self.name, self.dt = spec, spec.name, dt
        self.on_slope = isinstance(spec, SlopeSpec)
        self.count = 0
        self.last_t = -1.0
        self.prev: Any = None
        self.ref: Optional[float] = None       # energy at the first sample of the segment
        self.roll_ref: Optional[float] = None  # on a slope: energy at the first sample of the current rolling stretch
        self.max_drift = 0.0                   # J, over all segments
        self.max_rel = 0.0                     # off a slope: drift / energy at the segment's start
        self.max_gain = -math.inf              # on a slope: the largest energy increase over a segment
        self.max_roll = 0.0                    # on a slope: the largest |drift| while rolling
        self.nonfinite = 0

    def new_segment(self) -> None:
        self.ref = self.roll_ref = self.prev = None

    def restarted(self, msg: Any) -> bool:
        """A lap: x moved otherwise than the mean velocity allows between two samples."""
        if not self.on_slope or self.prev is None:
            return False
        return abs(msg.x - self.prev.x - 0.5 * (msg.v + self.prev.v) * self.dt) > 0.01

    def on_state(self, msg: Any) -> None:
        self.count += 1
        self.last_t = msg.t
        if not all(math.isfinite(v) for v in state_numbers(msg)):
            self.nonfinite += 1
            return
        if self.restarted(msg):
            self.ref = self.roll_ref = None
        self.prev = msg
        if self.ref is None:
            self.ref = msg.energy
        drift = msg.energy - self.ref
        self.max_drift = max(self.max_drift, abs(drift))
        if not self.on_slope:
            if self.ref > 0:
                self.max_rel = max(self.max_rel, abs(drift) / self.ref)
            return
        self.max_gain = max(self.max_gain, drift)
        if msg.mode != "rolling":
            self.roll_ref = None
            return
        if self.roll_ref is None:
            self.roll_ref = msg.energy
        self.max_roll = max(self.max_roll, abs(msg.energy - self.roll_ref))


def rod_change(rng: random.Random, spec: RodSpec) -> Dict[str, float]:
    """k and new initial conditions."""
    # On a bounded floor (floor_length > 0) x0 must lie on it: from 0, as far as 2 m.
    x0 = rng.uniform(0, min(2.0, spec.floor_length)) if spec.floor_length > 0 else rng.uniform(-1, 1)
    return {"k": 10 ** rng.uniform(2, 5), "x0": x0, "y0": rng.uniform(0.5, 5),
            "vx0": rng.uniform(-3, 3), "vy0": rng.uniform(-3, 3), "theta0": rng.uniform(0, 2 * math.pi),
            "omega0": rng.uniform(-10, 10)}


def slope_change(rng: random.Random, spec: SlopeSpec) -> Dict[str, float]:
    """mu and a new start on the slope."""
    mu_s = rng.uniform(0, 1)
    return {"mu_s": mu_s, "mu_d": rng.uniform(0, mu_s), "x0": rng.uniform(0, spec.slope / 2), "v0": rng.uniform(-2, 4)}


def roller_change(rng: random.Random, spec: RollerSpec) -> Dict[str, float]:
    """mu, a new start on the slope and a spin."""
    return {**slope_change(rng, spec), "theta0": 0.0, "omega0": rng.uniform(-30, 30)}


# A random, valid reconfigure of one body, by its `type`.
CHANGES: Dict[str, Callable[[random.Random, Any], Dict[str, float]]] = {
    RodSpec.TYPE: rod_change, RollerSpec.TYPE: roller_change, BlockSpec.TYPE: slope_change}


def random_change(rng: random.Random, spec: BodySpec) -> Dict[str, float]:
    return face_of(CHANGES, spec.TYPE, "random change (its row in CHANGES)", "scripts/soak_driver.py")(rng, spec)


class Driver:
    """The node held paused and advanced a second at a time, every body reconfigured before each second."""

    def __init__(self, config_path: str, seed: int, max_speed: float) -> None:
        config = load_config(config_path)
        self.steps = round(float(world_value(config, "rate")))
        self.samples = round(float(world_value(config, "publish_rate")))
        self.bodies = [Body(spec, 1.0 / self.samples) for spec in body_specs(config)]
        self.rng = random.Random(seed)
        self.max_speed = max_speed
        self.lock = threading.Lock()
        self.subscribers = [self.subscribe(body) for body in self.bodies]
        rospy.wait_for_service("/sim/step", timeout=60)
        self.step = rospy.ServiceProxy("/sim/step", Step, persistent=True)
        self.clients = {b.name: Client(f"/sim/{b.name}", timeout=30) for b in self.bodies}
        # start_paused holds the node at t = 0 (its state then went out before anyone could subscribe):
        # the first step waits until this driver and the recorder take every state topic and /tf.
        states = [f"/sim/{b.name}/state" for b in self.bodies]

        def subscribed() -> bool:
            connected = subscribers("/sim", "/soak")
            return (all({"/soak", "/record"} <= connected.get(topic, set()) for topic in states)
                    and "/record" in connected.get("/tf", set()))
        try:
            wait_for("the driver's and the recorder's subscriptions to the states and /tf", subscribed, 60.0,
                     period=0.1)
        except TimeoutError as error:
            sys.exit(f"soak: {error}")

    def subscribe(self, body: Body) -> Any:
        def on_state(msg: Any) -> None:
            with self.lock:
                body.on_state(msg)
        return rospy.Subscriber(f"/sim/{body.name}/state", state_message(body.spec.TYPE), on_state,
                                queue_size=None, tcp_nodelay=True)

    def wait_until_every_body_at(self, t: float) -> None:
        """Until every body's state at t has arrived (a segment's drift is measured before the next change)."""
        def arrived() -> bool:
            with self.lock:
                return all(b.last_t >= t for b in self.bodies)
        wait_for(f"the states of t = {t}", arrived, 60.0, period=0.0005)

    def second(self, second: int, wall0: float) -> None:
        """Reconfigures every body at random, then steps a simulated second."""
        with self.lock:
            for body in self.bodies:
                body.new_segment()
        for body in self.bodies:
            change = random_change(self.rng, body.spec)
            shown = self.clients[body.name].update_configuration(change)
            refused = {key: shown.get(key) for key, value in change.items() if shown.get(key) != value}
            if refused:  # the run would go on unchanged, and no longer be the seed's
                sys.exit(f"soak: the node refused {body.name}'s reconfigure at t = {second}: {change} shows {refused} "
                         "(its WARN line in roslaunch.log says why)")
        # A tenth of a second per ~step call, each time until this driver has the last sample: bursts of
        # 5 samples a topic, well inside the recorder's subscriber queue of 100 messages.
        calls = 10 if self.steps % 10 == 0 and self.samples % 10 == 0 else 1
        for _ in range(calls):
            reply = self.step(self.steps // calls)
            if not reply.success:
                sys.exit(f"soak: ~step refused at t = {second}: {reply.message}")
            self.wait_until_every_body_at(reply.t)
            if self.max_speed > 0:
                time.sleep(max(0.0, wall0 + reply.t / self.max_speed - time.time()))
        if reply.t != second + 1:
            sys.exit(f"soak: the node is at t = {reply.t}, expected {second + 1}: it was not held at t = 0 "
                     "(scripts/soak.launch sets start_paused)")

    def report(self, duration: int, seed: int, wall: float, rss: List[Tuple[int, int, int]]) -> None:
        expected = duration * self.samples  # every sample after t = 0
        print(f"\nsoak: seed {seed}, {duration} simulated s, {len(self.bodies)} bodies, reconfigured every "
              f"simulated second; {wall:.1f} s wall ({duration / wall:.1f} x real time)")
        print(f"RSS sim_node: {rss[0][1]} kB at t = {rss[0][0]} s, {rss[-1][1]} kB at t = {rss[-1][0]} s "
              f"(change {rss[-1][1] - rss[0][1]:+d} kB); recorder {rss[0][2]} -> {rss[-1][2]} kB")
        print("body      type    states received/expected  non-finite  max |dE| in a segment   notes")
        for b in self.bodies:
            note = (f"largest gain {b.max_gain:.3g} J; max |dE| while rolling {b.max_roll:.3g} J" if b.on_slope
                    else f"max |dE|/E0 = {b.max_rel:.3g}")
            print(f"{b.name:9s} {b.spec.TYPE:7s} {b.count:8d}/{expected:<8d}          "
                  f"{b.nonfinite:4d}        {b.max_drift:12.6g} J    {note}")
        bad = [b.name for b in self.bodies if b.count != expected or b.nonfinite]
        if bad:
            sys.exit(f"soak: FAILED for {', '.join(bad)}")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("config")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--duration", type=int, default=3600, help="simulated seconds")
    parser.add_argument("--max-speed", type=float, default=0.0,
                        help="at most this many simulated seconds per wall second (0: as fast as possible)")
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node("soak", disable_signals=True)
    driver = Driver(args.config, args.seed, args.max_speed)
    sim_pid, rec_pid = node_pid("/sim", "/soak"), node_pid("/record", "/soak")
    wall0 = time.time()
    rss = []  # (t, sim_node kB, recorder kB)
    for second in range(args.duration):
        driver.second(second, wall0)
        if second == 0 or (second + 1) % 300 == 0 or second + 1 == args.duration:
            rss.append((second + 1, resident_kib(sim_pid), resident_kib(rec_pid)))
            print(f"t = {second + 1:5d} s  wall {time.time() - wall0:7.1f} s  RSS sim_node {rss[-1][1]} kB, "
                  f"recorder {rss[-1][2]} kB", flush=True)
    driver.report(args.duration, args.seed, time.time() - wall0, rss)
    return 0


if __name__ == "__main__":
    sys.exit(main())
