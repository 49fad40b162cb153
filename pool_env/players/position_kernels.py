"""The ghost-ball planner's compiled calls for one position: its windows, and its pots from its cue-ball spots.

A decision of `GameGhostBallAgent.decide` is one of these calls (or two, with ball in hand):
each runs `window_kernels`' and `plan_kernels`' loops over the position's candidates (every legal ball into every
pocket, in `planner.ShotPlanner.candidates` order) without the batch arrays' setup, and
picks the best pot as `plan_kernels.group_best` does; the safety's ball and the ball-in-hand
spots are chosen here too.
"""

from __future__ import annotations

import math

import numpy as np

from ..physics.jit import helper, kernel
from .plan_kernels import OK, PLAN_COLUMNS, R_, SCORE, batch_fault, path_clear, plan_kernel
from .window_kernels import aim_kernel


@kernel
def position_windows(xy, on, legal, tables, index, aims):
    """One position's candidates and their windows in one call: every legal ball (legal (n,),
    of position 0 of xy (1, n, 2), whose object balls on the table are on (1, n)) into every
    pocket, in `planner.ShotPlanner.candidates` order, into index (M, 3), and `aim_kernel`'s
    rows into aims (M, 3); `tables` holds the planner's (jaws, rails, lams, reach, near,
    constants, captures). Returns the candidates' count, or -1 if a position is not finite."""
    jaws, rails, lams, reach, near = tables[0], tables[1], tables[2], tables[3], tables[4]
    if batch_fault(xy, on, index[:0], jaws.shape[0]) != 0:
        return -1
    k = 0
    for ball in range(1, xy.shape[1]):
        if legal[ball]:
            for p in range(jaws.shape[0]):
                index[k, 0], index[k, 1], index[k, 2] = 0, ball, p
                aims[k, 0], aims[k, 1], aims[k, 2] = 0.0, 0.0, 0.0
                k += 1
    aim_kernel(xy, on, index[:k], jaws, rails, lams, reach, near, aims[:k])
    return k


@kernel
def plan_lie(xy, on, legal, tables, arrival, buffers):
    """One position's pots from where its cue ball lies, in one call: `position_windows`,
    then each candidate's pot (`plan_kernel`, the cue ball at xy[0, 0], the object ball
    arriving at `arrival`). `buffers` holds (index (M, 3), aims (M, 3), rows (M,
    PLAN_COLUMNS), cue (M, 2), arrivals (M,), work (6,)), M at least the candidates. Returns
    (candidates, the row of the best pot, the first of equal ones, or -1); (-1, -1) if a
    position is not finite."""
    index, aims, rows, cue, arrivals, work = buffers
    k = position_windows(xy, on, legal, tables, index, aims)
    if k < 0:
        return -1, -1
    for i in range(k):
        cue[i, 0], cue[i, 1], arrivals[i] = xy[0, 0, 0], xy[0, 0, 1], arrival
    plan_kernel(cue[:k], xy, on, index[:k], aims[:k], arrivals[:k], tables[5], tables[6], work, rows[:k])
    best = -1
    for i in range(k):
        if rows[i, OK] > 0.0 and (best < 0 or rows[i, SCORE] > rows[best, SCORE]):
            best = i
    return k, best


@kernel
def best_lie(xy, on, legal, tables, arrival, buffers):
    """`plan_lie`'s choice without its rows, in one call: `position_windows`, then `best_from`
    from where the cue ball lies (the candidates whose score bound falls below the best so far
    are not planned). buffers = (index (M, 3), aims (M, 3), spot (1, 2), best_from's buffers;
    the best pot's row goes into their best). Returns (candidates, the best pot's candidate,
    the first of equal ones, or -1); (-1, -1) if a position is not finite."""
    index, aims, spot, single = buffers
    k = position_windows(xy, on, legal, tables, index, aims)
    if k < 0:
        return -1, -1
    spot[0, 0], spot[0, 1] = xy[0, 0, 0], xy[0, 0, 1]
    _, i = best_from(xy, on, index[:k], aims[:k], spot, tables, arrival, single)
    return k, i


@helper
def spot_free(xy, on, x, y, limits):
    """A cue-ball spot (x, y) inside the area limits[0:4] (x_lo, x_hi, y_lo, y_hi) and at least
    limits[4] from every object ball on the table (on (n,) of xy (n, 2))."""
    if not (limits[0] <= x <= limits[1] and limits[2] <= y <= limits[3]):
        return False
    for j in range(xy.shape[0]):
        if on[j] and not math.hypot(xy[j, 0] - x, xy[j, 1] - y) >= limits[4]:
            return False
    return True


@kernel
def straight_in_spots(xy, on, index, aims, backs, limits, spots, ranks):
    """The straight-in cue-ball spots of one position (xy (n, 2), on (n,)): behind each
    candidate's object ball (index (N, 3), aims (N, 3) its window, an open one only) on the
    line from its aim point, 2 R + backs[b] from it (limits[5] the radius), and each one's
    rank (the open share over the distances); those `spot_free` keeps go into spots (K, 2),
    ranks (K,), candidate by candidate, back by back. Returns how many."""
    m = 0
    for i in range(index.shape[0]):
        share = aims[i, 2]
        if not share > 0.0:
            continue
        bx, by = xy[index[i, 1], 0], xy[index[i, 1], 1]
        vx, vy = aims[i, 0] - bx, aims[i, 1] - by
        d2 = math.hypot(vx, vy)
        length = d2 if d2 > 0.0 else 1.0
        ux, uy = vx / length, vy / length
        for b in range(backs.shape[0]):
            scale = 2.0 * limits[5] + backs[b]
            x, y = bx - ux * scale, by - uy * scale
            if spot_free(xy, on, x, y, limits):
                spots[m, 0], spots[m, 1] = x, y
                ranks[m] = share / ((d2 + 0.5) * (backs[b] + 0.5))
                m += 1
    return m


@kernel
def free_spots(xy, on, spots, limits, keep):
    """keep[k]: spot k of spots (K, 2) is `spot_free`."""
    for k in range(spots.shape[0]):
        keep[k] = spot_free(xy, on, spots[k, 0], spots[k, 1], limits)


@kernel
def plan_from(xy, on, index, aims, spots, tables, arrival, buffers):
    """The candidates (index (N, 3), of position 0 of xy (1, n, 2) and on (1, n), with their
    windows aims (N, 3)) planned from each cue-ball spot (spots (S, 2)) in turn, the object
    ball arriving at `arrival`; `tables` as `plan_lie` reads them, `buffers` (rows (S * N,
    PLAN_COLUMNS): spot s's pots in rows s * N to s * N + N - 1, cue (N, 2), arrivals (N,),
    work (6,)). Returns (the spot of the highest-scoring pot, the first such spot, and that
    pot's row), or (-1, -1) if no spot has a pot."""
    c, captures = tables[5], tables[6]
    rows, cue, arrivals, work = buffers
    n = index.shape[0]
    best_spot, best_row, best_score = -1, -1, -np.inf
    for s in range(spots.shape[0]):
        for i in range(n):
            cue[i, 0], cue[i, 1], arrivals[i] = spots[s, 0], spots[s, 1], arrival
        block = rows[s * n:(s + 1) * n]
        plan_kernel(cue[:n], xy, on, index, aims, arrivals[:n], c, captures, work, block)
        head = -1  # the spot's best pot, the first of equal ones (group_best)
        for i in range(n):
            if block[i, OK] > 0.0 and (head < 0 or block[i, SCORE] > block[head, SCORE]):
                head = i
        if head >= 0 and block[head, SCORE] > best_score:  # the first spot of the highest score
            best_spot, best_row, best_score = s, s * n + head, block[head, SCORE]
    return best_spot, best_row


@helper
def ahead(spots, ranks, a, b):
    """Spot a of spots (K, 2) ranks before spot b: (rank, x, y) greater, as sorting them in reverse orders them."""
    if ranks[a] != ranks[b]:
        return ranks[a] > ranks[b]
    if spots[a, 0] != spots[b, 0]:
        return spots[a, 0] > spots[b, 0]
    return spots[a, 1] > spots[b, 1]


@helper
def top_spots(spots, ranks, kept, order):
    """The best-ranked of spots[:kept] (`ahead`; equal ones, the same spot, the later first),
    at most order.shape[0] of them, by index into order, best first; returns how many."""
    t = 0
    for m in range(kept):
        j = t
        while j > 0 and not ahead(spots, ranks, order[j - 1], m):
            j -= 1
        if j >= order.shape[0]:
            continue
        for u in range(min(t, order.shape[0] - 1), j, -1):
            order[u] = order[u - 1]
        order[j] = m
        t = min(t + 1, order.shape[0])
    return t


@kernel
def plan_in_hand(xy, on, legal, tables, arrival, hand, buffers):
    """One position's ball-in-hand pots in one call: its windows (`position_windows`), the
    straight-in spots behind its open windows (`straight_in_spots`), the best-ranked of them
    (`top_spots`, as many as `order` holds) or, if none is free, the free spots of the grid
    (`free_spots`), and the best pot from those (`best_from`). hand = (backs, limits, grid
    (G, 2)) as `straight_in_spots` and `free_spots` read them; buffers = (index (M, 3), aims
    (M, 3), spots (2 M, 2), ranks (2 M,), order (T,) int, tries (max(T, G), 2), keep (G,),
    best_from's buffers). The spots tried go into tries. Returns (candidates, spots tried,
    the spot of the best pot or -1, its candidate or -1); (-1, 0, -1, -1) if a position is
    not finite."""
    index, aims, spots, ranks, order, tries, keep, single = buffers
    backs, limits, grid = hand
    k = position_windows(xy, on, legal, tables, index, aims)
    if k < 0:
        return -1, 0, -1, -1
    kept = straight_in_spots(xy[0], on[0], index[:k], aims[:k], backs, limits, spots, ranks)
    t = top_spots(spots, ranks, kept, order)
    for u in range(t):
        tries[u, 0], tries[u, 1] = spots[order[u], 0], spots[order[u], 1]
    if t == 0:  # no straight-in spot is free: the grid's free spots
        free_spots(xy[0], on[0], grid, limits, keep)
        for g in range(grid.shape[0]):
            if keep[g]:
                tries[t, 0], tries[t, 1] = grid[g, 0], grid[g, 1]
                t += 1
    spot, i = best_from(xy, on, index[:k], aims[:k], tries[:t], tables, arrival, single)
    return k, t, spot, i


@helper
def finite_2d(x):
    """Every entry of the 2-D array x is finite."""
    for i in range(x.shape[0]):
        for k in range(x.shape[1]):
            if not math.isfinite(x[i, k]):
                return False
    return True


@kernel
def all_finite(a, b):
    """Every entry of the 2-D arrays a and b is finite (`np.isfinite(x).all()` of both, in
    one call: a ball-in-hand decision checks its windows and spots with it)."""
    return finite_2d(a) and finite_2d(b)


# A pot's score is dn * share / ((d1 + 0.5) * (d2 + 0.5)) (scaled down if it scratches), with
# dn <= 1, d2 the ball's distance to its aim point (exact before planning) and d1 at least the
# ball's distance to the cue ball less 2 R: `best_from`'s bound, widened by this share for roundings.
BOUND_SLACK = 1e-9


@kernel
def best_from(xy, on, index, aims, spots, tables, arrival, buffers):
    """`plan_from`'s choice without its rows: the (spot, candidate) of the highest-scoring
    pot, the first in spot-then-candidate order of equal ones, found by planning only the
    candidates whose score bound (BOUND_SLACK) reaches the best so far; its row goes into
    buffers' best (PLAN_COLUMNS,). `buffers` holds (cue (1, 2), arrivals (1,), work (6,),
    trial (1, PLAN_COLUMNS), best (PLAN_COLUMNS,)). Returns (spot, candidate), or (-1, -1)
    if no spot has a pot."""
    c, captures = tables[5], tables[6]
    cue, arrivals, work, trial, best = buffers
    reach = 2.0 * c[R_] * (1.0 + BOUND_SLACK)
    best_spot, best_i, best_score = -1, -1, -np.inf
    arrivals[0] = arrival
    for s in range(spots.shape[0]):
        cue[0, 0], cue[0, 1] = spots[s, 0], spots[s, 1]
        for i in range(index.shape[0]):
            share = aims[i, 2]
            if not share > 0.0:  # a closed window: plan_kernel gives no pot
                continue
            ox, oy = xy[0, index[i, 1], 0], xy[0, index[i, 1], 1]
            d2 = math.hypot(aims[i, 0] - ox, aims[i, 1] - oy)
            d1 = max(math.hypot(ox - spots[s, 0], oy - spots[s, 1]) - reach, 0.0)
            if share / ((d1 + 0.5) * (d2 + 0.5)) * (1.0 + BOUND_SLACK) < best_score:
                continue  # it cannot score the best so far, let alone beat it
            plan_kernel(cue, xy, on, index[i:i + 1], aims[i:i + 1], arrivals, c, captures, work, trial)
            if trial[0, OK] > 0.0 and trial[0, SCORE] > best_score:
                best_spot, best_i, best_score = s, i, trial[0, SCORE]
                for col in range(PLAN_COLUMNS):
                    best[col] = trial[0, col]
    return best_spot, best_i


@kernel
def safety_ball(xy, on, legal, clearance, order, gaps):
    """The ball a safety goes at, in position 0 of xy (1, n, 2) (on (1, n): the object balls
    on the table): of its legal balls (legal (n,) by number), nearest the cue ball first (ties
    in number order), the first whose line from the cue ball keeps `clearance` from every
    other object ball (`path_clear`), else the nearest; -1 if none is legal. order (n,) int
    and gaps (n,) are scratch space."""
    cx, cy = xy[0, 0, 0], xy[0, 0, 1]
    m = 0
    for b in range(1, xy.shape[1]):
        if on[0, b] and legal[b]:
            d = math.hypot(xy[0, b, 0] - cx, xy[0, b, 1] - cy)
            k = m
            while k > 0 and gaps[k - 1] > d:  # insertion after the equal ones: a stable sort
                gaps[k], order[k] = gaps[k - 1], order[k - 1]
                k -= 1
            gaps[k], order[k] = d, b
            m += 1
    if m == 0:
        return -1
    for k in range(m):
        ball = order[k]
        if path_clear(xy, on, 0, ball, cx, cy, xy[0, ball, 0], xy[0, ball, 1], clearance):
            return ball
    return order[0]
