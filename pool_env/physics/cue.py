"""The cue strike: an impulse on the cue ball, off-centre for English, draw or follow, with squirt."""

from __future__ import annotations

import math

import numpy as np

from .objects import BALL_MASS, Balls

# The miscue limit, in ball radii: a tip farther than this from the centre of the ball's face
# slips off (D. G. Alciatore, "How High or Low Should You Hit the Cue Ball?", Billiards Digest,
# Illustrated Principles series, Diagram 1: "generally accepted to be half the ball's radius").
MISCUE_LIMIT = 0.5

# Rounding allowed over MISCUE_LIMIT, relative: an offset clamped to the limit by scaling
# (side, top) can come out a few ulps longer than 0.5.
MISCUE_ROUNDING = 1e-12

# The cue's default effective end mass (kg), the mass near the tip that the ball pushes
# sideways during contact (Alciatore, TP A-31): a thirtieth of a regulation ball, 5.67 g,
# pooltool 0.6's default cue (pooltool.objects.cue.datatypes.CueSpecs, end_mass =
# 0.170097 / 30, citing TP A-31). It squirts the ball 1.9 degrees at the miscue limit.
END_MASS = BALL_MASS / 30.0


def strike(balls: Balls, force, offset=(0.0, 0.0), contact_time=0.005, ball=0, end_mass=END_MASS) -> Balls:
    """Hit ball `ball` (the cue ball) with a level cue pushing `force` (N) along its axis for
    `contact_time` s; the cue's effective end mass is `end_mass` kg (0: no squirt).

    `offset = (side, top)` = (a, b) is where the tip meets the ball face, in units of R, seen
    from behind the cue: side > 0 is right English, top > 0 follow, top < 0 draw. It must lie
    within the miscue limit, |offset| <= 0.5 (`MISCUE_LIMIT`); beyond it the tip would slip off
    and `strike` raises a ValueError naming the miscue.

    Model (Alciatore's technical proof TP A-31, "Squirt angle as a function of tip offset and
    cue endmass", billiards.colostate.edu/technical_proofs/new/TP_A-31.pdf, extended to top and
    draw with the same assumptions). d is the cue direction, l = z x d its left; the tip meets
    the ball at p = R (-c d - a l + b z), c = sqrt(1 - a^2 - b^2). The axial impulse is the
    cue's push, J_d = F dt (the report's eq. 2.1); the end mass m_e, free to move sideways,
    takes -J_l while the ball (mass m, I = 2/5 m R^2) takes J = J_d d + J_l l, so
    v = J / m and w = p x J / I = 5/(2 m R) ((a J_d - c J_l) z + b z x J). The tip does not
    slip on the ball, so when they part the contact point and the tip move sideways together:
        J_l/m + 5/(2m) ((1 - a^2) J_l - a c J_d) = -J_l / m_e,
    whence the squirt angle alpha between the ball's path and the cue,
        tan(alpha) = J_l / J_d = (5/2) a c / (1 + m/m_e + (5/2)(1 - a^2)),
    which for b = 0 is TP A-31's closed form. Right English (a > 0) sends the ball left of the
    cue (J_l > 0): away from the side of the hit; a pure top or draw hit (a = 0) goes straight.
    The speed along the cue stays F dt / m, so the ball leaves at F dt / (m cos alpha); the
    spin's top/draw part b z x v follows the path it actually takes (b = 2/5, the 7/5 R
    height, still leaves the ball rolling at once), and the side spin is 5/(2R) (a v_d - c v_l)
    with v_d, v_l the speeds along d and l: the squirt impulse turns it back a little. With
    m_e = 0 the tip cannot push sideways: J_l = 0, the ball leaves along the cue with
    w = 5 v0 / (2R) (a z + b z x d). Cue elevation (swerve, masse) is not modelled. Returns
    new Balls.
    """
    fx, fy = (float(c) for c in np.asarray(force, dtype=np.float64).reshape(2))
    if not (math.isfinite(fx) and math.isfinite(fy)):
        raise ValueError(f"cue force must be finite, got ({fx}, {fy})")
    magnitude = math.hypot(fx, fy)
    if magnitude == 0.0:
        raise ValueError("cue force is zero: the cue must push the ball")
    side, top = _tip_offset(offset)
    contact_time = float(contact_time)
    if not (math.isfinite(contact_time) and contact_time > 0):
        raise ValueError(f"contact_time must be finite and > 0, got {contact_time!r}")
    end_mass = float(end_mass)
    if not (math.isfinite(end_mass) and end_mass >= 0):
        raise ValueError(f"end_mass must be finite and >= 0 (kg; 0 switches squirt off), got {end_mass!r}")
    if not 0 <= ball < len(balls):
        raise ValueError(f"there is no ball {ball} to strike (have {len(balls)})")
    if balls.pocketed[ball]:
        raise ValueError(f"ball {ball} is pocketed and cannot be struck")
    m, r = balls.masses[ball], balls.radii[ball]
    v_d = magnitude * contact_time / m
    v_l = v_d * squirt_tangent(side, top, m, end_mass)
    dx, dy = fx / magnitude, fy / magnitude
    vx, vy = v_d * dx - v_l * dy, v_d * dy + v_l * dx  # v_d d + v_l l, l = z x d = (-dy, dx)
    depth = math.sqrt(1.0 - side * side - top * top)
    k = 2.5 / r
    v = balls.v.copy()
    w = balls.w.copy()
    v[ball] = (vx, vy)
    w[ball] = (-k * top * vy, k * top * vx, k * (side * v_d - depth * v_l))
    return Balls._trusted(balls.xy, v, w, balls.pocketed, balls)


def squirt_tangent(side, top, mass, end_mass):
    """tan of the squirt angle (see `strike`): the ball's speed to the cue's left over its speed
    along the cue, for tip offset (side, top) in units of R, ball mass and cue end mass in kg.
    Written (5/2) a c m_e / (m_e (1 + 5/2 (1 - a^2)) + m) so that m_e = 0 gives 0."""
    depth = math.sqrt(1.0 - side * side - top * top)
    return 2.5 * side * depth * end_mass / (end_mass * (1.0 + 2.5 * (1.0 - side * side)) + mass)


def _tip_offset(offset):
    """(side, top) as floats, checked finite and within the miscue limit."""
    side, top = (float(c) for c in np.asarray(offset, dtype=np.float64).reshape(2))
    if not (math.isfinite(side) and math.isfinite(top)):
        raise ValueError(f"cue tip offset must be finite, got ({side}, {top})")
    reach = math.hypot(side, top)
    if reach > MISCUE_LIMIT * (1.0 + MISCUE_ROUNDING):
        raise ValueError(f"cue tip offset ({side}, {top}) is {reach:.4g} R from the centre, beyond the miscue "
                         f"limit of {MISCUE_LIMIT} R: the tip would slip off the ball (a miscue)")
    return side, top
