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
from numba import njit

_MAX_ITER = 100


@njit(cache=True, inline="always")
def _f(c0, c1, c2, c3, c4, t):
    return (((c4 * t + c3) * t + c2) * t + c1) * t + c0


@njit(cache=True, inline="always")
def _df(c1, c2, c3, c4, t):
    return ((4.0 * c4 * t + 3.0 * c3) * t + 2.0 * c2) * t + c1


@njit(cache=True, inline="always")
def _ddf(c2, c3, c4, t):
    return (12.0 * c4 * t + 6.0 * c3) * t + 2.0 * c2


@njit(cache=True)
def _bracket_root(c0, c1, c2, c3, c4, lo, hi, flo, derivative):
    """Root of f (derivative=0) or f' (derivative=1) in [lo, hi], where the function is
    monotone and changes sign. Returns the endpoint of the final bracket on the side of `lo`
    (for f that is the last instant before contact: the gap is never negative)."""
    for _ in range(_MAX_ITER):
        if hi - lo <= 4e-16 * max(abs(hi), 1e-300):
            break
        mid = 0.5 * (lo + hi)
        # One Newton step from the midpoint; fall back to the midpoint if it leaves the bracket.
        if derivative == 0:
            fm = _f(c0, c1, c2, c3, c4, mid)
            slope = _df(c1, c2, c3, c4, mid)
        else:
            fm = _df(c1, c2, c3, c4, mid)
            slope = _ddf(c2, c3, c4, mid)
        if fm == 0.0:
            return mid
        if (fm > 0.0) == (flo > 0.0):
            lo = mid
        else:
            hi = mid
        if slope != 0.0:
            guess = mid - fm / slope
            if lo < guess < hi:
                fg = _f(c0, c1, c2, c3, c4, guess) if derivative == 0 else _df(c1, c2, c3, c4, guess)
                if fg == 0.0:
                    return guess
                if (fg > 0.0) == (flo > 0.0):
                    lo = guess
                else:
                    hi = guess
    return lo


@njit(cache=True)
def _critical_points(c1, c2, c3, c4, horizon, out):
    """Roots of f' in (0, horizon), ascending, written to out; returns how many."""
    n = 0
    if c4 == 0.0 and c3 == 0.0:
        if c2 != 0.0:
            t = -c1 / (2.0 * c2)
            if 0.0 < t < horizon:
                out[0] = t
                n = 1
        return n
    # Split (0, horizon) where f'' = 0 (a quadratic, solved in its cancellation-free form).
    a, b, c = 12.0 * c4, 6.0 * c3, 2.0 * c2
    knots = np.empty(4)
    k = 0
    knots[k] = 0.0
    k += 1
    if a == 0.0:
        if b != 0.0:
            t = -c / b
            if 0.0 < t < horizon:
                knots[k] = t
                k += 1
    else:
        disc = b * b - 4.0 * a * c
        if disc > 0.0:
            q = -0.5 * (b + math.copysign(math.sqrt(disc), b))
            r1, r2 = q / a, (c / q if q != 0.0 else q / a)
            if r1 > r2:
                r1, r2 = r2, r1
            if 0.0 < r1 < horizon:
                knots[k] = r1
                k += 1
            if 0.0 < r2 < horizon and r2 != r1:
                knots[k] = r2
                k += 1
    knots[k] = horizon
    k += 1
    # On each piece f' is monotone: a sign change there is exactly one critical point.
    lo = knots[0]
    dlo = _df(c1, c2, c3, c4, lo)
    for m in range(1, k):
        hi = knots[m]
        dhi = _df(c1, c2, c3, c4, hi)
        if (dlo > 0.0 and dhi < 0.0) or (dlo < 0.0 and dhi > 0.0):
            out[n] = _bracket_root(0.0, c1, c2, c3, c4, lo, hi, dlo, 1)
            n += 1
        elif dhi == 0.0 and m < k - 1:
            out[n] = hi
            n += 1
        lo, dlo = hi, dhi
    return n


@njit(cache=True)
def first_entry(c0, c1, c2, c3, c4, horizon, min_slope):
    """Earliest tau in [0, horizon] at which f(tau) = c0 + c1 tau + ... + c4 tau^4 enters
    f <= 0 falling faster than `min_slope`; inf if it never does.

    A contact counts only if f is decreasing there by more than min_slope (the caller's
    approach-speed threshold): touching balls that are separating, at rest against each
    other, or meeting at a tangent do not collide. The same threshold is what makes a
    resolved collision never be found again at the same instant.
    """
    if not (horizon >= 0.0):
        return np.inf
    if c0 <= 0.0 and c1 < -min_slope:
        return 0.0
    crit = np.empty(3)
    n = _critical_points(c1, c2, c3, c4, horizon, crit)
    lo = 0.0
    flo = c0
    for m in range(n + 1):
        hi = crit[m] if m < n else horizon
        fhi = _f(c0, c1, c2, c3, c4, hi)
        if flo > 0.0 and fhi <= 0.0:
            root = _bracket_root(c0, c1, c2, c3, c4, lo, hi, flo, 0)
            if _df(c1, c2, c3, c4, root) < -min_slope:
                return root
            # A graze: f only touches zero. Keep looking further on.
        lo, flo = hi, fhi
    return np.inf
