"""What the ghost-ball model predicts of each candidate shot's contact: both balls' paths, rests, scratches, kisses."""

from __future__ import annotations

import dataclasses

import numpy as np

from pool_env import rules
from pool_env.game import MAX_SPEED
from pool_env.physics import Table
from pool_env.players import geometry as geo

OUTCOME_FEATURES = 16  # see `outcome_features`
GAP_CAP = 0.5  # m: gaps (to a pocket, to a ball) beyond this are all "far"
RAIL_TOUCH = 2e-3  # m: a path point this near a cushion line is a cushion contact


def contact_frame(cue, obj, d, radius: float, clamp: bool = False) -> tuple:
    """(the cue ball's run to the contact, its centre there (the ghost ball), the unit line of
    centres n and its normal t) of a cue ball at `cue` sent along the unit `d` at the ball at
    `obj`; `clamp`: a run never below 0 (a cue ball already touching the ball)."""
    to_obj = obj - cue
    along = float(to_obj @ d)
    off = float(d[0] * to_obj[1] - d[1] * to_obj[0])
    travel = along - np.sqrt(max(4.0 * radius * radius - off * off, 0.0))
    if clamp:
        travel = max(travel, 0.0)
    ghost = cue + d * travel
    n = geo.unit(obj - ghost)
    return travel, ghost, n, np.array([-n[1], n[0]])


def roll_at_contact(v0: float, top: float, distance: float, physics) -> float:
    """R times the forward spin of a cue ball struck at `v0` m/s with the tip `top` ball radii
    above centre (R w = 5/2 top v0 at the strike) after `distance` m: the slip v - R w decays at
    7/2 mu_s g (v changes at mu_s g, R w at 5/2 mu_s g, opposite ways) until it rolls, then
    v = R w falls at mu_r g."""
    g, mu_s, mu_r = physics.g, physics.mu_s, physics.mu_r
    slip = v0 * (1.0 - 2.5 * top)
    a = mu_s * g * np.sign(slip)  # the deceleration of v while sliding
    t_slide = 2.0 * abs(slip) / (7.0 * mu_s * g)
    x_slide = v0 * t_slide - 0.5 * a * t_slide**2
    if distance <= x_slide:
        disc = max(v0 * v0 - 2.0 * a * distance, 0.0)
        t = distance / v0 if abs(a) < 1e-12 else (v0 - np.sqrt(disc)) / a
        return 2.5 * top * v0 + 2.5 * a * t
    v_roll = v0 - a * t_slide
    return float(np.sqrt(max(v_roll * v_roll - 2.0 * mu_r * g * (distance - x_slide), 0.0)))


@dataclasses.dataclass
class Contact:
    """The ghost-ball model of one shot's first contact: the ball met, where the cue ball is
    then (`ghost`), and both balls' predicted paths after it (points (K, 2))."""

    ball: int
    ghost: np.ndarray
    object_speed: float
    object_path: np.ndarray
    cue_path: np.ndarray


def contact(cue, obj, d, speed: float, top: float, ball: int, physics, table: Table, radius: float) -> Contact:
    """The cue ball sent from `cue` along the unit `d` at `speed` m/s with the tip `top` meets
    the ball at `obj`: the contact (`geometry.collision`, friction and throw included) and the
    paths both balls then roll (`geometry.cue_path`: slide, roll, rails, rest)."""
    travel, ghost, n, t = contact_frame(cue, obj, d, radius, clamp=True)
    v = geo.speed_after(speed, travel, physics)
    roll = roll_at_contact(speed, top, travel, physics)
    on, ot, cn, ct = geo.collision(v, roll, float(d @ n), float(d @ t), physics)
    object_path = geo.cue_path(obj, on * n + ot * t, np.zeros(2), physics, table, radius)
    cue_path = geo.cue_path(ghost, cn * n + ct * t, roll * d, physics, table, radius)
    return Contact(ball, ghost, float(np.hypot(on, ot)), object_path if len(object_path) else obj[None],
                   cue_path if len(cue_path) else ghost[None])


def pocket_gap(points, pockets) -> float:
    """The least distance (m) of the points to a pocket's capture circle (< 0: inside one)."""
    centres = np.array([p.centre for p in pockets])
    radii = np.array([p.radius for p in pockets])
    dist = np.hypot(points[:, None, 0] - centres[None, :, 0], points[:, None, 1] - centres[None, :, 1])
    return float(np.min(dist - radii[None, :]))


def ball_gap(points, balls, radius: float) -> float:
    """The least gap (m) between a ball rolling through the points and the balls (K, 2) at rest."""
    if not len(balls):
        return GAP_CAP
    dist = np.hypot(points[:, None, 0] - balls[None, :, 0], points[:, None, 1] - balls[None, :, 1])
    return float(np.min(dist)) - 2.0 * radius


def touches_rail(points, table: Table, radius: float) -> bool:
    """Some point of the path lies on a cushion line (the ball reaches a rail)."""
    x, y = points[:, 0], points[:, 1]
    edge = np.minimum.reduce([x - radius, table.length - radius - x, y - radius, table.width - radius - y])
    return bool(np.min(edge) < RAIL_TOUCH)


def contact_row(c: Contact, xy, on_table, table: Table, pockets, radius: float) -> np.ndarray:
    """(OUTCOME_FEATURES - 1,): met a ball, its speed / MAX_SPEED, its path enters a pocket,
    its least pocket gap, it reaches a rail; the cue ball's path enters a pocket, its least
    pocket gap, it reaches a rail, its least gap to another object ball (a kiss); the object
    ball's least gap to another ball; both rests (x, y in [-1, 1]); the cue ball's path
    length (m, capped at 3)."""
    others = [k for k in np.flatnonzero(on_table) if k not in (0, c.ball)]
    rest_balls = xy[others]
    scale = np.array([2.0 / table.length, 2.0 / table.width])
    o_gap, c_gap = pocket_gap(c.object_path, pockets), pocket_gap(c.cue_path, pockets)
    steps = np.hypot(*np.diff(c.cue_path, axis=0).T).sum() if len(c.cue_path) > 1 else 0.0
    return np.array([
        1.0, c.object_speed / MAX_SPEED, o_gap < 0.0, np.clip(o_gap, -0.05, GAP_CAP),
        touches_rail(c.object_path, table, radius), c_gap < 0.0, np.clip(c_gap, -0.05, GAP_CAP),
        touches_rail(c.cue_path, table, radius), np.clip(ball_gap(c.cue_path, rest_balls, radius), 0.0, GAP_CAP),
        np.clip(ball_gap(c.object_path, rest_balls, radius), 0.0, GAP_CAP),
        *(c.object_path[-1] * scale - 1.0), *(c.cue_path[-1] * scale - 1.0), min(steps, 3.0)])


def opponent_qualities(search, xy, on_table, state, contacts) -> np.ndarray:
    """(K,): the best ghost-ball score (capped at 1) the opponent would have if each contact's
    balls stop where the model leaves them (a ball whose path enters a pocket taken off),
    planned at once; 0 for a shot that meets no ball."""
    hit = [i for i, c in enumerate(contacts) if c is not None]
    out = np.zeros(len(contacts))
    if state is None or not hit:
        return out
    try:
        legal = rules.legal_targets(dataclasses.replace(state, shooter=1, is_break=False))
    except (ValueError, KeyError, IndexError):  # a state the rules cannot hand over: our own legal balls
        legal = rules.legal_targets(state)
    mask = np.zeros(len(on_table), dtype=bool)
    mask[[int(b) for b in legal]] = True
    xys = np.repeat(np.asarray(xy, dtype=np.float64)[None], len(hit), axis=0)
    ons = np.repeat(np.asarray(on_table, dtype=bool)[None], len(hit), axis=0)
    ons[:, 0] = True  # the cue ball stops on the table, even if it was in hand (after a scratch)
    for row, i in enumerate(hit):
        c = contacts[i]
        xys[row, 0], xys[row, c.ball] = c.cue_path[-1], c.object_path[-1]
        if pocket_gap(c.object_path, search.pockets) < 0.0:
            ons[row, c.ball] = False
    out[hit] = search.plans.qualities(xys, ons, mask[None] & ons, 1.0)
    return out


def outcome_features(search, d, state, cands, rows, hits) -> np.ndarray:
    """(K, OUTCOME_FEATURES) float32 of a decision's candidates: `contact_row` of the first
    contact (a pot's own ball; a safety's or kick's first ball on its line, `hits` from
    `learned.first_contacts`; zeros when it meets none before a rail) and the opponent's best
    score from the balls' predicted rests (`opponent_qualities`)."""
    out = np.zeros((len(cands), OUTCOME_FEATURES), dtype=np.float32)
    contacts = []
    for i, (c, row) in enumerate(zip(cands, rows, strict=True)):
        cue = d.xy[0] if c.spot is None else np.asarray(c.spot, dtype=np.float64)
        ball = int(row[0]) if row is not None else int(hits[i, 0])
        if ball <= 0 or c.kind == "break":
            contacts.append(None)
            continue
        xy = d.xy.copy()
        xy[0] = cue
        k = contact(cue, xy[ball], np.asarray(c.direction, dtype=np.float64), c.speed, c.tip[1], ball,
                    search.physics, search.table, search.radius)
        contacts.append(k)
        out[i, :-1] = contact_row(k, xy, d.on_table, search.table, search.pockets, search.radius)
    out[:, -1] = opponent_qualities(search, d.xy, d.on_table, state, contacts)
    return out
