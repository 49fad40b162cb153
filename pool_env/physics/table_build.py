"""A table's cushions and pockets: its plan (what the mouths leave alone) once, the rest in one compiled call.

`Table` keeps, for its size, its pockets' places and its pocket shapes, a `Plan`: where each
pocket sits (the rails it cuts, its axis, the room its mouth has) and the directions of its
jaws' facings, none of which depends on a mouth. `geometry(plan, entries)` then builds the
whole table for any mouths in one compiled call: the jaw points, the nose rails between the
pockets, the facings, jaw tips and openings (the geometry pocket_shape.py describes) and the
checks that refuse a mouth that does not fit. A randomized reset draws mouths on a table whose
plan is known (`Table.variant`), so it pays for the call alone.

The compiled arithmetic is Python's IEEE arithmetic, in its order, so a table is the same bit
for bit whichever way it is built; the one exception is `math.hypot`, which the compiled code
takes from the C library (it may differ from Python's in the last bit). It only matters for
each pocket's broad-phase radius: `Table` has Python work it out again among the candidates
the compiled code found (`exact`), as it always has; `Table.variant` keeps the C library's.
"""

from __future__ import annotations

import functools
import math
import operator
from collections import namedtuple

import numpy as np

from .jit import allocating, allocating_helper, helper
from .motion import copy_row
from .pocket_shape import jaw_constants, jaw_frame
from .tolerances import PLACEMENT_SLACK

Plan = namedtuple("Plan", ["flat", "sides", "pockets", "touch", "jaws", "corner", "shapes", "size"])
Plan.__doc__ = """What a table's geometry needs besides its mouths, in `flat` (1D: what `build` takes),
and its parts, views of it: sides (4, 8) [start x, y, along x, y, inward normal x, y, length,
depth across]; pockets (P, 11) [corner (1.0) or rail (0.0) pocket, the mouth's divisor to its
half-width along a rail (sqrt 2 or 2), the nose rail's trim past a jaw point, the room the
mouth has, axis x, y, a jaw tip's tangent distance t and centre distance c, jaw radius, shelf,
opening radius (nan: half the mouth)]; touch (P, 2, 2) [side (-1: none), distance along it] of
each rail a pocket sits on; jaws (P, 2, 2, 7) [nose x, y, facing x, y, the facing's component
along the axis, the tip's bisector x, y] for each rail a pocket sits on and each direction
along it (towards the rail's start, then its end); corner (P,) bool; shapes and size as
`plan_of` took them (for the messages)."""

# Pocket columns of Plan.pockets.
CORNER, DIVISOR, TRIM, ROOM, AX, AY, TANGENT, CENTRE, JAW_R, SHELF, OPENING = range(11)
# What `build` reports: every pocket fits, or which check refused which pocket.
FITS, TOO_WIDE, OVERLAP, BACKWARDS, SHORT_OPENING, CROSSING, BAD_MOUTH = range(7)
POINTS = 8  # the points a pocket's broad-phase circle encloses: nose ends, tips, facing starts and entries
CANDIDATE = 1e-12  # relative: a point within this of the farthest may be the farthest for Python's hypot


def sides_of(L, W):
    """Each side of an L x W table: start corner, direction along it, inward normal, length, depth
    across the table from it."""
    return [((0.0, 0.0), (1.0, 0.0), (0.0, 1.0), L, W), ((L, W), (-1.0, 0.0), (0.0, -1.0), L, W),
            ((0.0, W), (0.0, -1.0), (1.0, 0.0), W, L), ((L, 0.0), (0.0, 1.0), (-1.0, 0.0), W, L)]


@functools.lru_cache(maxsize=256)
def placement(number, x, y, shapes, size):
    """What of pocket `number`'s place does not depend on its mouth: the (side, distance along it)
    of each rail it sits on, whether it is a corner pocket, its shape, the trim of the nose rail
    past its jaw points, the room its mouth has and its axis off the table."""
    (corner_shape, side_shape), (L, W) = shapes, size
    sides = sides_of(L, W)
    touching = []
    for s, (start, along, _, span, _) in enumerate(sides):
        rel = (x - start[0]) * along[0] + (y - start[1]) * along[1]
        off = (x - start[0]) * along[1] - (y - start[1]) * along[0]
        if abs(off) < PLACEMENT_SLACK and -PLACEMENT_SLACK <= rel <= span + PLACEMENT_SLACK:
            touching.append((s, rel))
    if not touching:
        raise ValueError(f"pocket {number} at ({x}, {y}) is not on a rail or corner of the table")
    corner = len(touching) == 2
    shape = corner_shape if corner else side_shape
    # The nose rail stops on the rounded tip, this far past the jaw point.
    trim = shape.jaw_radius / math.tan(math.radians(0.5 * shape.cut_angle))
    # The room the mouth has: along each rail it sits on, to the far end of the rail
    # (at a corner) or to the nearer end (on a rail); across the table, the depth.
    room = min(min(sides[s][3] if corner else min(rel, sides[s][3] - rel), sides[s][4]) for s, rel in touching)
    normals = [sides[s][2] for s, _ in touching]
    ax, ay = -sum(n[0] for n in normals), -sum(n[1] for n in normals)
    norm = math.hypot(ax, ay)
    return tuple(touching), corner, shape, trim, room, (ax / norm, ay / norm)


@functools.lru_cache(maxsize=64)
def plan_of(places, shapes, size) -> Plan:
    """The Plan of an L x W table (`size`) with pockets at `places` ((x, y) each) of `shapes`
    (corner, side). ValueError naming a pocket that is not on a rail or a corner."""
    n = len(places)
    flat, corner = np.zeros(_plan_size(n)), np.zeros(n, dtype=bool)
    sides, pockets = flat[:32].reshape(4, 8), flat[32:32 + 11 * n].reshape(n, 11)
    touch, jaws = flat[32 + 11 * n:32 + 15 * n].reshape(n, 2, 2), flat[32 + 15 * n:].reshape(n, 2, 2, 7)
    sides[:] = [(*start, *along, *normal, span, depth) for start, along, normal, span, depth in sides_of(*size)]
    touch[:] = -1.0
    for k, (x, y) in enumerate(places):
        touching, corner[k], shape, trim, room, (ax, ay) = placement(k, x, y, shapes, size)
        _, _, t, c = jaw_constants(shape)
        opening = math.nan if shape.opening_radius is None else shape.opening_radius
        divisor = math.sqrt(2.0) if corner[k] else 2.0
        pockets[k] = (corner[k], divisor, trim, room, ax, ay, t, c, shape.jaw_radius, shape.shelf, opening)
        for j, (s, rel) in enumerate(touching):
            touch[k, j] = (s, rel)
            along = sides_of(*size)[s][1]
            for d, sign in enumerate((-1.0, 1.0)):
                ux, uy = sign * along[0], sign * along[1]
                jaws[k, j, d] = (ux, uy, *jaw_frame(ux, uy, ax, ay, shape))
    corner.setflags(write=False)  # Table.corner_pockets hands it out
    return Plan(flat, sides, pockets, touch, jaws, corner, shapes, size)


def geometry(plan: Plan, entries: np.ndarray, corner_mouth=math.nan, side_mouth=math.nan, exact=True) -> dict:
    """The pocket_entries, rails, rail_pockets, jaws, jaw_pockets, pockets, pocket_reach and mouths
    (Table's arrays, read-only) of the table `plan` is for, with pockets `entries` (P, 3) [x, y,
    mouth] (their places the plan's), every corner (rail) pocket's mouth `corner_mouth`
    (`side_mouth`) instead unless NaN. ValueError naming the first pocket that does not fit.
    Not `exact`: each pocket's broad-phase radius by the C library's hypot, which may differ
    from Python's in the last bit (and spares the few microseconds of working it out again)."""
    n = entries.shape[0]
    wide, narrow = np.empty((7 * n + 4, 6)), np.empty(((5 + POINTS) * n, 3))
    code, which, nose, width = build(plan.flat, entries, corner_mouth, side_mouth, wide, narrow)
    if code != FITS:
        raise ValueError(refusal(code, which, plan, narrow[4 * n:5 * n]))
    if exact:
        # Each pocket's broad-phase circle: the farthest of its points by Python's math.hypot,
        # among those the compiled code found within CANDIDATE of the farthest (`width` of them
        # per pocket, the first one repeated to fill).
        dx, dy, r = narrow[5 * n:(5 + width) * n].T.tolist()
        values = list(map(operator.add, map(math.hypot, dx, dy), r))
        narrow[3 * n:4 * n, 2] = values if width == 1 else list(map(max, *(values[j::width] for j in range(width))))
    wide.setflags(write=False)  # and so every view of them below
    narrow.setflags(write=False)
    return {"pocket_entries": narrow[4 * n:5 * n], "rails": wide[:nose + 2 * n], "rail_pockets": _rail_pockets(nose, n),
            "jaws": narrow[:2 * n], "jaw_pockets": _jaw_pockets(n), "pockets": narrow[2 * n:3 * n],
            "pocket_reach": narrow[3 * n:4 * n], "mouths": wide[6 * n + 4:7 * n + 4]}


@functools.lru_cache(maxsize=64)
def _rail_pockets(nose, n):
    """Each rail's pocket: -1 for the `nose` nose rails, then pocket k for its two facings."""
    out = np.array([-1] * nose + [k for k in range(n) for _ in range(2)], dtype=np.int64)
    out.setflags(write=False)
    return out


@functools.lru_cache(maxsize=64)
def _jaw_pockets(n):
    """Each jaw tip's pocket, two per pocket."""
    out = np.array([k for k in range(n) for _ in range(2)], dtype=np.int64)
    out.setflags(write=False)
    return out


def refusal(code, which, plan, entries) -> str:
    """The message of a `build` refusal: pocket `which` failed check `code`."""
    x, y, mouth = (float(v) for v in entries[which])
    shape = plan.shapes[0] if plan.corner[which] else plan.shapes[1]
    if code == TOO_WIDE:
        corner, (L, W) = plan.corner[which], plan.size
        room, trim = plan.pockets[which, ROOM], plan.pockets[which, TRIM]
        widest = (room - trim) * (math.sqrt(2.0) if corner else 2.0)
        return (f"pocket {which} at ({x}, {y}) has a {mouth} m mouth, too wide for the {L} x {W} m table: its jaw "
                f"points must lie on the rail{'s' if corner else ''} it sits on and its mouth must not reach past "
                f"the opposite rail, so its mouth can be at most {widest:.4g} m")
    if code == OVERLAP:
        return f"pocket {which} overlaps another pocket's mouth"
    if code == BACKWARDS:
        return f"pocket {which}: a {shape.cut_angle} degree cut sends the facing back onto the table"
    if code == SHORT_OPENING:
        opening_radius = 0.5 * mouth if shape.opening_radius is None else shape.opening_radius
        return (f"pocket {which}: its opening (radius {opening_radius:.4g} m, {shape.shelf:.4g} m behind the mouth) "
                f"does not reach its facings; make the opening wider or the shelf shallower")
    if code == CROSSING:
        return f"pocket {which}: its facings cross before they reach the opening"
    return f"pocket {which} must be finite (x, y, mouth > 0), got {(x, y, mouth)!r}"


def _plan_size(n):
    """The length of the flat plan of a table with n pockets."""
    return 32 + n * (11 + 4 + 28)


@allocating_helper
def _plan_parts(flat, n):
    """The sides, pockets, touch and jaws of a flat plan (Plan), views of it (in compiled code;
    plan_of cuts them the same way)."""
    sides = flat[:32].reshape((4, 8))
    pockets = flat[32:32 + 11 * n].reshape((n, 11))
    touch = flat[32 + 11 * n:32 + 15 * n].reshape((n, 2, 2))
    jaws = flat[32 + 15 * n:32 + 43 * n].reshape((n, 2, 2, 7))
    return sides, pockets, touch, jaws


@allocating
def build(plan, entries, corner_mouth, side_mouth, wide, narrow):
    """Every pocket's jaw points, facings, tips, opening and mouth, then each side's nose rails
    between the mouths, from the flat `plan` (Plan.flat) and the pockets' `entries` (P, 3), the
    corner and side mouths instead unless NaN. Written to `wide` (7P + 4, 6): the rails from its
    start (the nose rails, then the facings), the mouths from row 6P + 4; to `narrow` (13P, 3):
    tips (2P), openings, reach [mouth middle x, y, 0: Python fills the radius], the entries as
    built (P each), then the points [dx, dy from the middle, r] that may be each pocket's
    farthest, w per pocket. Returns (code, pocket, nose rails, w): code FITS, or the first check
    that refused `pocket`."""
    n = entries.shape[0]
    sides, pockets, touch, jaws = _plan_parts(plan, n)
    tips, openings, reach, given = narrow[:2 * n], narrow[2 * n:3 * n], narrow[3 * n:4 * n], narrow[4 * n:5 * n]
    mouths = wide[6 * n + 4:7 * n + 4]
    facings, points, frame = np.empty((2 * n, 6)), np.empty((n, POINTS, 3)), np.empty((2, 9))
    cuts, counts = np.empty((4, n + 1, 3)), np.zeros(4, dtype=np.int64)
    for k in range(n):
        mouth = corner_mouth if pockets[k, CORNER] == 1.0 else side_mouth
        given[k, 0], given[k, 1] = entries[k, 0], entries[k, 1]
        given[k, 2] = entries[k, 2] if math.isnan(mouth) else mouth
    for k in range(n):
        code = _place(k, given[k, 2], sides, pockets[k], touch[k], jaws[k], cuts, counts, frame)
        if code == FITS:
            code = _jaws(k, given[k, 2], pockets[k], frame, (facings, tips, openings, reach, mouths), points[k])
        if code != FITS:
            return code, k, 0, 0
    code, which, count = _nose_rails(sides, cuts, counts, wide)
    for r in range(2 * n):  # row by row: a slice assignment compiles its error path (see motion.copy_row)
        copy_row(wide[count + r], facings[r])
    return code, which, count, _candidates(points, np.empty((n, POINTS)), reach, narrow[5 * n:])


@helper
def _place(k, mouth, sides, pocket, touch, jaws, cuts, counts, frame):
    """Pocket k's jaw points (on the rails it sits on: `touch`) and their jaw constants, written
    to frame (2, 9) [x, y, nose x, y, facing x, y, along, bisector x, y], and its cuts of those
    rails (added to `cuts`, `counts`); FITS or the check that refused it."""
    if not (math.isfinite(mouth) and mouth > 0.0):
        return BAD_MOUTH
    half = mouth / pocket[DIVISOR]
    trim = pocket[TRIM]
    if half + trim >= pocket[ROOM]:  # the jaw points and their rounded tips must lie on the rail(s)
        return TOO_WIDE
    found = 0
    for j in range(2):
        s = int(touch[j, 0])
        if s < 0:
            continue
        rel, span = touch[j, 1], sides[s, 6]
        for edge in (rel - half, rel + half):
            if 0.0 < edge < span:
                if found == 2:
                    return TOO_WIDE
                frame[found, 0] = sides[s, 0] + edge * sides[s, 2]
                frame[found, 1] = sides[s, 1] + edge * sides[s, 3]
                d = 1 if edge > rel else 0  # the nose runs away from the pocket
                for col in range(7):
                    frame[found, 2 + col] = jaws[j, d, col]
                found += 1
        c = counts[s]
        cuts[s, c, 0] = max(rel - half - trim, 0.0)
        cuts[s, c, 1] = min(rel + half + trim, span)
        cuts[s, c, 2] = k
        counts[s] = c + 1
    return FITS if found == 2 else TOO_WIDE


@helper
def _jaws(k, mouth, pocket, frame, out, points):
    """Pocket k's facings, tips, opening, mouth row and broad-phase points (written to `out`,
    `points`) from its jaw points and constants (`frame`, `_place`); FITS or the check that
    refused it (the arithmetic of pocket_shape's geometry, in its order)."""
    facings, tips, openings, reach, mouths = out
    ax, ay, t, c = pocket[AX], pocket[AY], pocket[TANGENT], pocket[CENTRE]
    mx, my = 0.5 * (frame[0, 0] + frame[1, 0]), 0.5 * (frame[0, 1] + frame[1, 1])
    opening_radius = 0.5 * mouth if math.isnan(pocket[OPENING]) else pocket[OPENING]
    depth_end = pocket[SHELF] + opening_radius
    ox, oy = mx + depth_end * ax, my + depth_end * ay
    for j in range(2):
        px, py, qx, qy = frame[j, 0], frame[j, 1], frame[1 - j, 0], frame[1 - j, 1]
        ux, uy, fx, fy, along, bx, by = frame[j, 2], frame[j, 3], frame[j, 4], frame[j, 5], frame[j, 6], \
            frame[j, 7], frame[j, 8]
        if along <= 0.0:
            return BACKWARDS
        tips[2 * k + j, 0], tips[2 * k + j, 1], tips[2 * k + j, 2] = px + c * bx, py + c * by, pocket[JAW_R]
        points[j, 0], points[j, 1], points[j, 2] = px + t * ux, py + t * uy, 0.0  # where the nose rail stops
        points[2 + j, 0], points[2 + j, 1], points[2 + j, 2] = tips[2 * k + j, 0], tips[2 * k + j, 1], pocket[JAW_R]
        end = depth_end / along
        ex, ey = px + end * fx, py + end * fy
        # The facing's normal into the throat: towards the other jaw point's side.
        nx, ny = -fy, fx
        if nx * (qx - px) + ny * (qy - py) < 0.0:
            nx, ny = -nx, -ny
        if math.hypot(ex - ox, ey - oy) >= opening_radius:
            return SHORT_OPENING
        if nx * (ox - ex) + ny * (oy - ey) <= 0.0:
            return CROSSING
        row = facings[2 * k + j]
        row[0], row[1], row[2], row[3], row[4], row[5] = px + t * fx, py + t * fy, ex, ey, nx, ny
    for j in range(2):
        row = facings[2 * k + j]
        points[4 + j, 0], points[4 + j, 1] = _entry(row[0], row[1], row[2], row[3], ox, oy, opening_radius)
        points[4 + j, 2] = 0.0
        points[6 + j, 0], points[6 + j, 1], points[6 + j, 2] = row[0], row[1], 0.0
    openings[k, 0], openings[k, 1], openings[k, 2] = ox, oy, opening_radius
    reach[k, 0], reach[k, 1], reach[k, 2] = mx, my, 0.0
    m = mouths[k]
    m[0], m[1], m[2], m[3], m[4], m[5] = frame[0, 0], frame[0, 1], frame[1, 0], frame[1, 1], ax, ay
    for i in range(POINTS):  # relative to the circle's centre, for `_candidates`
        points[i, 0], points[i, 1] = points[i, 0] - mx, points[i, 1] - my
    return FITS


@helper
def _entry(x1, y1, x2, y2, ox, oy, r):
    """Where the facing from (x1, y1) to (x2, y2) first enters the opening circle (ox, oy, r)."""
    dx, dy = x2 - x1, y2 - y1
    fx, fy = x1 - ox, y1 - oy
    a, b, c = dx * dx + dy * dy, 2.0 * (fx * dx + fy * dy), fx * fx + fy * fy - r * r
    if c <= 0.0:  # starts inside the opening already
        return x1, y1
    s = (-b - math.sqrt(max(b * b - 4.0 * a * c, 0.0))) / (2.0 * a)
    return x1 + s * dx, y1 + s * dy


@helper
def _candidates(points, far, reach, out):
    """Each pocket's broad-phase radius by the C library's hypot (to `reach`'s last column), and
    the points of each pocket (`points` (P, POINTS, 3): dx, dy from its circle's centre, r) that
    may be its farthest by Python's to the rows of `out`, w per pocket, w the most any pocket
    has (the pocket's first one repeated to fill); returns w. `far` (P, POINTS): scratch."""
    n = points.shape[0]
    width = 1
    for k in range(n):
        reach[k, 2] = -math.inf
        for i in range(POINTS):
            far[k, i] = math.hypot(points[k, i, 0], points[k, i, 1]) + points[k, i, 2]
            reach[k, 2] = max(reach[k, 2], far[k, i])
        count = 0
        for i in range(POINTS):
            count += far[k, i] >= reach[k, 2] * (1.0 - CANDIDATE)
        width = max(width, count)
    for k in range(n):
        at, first = 0, -1
        for i in range(POINTS):
            if far[k, i] >= reach[k, 2] * (1.0 - CANDIDATE):
                first = i if first < 0 else first
                for c in range(3):
                    out[k * width + at, c] = points[k, i, c]
                at += 1
        for j in range(at, width):
            for c in range(3):
                out[k * width + j, c] = points[k, first, c]
    return width


@helper
def _nose_rails(sides, cuts, counts, out):
    """The nose rails of each side between the pockets' cuts (`cuts` [lo, hi, pocket], counts[s]
    of them on side s), in (lo, hi, pocket) order, written to `out`: (code, pocket, rails
    written), code OVERLAP naming the pocket whose cut starts inside another's."""
    count = 0
    for s in range(4):
        side = cuts[s]
        m = counts[s]
        for i in range(1, m):  # insertion sort: a side has a few cuts
            j = i
            while j > 0 and _before(side[j], side[j - 1]):
                for col in range(3):
                    side[j, col], side[j - 1, col] = side[j - 1, col], side[j, col]
                j -= 1
        pos, span = 0.0, sides[s, 6]
        for i in range(m):
            lo, hi = side[i, 0], side[i, 1]
            if lo < pos - PLACEMENT_SLACK:
                return OVERLAP, int(side[i, 2]), count
            if lo > pos:
                _rail(sides[s], pos, lo, out[count])
                count += 1
            pos = hi
        if pos < span:
            _rail(sides[s], pos, span, out[count])
            count += 1
    return FITS, -1, count


@helper
def _before(a, b):
    """Cut a comes before cut b: (lo, hi, pocket) in tuple order."""
    if a[0] != b[0]:
        return a[0] < b[0]
    if a[1] != b[1]:
        return a[1] < b[1]
    return a[2] < b[2]


@helper
def _rail(side, a, b, row):
    """The nose rail of `side` from a to b along it: [x1, y1, x2, y2, nx, ny]."""
    row[0], row[1] = side[0] + a * side[2], side[1] + a * side[3]
    row[2], row[3] = side[0] + b * side[2], side[1] + b * side[3]
    row[4], row[5] = side[4], side[5]
