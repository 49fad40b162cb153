"""Pressed contacts: touching balls (or a ball and a cushion) pushed together, and how they resolve.

Between events each ball moves under constant friction, so two touching balls can be
pressed together with no approach speed at all (a ball spun into another, a faster rolling
ball behind a slower one, a ball spinning into a rail), or close in a train of ever smaller
bounces. Real balls then push each other along; the push has no closed form, and bouncing
would take endless events. roots.first_entry finds such a contact once the pair has sunk
ball_ball.MIN_DEPTH (0.1 nm) into each other, and `pressed` tells it from a collision: the
accelerations press the pair together and a bounce at the approach speed would rise less
than SETTLE_HEIGHT before they met again. `settle` (balls) and `settle_cushion` then apply
the push's outcome at once. The cloth takes part in both, so a settle does not conserve
momentum (the engine records it as a "ball_ball_settle" event); it never adds energy.
"""

import math

import numpy as np

from .geometry import roll
from .jit import allocating_helper, helper
from .kinds import SLIDING, T0, VX, VY, WX, WY
from .motion import acceleration, copy_row, slip, state_of, transition_time
from .tolerances import EPS_V, PRESS_TOL, SETTLE_HEIGHT, SETTLE_OVERLAP

# The functions here are called only from compiled code (no_cpython_wrapper: each wrapper
# costs cold-compile time, about 0.1 s).


@helper
def gap_acceleration(bi, bj, nx, ny, ri, rj, params):
    """Second derivative of the gap between two touching balls: their relative acceleration
    along n plus the centripetal part of their relative tangential motion. Negative: their
    accelerations press them together."""
    axi, ayi = acceleration(bi, ri, params)
    axj, ayj = acceleration(bj, rj, params)
    vt = -(bj[VX] - bi[VX]) * ny + (bj[VY] - bi[VY]) * nx
    return (axj - axi) * nx + (ayj - ayi) * ny + vt * vt / (ri + rj)


@helper
def pressed(bi, bj, nx, ny, ri, rj, params):
    """True if a contact is a pressed one: the balls' accelerations push them together and a
    bounce at the approach speed would rise less than SETTLE_HEIGHT before they met again
    (the tail of an endless train of ever smaller bounces, or no bounce at all)."""
    approach = (bi[VX] - bj[VX]) * nx + (bi[VY] - bj[VY]) * ny
    a = gap_acceleration(bi, bj, nx, ny, ri, rj, params)
    return a < 0.0 and approach * approach <= -2.0 * a * SETTLE_HEIGHT


@helper
def _response(row, r):
    """How a ball's velocity answers an impulse through its centre: 1 if it slides (dv = J/m),
    5/7 if it rolls or rests (the cloth keeps it rolling, a small impulse's short slide
    taken at once: dv = 5/7 J/m)."""
    return 1.0 if state_of(row, r) == SLIDING else 5.0 / 7.0


@helper
def _push(bi, bj, n, w, s, radii, masses, responses):
    """Impulse J along n taking the normal relative velocity from w to s, with velocity
    responses (ki, kj) (see `_response`); a ball answering 5/7 is left rolling. radii and
    masses are the pairs (ri, rj), (mi, mj). Returns the kinetic energy it adds,
    (s^2 - w^2) / 2 / (ki/mi + kj/mj)."""
    nx, ny = n
    ri, rj = radii
    mi, mj = masses
    ki, kj = responses
    inv = ki / mi + kj / mj
    j = (s - w) / inv
    bi[VX] -= ki * j * nx / mi
    bi[VY] -= ki * j * ny / mi
    bj[VX] += kj * j * nx / mj
    bj[VY] += kj * j * ny / mj
    if ki != 1.0:
        roll(bi, ri)
    if kj != 1.0:
        roll(bj, rj)
    return 0.5 * (s * s - w * w) / inv


@helper
def _brake(b, r, m, energy):
    """Cloth friction impulse against the ball's slip removing at least `energy` (J); False
    if the slip cannot supply it. An impulse lam against a slip u changes the energy by
    -lam |u| + 7/4 lam^2 / m (the slip falls by 7/2 lam / m), so lam is the smaller root."""
    ux, uy = slip(b[VX], b[VY], b[WX], b[WY], r)
    un = math.hypot(ux, uy)
    disc = un * un - 7.0 * energy / m
    if un <= EPS_V or disc < 0.0:
        return False
    lam = (un - math.sqrt(disc)) * m / 3.5
    ex, ey = ux / un, uy / un
    b[VX] -= lam * ex / m
    b[VY] -= lam * ey / m
    k = 2.5 * lam / (m * r)
    b[WX] -= k * ey
    b[WY] += k * ex
    return True


@helper
def _cloth_kick(b, p, nx, ny, r, m):
    """Impulse p n (N s) of the cloth at the contact point -R z: dv = p n / m and
    dw = (R p / I) (n_y, -n_x, 0), which changes the slip by 7/2 p n / m in all."""
    b[VX] += p * nx / m
    b[VY] += p * ny / m
    k = 2.5 * p / (m * r)
    b[WX] += k * ny
    b[WY] -= k * nx


@helper
def _hold(bi, bj, nx, ny, ri, rj, mi, mj):
    """The end of a push along n, at once: the contact impulse J >= 0 and cloth impulses
    P_i, P_j along n that leave no normal relative velocity and no slip along n on either
    ball. The push obeys the same linear impulse-momentum relations and ends in the same
    state, so along the line of centres this is exactly its outcome. J acts on a closing gap
    and each P against its ball's slip, so no energy is gained; a ball whose P would push
    along its slip keeps its normal slip (its slip outlasts the push). False if even that
    gives no valid J."""
    w = (bj[VX] - bi[VX]) * nx + (bj[VY] - bi[VY]) * ny
    uix, uiy = slip(bi[VX], bi[VY], bi[WX], bi[WY], ri)
    ujx, ujy = slip(bj[VX], bj[VY], bj[WX], bj[WY], rj)
    ui = uix * nx + uiy * ny
    uj = ujx * nx + ujy * ny
    for combo in range(4):
        kill_i, kill_j = combo < 2, combo % 2 == 0
        # Ball b's normal velocity changes by alpha_b J / m_b - beta_b along its push.
        ai = 5.0 / 7.0 if kill_i else 1.0
        aj = 5.0 / 7.0 if kill_j else 1.0
        bi_ = ui / 3.5 if kill_i else 0.0
        bj_ = uj / 3.5 if kill_j else 0.0
        j = (bj_ - bi_ - w) / (ai / mi + aj / mj)
        pi = (j - mi * ui) / 3.5 if kill_i else 0.0
        pj = -(j + mj * uj) / 3.5 if kill_j else 0.0
        if j >= 0.0 and pi * ui <= 0.0 and pj * uj <= 0.0:
            bi[VX] -= j * nx / mi
            bi[VY] -= j * ny / mi
            bj[VX] += j * nx / mj
            bj[VY] += j * ny / mj
            _cloth_kick(bi, pi, nx, ny, ri, mi)
            _cloth_kick(bj, pj, nx, ny, rj, mj)
            return True
    return False


@allocating_helper
def _lead(bi, bj, nx, ny, ri, rj, mi, mj, params):
    """Hand the push's momentum over at once: an impulse along n leaving the balls separating
    at s = 1.1 |a| T / 2, a (< 0) the gap's acceleration and T the time to the earlier of
    their next motion changes, so the gap s tau + a tau^2 / 2 stays open until then (found
    by a few fixed-point steps: the impulse changes a and T). The energy this adds is taken
    off by cloth friction against a sliding ball's slip. False if no slip can pay it."""
    w = (bj[VX] - bi[VX]) * nx + (bj[VY] - bi[VY]) * ny
    ki, kj = _response(bi, ri), _response(bj, rj)
    ti = np.empty(8)
    tj = np.empty(8)
    s = 0.0
    for _ in range(4):
        copy_row(ti, bi)
        copy_row(tj, bj)
        _push(ti, tj, (nx, ny), w, max(s, w, 0.0), (ri, rj), (mi, mj), (ki, kj))
        a = gap_acceleration(ti, tj, nx, ny, ri, rj, params)
        if a >= 0.0:
            break
        horizon = min(transition_time(ti, state_of(ti, ri), ri, params),
                      transition_time(tj, state_of(tj, rj), rj, params)) - bi[T0]
        need = 0.55 * -a * max(horizon, 0.0)
        if need <= s:
            break
        s = need
    copy_row(ti, bi)
    copy_row(tj, bj)
    gain = _push(ti, tj, (nx, ny), w, max(s, w, 0.0), (ri, rj), (mi, mj), (ki, kj))
    if gain > 0.0:
        gain = gain * (1.0 + 1e-9) + 1e-300
        uix, uiy = slip(ti[VX], ti[VY], ti[WX], ti[WY], ri)
        ujx, ujy = slip(tj[VX], tj[VY], tj[WX], tj[WY], rj)
        ui, uj = math.hypot(uix, uiy), math.hypot(ujx, ujy)
        if not (_brake(ti, ri, mi, gain) if mi * ui * ui >= mj * uj * uj else _brake(tj, rj, mj, gain)):
            return False
    copy_row(bi, ti)
    copy_row(bj, tj)
    return True


@helper
def settle(bi, bj, nx, ny, ri, rj, mi, mj, params, overlap):
    """Resolve a pressed contact: two touching balls whose accelerations push them together.

    In reality they push each other along until their motions change; that push has no
    closed form, and ever smaller bounces would take endless events. So its outcome is
    applied at once, in the first of these ways that applies:

    1. `_hold`, unless both balls slide with their slips pressing the same way along n (then
       the push is one ball's slip slightly outpulling the other's and ends long before
       either slip does): the push's end state, exactly as far as the line of centres goes.
    2. `_lead`, if the pair is still pressed together: the push's momentum handed over in
       one impulse, its extra energy paid for by cloth friction on a sliding ball.
    3. `_roll_together`, if neither applies (no slip to pay with: two rolling balls pressed
       by rolling resistance) or the pair has sunk SETTLE_OVERLAP into each other.

    The cloth takes part, so a settle does not conserve momentum; it never adds energy.
    """
    if overlap <= SETTLE_OVERLAP:
        uix, uiy = slip(bi[VX], bi[VY], bi[WX], bi[WY], ri)
        ujx, ujy = slip(bj[VX], bj[VY], bj[WX], bj[WY], rj)
        same_way = (state_of(bi, ri) == SLIDING and state_of(bj, rj) == SLIDING
                    and (uix * nx + uiy * ny) * (ujx * nx + ujy * ny) > 0.0)
        if not same_way:
            _hold(bi, bj, nx, ny, ri, rj, mi, mj)
        if gap_acceleration(bi, bj, nx, ny, ri, rj, params) >= -PRESS_TOL:
            return
        if _lead(bi, bj, nx, ny, ri, rj, mi, mj, params):
            return
    _roll_together(bi, bj, ri, rj, mi, mj)


@helper
def _roll_together(bi, bj, ri, rj, mi, mj):
    """Both balls roll on with their common velocity: the cloth takes out each ball's slip
    (v -= 2/7 u, the rolling velocity sliding would end at), then an internal impulse with
    the cloth keeping both rolling (effective masses 7/5 m each: momentum is shared by mass)
    evens out their velocities. Both steps dissipate energy; the two then move as one."""
    uix, uiy = slip(bi[VX], bi[VY], bi[WX], bi[WY], ri)
    ujx, ujy = slip(bj[VX], bj[VY], bj[WX], bj[WY], rj)
    vix, viy = bi[VX] - uix * 2.0 / 7.0, bi[VY] - uiy * 2.0 / 7.0
    vjx, vjy = bj[VX] - ujx * 2.0 / 7.0, bj[VY] - ujy * 2.0 / 7.0
    vx = (mi * vix + mj * vjx) / (mi + mj)
    vy = (mi * viy + mj * vjy) / (mi + mj)
    bi[VX], bi[VY], bj[VX], bj[VY] = vx, vy, vx, vy
    roll(bi, ri)
    roll(bj, rj)


@allocating_helper
def roll_group(S, R, M, ca, cb, n_c, walls, wall_ball, n_walls):
    """`_roll_together` for each pack, a set of balls linked by the pairs (ca[c], cb[c]),
    c < n_c: each ball rolls at once (the cloth takes its slip), then the pack's balls share
    one velocity by mass: pressed together, they roll on as one. The cushions a pack touches
    (inward normals walls[w], touched by ball wall_ball[w]) take the part of its velocity
    into them (cyclic projections onto the cone of velocities leaving every cushion alone),
    so a pack wedged against a rail slides along it. Every step removes energy."""
    n = S.shape[0]
    label = np.full(n, -1)
    for c in range(n_c):
        label[ca[c]] = ca[c]
        label[cb[c]] = cb[c]
    for _ in range(n_c):
        for c in range(n_c):
            low = min(label[ca[c]], label[cb[c]])
            label[ca[c]] = label[cb[c]] = low
    for pack in range(n):
        px, py, mass = 0.0, 0.0, 0.0
        for k in range(n):
            if label[k] == pack:
                ux, uy = slip(S[k, VX], S[k, VY], S[k, WX], S[k, WY], R[k])
                px += M[k] * (S[k, VX] - ux * 2.0 / 7.0)
                py += M[k] * (S[k, VY] - uy * 2.0 / 7.0)
                mass += M[k]
        if mass == 0.0:
            continue
        vx, vy = _leave_walls(px / mass, py / mass, walls, wall_ball, n_walls, label, pack)
        for k in range(n):
            if label[k] == pack:
                S[k, VX], S[k, VY] = vx, vy
                roll(S[k], R[k])


@helper
def _leaves(vx, vy, walls, wall_ball, n_walls, label, pack):
    """True if the velocity moves into none of the pack's cushions (to rounding)."""
    for w in range(n_walls):
        if label[wall_ball[w]] == pack and vx * walls[w, 0] + vy * walls[w, 1] < -1e-12 * math.hypot(vx, vy):
            return False
    return True


@helper
def _leave_walls(vx, vy, walls, wall_ball, n_walls, label, pack):
    """The pack's velocity projected onto the cone of velocities that move into none of its
    cushions (inward normals walls[w] touched by a pack ball). In the plane that cone is
    bounded by lines through 0, so the nearest point of it is the velocity itself, its
    projection onto one cushion's line, or 0 (a pack wedged into a corner or between two
    pocket facings stops); taken exactly, not by repeated projections, which creep along a
    narrow wedge (the 14 degrees between a corner pocket's facings) without reaching it."""
    if _leaves(vx, vy, walls, wall_ball, n_walls, label, pack):
        return vx, vy
    best_x, best_y, best = 0.0, 0.0, 0.0
    for w in range(n_walls):
        vn = vx * walls[w, 0] + vy * walls[w, 1]
        if label[wall_ball[w]] != pack or vn >= 0.0:
            continue
        cx, cy = vx - vn * walls[w, 0], vy - vn * walls[w, 1]
        speed = math.hypot(cx, cy)
        if speed > best and _leaves(cx, cy, walls, wall_ball, n_walls, label, pack):
            best_x, best_y, best = cx, cy, speed
    return best_x, best_y


@helper
def pressed_cushion(b, nx, ny, radius, params):
    """True if the ball is pressed against a cushion (inward normal n): its acceleration
    pushes it into the cushion and a bounce at its approach speed would rise less than
    SETTLE_HEIGHT (see `pressed`)."""
    ax, ay = acceleration(b, radius, params)
    a = ax * nx + ay * ny
    vn = b[VX] * nx + b[VY] * ny
    return a < 0.0 and vn * vn <= -2.0 * a * SETTLE_HEIGHT


@helper
def settle_cushion(b, nx, ny, radius):
    """A ball pressed against a cushion by its slip (say, sliding along a rail with spin
    into it) is held there until its slip along n is gone: the cushion keeps its normal
    velocity at zero while the cloth turns the slip's normal part into spin. Applied at
    once: the cushion's impulse J >= 0 and the cloth's P along n, per unit mass, with
    J + P = -v_n (no normal velocity) and J + 7/2 P = -u_n (no normal slip). The hold obeys
    the same linear relations and ends in the same state, and a slip left along the rail
    then ends in the same rolling velocity, so only the timing is compressed. P opposes the
    slip and J acts on a closing gap: no energy is gained. Cushion friction during the hold
    is neglected."""
    vn = b[VX] * nx + b[VY] * ny
    ux, uy = slip(b[VX], b[VY], b[WX], b[WY], radius)
    un = ux * nx + uy * ny
    p = -(un - vn) / 2.5
    j = -vn - p
    if j < 0.0 or p * un > 0.0:
        p, j = 0.0, max(-vn, 0.0)
    b[VX] += (j + p) * nx
    b[VY] += (j + p) * ny
    k = 2.5 * p / radius
    b[WX] += k * ny
    b[WY] -= k * nx
