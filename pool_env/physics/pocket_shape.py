"""A pocket as a player sees it: two jaws with angled facings and rounded tips, and the opening behind them.

Geometry (plan view, the pocket's own frame: the mouth line between the two jaw points, the
pocket axis through its middle pointing off the table):

- **Jaw points** are where the cushion nose meets the facing, the points WPA measures the
  mouth between ("from pointed lip to pointed lip"). They sit on the rail(s) the pocket cuts:
  mouth/2 either side of a side pocket's centre, mouth/sqrt(2) from the corner along both
  rails of a corner pocket (so the mouth line is at 45 degrees and `mouth` long).
- **Facings** leave each jaw point into the pocket at the **cut angle** to the nose: the
  angle inside the cushion between the nose (running away from the pocket) and the facing.
  WPA Equipment Specifications: 142 +- 1 degrees at corners, 104 +- 1 at sides, the same on
  both sides of a pocket. Past 90 degrees (side) or 135 (corner) the facings close in on
  the axis, so the throat narrows behind the mouth.
- **Jaw tips** are rounded: a circle of `jaw_radius` inscribed in the cushion's wedge at
  each jaw point, tangent to the nose and to the facing. The nose rail stops at its tangent
  point on the tip, the facing starts at its own. WPA gives no radius (the cloth-wrapped
  rubber is a few mm); 5 mm is our choice (pooltool 0.6 uses 8 mm at sides, 21 mm at
  corners).
- **Opening**: the slate cut-out, a circle of `opening_radius` on the pocket axis whose near
  edge is `shelf` behind the middle of the mouth line. A ball drops when its centre crosses
  that edge (its weight is then past the slate), as in pooltool. WPA's shelf ranges: corner
  1-2.25 in, side 0-0.375 in; the defaults take the middles (41.3 mm, 4.8 mm). WPA does not
  specify the opening's size; by default it is as wide as the mouth (radius mouth/2: 58 mm
  at the regulation corner, 64 mm at the side; pooltool 0.6 uses 62 and 64.5 mm for its 118
  and 137 mm mouths).
- Each facing runs back to the depth of the opening's centre, where it is well inside the
  opening: a ball reaches the end of a facing only over the opening, after it has dropped.

Ball centres meet these cushions at the nose height: a rail or facing when the centre is the
ball's cushion reach from it (R, or R cos theta for the models that touch the ball at the
nose height h, sin theta = h/R - 1), a jaw tip at reach + jaw_radius from the tip's centre.
"""

from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np

INCH = 0.0254


@dataclasses.dataclass(frozen=True)
class PocketShape:
    """The shape of a pocket behind its mouth (the mouth width is the pocket's own entry).

    | field | meaning | unit |
    | --- | --- | --- |
    | `cut_angle` | angle inside the cushion between the nose and the facing | degrees |
    | `jaw_radius` | radius of the rounded jaw tip (0: a sharp point) | m |
    | `shelf` | from the middle of the mouth line to the opening's near edge | m |
    | `opening_radius` | radius of the opening (slate cut-out) the ball drops through; None: half the mouth | m |
    """

    cut_angle: float
    jaw_radius: float
    shelf: float
    opening_radius: float | None = None

    def __post_init__(self):
        for name in ("cut_angle", "jaw_radius", "shelf", "opening_radius"):
            value = getattr(self, name)
            if value is None and name == "opening_radius":
                continue
            if not (isinstance(value, (int, float)) and math.isfinite(value)):
                raise ValueError(f"PocketShape.{name} must be a finite number, got {value!r}")
            object.__setattr__(self, name, float(value))
        if not 90.0 < self.cut_angle < 180.0:
            raise ValueError(f"PocketShape.cut_angle must be between 90 and 180 degrees, got {self.cut_angle!r}")
        if self.jaw_radius < 0 or self.shelf < 0 or (self.opening_radius is not None and self.opening_radius <= 0):
            raise ValueError(
                f"PocketShape needs jaw_radius >= 0, shelf >= 0 and opening_radius > 0, got {self!r}"
            )

    @classmethod
    def corner(cls) -> PocketShape:
        """A regulation corner pocket: 142 degree cut, 1.625 in shelf (WPA), the opening as wide as the mouth."""
        return cls(cut_angle=142.0, jaw_radius=0.005, shelf=1.625 * INCH)

    @classmethod
    def side(cls) -> PocketShape:
        """A regulation side pocket: 104 degree cut, 3/16 in shelf (WPA), the opening as wide as the mouth."""
        return cls(cut_angle=104.0, jaw_radius=0.005, shelf=0.1875 * INCH)


def _unit(x, y):
    d = math.hypot(x, y)
    return x / d, y / d


def build_pocket(number, jaw_points, noses, axis, shape, mouth):
    """The cushions and opening of pocket `number`.

    `jaw_points` are its two jaw points, `noses` the unit vectors along the nose from each
    jaw point away from the pocket, `axis` the unit vector off the table through the middle
    of the mouth, `mouth` its width. Returns a dict: `facings` (two [x1, y1, x2, y2, nx, ny] rail rows, n into
    the throat), `tips` (two [x, y, r] jaw-tip circles), `nose_ends` (the points where each
    nose rail stops, on its tip), `opening` [x, y, r], `reach` [x, y, r] (a circle around
    all of it, for the engine's broad phase) and `mouth` [x1, y1, x2, y2, ax, ay] (the jaw
    points and the axis)."""
    (p1, p2), (u1, u2), (ax, ay) = jaw_points, noses, axis
    mx, my = 0.5 * (p1[0] + p2[0]), 0.5 * (p1[1] + p2[1])
    cos_cut, sin_cut, t, c = _jaw_constants(shape)
    opening_radius = 0.5 * mouth if shape.opening_radius is None else shape.opening_radius
    depth_end = shape.shelf + opening_radius
    ox, oy = mx + depth_end * ax, my + depth_end * ay
    facings, tips, nose_ends = [], [], []
    for (px, py), (ux, uy), (qx, qy) in (((p1, u1, p2)), ((p2, u2, p1))):
        # Unit vector across the table from this jaw (its rail's inward normal) and the facing
        # direction: the nose turned by the cut angle towards the cushion's side.
        nx, ny = _inward(ux, uy, ax, ay)
        fx, fy = cos_cut * ux - sin_cut * nx, cos_cut * uy - sin_cut * ny
        along = fx * ax + fy * ay
        if along <= 0.0:
            raise ValueError(f"pocket {number}: a {shape.cut_angle} degree cut sends the facing back onto the table")
        bx, by = _unit(ux + fx, uy + fy)  # into the cushion's wedge, halving it
        tips.append((px + c * bx, py + c * by, shape.jaw_radius))
        nose_ends.append((px + t * ux, py + t * uy))
        end = depth_end / along
        ex, ey = px + end * fx, py + end * fy
        # The facing's normal into the throat: towards the other jaw point's side.
        mx_, my_ = -fy, fx
        if mx_ * (qx - px) + my_ * (qy - py) < 0.0:
            mx_, my_ = -mx_, -my_
        if math.hypot(ex - ox, ey - oy) >= opening_radius:
            raise ValueError(
                f"pocket {number}: its opening (radius {opening_radius:.4g} m, {shape.shelf:.4g} m behind the mouth) "
                f"does not reach its facings; make the opening wider or the shelf shallower"
            )
        if mx_ * (ox - ex) + my_ * (oy - ey) <= 0.0:
            raise ValueError(f"pocket {number}: its facings cross before they reach the opening")
        facings.append((px + t * fx, py + t * fy, ex, ey, mx_, my_))
    opening = (ox, oy, opening_radius)
    # The broad phase's circle: around the jaw tips, the nose ends and each facing up to where
    # it enters the opening. A ball meets the rest of a facing only over the opening, after it
    # dropped, and it can enter the opening only through the mouth, inside this circle.
    points = [(x, y, 0.0) for x, y in nose_ends] + list(tips)
    points += [(*_entry(f, opening), 0.0) for f in facings] + [(f[0], f[1], 0.0) for f in facings]
    reach = max(math.hypot(x - mx, y - my) + r for x, y, r in points)
    return {"facings": facings, "tips": tips, "nose_ends": nose_ends, "opening": opening,
            "reach": (mx, my, reach), "mouth": (p1[0], p1[1], p2[0], p2[1], ax, ay)}


@functools.lru_cache(maxsize=64)
def _jaw_constants(shape):
    """What a jaw of `shape` needs of its cut angle alpha: cos alpha, sin alpha, the distance t
    from the jaw point to each tangent point of the rounded tip (r / tan(alpha / 2)) and from
    the jaw point to the tip's centre (r / sin(alpha / 2)); worked out once per shape."""
    alpha = math.radians(shape.cut_angle)
    return (math.cos(alpha), math.sin(alpha), shape.jaw_radius / math.tan(0.5 * alpha),
            shape.jaw_radius / math.sin(0.5 * alpha))


def _entry(facing, opening):
    """Where the facing (from its start, at the jaw tip) first enters the opening circle."""
    x1, y1, x2, y2 = facing[:4]
    ox, oy, r = opening
    dx, dy = x2 - x1, y2 - y1
    fx, fy = x1 - ox, y1 - oy
    a, b, c = dx * dx + dy * dy, 2.0 * (fx * dx + fy * dy), fx * fx + fy * fy - r * r
    if c <= 0.0:  # starts inside the opening already
        return x1, y1
    u = (-b - math.sqrt(max(b * b - 4.0 * a * c, 0.0))) / (2.0 * a)
    return x1 + u * dx, y1 + u * dy


def _inward(ux, uy, ax, ay):
    """The unit normal to a nose direction u that points onto the table (against the axis)."""
    nx, ny = -uy, ux
    if nx * ax + ny * ay > 0.0:
        nx, ny = -nx, -ny
    return nx, ny


def as_rows(items, width):
    """A read-only (K, width) float array of the rows."""
    out = np.array(items, dtype=np.float64).reshape(-1, width)
    out.setflags(write=False)
    return out
