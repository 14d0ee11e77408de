"""What a class must see in a saved view at any moment, checked on the geometry the node published (its
markers and transforms, projected with the view's camera), not on pixels:
- each label (a roller's name, a rod's name and energy) whole in the 3-D view and beside its own body, on screen
  nearer to it than to any other body; each board (a roller's mode and figures, at its lane's lower end)
  whole in the view and touching no body; no two of these texts touching;
- each body at least MIN_BODY_PX across, each text's characters MIN_TEXT_PX high;
- a rod over its floor (a floor marker under its centre, in the view) and, on an unbounded floor, rviz's Grid
  drawn in the rod's ground frame;
- no slope crossing another's lane (their top faces apart on screen).

Pure functions of a PublishedScene (markers by (ns, id), world poses of frames) and a picture_check.Camera,
so that they run on the scene rviz was sent (rviz_screenshot) and on a recorded run (views_over_a_run)."""
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np
from rigid_body_sim.sim_tools import BodySpec, RodSpec, RollerSpec

import picture_check as pc
from picture_check import Finding

MIN_BODY_PX = 20
# Each text's characters at least this high (a line's height: rviz draws a text's scale.z as its character
# height), the size of the plots' axis titles. rviz's ink is a font's share of it, measured at 1600x900:
# 0.52 (Debian 13) to 0.6 (Debian 12) for a word with no descender ("bowler"), 0.67 to 0.74 with one; the
# picture tests hold the ink to INK_SHARE of the height the geometry gives (0.52 less a pixel's rounding).
MIN_TEXT_PX = 20
INK_SHARE = 0.45
# rviz's text: a glyph's width over the text's height. Measured on rviz's pictures at 1600x900: 0.5 to 0.56,
# with a margin.
GLYPH_WIDTH = 0.6
Box = Tuple[float, float, float, float]  # left, top, right, bottom (pixels)


def flag(what: str, ok: bool) -> Finding:
    return pc.Finding(what, "-", 1, int(ok), 1)


TEXT_KINDS = ("label", "board")  # the marker namespaces of the node's texts
# rviz's 3-D view in every saved view's window at 1600x900 (left, top, width, height), the display tree and
# the Simulation panel docked at the left, as the picture tests find it (rviz_screenshot.render_window): each
# edge within RENDER_SLACK pixels of this (its top and height vary by a few pixels from one start to the
# next). A run checked without rviz holds its texts that much inside (views_over_a_run).
RENDER_AT_1600X900 = (471, 58, 1114, 816)
RENDER_SLACK = 12


def near_render_at_1600x900(window: Tuple[int, int, int, int]) -> bool:
    left, top, width, height = window
    nominal_left, nominal_top, nominal_width, nominal_height = RENDER_AT_1600X900
    edges = (left, top, left + width, top + height)
    nominal = (nominal_left, nominal_top, nominal_left + nominal_width, nominal_top + nominal_height)
    return all(abs(a - b) <= RENDER_SLACK for a, b in zip(edges, nominal))


class PublishedScene:
    """What the node published, as a viewer holds it: the world pose of every frame (/tf, /tf_static) and the
    markers of ~scene and ~markers by (ns, id)."""

    def __init__(self) -> None:
        self.frames: Dict[str, Tuple[np.ndarray, np.ndarray]] = {}
        # Markers by topic: a DELETEALL clears those of its own topic only, as in rviz's displays.
        self.by_topic: Dict[str, Dict[Tuple[str, int], Any]] = {"/sim/scene": {}, "/sim/markers": {}}

    def on_tf(self, msg: Any) -> None:
        for t in msg.transforms:
            r, q = t.transform.translation, t.transform.rotation
            self.frames[t.child_frame_id] = (pc.quaternion_matrix([q.x, q.y, q.z, q.w]), np.array([r.x, r.y, r.z]))

    def on_markers(self, msg: Any, topic: str) -> None:
        markers = self.by_topic[topic]
        for m in msg.markers:
            if m.action == m.DELETEALL:
                markers.clear()
            elif m.action == m.DELETE:
                markers.pop((m.ns, m.id), None)
            else:
                markers[(m.ns, m.id)] = m

    @property
    def markers(self) -> Dict[Tuple[str, int], Any]:
        return {key: m for markers in self.by_topic.values() for key, m in markers.items()}

    def world_pose(self, frame_id: str, pose: Any) -> Tuple[np.ndarray, np.ndarray]:
        """Rotation and position in the world of a marker's pose in `frame_id` (a child of the world)."""
        rotation, origin = self.frames.get(frame_id, (np.eye(3), np.zeros(3)))
        q, p = pose.orientation, pose.position
        return rotation @ pc.quaternion_matrix([q.x, q.y, q.z, q.w]), origin + rotation @ [p.x, p.y, p.z]


def text_name(ns: str, marker: Any) -> str:
    """"<body>'s label" or "<body>'s board": a text names its body before any colon."""
    return f"{marker.text.split(':')[0]}'s {ns}"


def label_box(scene: Any, camera: pc.Camera, marker: Any) -> Optional[Box]:
    """The box a label's text takes on screen (rviz centres it on its position); None behind the camera."""
    _, centre = scene.world_pose(marker.header.frame_id, marker.pose)
    (pixel,), (depth,) = camera.project(centre)
    if depth <= 0:
        return None
    height = marker.scale.z * camera.pixels_per_metre_at(depth)
    lines = marker.text.split("\n")
    half_w = 0.5 * GLYPH_WIDTH * max(len(line) for line in lines) * height
    half_h = 0.5 * height * len(lines)
    return pixel[0] - half_w, pixel[1] - half_h, pixel[0] + half_w, pixel[1] + half_h


def box_distance(box: Box, point: Any) -> float:
    dx = max(box[0] - point[0], 0.0, point[0] - box[2])
    dy = max(box[1] - point[1], 0.0, point[1] - box[3])
    return float(np.hypot(dx, dy))


def body_discs(scene: Any, camera: pc.Camera, reaches: Dict[str, float]) -> Dict[str, Tuple[np.ndarray, float]]:
    """{body: (centre pixel, radius in pixels)} of every body with a pose, `reaches` its radius (m)."""
    discs = {}
    for name, reach in reaches.items():
        if name not in scene.frames:
            continue
        (pixel,), (depth,) = camera.project(scene.frames[name][1])
        if depth > 0:
            discs[name] = (pixel, reach * camera.pixels_per_metre_at(depth))
    return discs


def labels(scene: Any, camera: pc.Camera, reaches: Dict[str, float], inset: int = 0) -> List[Finding]:
    """Each label nearer its own body's outline than any other body's, each board touching no body, all
    whole in the view (inset pixels inside its edges) and apart from one another."""
    findings = []
    discs = body_discs(scene, camera, reaches)
    boxes: Dict[str, Box] = {}
    for (ns, _), m in sorted(scene.markers.items()):
        if ns not in TEXT_KINDS:
            continue
        name, what = m.text.split(":")[0], text_name(ns, m)
        box = label_box(scene, camera, m)
        if box is None:
            findings.append(flag(f"{what} in front of the camera", False))
            continue
        boxes[what] = box
        inside = (box[0] >= camera.left + inset and box[2] <= camera.left + camera.width - inset and
                  box[1] >= camera.top + inset and box[3] <= camera.top + camera.height - inset)
        findings.append(flag(f"{what} whole in the view ({box_text(box)})", inside))
        if name not in discs:
            findings.append(flag(f"{name}'s pose received", False))
            continue
        gaps = {body: max(0.0, box_distance(box, centre) - radius) for body, (centre, radius) in discs.items()}
        if ns == "board":
            nearest = min(gaps, key=lambda body: gaps[body])
            findings.append(flag(f"{what} touching no body ({nearest} {gaps[nearest]:.0f} px)", gaps[nearest] > 0))
            continue
        nearest = min(gaps, key=lambda body: (gaps[body], body != name))
        beside = nearest == name and all(gaps[name] < gap for body, gap in gaps.items() if body != name)
        findings.append(flag(f"{what} nearest its body ({gaps[name]:.0f} px; {nearest} {gaps[nearest]:.0f} px)",
                             beside))
    named = sorted(boxes.items())
    for i, (a, box_a) in enumerate(named):
        for b, box_b in named[i + 1:]:
            apart = box_a[2] < box_b[0] or box_b[2] < box_a[0] or box_a[3] < box_b[1] or box_b[3] < box_a[1]
            findings.append(flag(f"{a} and {b} apart on screen", apart))
    return findings


def box_text(box: Box) -> str:
    return f"{box[0]:.0f}..{box[2]:.0f} x {box[1]:.0f}..{box[3]:.0f}"


def text_sizes(scene: Any, camera: pc.Camera) -> List[Finding]:
    """Each label's and board's characters at least MIN_TEXT_PX high on screen (a line's projected height)."""
    findings = []
    for (ns, _), m in sorted(scene.markers.items()):
        box = label_box(scene, camera, m) if ns in TEXT_KINDS else None
        if box is not None:
            line = int((box[3] - box[1]) / len(m.text.split("\n")))
            findings.append(pc.Finding(f"{text_name(ns, m)}: characters {line} px high", "-", 1, line, MIN_TEXT_PX))
    return findings


def body_sizes(scene: Any, camera: pc.Camera, rollers: Dict[str, float]) -> List[Finding]:
    """Each roller at least MIN_BODY_PX across, by its projected radius."""
    return [pc.Finding(f"{name}: {2 * radius:.0f} px across (projected)", "-", 1, int(2 * radius), MIN_BODY_PX)
            for name, (_, radius) in body_discs(scene, camera, rollers).items()]


def top_face(scene: Any, camera: pc.Camera, marker: Any) -> Optional[List[pc.Pixel]]:
    """The projected hull of a box marker's top face (its frame's +y side: a slope's or a floor's surface)."""
    rotation, centre = scene.world_pose(marker.header.frame_id, marker.pose)
    size = np.array([marker.scale.x, marker.scale.y, marker.scale.z])
    up = int(np.argmax(np.abs(rotation[2])))  # the box's axis nearest the world's z
    offset = 0.5 * size[up] * rotation[:, up] * np.sign(rotation[2, up])
    flat = size.copy()
    flat[up] = 0.0
    pixels, depth = camera.project(pc.box_corners(rotation, centre + offset, flat))
    return pc.convex_hull(pixels) if (depth > 0).all() else None


def hulls_apart(a: Sequence[pc.Pixel], b: Sequence[pc.Pixel]) -> bool:
    """Whether two convex polygons have a separating line (an edge of either)."""
    for poly in (a, b):
        n = len(poly)
        for i in range(n):
            (x0, y0), (x1, y1) = poly[i], poly[(i + 1) % n]
            normal = np.array([y0 - y1, x1 - x0])
            pa, pb = np.asarray(a) @ normal, np.asarray(b) @ normal
            if pa.max() < pb.min() or pb.max() < pa.min():
                return True
    return False


def lanes(scene: Any, camera: pc.Camera) -> List[Finding]:
    """The slopes' top faces apart on screen, two by two: no slope crosses another's lane."""
    faces = {m.header.frame_id: top_face(scene, camera, m) for (ns, _), m in scene.markers.items() if ns == "slope"}
    named = sorted((frame, face) for frame, face in faces.items() if face is not None)
    findings = []
    for i, (a, face_a) in enumerate(named):
        for b, face_b in named[i + 1:]:
            findings.append(flag(f"slopes {a} and {b} apart on screen", hulls_apart(face_a, face_b)))
    return findings


def point_in(hull: Optional[Sequence[pc.Pixel]], point: Any) -> bool:
    if hull is None:
        return False
    n = len(hull)
    signs = [np.sign((hull[(i + 1) % n][0] - hull[i][0]) * (point[1] - hull[i][1]) -
                     (hull[(i + 1) % n][1] - hull[i][1]) * (point[0] - hull[i][0])) for i in range(n)]
    return all(s >= 0 for s in signs) or all(s <= 0 for s in signs)


def rod_floor(scene: Any, camera: pc.Camera, rod: str, unbounded: bool, grid: Dict[str, Any]) -> List[Finding]:
    """A floor marker's top under the rod's centre (its pixels: rviz_screenshot's floor_under); on an unbounded
    floor, a Grid display that reaches 5 m beyond the rod (drawn in the rod's ground frame)."""
    if rod not in scene.frames:
        return [flag(f"{rod}'s pose received", False)]
    x, y, _ = scene.frames[rod][1]
    (under,), _ = camera.project(np.array([x, y, 0.0]))
    floors = [top_face(scene, camera, m) for (ns, _), m in scene.markers.items() if ns == "floor"]
    under_one = any(point_in(hull, under) for hull in floors)
    findings = [flag(f"a floor marker under {rod} (x = {x:.1f} m)", under_one)]
    if unbounded:
        frame = grid.get("Reference Frame", "<Fixed Frame>")
        origin = scene.frames.get(frame, (None, np.zeros(3)))[1] if frame != "<Fixed Frame>" else np.zeros(3)
        offset = grid.get("Offset", {})
        half = 0.5 * float(grid.get("Cell Size", 1)) * int(grid.get("Plane Cell Count", 10))
        centre_x = origin[0] + float(offset.get("X", 0))
        findings.append(flag(f"the grid (in {frame}, x {centre_x - half:.0f}..{centre_x + half:.0f}) under {rod}",
                             abs(x - centre_x) + 5.0 <= half))
    return findings


def reach(spec: BodySpec) -> float:
    """How far a body reaches from its centre: a roller's radius, half a rod's length or a block's edge."""
    if isinstance(spec, RollerSpec):
        return spec.radius
    return 0.5 * (spec.length if isinstance(spec, RodSpec) else spec.size)


def view_checks(scene: Any, camera: pc.Camera, specs: Sequence[BodySpec],
                grid: Dict[str, Any], inset: int = 0) -> List[Finding]:
    """Every rule above on the published geometry: labels by their bodies, boards, all in the view (inset
    pixels inside it) and apart; rollers large enough; slopes apart; each rod over its floor (and grid)."""
    reaches = {spec.name: reach(spec) for spec in specs}
    rollers = {spec.name: spec.radius for spec in specs if isinstance(spec, RollerSpec)}
    found = labels(scene, camera, reaches, inset) + text_sizes(scene, camera) + body_sizes(scene, camera, rollers)
    found += lanes(scene, camera)
    for spec in specs:
        if isinstance(spec, RodSpec):
            found += rod_floor(scene, camera, spec.name, spec.floor_length <= 0.0, grid)
    return found
