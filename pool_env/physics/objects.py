"""The things on the table, in one place: `Balls` (balls.py), `Table` (table.py) and `rack`, the
racked balls on a table."""

from __future__ import annotations

import functools
import math

import numpy as np

from .balls import (  # noqa: F401  (re-exported: the physics' names for balls live here too)
    BALL_MASS,
    BALL_RADIUS,
    CAROM_MASS,
    CAROM_RADIUS,
    SEED_MASS,
    SEED_RADIUS,
    Balls,
    kinetic_energy,
    read_only,
)
from .bundles import bounds_of
from .placement import first_misplaced
from .table import CAROM_CUSHION_HEIGHT, CAROM_LENGTH, CAROM_WIDTH, Table  # noqa: F401  (re-exported)
from .tolerances import CONTACT_TOLERANCE

# The standard 8-ball rack read from the apex row by row (8 in the middle, a solid and a
# stripe in the back corners).
RACK_ORDER = ((1,), (9, 2), (10, 8, 3), (11, 7, 14, 4), (5, 13, 15, 6, 12))


def rack(table: Table, seed=None, jitter=None, radius=BALL_RADIUS, mass=BALL_MASS, cue_xy=None) -> Balls:
    """The report's triangle of 15 object balls with its apex on the foot spot (3/4 of the
    length, mid-width) and the cue ball on the head spot (1/4 of the length) unless `cue_xy`.

    `jitter` (m) is how far each object ball may sit from its ideal spot, drawn uniformly in a
    disc from `numpy.random.default_rng(seed)`; the ideal spots are spaced 2R + 2 jitter, so
    jittered balls never overlap. It defaults to 0.2 mm when a seed is given and to 0 (a
    perfect frozen rack, every neighbour touching) when it is not.

    `radius` (one number: every ball the same size) and `mass` default to regulation balls;
    any size works that fits the table. Raises ValueError when it does not: the rack (with
    its jitter) must lie inside the rails and off every pocket's capture circle, whatever the
    seed, which takes a playing area of at least 4 (2 sqrt(3) s + R + jitter) x
    2 (2 s + R + jitter) (s = 2R + 2 jitter; 0.913 x 0.288 m for regulation balls and the
    default jitter); and the balls must stand taller than the table's cushion nose
    (2R > `table.cushion_height`), or they would pass under the cushions.
    """
    if not isinstance(table, Table):
        raise TypeError(f"table must be pool_env.physics.Table, got {type(table).__name__}")
    if jitter is None:
        jitter = 2e-4 if seed is not None else 0.0
    if not (math.isfinite(jitter) and jitter >= 0):
        raise ValueError(f"jitter must be finite and >= 0, got {jitter!r}")
    if np.ndim(radius) != 0 or not (math.isfinite(float(radius)) and float(radius) > 0):
        raise ValueError(f"rack's radius must be one finite number > 0 (every ball the same size), got {radius!r}")
    radius = float(radius)
    if 2.0 * radius <= table.cushion_height:
        raise ValueError(
            f"balls of radius {radius} m are too small for this table: its cushion nose is "
            f"{table.cushion_height} m above the cloth, at or above the top of the balls ({2.0 * radius:.4g} m), "
            "so they would pass under the cushions; use balls with 2R > cushion_height, or a lower cushion_height"
        )
    if cue_xy is None and np.ndim(mass) == 0:
        spots, template = _rack_layout(table, radius, jitter, float(mass))
        xy = spots.copy()
    else:
        xy = _rack_spots(table, radius, jitter, cue_xy)
        _check_rack_fits(table, xy, radius, jitter, cue_xy is None)
        template = None
    if jitter > 0:
        rng = np.random.default_rng(seed)
        angle = rng.uniform(0.0, 2.0 * math.pi, 15)
        dist = jitter * np.sqrt(rng.uniform(0.0, 1.0, 15))
        xy[1:, 0] += dist * np.cos(angle)
        xy[1:, 1] += dist * np.sin(angle)
    if template is None:
        return Balls(xy, radius=radius, mass=mass)
    # Spots 2R + 2 jitter apart, each ball within jitter of its spot: no overlap to look for.
    # The per-ball radii and masses are the compiled engine's inputs (writable, like every
    # Balls' own): each rack gets its own copy, so no two racks share one.
    balls = Balls._trusted(xy, template.v, template.w, template.pocketed, template)
    balls._radii, balls._masses = template._radii.copy(), template._masses.copy()
    return balls


def _rack_spots(table, radius, jitter, cue_xy):
    """The cue ball's spot and the 15 object balls' ideal spots (before the jitter)."""
    spacing = 2.0 * radius + 2.0 * jitter
    L, W = table.length, table.width
    apex_x, mid_y = 0.75 * L, 0.5 * W
    xy = np.zeros((16, 2))
    xy[0] = cue_xy if cue_xy is not None else (0.25 * L, mid_y)
    for row, numbers in enumerate(RACK_ORDER):
        for k, number in enumerate(numbers):
            xy[number] = (apex_x + row * spacing * math.sqrt(3.0) / 2.0, mid_y + (k - row / 2.0) * spacing)
    return xy


@functools.lru_cache(maxsize=32)
def _rack_layout(table, radius, jitter, mass):
    """The default rack's spots on a table, checked once to fit, and a resting Balls on them
    whose radius, mass and zero velocities every rack of the same layout shares (`rack` runs
    at every env reset: this saves it the checks and the array building each time)."""
    spots = _rack_spots(table, radius, jitter, None)
    _check_rack_fits(table, spots, radius, jitter, True)
    return read_only(spots), Balls(spots, radius=radius, mass=mass)


def _check_rack_fits(table, xy, radius, jitter, check_cue):
    """Raise ValueError if a rack ball could sit outside the rails or over a pocket: the 15
    object balls anywhere within `jitter` of their spots, and the cue ball on the head spot
    (when `check_cue`; a cue_xy the caller chose is checked where it is simulated). Scalar
    arithmetic first (`rack` runs at every env reset): the exact check per ball only runs
    when a pocket comes near the rack's bounding box."""
    L, W = table.length, table.width
    s, reach, tol = 2.0 * radius + 2.0 * jitter, radius + jitter, CONTACT_TOLERANCE
    # The object balls' spots span x in [0.75 L, 0.75 L + 2 sqrt(3) s], y in W/2 +- 2 s.
    x_lo, x_hi = 0.75 * L - reach, 0.75 * L + 2.0 * math.sqrt(3.0) * s + reach
    y_lo, y_hi = 0.5 * W - 2.0 * s - reach, 0.5 * W + 2.0 * s + reach
    if x_lo < -tol or x_hi > L + tol or y_lo < -tol or y_hi > W + tol or (check_cue and 0.25 * L < radius - tol):
        raise ValueError(
            f"the {L} x {W} m table is too small for a rack of balls of radius {radius} m "
            f"(jitter {jitter} m): the rack needs a playing area of at least "
            f"{_up(4.0 * (2.0 * math.sqrt(3.0) * s + reach))} x {_up(2.0 * (2.0 * s + reach))} m"
        )
    for px, py, pr in table.pocket_reach.tolist():
        near = math.hypot(max(x_lo - px, 0.0, px - x_hi), max(y_lo - py, 0.0, py - y_hi)) < pr
        if check_cue:
            near = near or math.hypot(xy[0, 0] - px, xy[0, 1] - py) < pr + radius
        if near:
            break
    else:
        return
    first = 0 if check_cue else 1
    spots = np.ascontiguousarray(xy[first:])
    # Each ball anywhere within the jitter of its spot: a ball of radius R + jitter on it
    # must keep off every cushion and opening (R: the widest cushion reach of any model).
    n = len(spots)
    code, i, k = first_misplaced(spots, np.full(n, radius), np.full(n, radius + jitter), jitter,
                                 np.zeros(n, dtype=np.bool_), bounds_of(table), 0.0)
    if code != 0:
        x, y = spots[i]
        where = f"over pocket {k}" if code == 2 else "against a pocket's jaws"
        raise ValueError(
            f"the {L} x {W} m table is too small for a rack with these pockets: ball {i + first}'s spot "
            f"({x:.4f}, {y:.4f}) m is {where} or within the jitter ({jitter} m) of it"
        )


def _up(length):
    """A length rounded up to 0.1 mm, for messages stating a minimum."""
    return f"{math.ceil(length * 1e4 - 1e-9) / 1e4:.4f}"

