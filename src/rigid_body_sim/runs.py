"""Runs read back into the arrays `rigid_body_sim.core.World.run` returns: {body: {field: numpy array}}.

    from rigid_body_sim import core, runs
    world = core.World(open("config/rod.yaml").read())
    mine = world.run(10)
    theirs = runs.read_run("out/rod")            # the folder `simulate config/rod.yaml --out-dir out/rod` wrote
    assert (mine["rod"]["y"] == theirs["rod"]["y"]).all()   # bit for bit
    theirs = runs.read_bag("run.bag")            # the states a node (or `simulate --bag`) recorded
    samples, happened = world.run(10, events=True)
    assert happened == runs.read_events("out/rod")   # events.csv: the same instants, bit for bit

A CSV file's numbers are in their shortest round-trip form, so float() gives back the very doubles; a column
with a text (a roller's mode) comes back as str, as World.run and World.sweep return them.
"""
import csv
import glob
import os
from typing import Any, Dict, List

import numpy

Fields = Dict[str, numpy.ndarray]


def column(cells: List[str]) -> numpy.ndarray:
    """A CSV column as float64 (an empty cell, a sweep's roller that never rolled, as nan), or as str if a
    cell is a text."""
    try:
        return numpy.array([float(cell) if cell else numpy.nan for cell in cells], dtype=float)
    except ValueError:
        return numpy.array(cells, dtype=str)


def read_csv(path: str) -> Fields:
    """One body's CSV file (t and its state fields) as {field: array}."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    return {name: column([row[i] for row in body]) for i, name in enumerate(header)}


EVENTS_FILE = "events.csv"


def read_run(folder: str) -> Dict[str, Fields]:
    """Every <body>.csv of a folder `simulate` (or `simulate --replay`) wrote, by body name."""
    paths = sorted(glob.glob(os.path.join(folder, "*.csv")))
    return {os.path.basename(path)[:-len(".csv")]: read_csv(path) for path in paths
            if not os.path.basename(path).startswith("sweep") and os.path.basename(path) != EVENTS_FILE}


def _pairs(cell: str) -> Dict[str, Any]:
    """events.csv's "name=value name=value" cell: numbers as float (bit for bit), texts as str."""
    out: Dict[str, Any] = {}
    for pair in cell.split():
        name, text = pair.split("=", 1)
        try:
            out[name] = float(text)
        except ValueError:
            out[name] = text
    return out


def read_events(folder: str) -> List[Dict[str, Any]]:
    """The events.csv of a folder `simulate` wrote, as the records World.events() and World.run(...,
    events=True) give: {"t", "body", "type", "kind", "values": {...}, "state": {...}}."""
    with open(os.path.join(folder, EVENTS_FILE), newline="") as f:
        rows = list(csv.DictReader(f))
    return [{"t": float(row["t"]), "body": row["body"], "type": row["type"], "kind": row["kind"],
             "values": _pairs(row["values"]), "state": _pairs(row["state"])} for row in rows]


def event_record(message: Any) -> Dict[str, Any]:
    """A rigid_body_sim/Event message as the same record."""
    def values(items: Any) -> Dict[str, Any]:
        return {item.name: item.text if item.text else item.number for item in items}

    return {"t": message.t, "body": message.body, "type": message.type, "kind": message.kind,
            "values": values(message.values), "state": values(message.state)}


def read_bag_events(path: str, namespace: str = "/sim") -> List[Dict[str, Any]]:
    """The events of a bag (`NAMESPACE/events`, from sim_node's recording or `simulate --bag`) as records."""
    import rosbag  # only here: reading CSV needs no ROS

    topic = namespace.rstrip("/") + "/events"
    with rosbag.Bag(path) as bag:
        return [event_record(message) for _, message, _ in bag.read_messages(topics=[topic])]


def read_bag(path: str, namespace: str = "/sim") -> Dict[str, Fields]:
    """The state messages of a bag (`NAMESPACE/<body>/state`, from sim_node's recording or `simulate --bag`)
    as {body: {field: array}}: t, then the message's fields after its header and t, in the CSV's order."""
    import rosbag  # only here: reading CSV needs no ROS

    prefix, suffix = namespace.rstrip("/") + "/", "/state"
    samples: Dict[str, Dict[str, list]] = {}
    with rosbag.Bag(path) as bag:
        for topic, message, _ in bag.read_messages():
            if not (topic.startswith(prefix) and topic.endswith(suffix)) or "/" in topic[len(prefix):-len(suffix)]:
                continue
            fields = samples.setdefault(topic[len(prefix):-len(suffix)], {})
            for name in message.__slots__:
                if name != "header":
                    fields.setdefault(name, []).append(getattr(message, name))
    return {body: {name: numpy.array(values) for name, values in fields.items()} for body, fields in samples.items()}
