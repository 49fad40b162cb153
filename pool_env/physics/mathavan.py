"""Mathavan et al. (2010) ball-cushion impact: friction at the rail nose and on the cloth, integrated over the impulse.

S. Mathavan, M. R. Jackson, R. M. Parkin, "A theoretical analysis of billiard ball dynamics
under cushion impacts", Proc. IMechE Part C 224 (2010) 1863-1873 (section 3, eqs. for the
impulse increments; rigid cushion; restitution by the work of the normal impulse).

Frame (the paper's): y' into the cushion (-n), x' = y' x z along it, z up. The nose touches
the ball at I = R (0, cos th, sin th) with sin th = h/R - 1; the cloth at C = R (0, 0, -1).
Per unit mass and writing Omega = R w (m/s), the slips are

    at I:  a = v_x + Omega_y sin th - Omega_z cos th,   b = -v_y sin th + Omega_x
    at C:  p = v_x - Omega_y,                            q = v_y + Omega_x

The normal impulse P at I is the independent variable. Per unit dP the nose pushes with 1
along -(0, cos th, sin th) and friction F (|F| <= f_c, against the slip (a, b), in the basis
x', (0, -sin th, cos th)); the cloth pushes up with N_C = sin th - F_2 cos th (the ball does not
move vertically; gravity is negligible over the impact) and with friction G (|G| <= mu_s N_C,
against (p, q)). Newton and the moments about the centre (I = 2/5 m R^2) give

    dv_x = F_1 + G_1,                 dv_y = -cos th - F_2 sin th + G_2,
    dOmega_x = 5/2 (F_2 + G_2),       dOmega_y = 5/2 (F_1 sin th - G_1),   dOmega_z = -5/2 F_1 cos th,

so the slips move by d(a, b) = (0, sin th cos th) + A F + B G and
d(p, q) = (0, -cos th) + B F + 7/2 G with A = diag(7/2, 5/2 + sin^2 th) and
B = diag(1 - 5/2 sin th, 5/2 - sin th) (the paper's eq. 17 in these symbols, with
F = -f_c (cos phi, sin phi), G = -mu_s N_C (cos phi', sin phi')). The normal velocity at I is
v_y cos th, so the normal impulse does work dW = v_y cos th dP: compression ends at v_y = 0
with work W_c, restitution when the work returned reaches e_c^2 W_c (Stronge's energetic
coefficient, as the paper).

Integration: fixed impulse steps of v_y0 / N_STEPS, the friction of each step taken from the
slip at the step's midpoint by an implicit Coulomb solve (the slip a friction would leave
after half a step, projected on the cone), so a contact that sticks (the ball rolling on the
nose or on the cloth) holds its slip at zero instead of chattering about it; the two contacts'
friction is found by two Gauss-Seidel sweeps warm-started from the previous step. The last step
of each phase is cut where v_y reaches zero or the work reaches e_c^2 W_c (exact for the
step's constant rates). Against pooltool's model run to convergence (tests/data), N_STEPS = 200
leaves at most 7.2e-4 of the outgoing speed (velocity) and of max(|w|, |v|/R) (spin) over
speeds 0.2-4 m/s, incidence 0-80 degrees and seven spins.
"""

import math

from .jit import helper
from .kinds import VX, VY, WX, WY, WZ
from .motion import P_E_C, P_F_C, P_MU_S

N_STEPS = 200  # impulse steps per v_y0 (see the module docstring for the accuracy it buys)
SWEEPS = 2  # Gauss-Seidel sweeps between the two contacts per step
NEWTON = 30  # cap on the Newton iterations of the anisotropic cone solve


@helper
def _cone(z1, z2, a1, a2, limit):
    """The friction (f1, f2), |f| <= limit, with the slip s = z + diag(a1, a2) f: either s = 0
    (sticks: f = -(z1/a1, z2/a2) fits the cone) or f = -limit s / |s|. Then s_i = z_i r /
    (r + limit a_i) with r = |s| the root of sum z_i^2 / (r + limit a_i)^2 = 1, convex and
    decreasing in r > 0, so Newton climbs to it monotonically from below: from
    |z| - limit max(a_i), a lower bound as |A f| <= limit max(a_i)."""
    if limit <= 0.0:
        return 0.0, 0.0
    if a1 <= 0.0 or a2 <= 0.0:  # a step of no impulse: friction against the slip as it is
        n = math.hypot(z1, z2)
        return (-limit * z1 / n, -limit * z2 / n) if n > 0.0 else (0.0, 0.0)
    f1, f2 = -z1 / a1, -z2 / a2
    if f1 * f1 + f2 * f2 <= limit * limit:
        return f1, f2
    if a1 == a2:  # isotropic (the cloth): the slip keeps its direction
        n = math.hypot(z1, z2)
        return -limit * z1 / n, -limit * z2 / n
    r = max(math.hypot(z1, z2) - limit * max(a1, a2), 0.0)
    for _ in range(NEWTON):
        d1, d2 = r + limit * a1, r + limit * a2
        g = z1 * z1 / (d1 * d1) + z2 * z2 / (d2 * d2) - 1.0
        dg = 2.0 * (z1 * z1 / (d1 * d1 * d1) + z2 * z2 / (d2 * d2 * d2))
        step = g / dg
        r += step
        if step <= 1e-14 * (r + limit * a1):
            break
    d1, d2 = r + limit * a1, r + limit * a2
    return -limit * z1 / d1, -limit * z2 / d2


@helper
def _friction(st, tau, geom, mu, fg):
    """Friction at the nose F and on the cloth G (per unit normal impulse) for a step whose
    slips are taken at impulse tau ahead: st = (v_x, v_y, Omega_x, Omega_y, Omega_z),
    geom = (sin th, cos th), mu = (f_c, mu_s), fg = (F_1, F_2, G_1, G_2) to start from."""
    vx, vy, ox, oy, oz = st
    s, c = geom
    f_c, mu_s = mu
    f1, f2, g1, g2 = fg
    a, b = vx + oy * s - oz * c, -vy * s + ox
    p, q = vx - oy, vy + ox
    a2, b1, b2 = 2.5 + s * s, 1.0 - 2.5 * s, 2.5 - s
    for _ in range(SWEEPS):
        f1, f2 = _cone(a + tau * b1 * g1, b + tau * (s * c + b2 * g2), tau * 3.5, tau * a2, f_c)
        n_c = max(s - c * f2, 0.0)
        g1, g2 = _cone(p + tau * b1 * f1, q + tau * (b2 * f2 - c), tau * 3.5, tau * 3.5, mu_s * n_c)
    return f1, f2, g1, g2


@helper
def _advance(st, h, geom, fg):
    """The state after normal impulse h (per unit mass) under the friction fg (see the module)."""
    vx, vy, ox, oy, oz = st
    s, c = geom
    f1, f2, g1, g2 = fg
    return (vx + h * (f1 + g1), vy - h * (c + s * f2 - g2), ox + 2.5 * h * (f2 + g2),
            oy + 2.5 * h * (s * f1 - g1), oz - 2.5 * h * c * f1)


@helper
def _phase_step(st, h, geom, mu, fg, left):
    """One step of the compression (left < 0: until v_y = 0) or the restitution (left >= 0: the
    work still to return). Returns the step taken, the friction used, the work it did (|v_y|
    cos th dP, exact for v_y linear in P) and whether it ends the phase."""
    s, c = geom
    vy = st[1]
    fg = _friction(st, 0.5 * h, geom, mu, fg)
    for attempt in range(2):  # a cut step is solved again for its own length, then cut again
        k = c + s * fg[1] - fg[3]  # -dv_y/dP
        if left < 0.0:
            done = vy - k * h <= 0.0
            if done:
                h = vy / k
            work = c * h * (vy - 0.5 * k * h)
        else:
            w0 = -vy
            done = c * h * (w0 + 0.5 * k * h) >= left
            if done:  # c (w0 h + k h^2 / 2) = left, in the cancellation-free form
                h = 2.0 * left / c / (w0 + math.sqrt(w0 * w0 + 2.0 * k * left / c))
            work = c * h * (w0 + 0.5 * k * h)
        if not done or attempt == 1:
            break
        fg = _friction(st, 0.5 * h, geom, mu, fg)
    return h, fg, work, done


@helper
def _impact(st, geom, e, mu):
    """Integrate the compression and the restitution from st (v_y > 0); the state after."""
    h0 = st[1] / N_STEPS
    fg = (0.0, 0.0, 0.0, 0.0)
    work = 0.0
    left = -1.0
    for _ in range(100 * N_STEPS):
        h, fg, dw, done = _phase_step(st, h0, geom, mu, fg, left)
        st = _advance(st, h, geom, fg)
        if left < 0.0:
            work += dw
            if done:
                st = (st[0], 0.0, st[2], st[3], st[4])
                left = e * e * work
                if left <= 0.0:
                    return st
        else:
            left -= dw
            if done:
                return st
    return st


@helper
def mathavan2010(b, nx, ny, radius, params, height):
    """Mathavan et al. (2010) cushion on the ball row b (in place), inward normal n, nose at
    height `height`: restitution e_c by the work of the normal impulse, friction f_c at the
    nose and mu_s on the cloth throughout the impact (see the module docstring)."""
    ex, ey = -ny, nx  # x' along the cushion
    gx, gy = -nx, -ny  # y' into the cushion
    vy = b[VX] * gx + b[VY] * gy
    if vy <= 0.0:
        return
    sin_t = min(max(height / radius - 1.0, -1.0), 1.0)
    geom = (sin_t, math.sqrt(1.0 - sin_t * sin_t))
    if geom[1] <= 0.0:  # the nose at or above the top of the ball: it cannot push it (as han2005)
        return
    st = (b[VX] * ex + b[VY] * ey, vy, radius * (b[WX] * ex + b[WY] * ey), radius * (b[WX] * gx + b[WY] * gy),
          radius * b[WZ])
    vx, vy, ox, oy, oz = _impact(st, geom, params[P_E_C], (params[P_F_C], params[P_MU_S]))
    # The cushion pushes the ball out: round-off (or e_c = 0) never leaves it moving in.
    vy = min(vy, 0.0)
    b[VX] = vx * ex + vy * gx
    b[VY] = vx * ey + vy * gy
    b[WX] = (ox * ex + oy * gx) / radius
    b[WY] = (ox * ey + oy * gy) / radius
    b[WZ] = oz / radius
