"""Helpers for another package's rostests against rigid_body_sim's node (a .test that includes sim.launch).

They start nothing: the launch starts the node, and these only subscribe to it, call its services and
read its parameters, by the names of the node's interface (docs/DESIGN.md). Every wait has a deadline in
wall seconds; one that passes fails the test (AssertionError, unittest's failure) saying what it saw.

    sim = SimNode()                            # the node sim.launch starts: /sim
    sphere = sim.states("sphere")              # subscribed, and the node's publisher connected
    sim.unpause()                              # sim.launch start_paused:=true held it at t = 0
    state = sphere.wait_for(1.0)               # the first state at t >= 1 s
    phi = sim.body_param("sphere", "incline_angle")
    events = sim.events()                      # what happens, as it happens (~events)
    finished = events.wait_for("finished", "sphere")   # its exact instant: finished.t
    lap_time = value(finished, "lap_time")
"""
import threading
import time
from typing import Any, Callable, Dict, List, Optional

import rospy
import yaml
from dynamic_reconfigure import DynamicReconfigureParameterException
from dynamic_reconfigure.client import Client
from std_srvs.srv import Empty

from rigid_body_sim import description
from rigid_body_sim.sim_tools import state_message
from rigid_body_sim.msg import Event
from rigid_body_sim.srv import GetConfig, GetEvents, Step

DEADLINE = 10.0  # wall seconds of every wait unless told otherwise
STATE_TYPES = {name: state_message(name) for name in description.body_types()}  # a body's `type` -> its state message
# A state's t is a step count over rate: the one meant at t may come out a rounding below it.
T_TOLERANCE = 1e-9


def wait_until(what: str, condition: Callable[[], bool], deadline: float, seen: Callable[[], str]) -> None:
    """Until condition() holds; after `deadline` wall seconds (or at shutdown) fails the test naming `what`
    and what `seen()` says."""
    end = time.monotonic() + deadline
    while not condition():
        if time.monotonic() > end or rospy.is_shutdown():
            raise AssertionError(f"no {what} within {deadline:g} s ({seen()})")
        time.sleep(0.01)


class _Log:
    """Every message of one topic from the subscription on, in the order they came."""

    def __init__(self, topic: str, message: type, deadline: float) -> None:
        self.topic = topic
        self._messages: List[Any] = []
        self._arrived = threading.Condition()
        self._subscriber = rospy.Subscriber(topic, message, self._on_message, queue_size=10000)
        wait_until(f"publisher of {topic} connected", lambda: self._subscriber.get_num_connections() > 0,
                   deadline, lambda: "is the node running?")

    def _on_message(self, message: Any) -> None:
        with self._arrived:
            self._messages.append(message)
            self._arrived.notify_all()

    @property
    def received(self) -> List[Any]:
        with self._arrived:
            return list(self._messages)

    def _first(self, wanted: Callable[[Any], bool], what: str, deadline: float) -> Any:
        """The first message received that is `wanted`; fails the test, saying the last one's t, if none comes
        within `deadline` wall seconds (the simulation ended, died or is paused)."""
        def first() -> Any:
            return next((message for message in self._messages if wanted(message)), None)

        with self._arrived:
            if not self._arrived.wait_for(lambda: first() is not None or rospy.is_shutdown(), deadline) \
                    or first() is None:
                last = f"the last at t = {self._messages[-1].t:.6g} s of {len(self._messages)}" if self._messages \
                    else "none at all"
                raise AssertionError(f"no {what} on {self.topic} within {deadline:g} s ({last}): the simulation "
                                     "ended or died early, or is paused")
            return first()

    def close(self) -> None:
        self._subscriber.unregister()


class States(_Log):
    """Every state of one body from the subscription on, in the order they came."""

    def wait_for(self, t: float, deadline: float = DEADLINE) -> Any:
        """The first state at or after simulated time t; fails the test, saying the last state's t, if none
        comes within `deadline` wall seconds (the simulation ended, died or is paused)."""
        return self._first(lambda state: state.t >= t - T_TOLERANCE, f"state at t >= {t:g} s", deadline)


def value(event: Any, name: str) -> Any:
    """A value an event carries (a finish's lap_time, a rod's end), else its state field of that name: a
    number, or a text (a mode); fails the test if it has neither."""
    for values in (event.values, event.state):
        for item in values:
            if item.name == name:
                return item.text if item.text else item.number
    raise AssertionError(f"event {event.kind} of {event.body} at t = {event.t:.9g} s carries no {name}")


class Events(_Log):
    """Every event of the node (`<node>/events`) from the subscription on, in the order they came. Subscribe
    before the node steps (sim.launch start_paused:=true) to miss none; SimNode.run_events() has those of the
    current run so far."""

    def __init__(self, topic: str, deadline: float) -> None:
        super().__init__(topic, Event, deadline)

    def wait_for(self, kind: str, body: str = "", deadline: float = DEADLINE) -> Any:
        """The first event of `kind` (of `body`, unless empty); fails the test if none comes within `deadline`
        wall seconds."""
        return self._first(lambda event: event.kind == kind and (not body or event.body == body),
                           f"event {kind}" + (f" of {body}" if body else ""), deadline)


class SimNode:
    """The running node `name` (sim.launch's: /sim; with ns:=left, /left/sim)."""

    def __init__(self, name: str = "/sim", deadline: float = DEADLINE) -> None:
        self.name = name.rstrip("/")
        self.deadline = deadline

    # --- its parameters: as the launch loaded them (the config file's keys; not changed by `set`)
    def param(self, key: str) -> Any:
        """A world key of the config (gravity, rate, publish_rate, world_frame) or a node option."""
        return self._param(f"{self.name}/{key}")

    def body_param(self, body: str, key: str) -> Any:
        """A body's key as the config gave it (the parameter server holds `<node>/bodies/<body>/<key>`)."""
        return self._param(f"{self.name}/bodies/{body}/{key}")

    def config(self) -> Dict[str, Any]:
        """The world as it runs now, every key with its value in use (~get_config), as a config file's map."""
        config: Dict[str, Any] = yaml.safe_load(self._call("get_config", GetConfig).yaml)
        return config

    def _param(self, name: str) -> Any:
        if not rospy.has_param(name):
            raise AssertionError(f"no parameter {name}: the config does not give it (its default applies: "
                                 "config() has every key in use)")
        return rospy.get_param(name)

    # --- its topics
    def states(self, body: str, deadline: float = 0.0, message: Optional[type] = None) -> States:
        """A subscription to `body`'s states, waited for until the node's publisher has connected (every
        state it publishes from then on arrives). `message`, RodState or RollerState, by default from the
        body's type on the parameter server (a spawned body is not there: give it)."""
        message = message or STATE_TYPES[self.body_param(body, "type")]
        return States(f"{self.name}/{body}/state", message, deadline or self.deadline)

    def events(self, deadline: float = 0.0) -> Events:
        """A subscription to the node's events (rigid_body_sim/Event), waited for until connected."""
        return Events(f"{self.name}/events", deadline or self.deadline)

    # --- its services
    def run_events(self) -> List[Any]:
        """The events of the current run so far (since the start or the last reset), oldest first."""
        return list(self._call("get_events", GetEvents).events)

    def pause(self) -> None:
        self._call("pause", Empty)

    def unpause(self) -> None:
        self._call("unpause", Empty)

    def reset(self) -> None:
        """Every body back to its initial conditions; simulated time goes on."""
        self._call("reset", Empty)

    def step(self, steps: int) -> float:
        """`steps` physics steps while paused; the simulated time after them. A refusal fails the test."""
        answer = self._call("step", Step, steps)
        if not answer.success:
            raise AssertionError(f"{self.name}/step {steps} refused: {answer.message}")
        return float(answer.t)

    def set(self, body: str, **values: Any) -> Dict[str, Any]:
        """Keys of a body through its reconfigure server, as `dynparam set` does (the one path of every
        change); the values the server shows after. A value the node refused fails the test."""
        server = f"{self.name}/{body}"
        try:
            client = Client(server, timeout=self.deadline)
        except rospy.ROSException as error:
            raise AssertionError(f"{server}: {error}") from error
        try:
            # Its keys' types first, with the deadline (update_configuration would wait for them for ever).
            if client.get_parameter_descriptions(timeout=self.deadline) is None:
                raise AssertionError(f"no parameter descriptions from {server} within {self.deadline:g} s")
            shown: Dict[str, Any] = client.update_configuration(values)
        except DynamicReconfigureParameterException as error:
            raise AssertionError(f"{server}: {error}") from error
        finally:
            client.close()
        refused = {key: shown.get(key) for key, value in values.items() if shown.get(key) != value}
        if refused:
            raise AssertionError(f"{server} refused {values}: it shows {refused} (its WARN line says why)")
        return shown

    def _call(self, service: str, kind: type, *request: Any) -> Any:
        name = f"{self.name}/{service}"
        try:
            rospy.wait_for_service(name, self.deadline)
            return rospy.ServiceProxy(name, kind)(*request)
        except (rospy.ROSException, rospy.ServiceException) as error:
            raise AssertionError(f"{name} did not answer within {self.deadline:g} s: {error}") from error
