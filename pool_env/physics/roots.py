"""Earliest entry time of a polynomial of degree <= 4 into f <= 0, found robustly.

Every contact test in the engine (ball-ball, ball-cushion, ball-jaw, ball-pocket) asks the
same question: given f(tau) = distance^2 - contact^2 (or a signed gap), a polynomial in tau,
when does f first go from positive to <= 0 while decreasing? Closed-form quartic formulas
lose all accuracy on grazing contacts and double roots, so we never use them. Instead the
critical points of f are found from its derivatives (the quadratic f'' in closed form, then
the cubic f' by bracketed Newton on the monotone pieces f'' defines); between consecutive
critical points f is monotone, and the first piece on which it falls through zero holds the
root, which a safeguarded Newton-bisection pins to machine precision. No complex arithmetic,
no eigenvalues, and a tangent pass (a double root) is correctly reported as no contact.
"""

import math

import numpy as np

from .jit import helper
from .tolerances import ROOT_MAX_ITER, TOUCH_DEPTHS

# Which function _bracket_root solves: f itself or its slope f' (typed, not literal
# constants: one compiled version serves both, see jit.py).
VALUE, SLOPE = np.int64(0), np.int64(1)


@helper
def _f(c0, c1, c2, c3, c4, t):
    return (((c4 * t + c3) * t + c2) * t + c1) * t + c0


@helper
def _df(c1, c2, c3, c4, t):
    return ((4.0 * c4 * t + 3.0 * c3) * t + 2.0 * c2) * t + c1


@helper
def _ddf(c2, c3, c4, t):
    return (12.0 * c4 * t + 6.0 * c3) * t + 2.0 * c2


@helper
def _value_slope(c0, c1, c2, c3, c4, t, derivative):
    if derivative == 0:
        return _f(c0, c1, c2, c3, c4, t), _df(c1, c2, c3, c4, t)
    return _df(c1, c2, c3, c4, t), _ddf(c2, c3, c4, t)


@helper
def _bracket_root(c0, c1, c2, c3, c4, lo, hi, flo, derivative):
    """Root of f (derivative=0) or f' (derivative=1) in [lo, hi], where the function is
    monotone and changes sign (f(lo) = flo on one side of zero).

    Newton's method, kept inside the shrinking bracket (a step that would leave it bisects
    instead), stopping when the step falls to round-off: quadratic convergence on simple
    roots, guaranteed progress on double ones. For f the result is then moved to the `lo`
    side of the root by at most a few ulps, so the returned instant is the last one before
    contact: the gap there is never negative.
    """
    x = 0.5 * (lo + hi)
    for _ in range(ROOT_MAX_ITER):
        fx, slope = _value_slope(c0, c1, c2, c3, c4, x, derivative)
        if fx == 0.0:
            break
        if (fx > 0.0) == (flo > 0.0):
            lo = x
        else:
            hi = x
        step = fx / slope if slope != 0.0 else np.inf
        nxt = x - step
        if not (min(lo, hi) < nxt < max(lo, hi)):
            nxt = 0.5 * (lo + hi)
        if abs(nxt - x) <= 2e-16 * abs(x) or nxt == x:
            x = nxt
            break
        x = nxt
    if derivative == 1:
        return x
    # Land on the side where f has the sign of f(lo) (no contact yet).
    for _ in range(8):
        fx = _f(c0, c1, c2, c3, c4, x)
        if fx == 0.0 or (fx > 0.0) == (flo > 0.0):
            return x
        x = np.nextafter(x, lo)
    return lo


@helper
def _inflections(c2, c3, c4, horizon):
    """The roots of f'' = 12 c4 t^2 + 6 c3 t + 2 c2 inside (0, horizon), ascending; inf
    for a missing one. The quadratic is solved in its cancellation-free form."""
    a, b, c = 12.0 * c4, 6.0 * c3, 2.0 * c2
    r1, r2 = np.inf, np.inf
    if a == 0.0:
        if b != 0.0:
            r1 = -c / b
    else:
        disc = b * b - 4.0 * a * c
        if disc > 0.0:
            q = -0.5 * (b + math.copysign(math.sqrt(disc), b))
            r1, r2 = q / a, (c / q if q != 0.0 else q / a)
            if r1 > r2:
                r1, r2 = r2, r1
    if not (0.0 < r2 < horizon):
        r2 = np.inf
    if not (0.0 < r1 < horizon):
        r1, r2 = r2, np.inf
    return r1, r2


@helper
def _slope_root(c1, c2, c3, c4, lo, hi, last):
    """The critical point of f on a piece [lo, hi] where f' is monotone (inf if none). A zero
    of f' exactly at an interior knot counts once, as the end of the piece before it."""
    dlo = _df(c1, c2, c3, c4, lo)
    dhi = _df(c1, c2, c3, c4, hi)
    if (dlo > 0.0 and dhi < 0.0) or (dlo < 0.0 and dhi > 0.0):
        return _bracket_root(0.0, c1, c2, c3, c4, lo, hi, dlo, SLOPE)
    if dhi == 0.0 and not last:
        return hi
    return np.inf


@helper
def _critical_points(c1, c2, c3, c4, horizon):
    """Up to three roots of f' in (0, horizon), ascending, inf-padded (no heap allocation:
    this runs for every pair the broad phase lets through)."""
    if c4 == 0.0 and c3 == 0.0:
        t = -c1 / (2.0 * c2) if c2 != 0.0 else np.inf
        return (t if 0.0 < t < horizon else np.inf), np.inf, np.inf
    k1, k2 = _inflections(c2, c3, c4, horizon)
    # On each piece between inflections f' is monotone: a sign change is one critical point.
    out0, out1, out2 = np.inf, np.inf, np.inf
    lo = 0.0
    for m in range(3):
        hi = k1 if m == 0 else (k2 if m == 1 else horizon)
        last = hi == horizon
        if hi == np.inf:
            hi, last = horizon, True
        t = _slope_root(c1, c2, c3, c4, lo, hi, last)
        if t != np.inf:
            if out0 == np.inf:
                out0 = t
            elif out1 == np.inf:
                out1 = t
            else:
                out2 = t
        if last:
            break
        lo = hi
    return out0, out1, out2


@helper
def first_entry(c0, c1, c2, c3, c4, horizon, min_slope, min_depth):
    """Earliest tau in [0, horizon] at which f(tau) = c0 + c1 tau + ... + c4 tau^4 enters
    f <= 0 falling faster than `min_slope`, or sinks more than `min_depth` below zero however
    slowly; inf if it never does.

    A contact counts only if f is decreasing there by more than min_slope (the caller's
    approach-speed threshold): touching balls that are separating, at rest against each
    other, or meeting at a tangent do not collide. The same threshold is what makes a
    resolved collision never be found again at the same instant.

    Touching (|c0| <= min_depth: in contact, up to round-off) is measured from where f is now: the
    contact is found again when f falls back below c0 after rising (balls that barely
    separate, then re-approach while still in contact: rising only by round-off, f never
    turns positive, so entry into f <= 0 would never be seen), or when f sinks min_depth
    below c0 from the start (pressed together at second order: f'(0) = 0, f'' < 0). The
    latter returns the instant the depth is reached, never 0, so time always advances.
    A slow crossing that goes on sinking deeper than min_depth is a contact, not a graze.
    """
    if not (horizon >= 0.0):
        return np.inf
    level = 0.0
    if c0 <= min_depth:
        # Touching: within min_depth of contact either way. (Which side of zero round-off
        # leaves a just-resolved pair on must not matter: from just outside, a pair pressed
        # together would otherwise cross zero at once, a few nanoseconds later, faster than
        # min_slope, and from just inside be found min_depth deeper, microseconds later.)
        if c1 < -min_slope:
            return 0.0
        if c0 >= -TOUCH_DEPTHS * min_depth:
            level = c0
    h0 = c0 - level
    crit0, crit1, crit2 = _critical_points(c1, c2, c3, c4, horizon)
    lo = 0.0
    hlo = h0
    for m in range(4):
        hi = crit0 if m == 0 else (crit1 if m == 1 else (crit2 if m == 2 else horizon))
        if hi == np.inf:
            hi = horizon
        hhi = _f(h0, c1, c2, c3, c4, hi)
        if hlo > 0.0 and hhi <= 0.0:
            root = _bracket_root(h0, c1, c2, c3, c4, lo, hi, hlo, VALUE)
            if _df(c1, c2, c3, c4, root) < -min_slope:
                return root
            if hhi < -min_depth:
                # Crossing too slowly to count, but sinking on: pressed together. Found
                # where the depth is reached (a time the caller can resolve and move past).
                return _bracket_root(h0 + min_depth, c1, c2, c3, c4, root, hi, min_depth, VALUE)
            # A graze: f only touches zero (a shallow dip at most). Keep looking further on.
        elif -min_depth <= hlo <= 0.0 and hhi < -min_depth:
            # Touching and sinking (from the start, or after a rise too small to register, as
            # when f' starts at a subnormal): the instant the depth is reached.
            return _bracket_root(h0 + min_depth, c1, c2, c3, c4, lo, hi, hlo + min_depth, VALUE)
        if hi == horizon:
            break
        lo, hlo = hi, hhi
    return np.inf
