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


def jaw_frame(ux, uy, ax, ay, shape):
    """What a jaw needs of its nose direction u (a unit vector along the nose, away from the
    pocket) and its pocket's axis a (unit, off the table), whatever the mouth: the facing's
    direction f (the nose turned by the cut angle towards the cushion's side), f's component
    along the axis (> 0: the facing runs into the pocket) and the unit bisector b of the
    cushion's wedge at the jaw point, on which the rounded tip's centre sits. Returns (fx,
    fy, along, bx, by); the builder (table_build.py) does the rest of the geometry above."""
    cos_cut, sin_cut, _, _ = jaw_constants(shape)
    # Unit vector across the table from this jaw (its rail's inward normal) and the facing
    # direction: the nose turned by the cut angle towards the cushion's side.
    nx, ny = _inward(ux, uy, ax, ay)
    fx, fy = cos_cut * ux - sin_cut * nx, cos_cut * uy - sin_cut * ny
    bx, by = _unit(ux + fx, uy + fy)  # into the cushion's wedge, halving it
    return fx, fy, fx * ax + fy * ay, bx, by


@functools.lru_cache(maxsize=64)
def jaw_constants(shape):
    """What a jaw of `shape` needs of its cut angle alpha: cos alpha, sin alpha, the distance t
    from the jaw point to each tangent point of the rounded tip (r / tan(alpha / 2)) and from
    the jaw point to the tip's centre (r / sin(alpha / 2)); worked out once per shape."""
    alpha = math.radians(shape.cut_angle)
    return (math.cos(alpha), math.sin(alpha), shape.jaw_radius / math.tan(0.5 * alpha),
            shape.jaw_radius / math.sin(0.5 * alpha))


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
