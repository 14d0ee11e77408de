"""Checks an rviz screenshot against the scene that was published: where rviz/sim.rviz's orbit camera
puts each marker, and whether pixels of that marker's colour are there.

Pure functions (numpy only), so that they can be tried on any PNG: the projection follows rviz's
OrbitViewController (camera at focal + distance (cos yaw cos pitch, sin yaw cos pitch, sin pitch),
z up, vertical field of view), and colours are told apart by hue and saturation, which rviz's
lighting (a white light scaling each colour) leaves unchanged."""
import weakref
from dataclasses import dataclass
from functools import cached_property
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

# Arrays are np.ndarray, with no alias: bullseye has no numpy.typing (numpy 1.19), and its mypy (0.812)
# rejects an alias of np.ndarray, which is untyped there.
Pixel = Tuple[float, float]

# Colour classes: (hue range in degrees, saturation range, minimum value). The marker colours are those
# of src/ros/scene.cpp: rod (0.1, 0.3, 0.9), sphere (0.9, 0.1, 0.1), cylinder
# (0.1, 0.8, 0.1), ring (1, 0.6, 0), shell (0.7, 0.1, 0.9), slope (0.55, 0.4, 0.25), floor grey 0.75.
COLOUR_CLASSES: Dict[str, Tuple[Tuple[float, float], Tuple[float, float], float]] = {
    "blue": ((212, 236), (0.6, 1.0), 0.25),      # rod, hue 225 (TF's z axis is 240: outside)
    "red": ((346, 14), (0.6, 1.0), 0.25),        # sphere (a range through 0)
    "green": ((105, 135), (0.6, 1.0), 0.25),     # cylinder
    "orange": ((28, 46), (0.8, 1.0), 0.35),      # ring, hue 36, saturated
    "purple": ((270, 300), (0.6, 1.0), 0.25),    # spherical shell
    "brown": ((20, 42), (0.4, 0.72), 0.15),      # slopes, hue 30, half saturated
    "grey": ((0, 360), (0.0, 0.12), 0.33),      # floor (and the grid's lines); background is 0.19
    "floor": ((0, 360), (0.0, 0.12), 0.22),     # any floor: a rod's bounded one (grey 0.5) shows at 0.24
}
SHAPE_CLASS = {"sphere": "red", "cylinder": "green", "ring": "orange", "spherical_shell": "purple"}


# The checks of one picture ask for many colours (about 40 masks in a lesson's picture): a read-only picture
# (read_png's) has its hue, saturation and value computed once, and each colour's mask, which is read-only too.
# [a weak reference to that picture, its hsv, its masks by colour]
_picture: List[Any] = [None, None, {}]


def _cache_of(image: np.ndarray) -> Optional[List[Any]]:
    """The cache of a read-only picture (a new one replaces the last); None for a picture that may change."""
    if image.flags.writeable:
        return None
    if _picture[0] is None or _picture[0]() is not image:
        _picture[:] = [weakref.ref(image), None, {}]
    return _picture


def hsv(image: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Hue in degrees [0, 360), saturation and value in [0, 1] of an RGB(A) float image."""
    cache = _cache_of(image)
    if cache is not None and cache[1] is not None:
        return cache[1]
    rgb = image[..., :3].astype(float)
    if rgb.max() > 1.0:
        rgb = rgb / 255.0
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    top = rgb.max(axis=-1)
    span = top - rgb.min(axis=-1)
    safe = np.where(span > 0, span, 1.0)
    hue = np.where(top == r, ((g - b) / safe) % 6, np.where(top == g, (b - r) / safe + 2, (r - g) / safe + 4))
    hue = 60.0 * hue
    saturation = np.where(top > 0, span / np.where(top > 0, top, 1.0), 0.0)
    if cache is not None:
        for channel in (hue, saturation, top):
            channel.flags.writeable = False
        cache[1] = (hue, saturation, top)
    return hue, saturation, top


def colour_mask(image: np.ndarray, name: str) -> np.ndarray:
    cache = _cache_of(image)
    if cache is not None and name in cache[2]:
        return cache[2][name]
    (h0, h1), (s0, s1), v0 = COLOUR_CLASSES[name]
    hue, sat, val = hsv(image)
    in_hue = (hue >= h0) & (hue <= h1) if h0 <= h1 else (hue >= h0) | (hue <= h1)
    mask = in_hue & (sat >= s0) & (sat <= s1) & (val >= v0)
    if cache is not None:
        mask.flags.writeable = False
        cache[2][name] = mask
    return mask


@dataclass(frozen=True)
class Camera:
    """rviz's Orbit view, rendered into a window of width x height pixels at (left, top) on screen."""
    focal: np.ndarray
    distance: float
    pitch: float
    yaw: float
    fov: float
    left: int
    top: int
    width: int
    height: int

    def __post_init__(self) -> None:
        # A read-only copy of its own: the cached basis is computed from it once.
        focal = np.array(self.focal, dtype=float)
        focal.flags.writeable = False
        object.__setattr__(self, "focal", focal)

    @classmethod
    def from_rviz(cls, view: Dict[str, Any], window: Tuple[int, int, int, int],
                  target: Any = (0.0, 0.0, 0.0)) -> "Camera":
        """`target`: the world position of the view's Target Frame (rviz adds it to the focal point)."""
        focal = np.array([view["Focal Point"][k] for k in "XYZ"], dtype=float) + np.asarray(target, dtype=float)
        return cls(focal, float(view["Distance"]), float(view["Pitch"]), float(view["Yaw"]),
                   float(view.get("Field of View", 0.785398)), *window)

    @cached_property
    def basis(self) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Eye, forward, right and up in the world: once per camera (a run projects every label at 600
        instants)."""
        cp = np.cos(self.pitch)
        eye = self.focal + self.distance * np.array(
            [np.cos(self.yaw) * cp, np.sin(self.yaw) * cp, np.sin(self.pitch)])
        forward = (self.focal - eye) / np.linalg.norm(self.focal - eye)
        right = np.cross(forward, [0.0, 0.0, 1.0])
        right /= np.linalg.norm(right)
        vectors = eye, forward, right, np.cross(right, forward)
        for vector in vectors:
            vector.flags.writeable = False  # shared by every projection
        return vectors

    def pixels_per_metre_at(self, depth: Any) -> Any:
        return 0.5 * self.height / np.tan(0.5 * self.fov) / depth

    def project(self, points: Any) -> Tuple[np.ndarray, np.ndarray]:
        """Screen pixels (column, row) and depth of world points, shape (n, 3)."""
        eye, forward, right, up = self.basis
        rel = np.atleast_2d(points) - eye
        depth = rel @ forward
        f = self.pixels_per_metre_at(1.0)
        col = self.left + 0.5 * self.width + f * (rel @ right) / depth
        row = self.top + 0.5 * self.height - f * (rel @ up) / depth
        return np.stack([col, row], axis=1), depth


def quaternion_matrix(q: Sequence[float]) -> np.ndarray:
    x, y, z, w = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def box_corners(rotation: np.ndarray, centre: np.ndarray, scale: Any) -> np.ndarray:
    """The 8 corners of a box of size `scale` centred at `centre`, axes `rotation` (world)."""
    signs = np.array([[sx, sy, sz] for sx in (-.5, .5) for sy in (-.5, .5) for sz in (-.5, .5)])
    return centre + (signs * scale) @ rotation.T


def polygon_mask(shape: Tuple[int, int], polygon: Optional[Sequence[Pixel]]) -> np.ndarray:
    """Pixels inside a convex polygon (vertices in order, (col, row)); none without a polygon (a shape behind
    the camera has none)."""
    if polygon is None:
        return np.zeros(shape, dtype=bool)
    n = len(polygon)
    area: float = sum(polygon[i][0] * polygon[(i + 1) % n][1] - polygon[(i + 1) % n][0] * polygon[i][1]
                      for i in range(n))
    # A convex polygon lies within its bounding box: only the box's pixels are tested. A flat polygon (area
    # 0: every pixel passes its half-planes) or one with a vertex at infinity: every pixel.
    box = (slice(0, shape[0]), slice(0, shape[1]))
    corners = np.asarray(polygon, dtype=float)
    if area != 0 and np.isfinite(corners).all():
        (c0, r0), (c1, r1) = np.floor(corners.min(axis=0)), np.floor(corners.max(axis=0)) + 1
        box = (slice(int(np.clip(r0, 0, shape[0])), int(np.clip(r1, 0, shape[0]))),
               slice(int(np.clip(c0, 0, shape[1])), int(np.clip(c1, 0, shape[1]))))
    rows, cols = np.mgrid[box]
    inside = np.ones(rows.shape, dtype=bool)
    for i in range(n):
        (x0, y0), (x1, y1) = polygon[i], polygon[(i + 1) % n]
        cross = (x1 - x0) * (rows - y0) - (y1 - y0) * (cols - x0)
        inside &= cross * np.sign(area) >= 0
    mask = np.zeros(shape, dtype=bool)
    mask[box] = inside
    return mask


def convex_hull(points: Any) -> List[Pixel]:
    """Andrew's monotone chain; points (n, 2)."""
    pts = sorted(map(tuple, np.asarray(points)))

    def half(seq: Any) -> List[Pixel]:
        out: List[Pixel] = []
        for p in seq:
            while len(out) >= 2 and ((out[-1][0] - out[-2][0]) * (p[1] - out[-2][1]) -
                                     (out[-1][1] - out[-2][1]) * (p[0] - out[-2][0])) <= 0:
                out.pop()
            out.append(p)
        return out[:-1]
    return half(pts) + half(reversed(pts))


def disc_mask(shape: Tuple[int, int], centre: Any, radius: float) -> np.ndarray:
    rows, cols = np.mgrid[0:shape[0], 0:shape[1]]
    return (cols - centre[0]) ** 2 + (rows - centre[1]) ** 2 <= radius ** 2


def segment_mask(shape: Tuple[int, int], a: np.ndarray, b: np.ndarray, half_width: float) -> np.ndarray:
    rows, cols = np.mgrid[0:shape[0], 0:shape[1]]
    d = np.asarray(b, float) - a
    t = np.clip(((cols - a[0]) * d[0] + (rows - a[1]) * d[1]) / max(d @ d, 1e-9), 0, 1)
    return (cols - a[0] - t * d[0]) ** 2 + (rows - a[1] - t * d[1]) ** 2 <= half_width ** 2


def quadrants_with(image: np.ndarray, region: np.ndarray, centre: Any, colour: str) -> int:
    """How many of the four quadrants about `centre` hold pixels of `colour` inside `region`."""
    rows, cols = np.mgrid[0:image.shape[0], 0:image.shape[1]]
    found = colour_mask(image, colour) & region
    right, below = cols >= centre[0], rows >= centre[1]
    return sum(int((found & (right == r) & (below == b)).any()) for r in (False, True) for b in (False, True))


def white_mask(image: np.ndarray) -> np.ndarray:
    """rviz's label text (white, unlit): every channel at 200 or more (a thin stroke's core is drawn at 220 or
    so, the font hinted to whole pixels); the floor's lit grey (0.75) stays below."""
    return np.asarray((image[..., :3] >= 200).all(axis=-1))  # an array, as numpy 2's stubs cannot tell


def ink_box(mask: np.ndarray, region: np.ndarray) -> Optional[Tuple[int, int, int, int]]:
    """(top, left, bottom, right) of the mask's pixels inside the region, inclusive; None when there are none."""
    rows, cols = np.nonzero(mask & region)
    if rows.size == 0:
        return None
    return int(rows.min()), int(cols.min()), int(rows.max()), int(cols.max())


def boxes_overlap(a: Tuple[int, int, int, int], b: Tuple[int, int, int, int]) -> bool:
    return a[0] <= b[2] and b[0] <= a[2] and a[1] <= b[3] and b[1] <= a[3]


def extent_along(mask: np.ndarray, a: Any, b: Any) -> float:
    """Length in pixels of the mask's pixels projected on the line from a to b (0 when none)."""
    rows, cols = np.nonzero(mask)
    if rows.size == 0:
        return 0.0
    d = (np.asarray(b, float) - a) / max(float(np.linalg.norm(np.asarray(b, float) - a)), 1e-9)
    s = (cols - a[0]) * d[0] + (rows - a[1]) * d[1]
    return float(s.max() - s.min() + 1)


@dataclass
class Finding:
    what: str
    colour: str
    region_px: int
    colour_px: int
    needed_px: int

    @property
    def ok(self) -> bool:
        return self.region_px > 0 and self.colour_px >= self.needed_px

    def line(self) -> str:
        share = self.colour_px / self.region_px if self.region_px else 0.0
        return (f"{'ok  ' if self.ok else 'FAIL'} {self.what:28s} {self.colour:7s} {self.colour_px:6d} of "
                f"{self.region_px:6d} px ({100 * share:5.1f} %), needed {self.needed_px}")


def count(image: np.ndarray, region: np.ndarray, colour: str, what: str, share: float) -> Finding:
    """A finding: pixels of `colour` in `region`, at least `share` of the region needed."""
    n = int(region.sum())
    return Finding(what, colour, n, int((colour_mask(image, colour) & region).sum()), max(1, int(np.ceil(share * n))))
