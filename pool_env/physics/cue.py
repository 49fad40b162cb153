"""The cue strike: an impulse on the cue ball, off-centre for English, draw or follow, with squirt."""

from __future__ import annotations

import math

import numpy as np

from .airborne import table_impulse
from .config import Physics
from .kinds import ROW_WIDTH, VX, VY, VZ, WX, WY, WZ
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

# The steepest cue `strike` takes (rad): 85 degrees above horizontal. A vertical cue (90
# degrees) has no horizontal direction, which is what `force` names; a masse is played at
# 60-85 degrees.
MAX_ELEVATION = math.radians(85.0)

# The slate's coefficients when strike is given no Physics.
_STANDARD = Physics()


def strike(balls: Balls, force, offset=(0.0, 0.0), contact_time=0.005, ball=0, end_mass=END_MASS,
           elevation=0.0, physics=None) -> Balls:
    """Hit ball `ball` (the cue ball) with a cue pushing `force` (N) along its axis for
    `contact_time` s; the cue's effective end mass is `end_mass` kg (0: no squirt).

    `elevation` (rad, 0 <= elevation <= MAX_ELEVATION, 85 degrees) raises the butt of the cue
    above horizontal: the cue then points forward along force's direction and down.
    `force`'s direction is the aim (the cue's horizontal direction) and its norm the push
    along the cue's own axis, whatever the elevation. An elevated cue drives the ball down
    into the slate, which answers at once with its impulse (`physics`'s e_t and mu_t, the
    standard Physics() by default; airborne.table_impulse): the ball leaves sliding, or
    airborne when the bounce would rise higher than tolerances.BOUNCE_STOP_HEIGHT (its z and
    vz in the returned Balls). Elevated off-centre hits spin the ball about a tilted axis,
    which curves its path while it slides (swerve, masse). elevation=0 is the level cue.

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
    w = 5 v0 / (2R) (a z + b z x d). Returns new Balls.
    The elevated cue's model: `_elevated`.
    """
    fx, fy = _two_floats(force)
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
    elevation = _elevation(elevation)
    if not 0 <= ball < len(balls):
        raise ValueError(f"there is no ball {ball} to strike (have {len(balls)})")
    if balls.pocketed[ball]:
        raise ValueError(f"ball {ball} is pocketed and cannot be struck")
    if not balls.on_cloth and balls.airborne[ball]:
        raise ValueError(f"ball {ball} is in the air and cannot be struck")
    m, r = float(balls.masses[ball]), float(balls.radii[ball])
    v_d = magnitude * contact_time / m
    v_l = v_d * squirt_tangent(side, top, m, end_mass)
    dx, dy = fx / magnitude, fy / magnitude
    if elevation != 0.0:
        return _elevated(balls, ball, (dx, dy, elevation), (side, top), (v_d, v_l), physics)
    vx, vy = v_d * dx - v_l * dy, v_d * dy + v_l * dx  # v_d d + v_l l, l = z x d = (-dy, dx)
    depth = math.sqrt(1.0 - side * side - top * top)
    k = 2.5 / r
    v = balls.v.copy()
    w = balls.w.copy()
    v[ball, 0], v[ball, 1] = vx, vy  # entry by entry: cheaper than a row from a tuple
    w[ball, 0], w[ball, 1], w[ball, 2] = -k * top * vy, k * top * vx, k * (side * v_d - depth * v_l)
    return Balls._trusted(balls.xy, v, w, balls.pocketed, balls, balls.air)


def _two_floats(pair) -> tuple[float, float]:
    """Two numbers (anything numpy reshapes to (2,)) as Python floats; a tuple of two floats
    (what `Game` passes, once per shot) is taken as it is, anything else goes through numpy,
    whose error a wrong shape raises."""
    if type(pair) is tuple and len(pair) == 2 and type(pair[0]) is float and type(pair[1]) is float:
        return pair
    a, b = np.asarray(pair, dtype=np.float64).reshape(2).tolist()
    return a, b


def squirt_tangent(side, top, mass, end_mass):
    """tan of the squirt angle (see `strike`): the ball's speed to the cue's left over its speed
    along the cue, for tip offset (side, top) in units of R, ball mass and cue end mass in kg.
    Written (5/2) a c m_e / (m_e (1 + 5/2 (1 - a^2)) + m) so that m_e = 0 gives 0."""
    depth = math.sqrt(1.0 - side * side - top * top)
    return 2.5 * side * depth * end_mass / (end_mass * (1.0 + 2.5 * (1.0 - side * side)) + mass)


def _elevated(balls, ball, aim, tip, speeds, physics):
    """strike's elevated cue: aim = (dx, dy, elevation th), tip = (a, b), speeds = (v_e, v_l)
    along the cue's axis and to its left (v_l from the squirt, as for a level cue).

    Alciatore's TP A-30 ("Cue ball velocity and spin resulting from an elevated cue strike"),
    with strike's squirt: its derivation in the frame of the cue, e = cos(th) d - sin(th) z
    along the axis, l = z x d, and u = sin(th) d + cos(th) z, up in the plane normal to the
    axis (e x l = u), in place of (d, l, z): the tip meets the ball at p = R (-c e - a l + b u),
    the offsets (a, b) measured in that plane (where the miscue limit is checked), v = v_e e +
    v_l l and w = 5/(2R) (b u x v + (a v_e - c v_l) u). The tilted spin axis gives w a
    horizontal part a v_e sin(th) along d, which the slip (v + w x (-R z)) turns into a
    sideways push while the ball slides (swerve, masse); v_z = -v_e sin(th) goes into the
    slate, whose impulse (airborne.table_impulse) follows at once."""
    dx, dy, th = aim
    side, top = tip
    v_e, v_l = speeds
    r = balls.radii[ball]
    ce, se = math.cos(th), math.sin(th)
    e = np.array([ce * dx, ce * dy, -se])
    lft = np.array([-dy, dx, 0.0])
    up = np.array([se * dx, se * dy, ce])
    v3 = v_e * e + v_l * lft
    depth = math.sqrt(1.0 - side * side - top * top)
    w3 = 2.5 / r * (top * np.cross(up, v3) + (side * v_e - depth * v_l) * up)
    row = np.zeros(ROW_WIDTH)
    row[VX], row[VY], row[VZ] = v3
    row[WX], row[WY], row[WZ] = w3
    if physics is None:
        physics = _STANDARD
    table_impulse(row, float(r), physics.as_array())
    v, w = balls.v.copy(), balls.w.copy()
    v[ball] = row[VX], row[VY]
    w[ball] = row[WX], row[WY], row[WZ]
    air = balls.air
    if row[VZ] != 0.0:
        air = balls.air.copy()
        air[ball] = 0.0, row[VZ]
    return Balls._trusted(balls.xy, v, w, balls.pocketed, balls, air)


def _elevation(elevation):
    """The cue's elevation as a float, checked finite and in [0, MAX_ELEVATION]."""
    try:
        elevation = float(elevation)
    except (TypeError, ValueError):
        raise ValueError(f"cue elevation must be a number of radians, got {elevation!r}") from None
    if not math.isfinite(elevation):
        raise ValueError(f"cue elevation must be finite, got {elevation!r}")
    if not 0.0 <= elevation <= MAX_ELEVATION:
        raise ValueError(f"cue elevation {elevation!r} rad ({math.degrees(elevation):.4g} deg) is outside "
                         f"[0, {MAX_ELEVATION:.6g}] rad (0 to {math.degrees(MAX_ELEVATION):.4g} deg above horizontal)")
    return elevation


def _tip_offset(offset):
    """(side, top) as floats, checked finite and within the miscue limit."""
    side, top = _two_floats(offset)
    if not (math.isfinite(side) and math.isfinite(top)):
        raise ValueError(f"cue tip offset must be finite, got ({side}, {top})")
    reach = math.hypot(side, top)
    if reach > MISCUE_LIMIT * (1.0 + MISCUE_ROUNDING):
        raise ValueError(f"cue tip offset ({side}, {top}) is {reach:.4g} R from the centre (measured in the plane "
                         f"normal to the cue, at any elevation), beyond the miscue limit of {MISCUE_LIMIT} R: the tip "
                         "would slip off the ball (a miscue)")
    return side, top
