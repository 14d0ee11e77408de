#!/usr/bin/env python3
"""rviz, for real: starts sim_node and rviz (launch/sim.launch with rviz/sim.rviz, or --launch rod.launch,
incline.launch with their own views) on this X display, steps the simulation a few simulated seconds, takes a
screenshot (ImageMagick's import) and checks the picture against what the node published: the floor, every
slope, every roller and the rod must show their colours where rviz's camera puts them, each body must measure
at least MIN_BODY_PX across (a rod MIN_ROD_PX along), each text's ink as high as its projected size says and
clear of the others, the view's rules (view_rules.py) must hold, and rviz must report no error. With
--change BODY.KEY=VALUE (a look: a slope's angle or length, a radius, a rod's length), set through the body's
reconfigure server while paused before the picture, the picture must show the new look and nothing of a
changed slope where it was.

Run under Xvfb (test/pictures/rviz_screenshot.sh does). Exit 0 when every check passes, 1 otherwise.
Writes OUT (the screenshot), OUT's stem + "_regions.png" (the regions checked, outlined) and
OUT's stem + ".txt" (the findings)."""
import argparse
import math
import os
import re
import subprocess
import sys
import time
import xmlrpc.client
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np
import yaml
from rigid_body_sim.sim_tools import (Config, RodSpec, RollerSpec, body_spec, free_port, load_config,
                                      rospy_on_python39, wait_for, world_value)

import picture_check as pc
import view_rules as rules
from picture_check import Finding, Pixel
from rviz_log import output_tails, rviz_error_lines

HERE = os.path.dirname(os.path.abspath(__file__))
PACKAGE = os.path.dirname(os.path.dirname(HERE))

STATUS_COLOURS = {"error": (178, 23, 46), "warn": (192, 128, 0)}  # rviz's StatusProperty text colours
# What a class must see from the back row at 1600x900: bodies this many pixels across, a rod this long (the
# texts' size: view_rules.MIN_TEXT_PX).
MIN_BODY_PX = rules.MIN_BODY_PX
MIN_ROD_PX = 150
# ... but in the demo's view, which holds both problems at once (the rod beside four lanes far enough apart
# for their names and boards): there the rod's own saved view, rod.launch's and the lesson's show it at 150.
MIN_ROD_PX_BY_VIEW = {"sim.rviz": 100}
SETTLED_S = 2.0  # the 3-D view unchanged this long: rviz has drawn everything it was sent
MARKER_RATE = 10.0  # Hz: the node's default marker_rate, at which the labels are sent
# The config and rviz view each launch file runs with its defaults (the wrappers take no config argument).
LAUNCH_CONFIGS = {"sim.launch": ("demo.yaml", "sim.rviz"), "rod.launch": ("rod.yaml", "rod.rviz"),
                  "incline.launch": ("incline.yaml", "incline.rviz"),
                  "lesson.launch": ("race_below.yaml", "lesson_race.rviz"),
                  "lesson.launch part:=above": ("race_above.yaml", "lesson_above.rviz"),
                  "lesson.launch part:=block": ("race_block.yaml", "lesson_race.rviz"),
                  "lesson.launch part:=rod": ("rod.yaml", "lesson_rod.rviz")}
Outline = Tuple[str, Any]
Disc = Tuple[np.ndarray, Any, float]  # mask, centre pixel, radius in pixels


def subscribed(master: Any, subscriber: str, topics: Sequence[str]) -> Callable[[], bool]:
    """Whether the node /sim has `subscriber` connected on every one of `topics`, in the node's own view of
    its connections: a subscription is made in the background, and what the node publishes before it is
    connected never arrives there."""
    def check() -> bool:
        try:
            reply: Any = xmlrpc.client.ServerProxy(master.lookupNode("/sim")).getBusInfo("/rviz_screenshot")
            info = reply[2]
        except Exception:
            return False
        return {(c[1], c[4]) for c in info if c[2] == "o"} >= {(subscriber, topic) for topic in topics}
    return check


def wait_while_running(what: str, predicate: Callable[[], bool], timeout: float, launch: Any,
                       period: float = 0.25) -> None:
    """Until predicate() holds; an error at the timeout, or at once if roslaunch has ended."""
    def ready() -> bool:
        if predicate():
            return True
        if launch.poll() is not None:
            raise RuntimeError(f"roslaunch ended (status {launch.returncode}) while waiting for {what}: see its log")
        return False
    wait_for(what, ready, timeout, period)


class Scene(rules.PublishedScene):
    """What the node published, as it comes: world poses of every frame, markers by (ns, id), latest states."""

    def __init__(self, rospy: Any, config: Config) -> None:
        from rigid_body_sim.testing import STATE_TYPES
        from tf2_msgs.msg import TFMessage
        from visualization_msgs.msg import MarkerArray
        super().__init__()
        self.scene_messages = 0  # how many ~scene and /tf_static messages came
        self.static_messages = 0
        self.t: Optional[float] = None  # of the latest state of the first body
        self.state_stamp: Any = None  # of that state, and of the latest transform on /tf
        self.tf_stamp: Any = None
        self.states: Dict[str, Any] = {}  # every body's latest state
        self.names = list(config["bodies"])
        self.first = self.names[0]
        self.subscribers = [
            rospy.Subscriber("/tf", TFMessage, self.on_moving_tf, queue_size=100),
            rospy.Subscriber("/tf_static", TFMessage, self.on_static_tf, queue_size=100),
            rospy.Subscriber("/sim/scene", MarkerArray, self.on_markers, "/sim/scene", queue_size=10),
            rospy.Subscriber("/sim/markers", MarkerArray, self.on_markers, "/sim/markers", queue_size=100)]
        for name, body in config["bodies"].items():
            self.subscribers.append(rospy.Subscriber(
                f"/sim/{name}/state", STATE_TYPES[body["type"]],
                lambda msg, name=name: self.on_state(name, msg), queue_size=100))

    def on_state(self, name: str, msg: Any) -> None:
        self.states[name] = msg
        if name == self.first:
            self.t, self.state_stamp = msg.t, msg.header.stamp

    def on_moving_tf(self, msg: Any) -> None:
        self.on_tf(msg)
        self.tf_stamp = max(t.header.stamp for t in msg.transforms) if msg.transforms else self.tf_stamp

    def all_at(self, t: float) -> bool:
        """Every body's state at t has come, and the transforms of that instant."""
        return (all(self.states.get(name) is not None and self.states[name].t == t for name in self.names)
                and self.tf_stamp == self.state_stamp)

    def labels_at(self, stamp: Any) -> bool:
        """Every body's label has come with this stamp (the changes of a marker instant)."""
        stamps = {m.text.split(":")[0]: m.header.stamp for (ns, _), m in self.by_topic["/sim/markers"].items()
                  if ns == "label"}
        return set(stamps) >= set(self.names) and all(s == stamp for s in stamps.values())

    def held(self) -> str:
        """What came last, for a wait that timed out: each body's t, the stamps of the state and of /tf."""
        ts = ", ".join(f"{name} {self.states[name].t if name in self.states else None}" for name in self.names)
        return f"states at t: {ts}; state stamp {self.state_stamp}, /tf stamp {self.tf_stamp}"

    def rollers_high(self, rollers: Sequence[RollerSpec]) -> bool:
        """No roller on the lowest fifth of its slope: there, in sim.rviz's view, the long slope passes in
        front of the short ones and may hide it."""
        return all(name in self.states and self.states[name].x <= 0.8 * slope
                   for name, slope in ((r.name, r.slope) for r in rollers))

    def on_static_tf(self, msg: Any) -> None:
        self.on_tf(msg)
        self.static_messages += 1

    def on_markers(self, msg: Any, topic: str) -> None:
        super().on_markers(msg, topic)
        self.scene_messages += topic == "/sim/scene"


def displays_dock_height(window: Dict[str, Any]) -> int:
    """The height of the Displays dock (the display tree) in a view's Window Geometry: Qt's saveState holds
    each dock by its name (UTF-16), a visibility byte, then its position and size along the dock area."""
    state = bytes.fromhex(window["QMainWindow State"])
    name = "Displays".encode("utf-16-be")
    at = state.index(name) + len(name) + 1
    return int.from_bytes(state[at + 4:at + 8], "big")


def rviz_status_pixels(image: np.ndarray, render: Tuple[int, int, int, int], tree_height: int) -> Dict[str, int]:
    """Pixels in the text of rviz's display tree (left of the render view, in the Displays dock: the
    panel under it draws its own colours, a chart's lines among them) drawn in the colour of a warning or
    an error: rviz paints a display's name so when its status is not Ok."""
    left, top, _, _ = render
    panel = image[top:top + tree_height, 42:max(43, left - 20), :3].astype(int)
    return {name: int((np.abs(panel - colour).max(axis=-1) <= 24).sum()) for name, colour in STATUS_COLOURS.items()}


def render_window() -> Tuple[int, int, int, int]:
    """(left, top, width, height) of rviz's 3-D view: the largest unnamed X window (Ogre's)."""
    tree = subprocess.run(["xwininfo", "-root", "-tree"], capture_output=True, text=True, check=True).stdout
    best: Optional[Tuple[int, int, int, int]] = None
    for m in re.finditer(r"\(has no name\): \(\)\s+(\d+)x(\d+)\+-?\d+\+-?\d+\s+\+(-?\d+)\+(-?\d+)", tree):
        w, h, x, y = map(int, m.groups())
        if best is None or w * h > best[2] * best[3]:
            best = (x, y, w, h)
    if best is None or best[2] * best[3] < 10000:
        raise RuntimeError("rviz's render window not found in xwininfo -root -tree")
    return best


class Checker:
    """The checks of one picture. Regions are projected from the published scene and clipped to the
    3-D view; `findings` collects the results, `outlines` the regions (for rviz_regions.png)."""

    def __init__(self, image: np.ndarray, scene: Scene, camera: pc.Camera) -> None:
        self.image, self.scene, self.camera = image, scene, camera
        self.shape: Tuple[int, int] = (image.shape[0], image.shape[1])
        self.view = np.zeros(self.shape, dtype=bool)
        self.view[camera.top:camera.top + camera.height, camera.left:camera.left + camera.width] = True
        self.findings: List[Finding] = []
        self.outlines: List[Outline] = []
        self.text_heights: Dict[str, float] = {}  # each text's projected height (pixels, all its lines)

    def hull_of(self, corners: np.ndarray) -> Optional[List[Pixel]]:
        pixels, depth = self.camera.project(corners)
        return pc.convex_hull(pixels) if (depth > 0).all() else None

    def labels(self) -> np.ndarray:
        """Pixels the bodies' labels and boards may cover (white text in front of whatever is behind): a box
        around each text's projected centre, as wide as its text in glyphs of about its height, with a margin."""
        covered = np.zeros(self.shape, dtype=bool)
        for (ns, _), m in self.scene.markers.items():
            if ns not in rules.TEXT_KINDS:
                continue
            _, centre = self.scene.world_pose(m.header.frame_id, m.pose)
            (pixel,), (depth,) = self.camera.project(centre)
            if depth <= 0:
                continue
            height = m.scale.z * self.camera.pixels_per_metre_at(depth)
            lines = m.text.split("\n")
            half_w, half_h = 0.5 * (0.7 * max(map(len, lines)) + 1) * height, height * len(lines)
            col, row = pixel
            covered |= pc.polygon_mask(self.shape, [(col - half_w, row - half_h), (col + half_w, row - half_h),
                                                    (col + half_w, row + half_h), (col - half_w, row + half_h)])
        return covered

    def label_boxes(self) -> Dict[str, Optional[Tuple[int, int, int, int]]]:
        """{"<body>'s label" or "<body>'s board": ink box (top, left, bottom, right)} of each text's white
        pixels, searched in a box around its projected centre a little larger than its text: 1.6 text heights
        high, so that the ink of a text a line and a half above or below is not taken for its own."""
        white = pc.white_mask(self.image) & self.view
        found: Dict[str, Optional[Tuple[int, int, int, int]]] = {}
        for (ns, _), m in sorted(self.scene.markers.items()):
            if ns not in rules.TEXT_KINDS:
                continue
            _, centre = self.scene.world_pose(m.header.frame_id, m.pose)
            (pixel,), (depth,) = self.camera.project(centre)
            height = m.scale.z * self.camera.pixels_per_metre_at(depth) if depth > 0 else 0.0
            lines = m.text.split("\n")
            half_w, half_h = 0.5 * (0.7 * max(map(len, lines)) + 1) * height, (0.5 * len(lines) + 0.3) * height
            col, row = pixel
            region = pc.polygon_mask(self.shape, [(col - half_w, row - half_h), (col + half_w, row - half_h),
                                                  (col + half_w, row + half_h), (col - half_w, row + half_h)])
            what = rules.text_name(ns, m)
            found[what] = pc.ink_box(white, region)
            self.text_heights[what] = height * len(lines)
            self.outlines.append(("box", found[what]))
        return found

    def label_sizes(self) -> None:
        """Each label's and board's ink at least rules.INK_SHARE of the height its lines are drawn at (rviz drew
        it as large as the geometry says, which view_rules holds to rules.MIN_TEXT_PX a line), and no two
        texts' ink boxes touching."""
        boxes = self.label_boxes()
        for name, box in boxes.items():
            height = 0 if box is None else box[2] - box[0] + 1
            needed = math.ceil(rules.INK_SHARE * self.text_heights[name])
            self.findings.append(Measure(f"{name}: ink height", "white", 1, height, needed))
        named = [(name, box) for name, box in boxes.items() if box is not None]
        for i, (a, box_a) in enumerate(named):
            for b, box_b in named[i + 1:]:
                self.findings.append(flag(f"ink of {a} and {b} apart", not pc.boxes_overlap(box_a, box_b)))

    def roller_size(self, name: str, shape_name: str, disc: Optional[Disc]) -> None:
        """Pixels across: the extent of the body's colour in its projected disc (2 px margin)."""
        if disc is None:
            return
        mask, centre, radius = disc
        region = self.in_view(name, pc.disc_mask(self.shape, centre, radius + 2.0))
        box = pc.ink_box(pc.colour_mask(self.image, pc.SHAPE_CLASS[shape_name]), region)
        across = 0 if box is None else max(box[2] - box[0], box[3] - box[1]) + 1
        self.findings.append(Measure(f"{name}: across", pc.SHAPE_CLASS[shape_name], int(region.sum()), across,
                                     MIN_BODY_PX))

    def rod_size(self, name: str, length: float, min_px: int) -> None:
        """Pixels along: the extent of blue along the rod's projected segment (3 px either side)."""
        ends = self.rod_ends(name, length)
        if ends is None:
            return
        a, b = ends
        region = self.in_view(f"{name} along", pc.segment_mask(self.shape, a, b, 3.0))
        along = pc.extent_along(pc.colour_mask(self.image, "blue") & region, a, b)
        self.findings.append(Measure(f"{name}: along", "blue", int(region.sum()), int(along), min_px))

    def rod_ends(self, name: str, length: float) -> Optional[Tuple[np.ndarray, np.ndarray]]:
        """The projected ends of the rod's part above the floor (an end in the floor's spring is hidden)."""
        rotation, centre = self.scene.frames[name]
        half = 0.5 * length * rotation[:, 0]
        low, high = sorted([centre - half, centre + half], key=lambda end: end[2])
        if high[2] <= 0.0:
            return None
        if low[2] < 0.0:
            low = low + (high - low) * (-low[2] / (high[2] - low[2]))
        (a, b), _ = self.camera.project(np.array([low, high]))
        return a, b

    def count_unlabelled(self, region: np.ndarray, labels: np.ndarray, colour: str, what: str, share: float) -> Finding:
        """pc.count on the region less what the labels may cover; a region mostly under a label cannot show
        its colour and is not counted (a finding that says so)."""
        shown = region & ~labels
        if shown.sum() < region.sum() / 3:
            return flag(f"{what}: mostly under a label, not counted", True)
        return pc.count(self.image, shown, colour, what, share)

    def in_view(self, what: str, region: np.ndarray) -> np.ndarray:
        """The region clipped to the view; a finding when a tenth of it or more lies outside."""
        total, inside = int(region.sum()), int((region & self.view).sum())
        if inside < 0.9 * max(1, total):
            self.findings.append(pc.Finding(what + " inside the view", "-", total, inside, int(np.ceil(0.9 * total))))
        return region & self.view

    def slopes(self) -> Dict[str, Tuple[np.ndarray, np.ndarray]]:
        """{roller: (mask of the whole slope box, mask of its top face)}."""
        found = {}
        for (ns, _), m in self.scene.markers.items():
            if ns != "slope":
                continue
            rotation, centre = self.scene.world_pose(m.header.frame_id, m.pose)
            size = np.array([m.scale.x, m.scale.y, m.scale.z])
            # The lit face is the top one (the slope frame's +y): the sides are in the shade.
            top = self.hull_of(pc.box_corners(rotation, centre + 0.5 * size[1] * rotation[:, 1], size * [1, 0, 1]))
            box = self.hull_of(pc.box_corners(rotation, centre, size))
            found[m.header.frame_id[:-len("_slope")]] = (pc.polygon_mask(self.shape, box),
                                                         pc.polygon_mask(self.shape, top))
            self.outlines.append(("brown", top))
        return found

    def discs(self, rollers: Sequence[RollerSpec]) -> Dict[str, Disc]:
        """{roller: (disc mask, centre pixel, radius in pixels)} at each roller's last published pose."""
        found = {}
        for roller in rollers:
            name = roller.name
            if name not in self.scene.frames:
                continue
            (pixel,), (depth,) = self.camera.project(self.scene.frames[name][1])
            radius = roller.radius * self.camera.pixels_per_metre_at(depth)
            found[name] = (pc.disc_mask(self.shape, pixel, radius + 1.0), pixel, radius)
            self.outlines.append(("circle", (pixel, radius + 1.0)))
        return found

    def floor(self, covered: np.ndarray) -> None:
        """Every floor marker (the world's, a rod's bounded one, a rod's ground) that shows in the view, grey."""
        region = np.zeros(self.shape, dtype=bool)
        for (ns, _), m in self.scene.markers.items():
            if ns != "floor":
                continue
            rotation, centre = self.scene.world_pose(m.header.frame_id, m.pose)
            hull = self.hull_of(pc.box_corners(rotation, centre, [m.scale.x, m.scale.y, m.scale.z]))
            self.outlines.append(("grey", hull))
            region |= pc.polygon_mask(self.shape, hull)
        if ("floor", 0) not in self.scene.markers:
            self.findings.append(flag("floor marker received", False))
        region &= self.view & ~covered  # it runs out of the view: fine
        self.findings.append(pc.count(self.image, region, "grey", "floor", 0.6))

    def floor_under(self, name: str, covered: np.ndarray) -> None:
        """Grey on the floor under the rod: a metre either side of its x (the view may look past its foot when it
        is high), half a metre either side of its plane, less what the rod and the labels may cover."""
        if name not in self.scene.frames:
            return
        x, y, _ = self.scene.frames[name][1]
        corners = np.array([[x + dx, y + dy, 0.0] for dx in (-1.0, 1.0) for dy in (-0.5, 0.5)])
        hull = self.hull_of(corners)
        self.outlines.append(("grey", hull))
        region = pc.polygon_mask(self.shape, hull) & self.view & ~covered
        self.findings.append(pc.count(self.image, region, "floor", f"floor under {name}", 0.6))
        self.findings.append(pc.Finding(f"floor under {name} in the view", "-", 1, int(region.sum()), 400))

    def slope(self, name: str, slopes: Dict[str, Tuple[np.ndarray, np.ndarray]], covered: np.ndarray) -> None:
        """The top of a roller's slope, less what other slopes and the bodies may hide, brown."""
        if name not in slopes:
            self.findings.append(flag(f"{name}'s slope marker received", False))
            return
        own = self.in_view(f"{name}'s slope", slopes[name][1]) & ~covered
        for other, (box, _) in slopes.items():
            if other != name:
                own &= ~box
        self.findings.append(pc.count(self.image, own, "brown", f"{name}'s slope (top, unshared)", 0.5))

    def roller(self, name: str, shape_name: str, disc: Optional[Disc], labels: np.ndarray) -> None:
        if disc is None:
            self.findings.append(flag(f"{name}'s pose received", False))
            return
        mask, centre, radius = disc
        colour = pc.SHAPE_CLASS[shape_name]
        found = self.count_unlabelled(self.in_view(name, mask), labels, colour, f"{name} ({shape_name})", 0.35)
        # A ring is a line 0.15 R wide: most of its circumference, not a share of the disc.
        if shape_name == "ring" and found.colour != "-":
            found.needed_px = int(0.4 * 2 * np.pi * radius)
        self.findings.append(found)
        # A body, not a trail or a TF axis through its centre: its colour all round the centre.
        quarters = pc.quadrants_with(self.image, mask, centre, colour)
        self.findings.append(pc.Finding(f"{name}: quadrants with colour", "-", 4, quarters, 3))

    def in_front_of(self, name: str, discs: Dict[str, Disc]) -> np.ndarray:
        """Pixels of the other rollers' discs nearer the camera than this one's centre: they may hide it (rollers
        side by side in neighbouring lanes)."""
        hidden = np.zeros(self.shape, dtype=bool)
        if name not in self.scene.frames:
            return hidden
        _, (depth,) = self.camera.project(self.scene.frames[name][1])
        for other, (mask, _, _) in discs.items():
            if other != name and self.camera.project(self.scene.frames[other][1])[1][0] < depth:
                hidden |= mask
        return hidden

    def rod(self, name: str, length: float, labels: np.ndarray) -> None:
        """Blue along the rod's length above the floor (each quarter, less what the labels may cover), not
        only somewhere near its centre. An end pressed into the floor's spring is below its surface, hidden."""
        if name not in self.scene.frames:
            self.findings.append(flag(f"{name}'s pose received", False))
            return
        ends = self.rod_ends(name, length)
        if ends is None:
            self.findings.append(flag(f"{name}: below the floor, not counted", True))
            return
        a, b = ends
        self.outlines.append(("segment", (a, b)))
        for k in range(4):
            p, q = a + (b - a) * k / 4, a + (b - a) * (k + 1) / 4
            region = self.in_view(f"{name} quarter {k + 1}", pc.segment_mask(self.shape, p, q, 3.0))
            what = f"{name} (rod), quarter {k + 1}"
            self.findings.append(self.count_unlabelled(region, labels, "blue", what, 0.25))


def check_picture(image: np.ndarray, scene: Scene, camera: pc.Camera, config: Config,
                  min_rod_px: int = MIN_ROD_PX) -> Tuple[List[Finding], List[Outline]]:
    """Every finding (floor, each slope, each roller, each rod) and the outlines of the regions."""
    checker = Checker(image, scene, camera)
    specs = [body_spec(config, name) for name in config["bodies"]]
    slopes = checker.slopes()
    discs = checker.discs([spec for spec in specs if isinstance(spec, RollerSpec)])
    covered = np.zeros(image.shape[:2], dtype=bool)
    for mask in [box for box, _ in slopes.values()] + [disc[0] for disc in discs.values()]:
        covered |= mask
    checker.floor(covered)
    bodies_only = np.zeros_like(covered)
    for disc in discs.values():
        bodies_only |= disc[0]
    labels = checker.labels()
    for spec in specs:
        if isinstance(spec, RodSpec):
            checker.rod(spec.name, spec.length, labels)
            checker.rod_size(spec.name, spec.length, min_rod_px)
            ends = checker.rod_ends(spec.name, spec.length)
            rod_line = pc.segment_mask(checker.shape, *ends, 6.0) if ends else np.zeros_like(covered)
            checker.floor_under(spec.name, labels | rod_line)
        elif isinstance(spec, RollerSpec):
            checker.slope(spec.name, slopes, bodies_only)
            checker.roller(spec.name, spec.shape, discs.get(spec.name), labels | checker.in_front_of(spec.name, discs))
            checker.roller_size(spec.name, spec.shape, discs.get(spec.name))
    checker.label_sizes()
    return checker.findings, checker.outlines


def save_outlined(image: np.ndarray, outlines: List[Outline], path: str) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Circle, Polygon
    h, w = image.shape[:2]
    fig = plt.figure(figsize=(w / 100, h / 100), dpi=100)
    ax = fig.add_axes((0, 0, 1, 1))  # a tuple: matplotlib 3.8+'s stubs take no list
    ax.imshow(image)
    ax.set_axis_off()
    ax.set_autoscale_on(False)
    for kind, shape in outlines:
        if kind == "circle":
            ax.add_patch(Circle(shape[0], shape[1], fill=False, color="cyan", lw=0.8))
        elif kind == "segment":
            ax.plot(*np.transpose(shape), color="cyan", lw=0.8)
        elif kind == "box":
            if shape is not None:
                top, left, bottom, right = shape
                ax.add_patch(Polygon([(left, top), (right, top), (right, bottom), (left, bottom)], closed=True,
                                     fill=False, color="magenta", lw=0.8))
        elif shape is not None:
            ax.add_patch(Polygon(shape, closed=True, fill=False, color="cyan" if kind == "brown" else "yellow", lw=0.8))
    fig.savefig(path)
    plt.close(fig)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--launch", default="sim.launch", choices=sorted(LAUNCH_CONFIGS),
                        help="the launch file (and its arguments), started with rviz:=true; its view is its own")
    parser.add_argument("--config", help="sim.launch's config (default: config/demo.yaml)")
    parser.add_argument("--out", required=True, help="the screenshot (PNG)")
    parser.add_argument("--settle", type=float, default=1.0, help="simulated seconds before the picture")
    parser.add_argument("--moments", help="pictures at these simulated seconds after a reset (comma-separated, "
                        "increasing; the changes at the first): in place of --settle")
    parser.add_argument("--timeout", type=float, default=150.0, help="wall seconds for everything")
    parser.add_argument("--change", action="append", default=[], metavar="BODY.KEY=VALUE",
                        help="set before the picture, while paused (repeat for more)")
    args = parser.parse_args()
    start = time.monotonic()
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    stem = os.path.splitext(args.out)[0]

    port = free_port()
    os.environ["ROS_MASTER_URI"] = f"http://127.0.0.1:{port}"
    log = open(stem + "_roslaunch.log", "w")
    if args.config and args.launch != "sim.launch":
        parser.error("--config is sim.launch's: the other launch files run their own")
    config_arg = [f"config:={args.config}"] if args.config else []
    args.config = args.config or os.path.join(PACKAGE, "config", LAUNCH_CONFIGS[args.launch][0])
    launch = subprocess.Popen(["roslaunch", "-p", str(port), "rigid_body_sim"] + args.launch.split() + ["rviz:=true"] +
                              config_arg,
                              stdout=log, stderr=subprocess.STDOUT)
    try:
        return run(args, start, stem, launch)
    except (TimeoutError, RuntimeError):
        log.flush()
        print(output_tails(log.name), file=sys.stderr)
        raise
    finally:
        launch.send_signal(2)  # SIGINT: roslaunch stops its nodes
        try:
            launch.wait(timeout=20)
        except subprocess.TimeoutExpired:
            launch.kill()
        log.close()


def run(args: argparse.Namespace, start: float, stem: str, launch: Any) -> int:
    import rosgraph
    import rospy
    rospy_on_python39()
    from rosgraph_msgs.msg import Log
    from std_srvs.srv import Empty
    from rigid_body_sim.srv import Step

    def left() -> float:
        return max(1.0, args.timeout - (time.monotonic() - start))

    config = load_config(args.config)
    master = rosgraph.Master("/rviz_screenshot")
    wait_while_running("the ROS master", master.is_online, left(), launch)
    rospy.init_node("rviz_screenshot", disable_signals=True)
    scene = Scene(rospy, config)
    rviz_errors: List[str] = []
    rospy.Subscriber("/rosout_agg", Log, lambda m: rviz_errors.append(m.msg)
                     if m.name == "/rviz" and m.level >= Log.ERROR else None, queue_size=100)

    wait_while_running("rviz to subscribe to /sim/scene, /sim/markers and /tf",
                       subscribed(master, "/rviz", ["/sim/scene", "/sim/markers", "/tf"]), left(), launch, 0.5)
    # This test's own subscriptions too: the paused node publishes the last step's states once, and a state
    # topic this test is not yet connected to would never deliver it.
    wait_while_running("this test to subscribe to every topic it reads", subscribed(
        master, "/rviz_screenshot", [s.resolved_name for s in scene.subscribers]), left(), launch, 0.5)
    wait_while_running("the render window", lambda: try_render_window() is not None, left(), launch, 0.5)

    # rviz subscribed after the node started: the floor, slopes and bodies must come from the latched scene.
    scene.t = None
    wait_while_running("a state after rviz subscribed", lambda: scene.t is not None, left(), launch)
    t_connected: float = scene.t or 0.0
    rollers = [spec for spec in (body_spec(config, name) for name in config["bodies"])
               if isinstance(spec, RollerSpec)]
    rate = float(world_value(config, "rate"))
    marker_steps = round(rate / MARKER_RATE)  # the labels are sent at these steps (from t = 0)
    rospy.ServiceProxy("/sim/pause", Empty)()
    step = rospy.ServiceProxy("/sim/step", Step)

    def step_to(steps: int, labels: bool = True) -> float:
        """`steps` steps, then until the states, transforms (and labels) of the last one are here. The states and
        transforms of the last step are the last the node publishes, and each topic delivers in order: once
        they are here, nothing published before is still in flight to this node."""
        t_last = step(steps).t
        try:
            wait_while_running(f"the states, transforms and labels of the last step (t = {t_last})",
                               lambda: scene.all_at(t_last) and (not labels or scene.labels_at(scene.state_stamp)),
                               left(), launch)
        except TimeoutError as e:
            raise TimeoutError(f"{e}; {scene.held()}") from None
        return float(t_last)

    def step_until(t: float, t_now: float) -> float:
        """To the first marker instant (the labels are sent at whole marker periods of the step count) at or
        after t, at least one step."""
        now, target = round(t_now * rate), max(round(t_now * rate) + 1, math.ceil(t * rate - 1e-6))
        return step_to(marker_steps * math.ceil(target / marker_steps) - now)

    view_file = os.path.join(PACKAGE, "rviz", LAUNCH_CONFIGS[args.launch][1])  # the launch's view
    with open(view_file) as f:
        saved = yaml.safe_load(f)
    manager = saved["Visualization Manager"]
    tree_height = displays_dock_height(saved["Window Geometry"])
    view = manager["Views"]["Current"]
    target = view.get("Target Frame", "<Fixed Frame>")
    grid: Dict[str, Any] = next((d for d in manager["Displays"] if d.get("Class") == "rviz/Grid"), {})
    background = [int(v) for v in manager["Global Options"]["Background Color"].split(";")]
    window = render_window()
    moments = [float(m) for m in args.moments.split(",")] if args.moments else [args.settle]
    findings: List[Finding] = []
    report: List[str] = []
    # The picture's instants must not depend on when rviz subscribed (late on a loaded machine, the rod has
    # flown out of the view): every body back to its start, then steps to each moment (simulated seconds
    # after the reset, up to the next marker instant, so that the labels are of that instant). At the first
    # moment, further until every roller is high on its slope; then the changes, while paused, and steps to
    # the next marker instant.
    old_slopes: Dict[str, Tuple[Any, Tuple[np.ndarray, np.ndarray]]] = {}
    # The reset at a marker instant (time goes on from there), so that each moment is one exactly.
    t_now = step_to(1, labels=False)
    t_reset = t_now = step_until(t_now, t_now)
    rospy.ServiceProxy("/sim/reset", Empty)()
    for k, moment in enumerate(moments):
        t_now = step_until(t_reset + moment, t_now)
        if k == 0:
            while not scene.rollers_high(rollers):
                t_now = step_until(t_now + 0.05, t_now)
            if args.change:  # a step shows the bodies where the new look puts them
                old_slopes = change_looks(args.change, config, scene, left, launch)
                t_now = step_until(t_now, t_now)
        out = args.out if k == 0 else f"{stem}_t{moment:g}.png"
        camera = pc.Camera.from_rviz(view, window,
                                     scene.frames[target][1] if target != "<Fixed Frame>" else (0.0, 0.0, 0.0))
        # rviz renders in its own time (software OpenGL on a loaded machine). Everything it was sent is here
        # (above) and the node is paused: once the 3-D view stays the same for SETTLED_S seconds, rviz (which
        # takes its messages and redraws many times a second, at least once a second on a loaded machine) has
        # drawn all of it. That picture is checked, once.
        image = settled_picture(out, camera, left, launch)
        found, outlines = check_picture(image, scene, camera, config,
                                        MIN_ROD_PX_BY_VIEW.get(os.path.basename(view_file), MIN_ROD_PX))
        found += rules.view_checks(scene, camera, [body_spec(config, name) for name in config["bodies"]], grid)
        if k == 0:
            found += old_slopes_gone(image, scene, camera, old_slopes)
        status = rviz_status_pixels(image, (camera.left, camera.top, camera.width, camera.height), tree_height)
        found += [flag(f"rviz display tree free of {k} colour ({v} px)", v == 0) for k, v in status.items()]
        found.append(control(image, scene, camera, config, background))
        save_outlined(image, outlines, os.path.splitext(out)[0] + "_regions.png")
        report.append(f"t = {t_now:.3f} s, {t_now - t_reset:.3f} s after the reset ({os.path.basename(out)}):")
        report += ["  " + f.line() for f in found]
        findings += found
    rviz_log = rviz_error_lines()
    findings.append(flag(f"rviz: {len(rviz_errors)} ERROR messages on /rosout", not rviz_errors))
    findings.append(flag(f"rviz: {len(rviz_log)} ERROR lines in its log", not rviz_log))
    findings += [flag(f"  {m[:100]}", False) for m in rviz_errors + rviz_log]
    # views_over_a_run takes the 3-D view where it is here.
    findings.append(flag(f"rviz's 3-D view {window} within {rules.RENDER_SLACK} px of view_rules.RENDER_AT_1600X900",
                         rules.near_render_at_1600x900(window)))
    report = [f"{args.launch}, view {os.path.basename(view_file)}: "
              f"t = {t_connected:.3f} s when rviz had subscribed; render view {window[2]}x{window[3]}+{window[0]}+"
              f"{window[1]}; {time.monotonic() - start:.1f} s wall"] + report + [f.line() for f in findings[-4:]]
    with open(stem + ".txt", "w") as f:
        f.write("\n".join(report) + "\n")
    print("\n".join(report))
    return 0 if all(f.ok for f in findings) else 1


def settled_picture(out: str, camera: pc.Camera, left: Callable[[], float], launch: Any) -> np.ndarray:
    """The screen once its 3-D view has been the same in every screenshot for SETTLED_S seconds (one every
    half second; the last written to out)."""
    view = (slice(camera.top, camera.top + camera.height), slice(camera.left, camera.left + camera.width))
    same_since = time.monotonic()
    pictures: List[np.ndarray] = []

    def settled() -> bool:
        nonlocal same_since
        taken = time.monotonic()
        subprocess.run(["import", "-window", "root", out], check=True)
        pictures[:] = pictures[-1:] + [read_png(out)]
        if len(pictures) < 2 or not np.array_equal(pictures[0][view], pictures[1][view]):
            same_since = taken
        return taken - same_since >= SETTLED_S
    wait_while_running(f"rviz to draw the same 3-D view for {SETTLED_S:g} s", settled, left(), launch, 0.5)
    return pictures[-1]


def change_looks(changes: List[str], config: Config, scene: Scene, left: Callable[[], float],
                 launch: Any) -> Dict[str, Tuple[Any, Tuple[np.ndarray, np.ndarray]]]:
    """Sets each BODY.KEY=VALUE through the body's reconfigure server and waits until the scene and the
    static transforms the node sends say so; `config` takes the new values (the checks use them). Returns
    the slopes that changed as they were: {body: (slope marker, its frame's rotation and origin)}."""
    import dynamic_reconfigure.client
    old: Dict[str, Tuple[Any, Tuple[np.ndarray, np.ndarray]]] = {}
    for change in changes:
        target, value = change.split("=", 1)
        body, key = target.split(".", 1)
        if key in ("incline_angle", "incline_length"):
            old[body] = (scene.markers[("slope", slope_id(scene, body))], scene.frames[body + "_slope"])
        scene_messages, static_messages = scene.scene_messages, scene.static_messages
        client = dynamic_reconfigure.client.Client(f"/sim/{body}", timeout=left())
        applied = client.update_configuration({key: float(value)})
        if float(applied[key]) != float(value):
            raise RuntimeError(f"the node refused {change}: it runs {key} = {applied[key]}")
        config["bodies"][body][key] = float(value)
        # The node sends the fixed frames again, then the scene if a marker changed: all but a new angle
        # (a slope is drawn in its own frame) change one.
        wait_while_running(f"the fixed frames after {change}", lambda: scene.static_messages > static_messages,
                           left(), launch)
        if key != "incline_angle":
            wait_while_running(f"the scene after {change}", lambda: scene.scene_messages > scene_messages,
                               left(), launch)
    return old


def slope_id(scene: Scene, body: str) -> int:
    """The id of the slope marker drawn in the body's slope frame."""
    return next(key[1] for key, m in scene.markers.items()
                if key[0] == "slope" and m.header.frame_id == body + "_slope")


def old_slopes_gone(image: np.ndarray, scene: Scene, camera: pc.Camera,
                    old: Dict[str, Tuple[Any, Tuple[np.ndarray, np.ndarray]]]) -> List[Finding]:
    """Where a changed slope's top was, and nothing of the scene now is (no slope, body or label), no more
    than 5 % brown: rviz draws the slope where its new frame puts it, not the new slope in the old frame or
    the old one left behind."""
    checker = Checker(image, scene, camera)
    now = checker.slopes()
    covered = checker.labels()
    for box, _ in now.values():
        covered |= box
    for name in scene.frames:
        if name in scene.states:  # a body: a disc of its largest reach around its centre
            (pixel,), (depth,) = camera.project(scene.frames[name][1])
            covered |= pc.disc_mask(checker.shape, pixel, 0.6 * camera.pixels_per_metre_at(depth))
    findings = []
    for body, (marker, (rotation, origin)) in old.items():
        q, p = marker.pose.orientation, marker.pose.position
        centre = origin + rotation @ [p.x, p.y, p.z]
        rot = rotation @ pc.quaternion_matrix([q.x, q.y, q.z, q.w])
        size = np.array([marker.scale.x, marker.scale.y, marker.scale.z])
        top = checker.hull_of(pc.box_corners(rot, centre + 0.5 * size[1] * rot[:, 1], size * [1, 0, 1]))
        region = pc.polygon_mask(checker.shape, top) & checker.view & ~covered
        brown = int((pc.colour_mask(image, "brown") & region).sum())
        total = int(region.sum())
        if total == 0:  # the lanes went by steepness: other slopes (or bodies, labels) are there now
            findings.append(flag(f"{body}'s old slope: its place taken by the scene now", True))
            continue
        findings.append(pc.Finding(f"{body}'s old slope gone: not brown", "-", total, total - brown,
                                   int(np.ceil(0.95 * total))))
    return findings


def control(image: np.ndarray, scene: Scene, camera: pc.Camera, config: Config, background: List[int]) -> Finding:
    """The checks must be able to fail: on this picture with its 3-D view emptied (rviz's background
    colour everywhere), every check of a marker fails."""
    empty = image.copy()
    empty[camera.top:camera.top + camera.height, camera.left:camera.left + camera.width] = background
    empty.flags.writeable = False  # as a screenshot: its colour masks computed once
    passed = [f.what for f in check_picture(empty, scene, camera, config)[0] if f.ok and f.colour != "-"]
    return flag("control: an empty view fails every marker check" +
                (f" (passed: {', '.join(passed)})" if passed else ""), not passed)


class Measure(pc.Finding):
    """A size in pixels measured on the picture (colour_px), against the least needed (needed_px)."""

    def line(self) -> str:
        return (f"{'ok  ' if self.ok else 'FAIL'} {self.what:28s} {self.colour:7s} {self.colour_px:6d} px, "
                f"needed {self.needed_px}")


def try_render_window() -> Optional[Tuple[int, int, int, int]]:
    try:
        return render_window()
    except (RuntimeError, subprocess.CalledProcessError):
        return None


def flag(what: str, ok: bool) -> Finding:
    """A yes/no finding."""
    return pc.Finding(what, "-", 1, int(ok), 1)


def read_png(path: str) -> np.ndarray:
    """The picture's RGB, read-only: the checks share its colour masks (picture_check.colour_mask)."""
    import matplotlib.image
    image = matplotlib.image.imread(path)
    rgb = (image[..., :3] * 255).round().astype(np.uint8) if image.dtype != np.uint8 else image[..., :3]
    rgb.flags.writeable = False
    return rgb


if __name__ == "__main__":
    sys.exit(main())
