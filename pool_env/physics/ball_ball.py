"""Ball-ball events: when two balls meet, and what each collision model does to them.

Every model is a small function taking the two balls' state rows at contact (updated in
place), the unit normal n from ball i to ball j, radii, masses and the coefficients; the
engine picks one by its id (`BALL_BALL_MODELS` in config.py gives the names).
"""

import math

import numpy as np

from .config import BALL_BALL_MODELS
from .geometry import roll
from .jit import allocating_helper, helper, kernel
from .kinds import SLIDING, VX, VY, WX, WY, WZ, X, Y
from .motion import P_E_B, is_gentle, reroll, state_of
from .settle import pressed, settle
from .tolerances import GROUP_SWEEPS, GROUP_TOL, PARALLEL_SINE

# The model ids `resolve` dispatches on: each model's position in config.BALL_BALL_MODELS.
SEED, ELASTIC, FRICTIONAL = (BALL_BALL_MODELS.index(name) for name in ("seed", "elastic", "frictional"))

# Alciatore's fit of ball-ball friction against the sliding speed at the contact point,
# mu(v) = a + b exp(-c v) with v in m/s (D. G. Alciatore, "Throw" technical proof TP A-14,
# from Marlow's measurements).
ALCIATORE_A, ALCIATORE_B, ALCIATORE_C = 9.951e-3, 0.108, 1.088


@helper
def _normal_impulse(bi, bj, nx, ny, mi, mj, e):
    """Apply the restitution impulse along n; returns its magnitude (0 if not approaching)."""
    approach = (bi[VX] - bj[VX]) * nx + (bi[VY] - bj[VY]) * ny
    if approach <= 0.0:
        return 0.0
    jn = (1.0 + e) * approach * mi * mj / (mi + mj)
    bi[VX] -= jn / mi * nx
    bi[VY] -= jn / mi * ny
    bj[VX] += jn / mj * nx
    bj[VY] += jn / mj * ny
    return jn


@helper
def seed(bi, bj, nx, ny, ri, rj, mi, mj, params):
    """The report's model (its eq. 3.4 and code listing 5): normal components exchanged by the
    1-D elastic formula, then scaled by e; tangential components kept; no spin transfer, and
    both balls leave rolling (the report's stated simplification)."""
    e = params[P_E_B]
    vi_n = bi[VX] * nx + bi[VY] * ny
    vj_n = bj[VX] * nx + bj[VY] * ny
    if vi_n - vj_n <= 0.0:
        return
    vi_n_after = e * (vi_n * (mi - mj) + 2.0 * mj * vj_n) / (mi + mj)
    vj_n_after = e * (vj_n * (mj - mi) + 2.0 * mi * vi_n) / (mi + mj)
    bi[VX] += (vi_n_after - vi_n) * nx
    bi[VY] += (vi_n_after - vi_n) * ny
    bj[VX] += (vj_n_after - vj_n) * nx
    bj[VY] += (vj_n_after - vj_n) * ny
    _roll(bi, ri)
    _roll(bj, rj)


@helper
def _roll(b, r):
    """Set the spin of a ball to rolling without slipping at its current velocity."""
    roll(b, r)
    b[WZ] = 0.0


@helper
def elastic(bi, bj, nx, ny, ri, rj, mi, mj, params):
    """Frictionless contact: restitution e_b along the line of centres, spins untouched."""
    _normal_impulse(bi, bj, nx, ny, mi, mj, params[P_E_B])


@helper
def frictional(bi, bj, nx, ny, ri, rj, mi, mj, params):
    """Restitution e_b along n plus Coulomb friction at the contact point with Alciatore's
    speed-dependent coefficient: gives cut-induced throw and spin transfer.

    The friction impulse P = (P_t, P_z) acts on ball i in the contact plane (t = z x n, and
    z), -P on ball j, at the contact point R n from i's centre (-R n from j's). A unit impulse
    along t moves a ball's contact point by 1/m (translation) plus R^2/I = 5/(2m) (spin), so
    the slip s_t changes by k_t = 7/2 (1/mi + 1/mj). Along z, the ball pushed down is held by
    the cloth, whose reaction cancels its vertical translation: spin only, 5/(2m). The ball
    pushed up is not held (the cloth cannot pull it down): 1/m + 5/(2m) = 7/(2m). P_z opposes
    s_z, so s_z < 0 pushes ball i up, k_z = 7/(2 mi) + 5/(2 mj), and s_z > 0 ball j,
    k_z = 5/(2 mi) + 7/(2 mj) (6/m for equal masses). The lifted ball's small vertical speed,
    P_z / m, is not kept: the engine is planar and the ball drops back at once. If the impulse
    that stops the slip, (s_t/k_t, s_z/k_z), is within mu * J_n the surfaces stick; otherwise
    they slide with |P| = mu * J_n against the slip. Both branches dissipate energy (see
    docs/physics.md).
    """
    jn = _normal_impulse(bi, bj, nx, ny, mi, mj, params[P_E_B])
    if jn == 0.0:
        return
    p_t, p_z = _friction(bi, bj, nx, ny, ri, rj, mi, mj, jn, 1.0)
    _apply_friction(bi, bj, nx, ny, ri, rj, mi, mj, p_t, p_z)


@helper
def _friction(bi, bj, nx, ny, ri, rj, mi, mj, jn, alpha):
    """The friction impulse (P_t, P_z) on ball i for normal impulse jn (see `frictional`),
    with the effective inverse masses scaled by alpha >= 1 (1 for a lone contact)."""
    tx, ty = -ny, nx
    # Slip of i's surface over j's at the contact point (the normal impulse leaves it alone).
    s_t = (bi[VX] - bj[VX]) * tx + (bi[VY] - bj[VY]) * ty + ri * bi[WZ] + rj * bj[WZ]
    s_z = ri * (bi[WX] * ny - bi[WY] * nx) + rj * (bj[WX] * ny - bj[WY] * nx)
    s = math.hypot(s_t, s_z)
    if s == 0.0:
        return 0.0, 0.0
    inv_i, inv_j = alpha / mi, alpha / mj
    k_t = 3.5 * (inv_i + inv_j)
    if s_z < 0.0:  # P_z > 0 lifts ball i; the cloth holds j down
        k_z = 3.5 * inv_i + 2.5 * inv_j
    else:  # P_z <= 0 lifts ball j (or there is no vertical slip)
        k_z = 2.5 * inv_i + 3.5 * inv_j
    mu = ALCIATORE_A + ALCIATORE_B * math.exp(-ALCIATORE_C * s)
    p_t, p_z = -s_t / k_t, -s_z / k_z
    if math.hypot(p_t, p_z) > mu * jn:
        p_t, p_z = -mu * jn * s_t / s, -mu * jn * s_z / s
    return p_t, p_z


@helper
def _apply_friction(bi, bj, nx, ny, ri, rj, mi, mj, p_t, p_z):
    # Ball i: dv = P_t t / m, dw = R (P_t z - P_z t) / I; ball j gets the opposite impulse
    # at -R n, which turns its spin the same way.
    tx, ty = -ny, nx
    ii = 0.4 * mi * ri * ri
    ij = 0.4 * mj * rj * rj
    bi[VX] += p_t * tx / mi
    bi[VY] += p_t * ty / mi
    bj[VX] -= p_t * tx / mj
    bj[VY] -= p_t * ty / mj
    _spin_kick(bi, ri / ii, p_t, p_z, tx, ty)
    _spin_kick(bj, rj / ij, p_t, p_z, tx, ty)


@helper
def _spin_kick(b, r_over_i, p_t, p_z, tx, ty):
    """dw = (R / I) (P_t z - P_z t): the friction impulse's moment about the centre."""
    b[WX] -= r_over_i * p_z * tx
    b[WY] -= r_over_i * p_z * ty
    b[WZ] += r_over_i * p_t


@kernel
def resolve(model, bi, bj, ri, rj, mi, mj, params):
    """Apply ball-ball model `model` to two touching balls (rows at the contact time), or
    settle them if the contact is a pressed one (settle.pressed). A ball rolling before a
    gentle contact is left rolling (motion.reroll). True if the cloth took part (a settle or
    a reroll): momentum is then not conserved at this instant."""
    dx, dy = bj[X] - bi[X], bj[Y] - bi[Y]
    d = math.hypot(dx, dy)
    nx, ny = dx / d, dy / d
    if pressed(bi, bj, nx, ny, ri, rj, params):
        settle(bi, bj, nx, ny, ri, rj, mi, mj, params, ri + rj - d)
        return True
    rolled_i = state_of(bi, ri) != SLIDING
    rolled_j = state_of(bj, rj) != SLIDING
    # `model` None is frictional, and numba prunes the other branches before typing (the
    # event engine's core: see engine.run).
    if model is None or model == FRICTIONAL:
        frictional(bi, bj, nx, ny, ri, rj, mi, mj, params)
    elif model == SEED:
        seed(bi, bj, nx, ny, ri, rj, mi, mj, params)
    else:
        elastic(bi, bj, nx, ny, ri, rj, mi, mj, params)
    cloth = False
    if rolled_i:
        cloth = reroll(bi, ri, params) or cloth
    if rolled_j:
        cloth = reroll(bj, rj, params) or cloth
    return cloth



@allocating_helper
def resolve_group(model, S, R, M, params, pairs, n_c, e, normal_only, n_walls):
    """Resolve the contacts c = (pairs.ca[c], pairs.cb[c]), c < n_c, all at once (rows of S
    at the contact time); pairs.impulse[c] gets each contact's normal impulse. True if the
    cloth or a cushion took part (a gentle contact left a rolling ball rolling, a cushion
    pushed back). The first n_walls cushions in pairs.walls (inward normals, touched by ball
    pairs.wall_ball[w]) join as contacts with an immovable partner: a cluster wedged against
    a rail solved without it bounces off it and is pushed back in at one instant, without end.

    Normal impulses follow Poisson's hypothesis for simultaneous impacts: the compression
    impulses P_c >= 0 are the least change of the velocities (in the kinetic-energy metric)
    that leaves no contact approaching, the unique projection of the velocities onto the cone
    {every contact separating or resting}; restitution then adds e times the same change.
    This conserves momentum, changes the kinetic energy by -(1 - e^2)/2 P.W.P <= 0, does not
    depend on the order of the contacts (symmetric inputs give symmetric outputs), and for one
    contact is the ordinary restitution impulse. Projected Gauss-Seidel finds P.

    Then, unless normal_only: `frictional` adds each contact's friction impulse, computed
    from the same post-impact state with the effective inverse masses scaled by alpha_c, the
    larger number of group contacts on either of its balls; that bounds the group's energy
    change by the sum of the single-contact changes, each non-positive, so friction never
    adds energy however the contacts share balls. `seed` exchanges normal velocities
    elastically, scales each ball's velocity along its contact normals by e_b, and leaves
    every ball rolling, as for one contact.
    """
    n = S.shape[0]
    ca, cb = pairs.ca, pairs.cb
    nx = np.empty(n_c)
    ny = np.empty(n_c)
    deg = np.zeros(n, dtype=np.int64)
    for c in range(n_c):
        a, b = ca[c], cb[c]
        dx, dy = S[b, X] - S[a, X], S[b, Y] - S[a, Y]
        d = math.hypot(dx, dy)
        nx[c], ny[c] = dx / d, dy / d
        deg[a] += 1
        deg[b] += 1
    v0x = S[:, VX].copy()
    v0y = S[:, VY].copy()
    rolled = np.zeros(n, dtype=np.bool_)
    for k in range(n):
        rolled[k] = deg[k] > 0 and state_of(S[k], R[k]) != SLIDING
    # A rolling ball that a gentle group impulse would set sliding answers it as rolling
    # instead (5/7 of the velocity change, spin kept rolling: motion.reroll, inside the solve,
    # so that the velocities found still leave no contact approaching). Found by solving
    # once with every ball sliding, then again with the gentle ones rolling.
    response = np.ones(n)
    p = np.zeros(n_c + n_walls)
    _poisson(S, M, pairs, n_c, nx, ny, deg, response, p, n_walls)
    gentle = False
    for k in range(n):
        if rolled[k] and is_gentle(S[k], R[k], params):
            response[k] = 5.0 / 7.0
            gentle = True
    if gentle:
        for k in range(n):
            S[k, VX], S[k, VY] = v0x[k], v0y[k]
        p[:] = 0.0
        _poisson(S, M, pairs, n_c, nx, ny, deg, response, p, n_walls)
    restitution = 1.0 if (model is not None and model == SEED and not normal_only) else e  # None: see resolve
    for k in range(n):
        if deg[k] > 0:
            S[k, VX] += restitution * (S[k, VX] - v0x[k])
            S[k, VY] += restitution * (S[k, VY] - v0y[k])
            if response[k] != 1.0:
                roll(S[k], R[k])
    for c in range(n_c):
        pairs.impulse[c] = (1.0 + restitution) * p[c]
    if model is not None and model == SEED and not normal_only:
        _seed_group(S, R, pairs, n_c, e, nx, ny, deg)
    elif (model is None or model == FRICTIONAL) and not normal_only:
        _friction_group(S, R, M, pairs, n_c, nx, ny, deg)
    cloth = gentle
    for w in range(n_walls):
        cloth = cloth or p[n_c + w] > 0.0
    for k in range(n):
        if rolled[k]:
            cloth = reroll(S[k], R[k], params) or cloth
    return cloth


@helper
def _poisson(S, M, pairs, n_c, nx, ny, deg, response, p, n_walls):
    """Projected Gauss-Seidel for the compression impulses p >= 0 (see resolve_group), the
    n_walls cushion contacts' in p[n_c:]; ball k's velocity answers an impulse J with
    response[k] J / M[k]."""
    ca, cb, walls = pairs.ca, pairs.cb, pairs.walls
    scale = 0.0
    for k in range(S.shape[0]):
        if deg[k] > 0:
            scale = max(scale, math.hypot(S[k, VX], S[k, VY]))
    for _ in range(GROUP_SWEEPS):
        change = 0.0
        for c in range(n_c):
            a, b = ca[c], cb[c]
            ka, kb = response[a] / M[a], response[b] / M[b]
            u = (S[b, VX] - S[a, VX]) * nx[c] + (S[b, VY] - S[a, VY]) * ny[c]
            new = max(0.0, p[c] - u / (ka + kb))
            dp = new - p[c]
            if dp != 0.0:
                p[c] = new
                S[a, VX] -= dp * nx[c] * ka
                S[a, VY] -= dp * ny[c] * ka
                S[b, VX] += dp * nx[c] * kb
                S[b, VY] += dp * ny[c] * kb
                change = max(change, abs(dp) * (ka + kb))
        for w in range(n_walls):
            k = pairs.wall_ball[w]
            kk = response[k] / M[k]
            u = S[k, VX] * walls[w, 0] + S[k, VY] * walls[w, 1]
            new = max(0.0, p[n_c + w] - u / kk)
            dp = new - p[n_c + w]
            if dp != 0.0:
                p[n_c + w] = new
                S[k, VX] += dp * walls[w, 0] * kk
                S[k, VY] += dp * walls[w, 1] * kk
                change = max(change, abs(dp) * kk)
        if change <= GROUP_TOL * scale:
            return


@helper
def _seed_group(S, R, pairs, n_c, e, nx, ny, deg):
    """The seed model's part of resolve_group (after the elastic normal impulses): each
    ball's velocity along its contact normals scaled by e, then the ball left rolling."""
    for k in range(S.shape[0]):
        if deg[k] == 0:
            continue
        # The span of k's contact normals: one direction, or (two that differ) the plane.
        mx, my, spread = 0.0, 0.0, False
        for c in range(n_c):
            if pairs.ca[c] == k or pairs.cb[c] == k:
                if mx == 0.0 and my == 0.0:
                    mx, my = nx[c], ny[c]
                elif abs(mx * ny[c] - my * nx[c]) > PARALLEL_SINE:
                    spread = True
        if spread:
            S[k, VX] *= e
            S[k, VY] *= e
        else:
            vn = S[k, VX] * mx + S[k, VY] * my
            S[k, VX] -= (1.0 - e) * vn * mx
            S[k, VY] -= (1.0 - e) * vn * my
        _roll(S[k], R[k])


@allocating_helper
def _friction_group(S, R, M, pairs, n_c, nx, ny, deg):
    """The frictional model's part of resolve_group: every contact's friction impulse from
    the same post-impact state (inverse masses scaled by the contact's larger degree)."""
    ca, cb = pairs.ca, pairs.cb
    pt = np.empty(n_c)
    pz = np.empty(n_c)
    for c in range(n_c):
        a, b = ca[c], cb[c]
        pt[c], pz[c] = _friction(S[a], S[b], nx[c], ny[c], R[a], R[b], M[a], M[b], pairs.impulse[c],
                                 float(max(deg[a], deg[b])))
    for c in range(n_c):
        a, b = ca[c], cb[c]
        _apply_friction(S[a], S[b], nx[c], ny[c], R[a], R[b], M[a], M[b], pt[c], pz[c])
