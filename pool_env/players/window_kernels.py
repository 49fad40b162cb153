"""The ghost-ball planner's pocket windows, compiled: per candidate, the widest open run of points along the mouth.

A candidate (position, object ball, pocket; see `planner`) gets geometry.pocket_aim's window:
21 points along the pocket's mouth chord, each open if the line from the ball to it clears
the cushions near it and the other object balls, and the middle of the first longest run of
open points. `aim_kernel` gives what testing every point against every cushion and ball
gives, bit for bit, testing fewer: the obstacle that closed the last point first, only the
balls in the box of the lines, and no point past where the answer is known.
"""

from __future__ import annotations

from ..physics.jit import helper, inlined, kernel
from .plan_kernels import point_segment_within, segments_within

MAX_BALLS = 63  # the balls of a position the windows take (the cue ball's included): a bit each in an int64
BOX_HAIR = 1e-9  # m: the corridor's box grown past each line's own box, whatever the mouth points' roundings
REACH_MARGIN = 1e-9  # relative: `blocks_to_end`'s two tests are made with the reach shrunk by this share


@helper
def corridor_balls(xy, on, q, ball, ax, ay, jaw, clearance):
    """A bit mask of the object balls other than `ball` whose centres lie in the box of every
    line from (ax, ay) to the mouth jaw[0:2]-jaw[2:4], grown by `clearance` (and BOX_HAIR): a
    ball outside it is outside each line's own box, where `ball_blocks` passes it by."""
    lo_x = min(ax, min(jaw[0], jaw[2])) - clearance - BOX_HAIR
    hi_x = max(ax, max(jaw[0], jaw[2])) + clearance + BOX_HAIR
    lo_y = min(ay, min(jaw[1], jaw[3])) - clearance - BOX_HAIR
    hi_y = max(ay, max(jaw[1], jaw[3])) + clearance + BOX_HAIR
    mask = 0
    for j in range(1, xy.shape[1]):
        if on[q, j] and j != ball and lo_x <= xy[q, j, 0] <= hi_x and lo_y <= xy[q, j, 1] <= hi_y:
            mask |= 1 << j
    return mask


@helper
def ball_blocks(xy, q, j, ax, ay, bx, by, clearance):
    """Ball j of position q comes within `clearance` of the line (ax, ay)-(bx, by), as `path_clear` tests each ball."""
    px, py = xy[q, j, 0], xy[q, j, 1]
    if px < min(ax, bx) - clearance or px > max(ax, bx) + clearance or py < min(ay, by) - clearance \
            or py > max(ay, by) + clearance:
        return False
    return point_segment_within(px, py, ax, ay, bx, by, clearance)


@helper
def rail_blocks(line, near, r, reach):
    """Rail r of near comes within `reach` of the line (ax, ay, bx, by) (`segments_within`)."""
    return segments_within(line[0], line[1], line[2], line[3], near[r, 0], near[r, 1], near[r, 2], near[r, 3], reach)


@inlined
def line_blocker(xy, q, line, near, k, balls, reach, last):
    """What is in the way of the line (ax, ay, bx, by) from a ball to a mouth point
    (geometry.pocket_aim's test of one point): rail r of near[:k] (`segments_within`,
    reach[0]) as r, or object ball j of the mask `balls` (`corridor_balls`; `ball_blocks`,
    reach[1]) as k + j; -1 if nothing is. `last` (the last rail and ball found in the way, or
    -1) are tried first: what blocks one point's line usually blocks the next one's (the
    points an obstacle blocks are one run of the mouth), and the verdict does not depend on
    the order."""
    ax, ay, bx, by = line
    last_rail, last_ball = last
    if last_rail >= 0 and rail_blocks(line, near, last_rail, reach[0]):
        return last_rail
    if last_ball >= 0 and ball_blocks(xy, q, last_ball, ax, ay, bx, by, reach[1]):
        return k + last_ball
    for r in range(k):
        if r != last_rail and rail_blocks(line, near, r, reach[0]):
            return r
    j, rest = 0, balls
    while rest:  # the mask's balls, by number
        if rest & 1 and j != last_ball and ball_blocks(xy, q, j, ax, ay, bx, by, reach[1]):
            return k + j
        j, rest = j + 1, rest >> 1
    return -1


@helper
def blocks_to_end(xy, q, a, jaw, span, near, k, o, reach):
    """Obstacle o (as `line_blocker` numbers them) is in the way of the lines from the ball at
    a = (ax, ay) to both mouth points of span = (lam_from, lam_to), with its reach shrunk by
    REACH_MARGIN; then it is in the way of every point's line between, as the plain test
    computes it. (The points whose lines come within a distance of a convex obstacle, a
    rail's segment or a ball's centre, are one run of the mouth: the lines from a point
    through a convex set form a convex cone. The margin is far beyond the tests' roundings,
    about 1e-16 m, and beyond the mouth points' own off the chord.)"""
    shrunk = 1.0 - REACH_MARGIN
    for lam in span:
        bx, by = jaw[0] + lam * (jaw[2] - jaw[0]), jaw[1] + lam * (jaw[3] - jaw[1])
        if o < k:
            if not rail_blocks((a[0], a[1], bx, by), near, o, reach[0] * shrunk):
                return False
        elif not ball_blocks(xy, q, o - k, a[0], a[1], bx, by, reach[1] * shrunk):
            return False
    return True


@helper
def near_rails(rails, ax, ay, jaw, reach, out):
    """The rails whose box, grown by `reach`, meets the box of the paths from (ax, ay) to the
    mouth: the others are farther than `reach` from every such path (their verdict is open)."""
    lo_x, hi_x = min(ax, min(jaw[0], jaw[2])) - reach, max(ax, max(jaw[0], jaw[2])) + reach
    lo_y, hi_y = min(ay, min(jaw[1], jaw[3])) - reach, max(ay, max(jaw[1], jaw[3])) + reach
    k = 0
    for r in range(rails.shape[0]):
        if (min(rails[r, 0], rails[r, 2]) <= hi_x and max(rails[r, 0], rails[r, 2]) >= lo_x
                and min(rails[r, 1], rails[r, 3]) <= hi_y and max(rails[r, 1], rails[r, 3]) >= lo_y):
            for e in range(4):
                out[k, e] = rails[r, e]
            k += 1
    return k


@kernel
def aim_kernel(xy, on, index, jaws, rails, lams, reach, near, out):
    """Per candidate (position, ball, pocket): the middle of the widest open run of mouth
    points (the line from the ball to the point clears the rails by reach[0] and the other
    balls' centres by reach[1]: `line_blocker`) and the share of the mouth open, as out[i] =
    (x, y, share); share 0: closed. The scan stops where no run could any more be longer
    than the longest found (a run as long does not replace it), or where an obstacle met anew
    is in the way of every point to the end (`blocks_to_end`)."""
    samples = lams.shape[0]
    for i in range(index.shape[0]):
        q, ball, p = index[i, 0], index[i, 1], index[i, 2]
        ax, ay, jaw = xy[q, ball, 0], xy[q, ball, 1], jaws[p]
        k = near_rails(rails, ax, ay, jaw, reach[0], near)
        balls = corridor_balls(xy, on, q, ball, ax, ay, jaw, reach[1])
        best, best_start, run, last_rail, last_ball, previous = 0, 0, 0, -1, -1, -1
        for s in range(samples):
            if run + samples - s <= best:
                break
            bx = jaw[0] + lams[s] * (jaw[2] - jaw[0])
            by = jaw[1] + lams[s] * (jaw[3] - jaw[1])
            o = line_blocker(xy, q, (ax, ay, bx, by), near, k, balls, reach, (last_rail, last_ball))
            if o >= 0:
                run = 0
                if o < k:
                    last_rail = o
                else:
                    last_ball = o - k
                if o != previous and blocks_to_end(xy, q, (ax, ay), jaw, (lams[samples - 1], lams[s]), near, k, o,
                                                   reach):
                    break  # every point left is closed: no run to come
            else:
                run += 1
            previous = o
            if run > best:  # the first of the longest runs, as argmax picks
                best, best_start = run, s - run + 1
        out[i, 2] = best / samples
        if best > 0:
            middle = 0.5 * (lams[best_start] + lams[best_start + best - 1])
            out[i, 0] = jaw[0] + middle * (jaw[2] - jaw[0])
            out[i, 1] = jaw[1] + middle * (jaw[3] - jaw[1])
