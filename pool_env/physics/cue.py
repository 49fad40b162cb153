"""The cue strike: an impulse on the cue ball, optionally off-centre for English, draw or follow."""

from __future__ import annotations

import math

import numpy as np

from .objects import Balls


def strike(balls: Balls, force, offset=(0.0, 0.0), contact_time=0.005, ball=0) -> Balls:
    """Hit ball `ball` (the cue ball) with a horizontal cue force (N) held for `contact_time` s.

    The impulse is J = F dt (the report's eq. 2.1), so the ball leaves at v0 = F dt / m along
    the force (eq. 2.2). `offset = (side, top)` is where the tip meets the ball face, in units
    of R, seen from behind the cue: side > 0 is right English, top > 0 follow, top < 0 draw.
    The angular impulse r x J about the centre gives w = 5 v0 / (2R) (side z + top (z x d)),
    d the cue direction; a hit at top = 2/5 leaves the ball rolling at once (the classic
    7/5 R height). Squirt and cue elevation are not modelled. Returns new Balls.
    """
    fx, fy = (float(c) for c in np.asarray(force, dtype=np.float64).reshape(2))
    if not (math.isfinite(fx) and math.isfinite(fy)):
        raise ValueError(f"cue force must be finite, got ({fx}, {fy})")
    magnitude = math.hypot(fx, fy)
    if magnitude == 0.0:
        raise ValueError("cue force is zero: the cue must push the ball")
    side, top = (float(c) for c in np.asarray(offset, dtype=np.float64).reshape(2))
    if not (math.isfinite(side) and math.isfinite(top)):
        raise ValueError(f"cue tip offset must be finite, got ({side}, {top})")
    if math.hypot(side, top) >= 1.0:
        raise ValueError(f"cue tip offset ({side}, {top}) is off the ball: |offset| must be < 1 (in units of R)")
    contact_time = float(contact_time)
    if not (math.isfinite(contact_time) and contact_time > 0):
        raise ValueError(f"contact_time must be finite and > 0, got {contact_time!r}")
    if not 0 <= ball < len(balls):
        raise ValueError(f"there is no ball {ball} to strike (have {len(balls)})")
    if balls.pocketed[ball]:
        raise ValueError(f"ball {ball} is pocketed and cannot be struck")
    m, r = balls.masses[ball], balls.radii[ball]
    speed = magnitude * contact_time / m
    dx, dy = fx / magnitude, fy / magnitude
    v = balls.v.copy()
    w = balls.w.copy()
    v[ball] = (speed * dx, speed * dy)
    k = 2.5 * speed / r
    w[ball] = (-k * top * dy, k * top * dx, k * side)
    return Balls._trusted(balls.xy, v, w, balls.pocketed, balls)
