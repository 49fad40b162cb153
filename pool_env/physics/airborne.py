"""Airborne balls: their contacts in flight (balls, cushion noses, jaw tips), landing, bouncing, leaving the table.

The engine reaches this module only for a ball in the AIRBORNE state (predict.predict,
engine._resolve and _resolve_cushions test the state), and only in the full engine: a scene
with every ball on the cloth (and the core collision models) runs the core engine, in which
those branches are pruned before typing (see engine.run), so it neither compiles nor runs any of it
(`airborne_predictions` in Result.stats counts what it predicts). A ball in flight moves as motion.py says: xy
linear, its centre's height z above its resting height quadratic under g, spin constant.

- The slate (`table_impulse`): a ball meeting it at vz < 0 takes a normal impulse that
  leaves it rising at e_t |vz|, and a friction impulse against the slip of its contact
  point, at most mu_t times the normal impulse and never more than stops the slip (TP A-14's
  friction model, applied to the slate: D. G. Alciatore, technical proof A-14; pooltool's
  FrictionalInelasticTable is the same model). A rebound lower than BOUNCE_STOP_HEIGHT
  ends the bouncing: the ball stays on the cloth.
- Landing (the AIRBORNE state's transition, `land`): at z = 0 the ball bounces; landing with
  its centre over a pocket's opening drops it (a "ball_pocket" event), landing off the
  playing area (the rails' rectangle and the pockets' throats) puts it off the table.
- Cushions: a rail's or a facing's nose is an edge at height h (the cushion height for the
  models that touch at the nose, else the equator: the edge consistent with the ball's
  cushion reach Rc, h - R = sqrt(R^2 - Rc^2)). A ball touches it when its centre is R from
  the edge line: s^2 + (z - (h - R))^2 = R^2 with s the centre's horizontal distance in
  front of the nose line, a quartic in time (s linear, z quadratic). The rebound is
  frictionless, restitution e_c along that 3D normal. A ball whose centre crosses the nose
  line (alongside the segment) with its bottom above the edge clears the cushion: it leaves
  the table there ("ball_off_table", j the rail's row; the rail's top and what lies beyond
  are not modelled). A jaw tip is a sphere of its radius r_tip at the nose height (so its
  rim meets the nose edges' ends): met when the centres are R + r_tip apart (a quartic).
- Balls: two balls meet when their centres are R_i + R_j apart in 3D (a quartic). The
  impulse is frictionless, restitution e_b along the 3D normal; a ball on the cloth that it
  would push down into the slate is held by it: its vertical velocity stays 0, so its
  inverse mass along the normal n is (1 - n_z^2) / m (the slate takes the downward part of
  the impulse and does no work). A ball it pushes up leaves the cloth.
"""

import math

import numpy as np

from .geometry import along_rail, rail_gap
from .jit import helper, kernel
from .kinds import (
    AIRBORNE,
    BALL_BALL,
    BALL_OFF_TABLE,
    BALL_POCKET,
    BALL_TABLE,
    C_AIR,
    NO_EVENT,
    POCKETED,
    T0,
    VX,
    VY,
    VZ,
    WX,
    WY,
    WZ,
    X,
    Y,
    Z,
)
from .motion import P_E_B, P_E_C, P_E_T, P_G, P_MU_T, copy_row, slip, state_at, trajectory
from .placement import on_playing_area
from .roots import first_entry
from .tolerances import BOUNCE_STOP_HEIGHT, CONTACT_TOLERANCE, GENTLE_TIME, MIN_APPROACH, MIN_DEPTH


@kernel
def table_impulse(row, radius, params):
    """The slate's impulse on a ball at z = 0 moving down (row updated in place; nothing if
    vz >= 0). Normal: vz -> -e_t vz, an impulse (1 + e_t) |vz| per unit mass. Friction: the
    contact point's slip u (motion.slip) changes by 7/2 of the tangential impulse per unit
    mass (translation plus the spin its moment about the centre gives, I = 2/5 m R^2), so
    the impulse is min(mu_t (1 + e_t) |vz|, 2/7 |u|) against u. A rebound below
    BOUNCE_STOP_HEIGHT is no bounce: vz = 0."""
    row[Z] = 0.0
    vz = row[VZ]
    if vz >= 0.0:
        return
    pn = -(1.0 + params[P_E_T]) * vz
    row[VZ] = -params[P_E_T] * vz
    ux, uy = slip(row[VX], row[VY], row[WX], row[WY], radius)
    un = math.hypot(ux, uy)
    if un > 0.0:
        j = min(params[P_MU_T] * pn, un / 3.5)
        row[VX] -= j * ux / un
        row[VY] -= j * uy / un
        k = 2.5 * j / (radius * un)  # (-R z) x (-j u_hat) / (2/5 R^2), per unit mass
        row[WX] -= k * uy
        row[WY] += k * ux
    if row[VZ] * row[VZ] < 2.0 * params[P_G] * BOUNCE_STOP_HEIGHT:
        row[VZ] = 0.0


@kernel
def edge_offset(radius, reach, height):
    """The nose edge's height above a resting ball's centre (m): consistent with the ball's
    cushion reach, h - R = +-sqrt(R^2 - Rc^2) (0 for a wall at the equator, Rc = R)."""
    off = math.sqrt(max(radius * radius - reach * reach, 0.0))
    return off if height >= radius else -off


@helper
def _height(row, state, tau, g):
    """A ball's z, vz after tau seconds (0 for a ball on the cloth)."""
    if state != AIRBORNE:
        return 0.0, 0.0, 0.0
    return row[Z] + (row[VZ] - 0.5 * g * tau) * tau, row[VZ] - g * tau, -g


@helper
def pair_time(S, st, R, params, t_tr, i, k, now, counters):
    """Absolute time at which balls i and k (one at least airborne) first touch in 3D, or
    inf; predict.pair_time's arguments. |d|^2 - (R_i + R_k)^2 with d the 3D offset of the
    centres (each at height R + z) is a quartic: geometry.distance_entry's, one dimension more."""
    if st[i] == POCKETED or st[k] == POCKETED:
        return np.inf
    counters[C_AIR] += 1
    horizon = max(min(t_tr[i], t_tr[k]) - now, 0.0)
    g = params[P_G]
    xi, yi, vxi, vyi, axi, ayi = trajectory(S[i], st[i], now, R[i], params)
    xk, yk, vxk, vyk, axk, ayk = trajectory(S[k], st[k], now, R[k], params)
    zi, vzi, azi = _height(S[i], st[i], now - S[i, T0], g)
    zk, vzk, azk = _height(S[k], st[k], now - S[k, T0], g)
    d = (xk - xi, yk - yi, (R[k] + zk) - (R[i] + zi))
    dv = (vxk - vxi, vyk - vyi, vzk - vzi)
    h = (0.5 * (axk - axi), 0.5 * (ayk - ayi), 0.5 * (azk - azi))
    return now + _entry3(d, dv, h, R[i] + R[k], horizon)


@helper
def _entry3(d, dv, h, reach, horizon):
    """First tau in [0, horizon] at which |d + dv tau + h tau^2| falls to `reach` while
    approaching (3-vectors as tuples), inf if never: roots.first_entry on the quartic."""
    c4 = h[0] * h[0] + h[1] * h[1] + h[2] * h[2]
    c3 = 2.0 * (h[0] * dv[0] + h[1] * dv[1] + h[2] * dv[2])
    c2 = dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2] + 2.0 * (h[0] * d[0] + h[1] * d[1] + h[2] * d[2])
    c1 = 2.0 * (dv[0] * d[0] + dv[1] * d[1] + dv[2] * d[2])
    dist = math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
    c0 = (dist - reach) * (dist + reach)
    return first_entry(c0, c1, c2, c3, c4, horizon, 2.0 * reach * MIN_APPROACH, 2.0 * reach * MIN_DEPTH)


@helper
def _alongside_span(rail, here, horizon):
    """The times (lo, hi) within [0, horizon] while a centre moving at here = (x, y, vx, vy,
    ...) projects onto the rail segment (lo > hi if never): along_rail is linear in time."""
    x, y, vx, vy = here[0], here[1], here[2], here[3]
    u0 = along_rail(rail, x, y)
    dx, dy = rail[2] - rail[0], rail[3] - rail[1]
    u1 = (vx * dx + vy * dy) / (dx * dx + dy * dy)
    if u1 == 0.0:
        return (0.0, horizon) if 0.0 <= u0 <= 1.0 else (1.0, 0.0)
    lo, hi = -u0 / u1, (1.0 - u0) / u1
    if lo > hi:
        lo, hi = hi, lo
    return max(lo, 0.0), min(hi, horizon)


@helper
def _rail_entry(here, r, off, rail, horizon, g):
    """(tau, over) for an airborne ball at here = (x, y, vx, vy, z, vz) and one rail or
    facing: tau the first touch of its nose edge, or crossing of its nose line, while the
    centre is alongside the segment, within horizon (inf if neither); over is True for a
    crossing clear of the edge. Coming alongside past the segment's end already within R
    of the edge's line is no touch (the end is a jaw tip's, or a pocket's opening)."""
    x, y, vx, vy, z, vz = here
    s0 = rail_gap(rail, x, y, 0.0)
    s1 = rail[4] * vx + rail[5] * vy
    if s0 + min(s1, 0.0) * horizon > r:  # never within R of its line
        return np.inf, False
    lo, hi = _alongside_span(rail, here, horizon)
    sa = s0 + s1 * lo
    if lo > hi or sa < 0.0:  # never alongside, or behind it when alongside (a facing's line runs on)
        return np.inf, False
    # Touching the edge from lo on: s^2 + (z - off)^2 - R^2, s = sa + s1 tau, z - off = d0 + d1 tau + d2 tau^2.
    d0, d1, d2 = z + (vz - 0.5 * g * lo) * lo - off, vz - g * lo, -0.5 * g
    dist = math.hypot(sa, d0)
    tau = np.inf
    if lo == 0.0 or dist > r:
        tau = lo + first_entry((dist - r) * (dist + r), 2.0 * (sa * s1 + d0 * d1), s1 * s1 + d1 * d1 + 2.0 * d0 * d2,
                               2.0 * d1 * d2, d2 * d2, hi - lo, 2.0 * r * MIN_APPROACH, 2.0 * r * MIN_DEPTH)
        if s0 + s1 * tau < 0.0:
            tau = np.inf
    if s1 < 0.0:
        cross = -s0 / s1
        if cross < tau and lo <= cross <= hi:
            return cross, True
    return tau, False


@helper
def _jaw_entry(here, r, off, jaw, horizon, g):
    """First tau at which an airborne ball at here = (x, y, vx, vy, z, vz) meets a jaw tip
    [x, y, r_tip], taken as a sphere of radius r_tip centred on the tip's axis at the nose
    edge's height (R + off above the cloth): its rim reaches the nose edge's end, so a ball
    coming round a segment's end meets it first; inf if never."""
    x, y, vx, vy, z, vz = here
    return _entry3((x - jaw[0], y - jaw[1], z - off), (vx, vy, vz), (0.0, 0.0, -0.5 * g), r + jaw[2], horizon)


@helper
def _landing(bounds, x, y, reach):
    """Where a ball landing at (x, y) goes: (pocket id, True) over an opening, (-1, True) off
    the playing area or into a cushion, (-1, False) on the cloth."""
    pockets = bounds.pockets
    for k in range(pockets.shape[0]):
        if math.hypot(x - pockets[k, 0], y - pockets[k, 1]) < pockets[k, 2]:
            return k, True
    if not on_playing_area(x, y, bounds):
        return -1, True
    jaws = bounds.jaws
    for p in range(jaws.shape[0]):
        if math.hypot(x - jaws[p, 0], y - jaws[p, 1]) < reach + jaws[p, 2] - CONTACT_TOLERANCE:
            return -1, True
    return -1, False


@helper
def boundary_times(scene, bounds, sched, i, now, counters):
    """An airborne ball's next cushion contact (sched.t_cu, cu_id: rails by row, jaw tips
    after them) and its next drop (sched.t_po, po_id: a pocket id k < P for landing over
    opening k; P + c for leaving over rail c, P + the number of rails for landing off the
    bed). Its landing is its transition (sched.t_tr, motion.transition_time)."""
    S, params, r, rc = scene.S, scene.params, scene.R[i], scene.Rc[i]
    counters[C_AIR] += 1
    row, g = S[i], params[P_G]
    horizon = max(sched.t_tr[i] - now, 0.0)
    tau0 = now - row[T0]
    # The ball at now (its row holds from its own t0).
    x0, y0 = row[X] + row[VX] * tau0, row[Y] + row[VY] * tau0
    z0, vz0, _ = _height(row, AIRBORNE, tau0, g)
    off = edge_offset(r, rc, bounds.height)
    n_rails, n_pockets = bounds.rails.shape[0], bounds.pockets.shape[0]
    t_cu, cu, t_po, po = np.inf, -1, np.inf, -1
    here = (x0, y0, row[VX], row[VY], z0, vz0)
    for c in range(n_rails):
        tau, over = _rail_entry(here, r, off, bounds.rails[c], horizon, g)
        if over and now + tau < t_po:
            t_po, po = now + tau, n_pockets + c
        elif not over and now + tau < t_cu:
            t_cu, cu = now + tau, c
    for p in range(bounds.jaws.shape[0]):
        tau = _jaw_entry(here, r, off, bounds.jaws[p], horizon, g)
        if now + tau < t_cu:
            t_cu, cu = now + tau, n_rails + p
    if sched.t_tr[i] < np.inf:
        k, gone = _landing(bounds, x0 + row[VX] * horizon, y0 + row[VY] * horizon, rc)
        if gone and sched.t_tr[i] <= t_po:
            t_po, po = sched.t_tr[i], (k if k >= 0 else n_pockets + n_rails)
    sched.t_cu[i], sched.cu_id[i], sched.t_po[i], sched.po_id[i] = t_cu, cu, t_po, po


@kernel
def land(row, radius, params):
    """An airborne ball reaching the slate (row at the landing): the table's impulse; it bounces
    on (still airborne) or stays on the cloth. Returns the event kind."""
    table_impulse(row, radius, params)
    return BALL_TABLE


@helper
def drop(row, po, bounds):
    """An airborne ball leaving the play at the drop boundary_times predicted (po_id `po`):
    it stops where it is; returns (event kind, j): ("ball_pocket", the pocket) landing over
    an opening, else ("ball_off_table", the rail it cleared, or -1 landing off the bed)."""
    row[VX] = row[VY] = row[WX] = row[WY] = row[WZ] = row[VZ] = 0.0
    row[Z] = 0.0
    n_pockets = bounds.pockets.shape[0]
    if po < n_pockets:
        return BALL_POCKET, po
    c = po - n_pockets
    return BALL_OFF_TABLE, (c if c < bounds.rails.shape[0] else -1)


@helper
def _cushion_normal(row, radius, reach, bounds, c):
    """The unit 3D normal from cushion c (a rail's or a facing's nose edge by row, else a jaw
    tip's sphere) to the centre of a ball touching it (row at the contact)."""
    n_rails = bounds.rails.shape[0]
    off = edge_offset(radius, reach, bounds.height)
    if c < n_rails:
        rail = bounds.rails[c]
        s = rail_gap(rail, row[X], row[Y], 0.0)
        nx, ny, nz = s * rail[4], s * rail[5], row[Z] - off
    else:
        jaw = bounds.jaws[c - n_rails]
        nx, ny, nz = row[X] - jaw[0], row[Y] - jaw[1], row[Z] - off
    norm = math.sqrt(nx * nx + ny * ny + nz * nz)
    return nx / norm, ny / norm, nz / norm


@helper
def cushion_bounce(row, radius, reach, params, bounds, c):
    """An airborne ball (row at the contact) touching cushion c: restitution e_c along the 3D
    normal from the edge (or the tip's sphere) to the centre, no friction, spin kept."""
    nx, ny, nz = _cushion_normal(row, radius, reach, bounds, c)
    vn = row[VX] * nx + row[VY] * ny + row[VZ] * nz
    if vn >= 0.0:
        return
    k = (1.0 + params[P_E_C]) * vn
    row[VX] -= k * nx
    row[VY] -= k * ny
    row[VZ] -= k * nz


@helper
def perch(scene, bounds, work, now, i, c):
    """Whether airborne ball i, meeting cushion c at `now` from above, stays on the rail: its
    rebound along the normal n would rise less than BOUNCE_STOP_HEIGHT against gravity's part
    g n_z (WPA: a ball that comes to rest other than on the bed is off the table; the rail's
    top is not modelled, and balls bouncing ever lower on a nose would never end). If so it
    is stopped there and marked off the table (the caller records "ball_off_table", j = c)."""
    S, st, R, params = scene.S, scene.st, scene.R, scene.params
    state_at(S[i], st[i], now, R[i], params, work.row)
    nx, ny, nz = _cushion_normal(work.row, R[i], scene.Rc[i], bounds, c)
    vn = params[P_E_C] * (work.row[VX] * nx + work.row[VY] * ny + work.row[VZ] * nz)
    if nz <= 0.0 or vn * vn >= 2.0 * params[P_G] * nz * BOUNCE_STOP_HEIGHT:
        return False
    copy_row(S[i], work.row)
    drop(S[i], np.int64(0), bounds)
    st[i] = POCKETED
    work.touched[0] = i
    work.rec_a[0], work.rec_b[0] = i, c
    return True


@helper
def _inverse_mass(state, mass, nz, pushed_down):
    """A ball's inverse mass along the contact normal (unit, vertical part nz): 1/m in
    flight; on the cloth and pushed down, (1 - nz^2)/m (the slate holds it up)."""
    if state != AIRBORNE and pushed_down:
        return (1.0 - nz * nz) / mass
    return 1.0 / mass


@helper
def _kick(b, state, jn, mass, n, pushed_down):
    """Impulse jn along n (3-vector) on ball b; the vertical part dropped for a ball on the
    cloth pushed down (the slate takes it)."""
    b[VX] += jn * n[0] / mass
    b[VY] += jn * n[1] / mass
    if not (state != AIRBORNE and pushed_down):
        b[VZ] += jn * n[2] / mass


@helper
def resolve_pair(scene, work, now, bi, bj):
    """Balls bi and bj touching in 3D at `now` (one at least airborne): both brought to now,
    then the frictionless impulse with restitution e_b along the line of centres (the module
    docstring). Returns what contacts.resolve_ball_ball does: (kind, pairs, balls, False)."""
    S, st, R, M, params = scene.S, scene.st, scene.R, scene.M, scene.params
    work.touched[0], work.touched[1] = bi, bj
    work.rec_a[0], work.rec_b[0] = bi, bj
    for b in (bi, bj):
        state_at(S[b], st[b], now, R[b], params, work.row)
        copy_row(S[b], work.row)
    a, b = S[bi], S[bj]
    n = (b[X] - a[X], b[Y] - a[Y], (R[bj] + b[Z]) - (R[bi] + a[Z]))
    d = math.sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2])
    n = (n[0] / d, n[1] / d, n[2] / d)
    vn = (b[VX] - a[VX]) * n[0] + (b[VY] - a[VY]) * n[1] + (b[VZ] - a[VZ]) * n[2]
    if vn < 0.0:
        # bi takes -jn n (pushed down if n_z > 0), bj takes +jn n (pushed down if n_z < 0).
        inv = _inverse_mass(st[bi], M[bi], n[2], n[2] > 0.0) + _inverse_mass(st[bj], M[bj], n[2], n[2] < 0.0)
        jn = -(1.0 + params[P_E_B]) * vn / inv
        _kick(a, st[bi], -jn, M[bi], n, n[2] > 0.0)
        _kick(b, st[bj], jn, M[bj], n, n[2] < 0.0)
    if _perched(st[bi], st[bj], n[2], -vn * params[P_E_B], params[P_G]):
        return NO_EVENT, np.int64(0), np.int64(0), False
    return BALL_BALL, np.int64(1), np.int64(2), False


@helper
def _perched(st_i, st_j, nz, rebound, g):
    """Whether a ball in the air has come to rest on top of a ball on the cloth: it sits on
    the upper side (its normal's vertical part nz, from the lower ball's centre, > 0) and
    gravity's part g nz would bring its rebound along the normal back within GENTLE_TIME
    (bounces shrinking towards rest; a rebound that is small only because the lower ball
    was knocked back into it at once is not this). On a convex ball it would roll off, a
    constrained motion the engine does not model (engine.run stops with PERCHED: simulate
    raises NotModelledError)."""
    if st_i == AIRBORNE and st_j != AIRBORNE:
        up = -nz  # bi above bj when the normal from bi to bj points down
    elif st_j == AIRBORNE and st_i != AIRBORNE:
        up = nz
    else:
        return False
    return up > 0.0 and 2.0 * rebound < g * up * GENTLE_TIME
