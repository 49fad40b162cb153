"""Ball-cushion events: when a ball reaches a rail or a pocket jaw, and the cushion models.

Rails are straight segments: the cushion noses and the pockets' facings (a ball touches one
when its centre is its cushion reach Rc away: R, or R cos theta for the models that touch the
ball at the nose height); jaw tips are the rounded ends of the noses at a pocket's mouth (a
ball touches one when its centre is Rc + the tip's radius from the tip's centre). See
pocket_shape.py. Every model takes the ball's row at contact (updated in place)
and the unit normal n pointing from the cushion into the table.
"""

import math

import numpy as np

from .config import CUSHION_MODELS
from .geometry import alongside, distance_entry, rail_gap, roll
from .jit import allocating, helper, kernel
from .kinds import ROW_WIDTH, SLIDING, VX, VY, WX, WY, WZ
from .mathavan import mathavan2010
from .motion import P_E_C, P_F_C, copy_row, reroll, state_of
from .roots import first_entry
from .settle import pressed_cushion, settle_cushion
from .tolerances import MIN_APPROACH, MIN_DEPTH

# The model ids `resolve` dispatches on: each model's position in config.CUSHION_MODELS.
SEED, RESTITUTION, HAN2005, MATHAVAN2010 = (
    CUSHION_MODELS.index(name) for name in ("seed", "restitution", "han2005", "mathavan2010")
)

# Rail rows in the table arrays: see geometry.py.


@helper
def rail_time(path, horizon, reach, rail):
    """Earliest tau in [0, horizon] at which the ball on `path` (its trajectory now, as
    motion.trajectory gives it) meets `rail` (a nose or a facing) moving into it (or inf);
    `reach` is the ball's cushion reach (Scene.Rc).

    The signed gap n.(p(tau) - p1) - reach is a quadratic in tau; the contact counts only if
    the ball's centre is then alongside the segment (beyond its ends the jaw tips take over).
    """
    x, y, vx, vy, ax, ay = path
    nx, ny = rail[4], rail[5]
    gap = rail_gap(rail, x, y, reach)
    c1, c2 = nx * vx + ny * vy, 0.5 * (nx * ax + ny * ay)
    # Clear of the rail (by far more than MIN_DEPTH and the round-off of the terms) and
    # gap - gap(0) = tau (c1 + c2 tau) >= 0 over the whole horizon: first_entry would find no
    # crossing (half the rails a ball is near, it moves away from).
    if gap > 1e3 * MIN_DEPTH and c1 >= 0.0 and c1 + c2 * horizon >= 0.0:
        return math.inf
    tau = first_entry(gap, c1, c2, 0.0, 0.0, horizon, MIN_APPROACH, MIN_DEPTH)
    if tau == math.inf:
        return tau
    if not alongside(rail, x + vx * tau + 0.5 * ax * tau * tau, y + vy * tau + 0.5 * ay * tau * tau):
        return math.inf
    return tau


@helper
def point_time(path, horizon, px, py, reach):
    """Earliest tau at which the centre of the ball on `path` (as in rail_time) comes within
    `reach` of the fixed point (px, py) while approaching: a jaw tip (reach = Rc + its
    radius) or a pocket's opening (reach = its radius)."""
    x, y, vx, vy, ax, ay = path
    return distance_entry(x - px, y - py, vx, vy, ax, ay, reach, horizon)


@helper
def seed(b, nx, ny, radius, params):
    """The report's model (eq. 3.9 and code listing 6): mirror the velocity in the rail, then
    scale the whole velocity by e_c; the ball leaves rolling."""
    vn = b[VX] * nx + b[VY] * ny
    if vn >= 0.0:
        return
    e = params[P_E_C]
    b[VX] = e * (b[VX] - 2.0 * vn * nx)
    b[VY] = e * (b[VY] - 2.0 * vn * ny)
    roll(b, radius)
    b[WZ] = 0.0


@helper
def restitution(b, nx, ny, radius, params):
    """Normal component reversed and scaled by e_c, tangential component and spin kept."""
    vn = b[VX] * nx + b[VY] * ny
    if vn >= 0.0:
        return
    k = (1.0 + params[P_E_C]) * vn
    b[VX] -= k * nx
    b[VY] -= k * ny


@helper
def han2005(b, nx, ny, radius, params, height):
    """Han (2005) cushion: the rail touches the ball above its equator, at height h, so the
    impulse acts along a line tilted by theta = asin(h/R - 1); restitution e_c on the normal
    part, Coulomb friction f_c (stick or slide) on the tangential slip at the contact point.
    (H. Han, "Dynamics in carom and three cushion billiards", J. Mech. Sci. Tech. 19, 2005;
    formulation as summarised by Mathavan et al. 2010 and pooltool's documentation.)

    Frame: x' into the cushion (-n), y' along it (z x x'), z up. The contact point is at
    R (cos th, 0, sin th) from the centre; the normal impulse P_n = (1+e) m vx' cos th, the
    tangential effective inverse mass is 7/(2m). The cloth absorbs the vertical impulse.
    """
    ex, ey = -nx, -ny  # x' axis
    fx, fy = -ey, ex  # y' = z x x'
    vx = b[VX] * ex + b[VY] * ey
    vy = b[VX] * fx + b[VY] * fy
    wx = b[WX] * ex + b[WY] * ey
    wy = b[WX] * fx + b[WY] * fy
    wz = b[WZ]
    sin_t = min(max(height / radius - 1.0, -1.0), 1.0)
    cos_t = math.sqrt(1.0 - sin_t * sin_t)
    approach = vx * cos_t
    if approach <= 0.0:
        return
    e, f = params[P_E_C], params[P_F_C]
    # Tangential slip of the contact point (its two components in the contact plane).
    s1 = vx * sin_t + radius * wy
    s2 = vy + radius * (wz * cos_t - wx * sin_t)
    pn = (1.0 + e) * approach  # per unit mass
    f1, f2 = -s1 / 3.5, -s2 / 3.5  # impulse per unit mass that stops the slip
    s = math.hypot(s1, s2)
    if s > 0.0 and math.hypot(f1, f2) > f * pn:
        f1, f2 = -f * pn * s1 / s, -f * pn * s2 / s
    px = -pn * cos_t + f1 * sin_t
    py = f2
    pz = -pn * sin_t - f1 * cos_t
    k = 2.5 / radius  # R m / I per unit mass
    vx += px
    vy += py
    wx += -k * sin_t * py
    wy += k * (sin_t * px - cos_t * pz)
    wz += k * cos_t * py
    # Cushions push the ball out: with tiny e_c and a high rail the normal speed could stay
    # inward (e_c < tan^2 theta); the rail then absorbs it rather than let the ball sink in.
    if vx > 0.0:
        vx = 0.0
    b[VX] = vx * ex + vy * fx
    b[VY] = vx * ey + vy * fy
    b[WX] = wx * ex + wy * fx
    b[WY] = wx * ey + wy * fy
    b[WZ] = wz


@kernel
def resolve(model, b, nx, ny, radius, params, height):
    """Apply cushion model `model` to a ball touching a cushion with inward normal n, or
    settle it if it is pressed against the cushion (settle.pressed_cushion). A ball rolling
    before a gentle contact is left rolling (motion.reroll)."""
    if pressed_cushion(b, nx, ny, radius, params):
        settle_cushion(b, nx, ny, radius)
        return
    rolled = state_of(b, radius) != SLIDING
    # `model` None is han2005, and numba prunes the other branches before typing (the event
    # engine's core: see engine.run).
    if model is None or model == HAN2005:
        han2005(b, nx, ny, radius, params, height)
    elif model == SEED:
        seed(b, nx, ny, radius, params)
    elif model == RESTITUTION:
        restitution(b, nx, ny, radius, params)
    else:
        mathavan2010(b, nx, ny, radius, params, height)
    if rolled:
        reroll(b, radius, params)


# The orders in which resolve_group tries two or three simultaneous cushion contacts.
_ORDERS2 = ((0, 1), (1, 0))
_ORDERS3 = ((0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0))


@allocating
def resolve_group(model, b, normals, n_c, radius, params, height):
    """A ball meeting n_c (2 or 3) cushions at once, say driven exactly into a corner.

    Contacts in sequence do not commute (friction along one rail is a push into the other),
    so the outcome is the average over every order of resolving them one after the other.
    That does not depend on how the cushions are numbered, so symmetric inputs give
    symmetric outputs (a ball into a corner along its diagonal leaves along it), and as the
    kinetic energy is convex in the velocities, the average has no more energy than the
    orders, none of which gains any.
    """
    start = np.zeros(ROW_WIDTH)
    copy_row(start, b)
    acc = np.zeros(ROW_WIDTH)
    trial = np.zeros(ROW_WIDTH)
    n_orders = 2 if n_c == 2 else 6
    for o in range(n_orders):
        copy_row(trial, start)
        for m in range(n_c):
            c = _ORDERS2[o][m] if n_c == 2 else _ORDERS3[o][m]
            resolve(model, trial, normals[c, 0], normals[c, 1], radius, params, height)
        acc += trial
    for k in range(b.shape[0]):  # a row of ROW_WIDTH, or its first columns (a test's row)
        b[k] = acc[k] / n_orders
