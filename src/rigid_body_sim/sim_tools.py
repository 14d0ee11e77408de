"""What the Python tools of rigid_body_sim share: a config's values with the documented defaults, each body
type's spec (SPECS, by its `type`: what Python knows of one type and no other), the state messages and the
events of a bag, the events' kinds and roles with lines that say them, the columns of a sweep, and waiting on
processes and ROS masters.

No instant is computed here: when a body started to roll, finished, came to rest or touched its floor is the
core's event (docs/events.md), read from events.csv, a bag's events topic or rigid_body_sim.core.

No list of fields is copied from the C++ here: a CSV file names its columns in its header, a state
message its fields in __slots__, both in the order of include/rigid_body_sim/core/state_fields.h.
The defaults and units of keys are the core's exported description (rigid_body_sim.description, written by
the build): run with the package's setup.bash sourced. test/tools/test_sim_tools.py checks them against
simulate."""
from __future__ import annotations

import math
import random
import socket
import threading
import time
import xmlrpc.client
from dataclasses import dataclass
from typing import Any, Callable, ClassVar, Dict, Iterable, List, Optional, Set, Tuple, Type, TypeVar, Union

import yaml
from rigid_body_sim import description

Config = Dict[str, Any]

# The defaults of the world's and each body type's keys (by its `type`): the core's description.
WORLD_DEFAULTS: Dict[str, Any] = {key["name"]: key["default"] for key in description.load()["world"]}
DEFAULTS: Dict[str, Dict[str, Any]] = {name: description.defaults(name) for name in description.body_types()}
# The units of the number keys by body type, for axis labels ("" for a pure number): the description's.
KEY_UNITS: Dict[str, Dict[str, str]] = {name: description.units(name) for name in description.body_types()}
# A sweep's row gives every body's final state and then what the run adds about it, starting with this
# column (docs/sweeps.md).
FIRST_SWEEP_RESULT = description.load()["energy_drift"]["name"]
# Words and units for the columns a sweep adds, for axis labels (a column not named here is shown by its
# own name, without a unit): the description's.
SWEEP_RESULT_LABELS: Dict[str, Tuple[str, str]] = {
    FIRST_SWEEP_RESULT: (description.load()["energy_drift"]["label"], description.load()["energy_drift"]["unit"]),
    **{t["sweep_column"]: (t["sweep_label"], t["sweep_unit"]) for t in description.body_types().values()}}
# Each type's event kinds, in the order it declares them, with their role ("finish", "restart" or ""): the
# description's. The tools read roles, never a kind's name, to cut a run into laps or mark a finish.
EVENT_ROLES: Dict[str, Dict[str, str]] = {
    name: {kind["name"]: kind["role"] for kind in t["event_kinds"]} for name, t in description.body_types().items()}


# --- configs ------------------------------------------------------------------------------------------
def load_config(path: str) -> Config:
    """A config file as written (defaults are filled in by world_value and body_spec)."""
    with open(path) as f:
        config: Config = yaml.safe_load(f)
    return config


def world_value(config: Config, key: str) -> Any:
    """A world key's value, or its default."""
    return config.get(key, WORLD_DEFAULTS[key])


def steps_per_sample(config: Config) -> int:
    return round(float(world_value(config, "rate")) / float(world_value(config, "publish_rate")))


@dataclass(frozen=True)
class Body:
    """What a body type's spec shares: the type it is the spec of, the body's name, and a body's keys with
    its defaults."""

    TYPE: ClassVar[str]
    name: str

    @classmethod
    def keys(cls, given: Config) -> Config:
        """A body's keys: its config's, its type's defaults where it leaves one out."""
        return {**DEFAULTS[cls.TYPE], **given}


@dataclass(frozen=True)
class RodSpec(Body):
    TYPE: ClassVar[str] = "rod"
    length: float
    mass: float
    k: float
    floor_length: float = 0.0  # m of floor from x = 0; 0: unbounded

    @classmethod
    def of(cls, name: str, given: Config) -> RodSpec:
        rod = cls.keys(given)
        return cls(name, float(rod["length"]), float(rod["mass"]), float(rod["k"]), float(rod["floor_length"]))


@dataclass(frozen=True)
class SlopeSpec(Body):
    """A body on a slope of its own: the slope and the friction on it."""
    angle: float  # incline_angle (rad)
    slope: float  # incline_length (m)
    mu_s: float
    mu_d: float

    @staticmethod
    def slope_of(body: Config) -> Tuple[float, float, float, float]:
        return (float(body["incline_angle"]), float(body["incline_length"]), float(body["mu_s"]),
                float(body["mu_d"]))


@dataclass(frozen=True)
class RollerSpec(SlopeSpec):
    TYPE: ClassVar[str] = "roller"
    # c = I / (M R^2) of the named shapes: what each choice of `shape` sets, in the description.
    INERTIA_FACTORS: ClassVar[Dict[str, float]] = {
        shape: float(sets["inertia_factor"])
        for shape, sets in (description.key("roller", "shape") or {"sets": {}})["sets"].items()
        if "inertia_factor" in sets}
    shape: str  # a named shape, or "custom"
    c: float  # I / (M R^2)
    radius: float
    mass: float

    @classmethod
    def keys(cls, given: Config) -> Config:
        """With its shape (custom when the config gives a c alone) and the c of a named shape (the
        description's default c for a shape without one, which the config loader refuses)."""
        roller = super().keys(given)
        shape = given.get("shape", "custom" if "inertia_factor" in given else roller["shape"])
        c = given.get("inertia_factor", cls.INERTIA_FACTORS.get(shape, roller["inertia_factor"]))
        return {**roller, "shape": shape, "inertia_factor": float(c)}

    @classmethod
    def of(cls, name: str, given: Config) -> RollerSpec:
        roller = cls.keys(given)
        return cls(name, *cls.slope_of(roller), shape=str(roller["shape"]), c=float(roller["inertia_factor"]),
                   radius=float(roller["radius"]), mass=float(roller["mass"]))

    def tan_critical(self) -> float:
        """tan(phi_c) = mu_s (1 + c) / c: the steepest slope on which it can roll without slipping."""
        return self.mu_s * (1 + self.c) / self.c

    def rolls(self) -> bool:
        return math.tan(self.angle) <= self.tan_critical()


@dataclass(frozen=True)
class BlockSpec(SlopeSpec):
    TYPE: ClassVar[str] = "block"
    size: float
    mass: float

    @classmethod
    def of(cls, name: str, given: Config) -> BlockSpec:
        block = cls.keys(given)
        return cls(name, *cls.slope_of(block), size=float(block["size"]), mass=float(block["mass"]))


BodySpec = Union[RodSpec, RollerSpec, BlockSpec]
# Each body type's spec by its `type`: where what Python knows of one type and no other lives.
SPECS: Dict[str, Union[Type[RodSpec], Type[RollerSpec], Type[BlockSpec]]] = {
    RodSpec.TYPE: RodSpec, RollerSpec.TYPE: RollerSpec, BlockSpec.TYPE: BlockSpec}
INERTIA_FACTORS = RollerSpec.INERTIA_FACTORS

Row = TypeVar("Row")


class MissingFace(LookupError):
    """A body type of the description without its row in a table of what the tools know of each type
    (SPECS here, plot_run.TYPES, soak_driver.CHANGES): test/tools/test_type_faces.py fails first."""


def face_of(table: Dict[str, Row], type_name: str, face: str, where: str) -> Row:
    """A body type's row of `table`, or a one-line MissingFace naming the type, the face and its file."""
    if type_name not in table:
        raise MissingFace(f"body type '{type_name}' has no {face} in {where} (it has rows for "
                          f"{', '.join(table)}; docs/DESIGN.md lists every file a type touches)")
    return table[type_name]


def spec_class(type_name: str) -> Union[Type[RodSpec], Type[RollerSpec], Type[BlockSpec]]:
    """The spec of a body type, by its `type`."""
    return face_of(SPECS, type_name, "Python spec (a class with its TYPE in SPECS)", "src/rigid_body_sim/sim_tools.py")


def body_type(config: Config, name: str) -> str:
    """Its `type` (a body without one is refused by the config loader before any run)."""
    return str(config["bodies"][name]["type"])


def with_defaults(body: Config) -> Config:
    """A body's keys (with its `type`), its type's defaults filled in and what its type derives from them (a
    roller's c from its shape)."""
    return spec_class(str(body["type"])).keys(body)


def body_spec(config: Config, name: str) -> BodySpec:
    """One body's values, the documented defaults where the config leaves a key out."""
    return spec_class(body_type(config, name)).of(name, config["bodies"][name])


def state_message(type_name: str) -> Any:
    """A body type's state message: rigid_body_sim/<Type>State (RodState for a rod)."""
    from rigid_body_sim import msg  # only here: a run of CSV files needs no ROS message

    return getattr(msg, type_name.capitalize() + "State")


def body_specs(config: Config) -> List[BodySpec]:
    return [body_spec(config, name) for name in config["bodies"]]


# --- runs ---------------------------------------------------------------------------------------------
def state_fields(msg: Any) -> List[str]:
    """The fields of a state message after its header: t, then the CSV's columns."""
    return [field for field in msg.__slots__ if field != "header"]


def state_numbers(msg: Any) -> List[float]:
    """The numbers of a state message, in its order: t and every float64 field (a roller's mode is text)."""
    return [getattr(msg, field) for field, kind in zip(msg.__slots__, msg._slot_types) if kind == "float64"]


def body_of_state_topic(topic: str) -> Union[str, None]:
    """`rod` for /sim/rod/state (and for /left/sim/rod/state, in a namespace); None for any other topic."""
    parts = topic.strip("/").split("/")
    return parts[-2] if len(parts) >= 3 and parts[-3] == "sim" and parts[-1] == "state" else None


def read_states(bag_path: str) -> Dict[str, List[Any]]:
    """{body: its state messages in the bag's order} from the topics [/<ns>]/sim/<body>/state."""
    import rosbag  # only for bags: a run of CSV files needs no ROS

    states: Dict[str, List[Any]] = {}
    with rosbag.Bag(bag_path) as bag:
        for topic, msg, _ in bag.read_messages():
            body = body_of_state_topic(topic)
            if body is not None:
                states.setdefault(body, []).append(msg)
    return states


# --- events -------------------------------------------------------------------------------------------
Event = Dict[str, Any]  # a record of rigid_body_sim.runs: {"t", "body", "type", "kind", "values", "state"}
LISTED = 12  # instants a kind's line lists; the rest are counted, the last given


def role(event: Event) -> str:
    """The role of an event's kind: "finish", "restart", or "" (also for a type or kind the description lacks)."""
    return EVENT_ROLES.get(str(event["type"]), {}).get(str(event["kind"]), "")


def events_namespace(topics: Iterable[str]) -> str:
    """The namespace of a bag's events topic: /sim for /sim/events, /left/sim for /left/sim/events (a node
    recorded in a namespace); /sim for a bag without one."""
    for topic in topics:
        parts = topic.strip("/").split("/")
        if parts[-2:] == ["sim", "events"]:
            return "/" + "/".join(parts[:-1])
    return "/sim"


def read_bag_events(bag_path: str) -> List[Event]:
    """The events of a bag in its order (runs.read_bag_events of the namespace the bag recorded)."""
    import rosbag  # only for bags: a run of CSV files needs no ROS
    from rigid_body_sim import runs

    with rosbag.Bag(bag_path) as bag:
        topics = list(bag.get_type_and_topic_info().topics)
    return runs.read_bag_events(bag_path, events_namespace(topics))


def number_text(value: Any) -> str:
    """A value as events.csv writes it: a number in its shortest round-trip form (float() gives back the very
    double; a whole number without ".0", such as a place), a text as it is."""
    if isinstance(value, str):
        return value
    number = float(value)
    return str(int(number)) if number.is_integer() and abs(number) < 1e15 else repr(number)


def instant_text(event: Event) -> str:
    """An event's instant with what its kind adds: `1.7491626163026333 (speed=2.08... lap_time=1.74...)`."""
    values = " ".join(f"{name}={number_text(value)}" for name, value in event["values"].items())
    return number_text(event["t"]) + (f" ({values})" if values else "")


def event_lines(events: Iterable[Event]) -> Dict[str, List[str]]:
    """A line per kind of each body (bodies as they first happen, kinds in their type's order): how often, and
    the instants, `slip_to_roll: 2 times, at t = 0.565892621098528, 2.315892621098528 s`; past LISTED of a
    kind, how many more and the last."""
    grouped: Dict[str, Dict[str, List[Event]]] = {}
    for event in events:
        grouped.setdefault(str(event["body"]), {}).setdefault(str(event["kind"]), []).append(event)
    lines: Dict[str, List[str]] = {}
    for body, kinds in grouped.items():
        declared = list(EVENT_ROLES.get(str(next(iter(kinds.values()))[0]["type"]), {}))
        order = sorted(kinds, key=lambda kind: declared.index(kind) if kind in declared else len(declared))
        lines[body] = []
        for kind in order:
            happened = kinds[kind]
            listed = ", ".join(instant_text(event) for event in happened[:LISTED])
            if len(happened) > LISTED:
                listed += f", and {len(happened) - LISTED} more, the last at {number_text(happened[-1]['t'])}"
            often = "once" if len(happened) == 1 else f"{len(happened)} times"
            lines[body].append(f"{kind}: {often}, at t = {listed} s")
    return lines


def subscribe_to_the_rest(bag_path: str, taken: Iterable[str], played_as: Optional[Dict[str, str]] = None) -> List[Any]:
    """Subscriptions (rospy.AnyMsg, the messages dropped) to every topic of a bag but the caller's own
    (`taken`), named as the player publishes them (`played_as`: its remaps): playback.launch plays nothing
    until every topic of the bag has a subscriber (rosbag play --wait-for-subscribers)."""
    import rosbag
    import rospy

    with rosbag.Bag(bag_path) as bag:
        topics = bag.get_type_and_topic_info().topics
    rest = {(played_as or {}).get(topic, topic) for topic in topics} - set(taken)
    return [rospy.Subscriber(topic, rospy.AnyMsg, lambda _: None) for topic in sorted(rest)]


def play_until(bag_path: str, what: str, done: Callable[[], bool], timeout: float, env: Dict[str, str],
               launch_args: Iterable[str] = ()) -> str:
    """playback.launch of a bag without rviz until done() holds, then the launch ended as by Ctrl-C; its output.
    The player stays past the bag's end (keep_alive:=true): one that exits drops what roscpp still queues for
    a subscriber behind it. TimeoutError naming `what`, with roslaunch's output, after `timeout` seconds."""
    import signal
    import subprocess
    import tempfile

    with tempfile.TemporaryFile("w+") as output:  # a file, not a pipe: rosbag play's progress line never blocks
        play = subprocess.Popen(["roslaunch", "rigid_body_sim", "playback.launch", f"bag:={bag_path}", "rviz:=false",
                                 "keep_alive:=true", *launch_args], env=env, stdout=output, stderr=subprocess.STDOUT)
        failure: Optional[TimeoutError] = None
        try:
            wait_for(what, done, timeout)
        except TimeoutError as error:
            failure = error
        play.send_signal(signal.SIGINT)
        play.wait(timeout=60)
        output.seek(0)
        said = output.read()[-3000:]
    if failure:
        raise TimeoutError(f"{failure}; roslaunch said:\n{said}")
    if play.returncode != 0:
        raise RuntimeError(f"playback.launch ended with exit status {play.returncode}:\n{said}")
    return said


# --- sweeps -------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class SweepColumns:
    """A sweep's header: `variant`, the swept BODY.KEYs, `t`, then BODY.FIELD for every body."""
    keys: List[str]  # the swept BODY.KEYs, in the order of the --sweep options
    fields: Dict[str, List[str]]  # body -> its fields, in the header's order

    def results(self, body: str) -> List[str]:
        """The fields the sweep adds after the body's final state."""
        fields = self.fields[body]
        return fields[fields.index(FIRST_SWEEP_RESULT):] if FIRST_SWEEP_RESULT in fields else []


def is_sweep_header(header: List[str]) -> bool:
    return len(header) > 1 and header[0] == "variant" and "t" in header


def sweep_columns(header: List[str]) -> SweepColumns:
    """The swept keys and the bodies' fields of a sweep's header (is_sweep_header must hold)."""
    end_of_keys = header.index("t")
    fields: Dict[str, List[str]] = {}
    for column in header[end_of_keys + 1:]:
        body, _, field = column.partition(".")
        fields.setdefault(body, []).append(field)
    return SweepColumns(header[1:end_of_keys], fields)


def key_unit(config: Config, swept: str) -> str:
    """The unit of a swept BODY.KEY ("" for a pure number or a key this module does not know)."""
    body, _, key = swept.partition(".")
    return KEY_UNITS[body_type(config, body)].get(key, "") if body in config["bodies"] else ""


def labelled(words: str, unit: str) -> str:
    """An axis label: `words (unit)`, or the words alone for a pure number."""
    return f"{words} ({unit})" if unit else words


# --- processes and ROS --------------------------------------------------------------------------------
def wait_for(what: str, predicate: Callable[[], bool], timeout: float, period: float = 0.05,
             slowest: float = 0.0) -> None:
    """Until predicate() holds, asking every `period` seconds; TimeoutError naming `what` after `timeout`
    seconds. With `slowest` > period, the period grows by a second for every 30 s waited up to `slowest`
    (a long wait asks a busy server, such as slurmctld, less and less often)."""
    start = time.monotonic()
    while not predicate():
        waited = time.monotonic() - start
        if waited > timeout:
            raise TimeoutError(f"timed out after {timeout:g} s waiting for {what}")
        time.sleep(max(period, min(slowest, period + waited / 30)))


# free_port's ports: from here up to the kernel's ephemeral range, above ROS's 11311 and the web view's 8080.
FREE_PORTS_FROM = 20000


def free_port() -> int:
    """A TCP port on the loopback that is free now (for a master or a server of one's own), below the kernel's
    ephemeral range (net.ipv4.ip_local_port_range). The kernel hands out ports of that range to every socket
    bound to port 0 (each node's XML-RPC and TCPROS servers) and to every connection's local end: a port of it
    taken between this answer and the caller's bind (roslaunch -p starts its master a second or two later)
    left `roslaunch -p` talking to another node's server as its master (a node answers getPid too), the
    launch hanging. Below that range only another caller of this function competes; each draws at random."""
    with open("/proc/sys/net/ipv4/ip_local_port_range") as f:
        ephemeral_from = int(f.read().split()[0])
    candidates = list(range(FREE_PORTS_FROM, ephemeral_from))
    random.SystemRandom().shuffle(candidates)
    for port in candidates + [0]:  # 0: the kernel's choice, should every port below its range be taken
        with socket.socket() as s:
            try:
                s.bind(("127.0.0.1", port))
            except OSError:
                continue
            chosen: int = s.getsockname()[1]
            return chosen
    raise OSError("no free TCP port on the loopback")


def node_pid(node: str, caller: str) -> int:
    """The process id of a running ROS node, from its own XML-RPC server."""
    import rosgraph

    uri = rosgraph.Master(caller).lookupNode(node)
    reply: Any = xmlrpc.client.ServerProxy(uri).getPid(caller)  # (code, message, pid)
    return int(reply[2])


def subscribers(node: str, caller: str) -> Dict[str, Set[str]]:
    """{topic: the subscribers connected to it} of the topics a running ROS node publishes, from the node's
    own bus information (the master forgets an unsubscription at once; the node, once the connection has
    closed)."""
    import rosgraph

    uri = rosgraph.Master(caller).lookupNode(node)
    reply: Any = xmlrpc.client.ServerProxy(uri).getBusInfo(caller)  # (code, message, connections)
    connected: Dict[str, Set[str]] = {}
    for connection in reply[2]:  # [id, destination, direction, transport, topic, connected, ...]
        if connection[2] == "o":
            connected.setdefault(connection[4], set()).add(connection[1])
    return connected


def resident_kib(pid: int) -> int:
    """Resident memory of a process (kB), -1 when it has none to report."""
    with open(f"/proc/{pid}/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return -1


def rospy_on_python39() -> None:
    """Debian 11's rospy (1.15.9) still calls Thread.isAlive, which Python 3.9 removed: rospy.signal_shutdown and a
    second shutdown thread raise AttributeError there. Gives the old name back (no effect elsewhere)."""
    if not hasattr(threading.Thread, "isAlive"):
        setattr(threading.Thread, "isAlive", threading.Thread.is_alive)
