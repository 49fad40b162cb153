"""The compiled ghost-ball planner (pool_env.players.planner) against geometry's scalar formulas, one by one."""

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest

from pool_env.game import MAX_SPEED, GameView
from pool_env.physics import BALL_RADIUS, Physics, Table
from pool_env.players import GameGhostBallAgent, GhostBallAgent
from pool_env.players import geometry as geo
from pool_env.players import plan_kernels as pk
from pool_env.players import planner as pl
from pool_env.players import window_kernels as wk

POSITIONS = json.loads((Path(__file__).parent / "data" / "planner_positions.json").read_text())["positions"]
TABLE, PHYSICS = Table.eight_foot(), Physics.standard()


def scalar_plan(cue, obj, pocket, others, arrival=0.3, captures=None, R=BALL_RADIUS):
    """The ghost-ball pot one candidate at a time, from geometry's scalar functions:
    (direction, speed, dn, score, scratch) or None; `captures`: the pockets the cue ball's
    path is checked against (default the table's)."""
    max_cut = math.radians(75.0)
    aim = geo.pocket_aim(obj, pocket, TABLE, R, others)
    if aim is None:
        return None
    target, open_fraction = aim
    u = geo.unit(target - obj)
    d2 = float(np.hypot(*(target - obj)))
    v_obj = geo.start_speed(arrival, d2, PHYSICS)
    n = u
    for _ in range(4):
        ghost = obj - 2.0 * R * n
        d1 = float(np.hypot(*(ghost - cue)))
        if d1 < 1e-9:
            return None
        d = (ghost - cue) / d1
        t = np.array([-n[1], n[0]])
        dn, dt = float(d @ n), float(d @ t)
        if dn < math.cos(max_cut):
            return None
        v_impact = v_obj / (0.5 * (1.0 + PHYSICS.e_b) * dn)
        speed = geo.start_speed(v_impact, d1, PHYSICS)
        roll = geo.forward_spin_after(speed, d1, PHYSICS)
        on, ot, cn, ct = geo.collision(v_impact, roll, dn, dt, PHYSICS)
        n = geo.rotate(u, -math.atan2(ot, on))
    if speed > MAX_SPEED or not (R <= ghost[0] <= TABLE.length - R and R <= ghost[1] <= TABLE.width - R):
        return None
    if not geo.path_clear(cue, ghost, others, 2.0 * R * 1.02):
        return None
    path = geo.cue_path(ghost, cn * n + ct * t, roll * d, PHYSICS, TABLE, R)
    scratch = geo.enters_pocket(path, geo.pockets_of(TABLE) if captures is None else captures)
    score = dn * open_fraction / ((d1 + 0.5) * (d2 + 0.5)) * (0.1 if scratch else 1.0)
    return d, speed, dn, score, scratch


def test_the_ball_models_match_geometry_element_wise():
    g, mu_s, mu_r = PHYSICS.g, PHYSICS.mu_s, PHYSICS.mu_r
    for v in (0.0, 0.3, 1.1, 4.0, 11.5):
        for distance in (0.0, 0.05, 0.4, 1.7, 3.5):
            assert pk.start_speed(v, distance, g, mu_s, mu_r) == pytest.approx(geo.start_speed(v, distance, PHYSICS),
                                                                               rel=1e-12, abs=1e-15)
            assert pk.forward_spin_after(v, distance, g, mu_s, mu_r) == pytest.approx(
                geo.forward_spin_after(v, distance, PHYSICS), rel=1e-12, abs=1e-15)
    for v, roll, cut in ((2.0, 0.0, 0.0), (2.0, 1.4, 0.6), (0.4, 0.4, 1.2), (5.0, 3.0, -0.9)):
        dn, dt = math.cos(cut), math.sin(cut)
        assert pk.collision(v, roll, dn, dt, PHYSICS.e_b) == pytest.approx(geo.collision(v, roll, dn, dt, PHYSICS),
                                                                           rel=1e-12, abs=1e-15)


def near_pocket_positions():
    """Object balls a few radii off each pocket, the cue ball behind them on assorted lines
    (the cue ball often follows them in)."""
    rng = np.random.default_rng(3)
    out = []
    for x, y, _ in TABLE.pockets:
        middle = np.array([TABLE.length / 2, TABLE.width / 2])
        pocket = np.array([x, y])
        obj = pocket + (middle - pocket) / np.linalg.norm(middle - pocket) * rng.uniform(0.1, 0.3)
        for turn in (-0.4, -0.1, 0.0, 0.2):
            cue = obj + geo.rotate(geo.unit(middle - pocket), turn) * rng.uniform(0.15, 0.6)
            out.append({"xy": [cue.tolist(), obj.tolist(), [1.2, 0.3]], "on_table": [True, True, True], "legal": [1]})
    return out


def inner_captures():
    """The pockets' capture circles pulled onto the cloth, where a mirrored cue-ball path
    (geometry.cue_path keeps to the cloth) can reach them: the scratch check then fires."""
    R = BALL_RADIUS
    return [dataclasses.replace(p, centre=np.clip(p.centre, R, (TABLE.length - R, TABLE.width - R)), radius=0.06)
            for p in geo.pockets_of(TABLE)]


@pytest.mark.parametrize("captures", [None, "inner"])
def test_every_candidate_of_real_positions_matches_the_scalar_plan(captures):
    batch = pl.ShotPlanner(TABLE, PHYSICS, BALL_RADIUS)
    if captures == "inner":
        captures = inner_captures()
        batch.captures = np.array([[*p.centre, p.radius] for p in captures])
    checked = feasible = scratched = 0
    cases = [(p, 0.3) for p in POSITIONS] + [(p, v) for p in near_pocket_positions() for v in (0.3, 0.7, 1.6)]
    for position, arrival in cases:
        xy, on_table = np.array(position["xy"]), np.array(position["on_table"])
        objects = on_table.copy()
        objects[0] = False
        legal = np.zeros_like(objects)
        legal[position["legal"]] = True
        index = batch.candidates((legal & objects)[None])
        aims = batch.aims(xy[None], objects[None], index)
        rows = batch.plan(np.repeat(xy[None, 0], len(index), axis=0), xy[None], objects[None], index, aims,
                          np.full(len(index), arrival))
        for (_, ball, pocket), row in zip(index, rows):
            others = xy[np.flatnonzero(objects)[np.flatnonzero(objects) != ball]]
            want = scalar_plan(xy[0], xy[ball], geo.pockets_of(TABLE)[pocket], others, arrival, captures)
            checked += 1
            assert bool(row[pl.OK]) == (want is not None), (position, ball, pocket)
            if want is None:
                continue
            d, speed, dn, score, scratch = want
            assert row[[pl.DX, pl.DY]] == pytest.approx(d, abs=1e-9)
            assert row[pl.SPEED] == pytest.approx(speed, rel=1e-9)
            assert row[pl.DN] == pytest.approx(dn, abs=1e-9)
            assert row[pl.SCORE] == pytest.approx(score, rel=1e-9)
            assert bool(row[pl.SCRATCH]) == scratch
            feasible += 1
            scratched += scratch
    assert checked > 500 and feasible > 50  # the set has pots and misses ...
    assert (scratched > 10) == (captures is not None)  # ... and scratches where the path can reach a pocket


def test_the_break_run_planner_keeps_its_scalar_plan():
    agent = GhostBallAgent(TABLE, PHYSICS)
    position = POSITIONS[0]
    xy, on_table = np.array(position["xy"]), np.array(position["on_table"])
    objects = np.flatnonzero(on_table[1:]) + 1
    shots = agent.shots(xy, on_table)
    for ball in objects:
        for pocket in agent.pockets:
            pot = agent.plan(xy[0], int(ball), xy[ball], pocket, xy[objects[objects != ball]])
            want = scalar_plan(xy[0], xy[ball], pocket, xy[objects[objects != ball]])
            assert (pot is None) == (want is None)
            if pot is not None:
                assert pot.speed == pytest.approx(want[1], rel=1e-9)
                assert any(s.ball == ball and s.pocket == pocket.index and s.score == pot.score for s in shots)
    best = agent.best_shot(xy, on_table)
    assert best is None or best.score == max(s.score for s in shots)


def test_a_batch_of_views_gets_the_shots_of_one_view_at_a_time():
    for game in ("nine_ball", "eight_ball"):
        agent = GameGhostBallAgent(game)
        views = [GameView(np.array(p["xy"]), np.array(p["on_table"]), frozenset(p["legal"]), p["ball_in_hand"])
                 for p in POSITIONS if p["game"] == game]
        assert any(v.ball_in_hand for v in views) and any(v.ball_in_hand is None for v in views)
        assert agent.decide_batch(views) == [agent.decide(view) for view in views]
        assert agent.decide_batch([]) == []


@pytest.mark.parametrize("change, match", [
    (lambda a: {**a, "xy": a["xy"][:, :, :1]}, "xy must be"),
    (lambda a: {**a, "index": a["index"][:, :2]}, "index must be"),
    (lambda a: {**a, "index": a["index"] + np.array([0, 0, 9])}, "out of range"),
    (lambda a: {**a, "index": a["index"] * np.array([1, 0, 1])}, "out of range"),  # ball 0, the cue ball
    (lambda a: {**a, "xy": np.where(np.arange(3)[None, :, None] == 1, np.nan, a["xy"])}, "finite"),
    (lambda a: {**a, "arrival": -a["arrival"] - 1.0}, "arrival"),
    (lambda a: {**a, "cue": a["cue"][:1]}, "cue, aims and arrival"),
])
def test_bad_batches_are_named(change, match):
    batch = pl.ShotPlanner(TABLE, PHYSICS, BALL_RADIUS)
    xy = np.array([[[0.5, 0.5], [1.0, 0.5], [1.5, 0.8]]])
    on = np.array([[False, True, True]])
    index = batch.candidates(on)
    good = {"xy": xy, "index": index, "cue": np.repeat(xy[:, 0], len(index), axis=0),
            "aims": batch.aims(xy, on, index), "arrival": np.full(len(index), 0.3)}
    bad = change(good)
    with pytest.raises(ValueError, match=match):
        batch.aims(bad["xy"], on, bad["index"])
        batch.plan(bad["cue"], bad["xy"], on, bad["index"], bad["aims"], bad["arrival"])


# --- the windows against a plain loop -----------------------------------------------------------
def plain_within(px, py, ax, ay, bx, by, r):
    """plan_kernels.point_segment_within in plain Python."""
    abx, aby = bx - ax, by - ay
    length2 = abx * abx + aby * aby
    s = min(max(((px - ax) * abx + (py - ay) * aby) / (length2 if length2 > 0 else 1.0), 0.0), 1.0)
    dx, dy = px - (ax + s * abx), py - (ay + s * aby)
    d2, r2 = dx * dx + dy * dy, r * r
    return d2 < r2 * (1.0 - 1e-12) or (d2 <= r2 * (1.0 + 1e-12) and math.hypot(dx, dy) < r)


def plain_rail_within(a, b, rail, reach):
    """plan_kernels.segments_within of the line a-b and a rail, in plain Python."""
    (ax, ay), (bx, by), (cx, cy, dx, dy) = a, b, rail

    def cross(ox, oy, px, py, qx, qy):
        return (px - ox) * (qy - oy) - (py - oy) * (qx - ox)

    if (max(cx, dx) < min(ax, bx) - reach or min(cx, dx) > max(ax, bx) + reach
            or max(cy, dy) < min(ay, by) - reach or min(cy, dy) > max(ay, by) + reach):
        return False
    if (cross(cx, cy, dx, dy, ax, ay) * cross(cx, cy, dx, dy, bx, by) < 0
            and cross(ax, ay, bx, by, cx, cy) * cross(ax, ay, bx, by, dx, dy) < 0):
        return True
    return (plain_within(ax, ay, cx, cy, dx, dy, reach) or plain_within(bx, by, cx, cy, dx, dy, reach)
            or plain_within(cx, cy, ax, ay, bx, by, reach) or plain_within(dx, dy, ax, ay, bx, by, reach))


def plain_window(batch, xy, on, ball, pocket):
    """A candidate's window row (x, y, share) the plain way: every mouth point's line tested
    against every rail and every other object ball on the table, then the first longest run."""
    (ax, ay), jaw = xy[ball], batch.jaws[pocket]
    rail_reach, ball_reach = batch.reach
    open_points = []
    for lam in batch.lams:
        bx, by = jaw[0] + lam * (jaw[2] - jaw[0]), jaw[1] + lam * (jaw[3] - jaw[1])
        rails = any(plain_rail_within((ax, ay), (bx, by), rail, rail_reach) for rail in batch.rails)
        balls = any(plain_within(xy[j, 0], xy[j, 1], ax, ay, bx, by, ball_reach)
                    for j in range(1, len(xy)) if on[j] and j != ball)
        open_points.append(not (rails or balls))
    best = best_start = run = 0
    for s, is_open in enumerate(open_points):
        run = run + 1 if is_open else 0
        if run > best:
            best, best_start = run, s - run + 1
    if best == 0:
        return [0.0, 0.0, 0.0]
    middle = 0.5 * (batch.lams[best_start] + batch.lams[best_start + best - 1])
    return [jaw[0] + middle * (jaw[2] - jaw[0]), jaw[1] + middle * (jaw[3] - jaw[1]), best / len(batch.lams)]


def crowded_positions(count=12, seed=5):
    """Positions of 15 object balls strewn over the table, a third of them near a pocket's
    mouth, so that rails and balls close some mouth points and leave others open."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(count):
        xy = rng.uniform([0.1, 0.1], [TABLE.length - 0.1, TABLE.width - 0.1], (16, 2))
        for j in rng.choice(np.arange(1, 16), 5, replace=False):
            xy[j] = TABLE.pockets[rng.integers(len(TABLE.pockets)), :2] + rng.normal(0.0, 0.12, 2)
            xy[j] = np.clip(xy[j], BALL_RADIUS, (TABLE.length - BALL_RADIUS, TABLE.width - BALL_RADIUS))
        out.append((xy, rng.uniform(size=16) < 0.9))
    return out


def test_the_windows_are_the_plain_loops_bit_for_bit():
    """aims (every candidate, `window_kernels.aim_kernel`: the obstacle that closed the last
    point tried first, the scan stopped once no longer run can come or once an obstacle closes
    every point left) gives what testing every point against every rail and ball gives, to the bit."""
    batch = pl.ShotPlanner(TABLE, PHYSICS, BALL_RADIUS)
    layouts = [(np.array(p["xy"]), np.array(p["on_table"])) for p in POSITIONS] + crowded_positions()
    shares = []
    for xy, on_table in layouts:
        objects = on_table.copy()
        objects[0] = False
        index = batch.candidates(objects[None])
        got = batch.aims(xy[None], objects[None], index)
        want = np.array([plain_window(batch, xy, objects, ball, pocket) for _, ball, pocket in index]).reshape(-1, 3)
        assert np.array_equal(got, want)
        shares.extend(want[:, 2])
    shares = np.array(shares)
    assert (shares == 0).mean() > 0.2 and ((shares > 0) & (shares < 0.3)).sum() > 100  # closed, part open ...
    assert (shares > 0.5).sum() > 100  # ... and mostly open mouths


def test_a_position_of_more_balls_than_the_windows_take_is_refused():
    batch = pl.ShotPlanner(TABLE, PHYSICS, BALL_RADIUS)
    xy = np.random.default_rng(0).uniform(0.2, 1.0, (wk.MAX_BALLS + 1, 2))
    on = np.ones(len(xy), dtype=bool)
    with pytest.raises(ValueError, match="at most 63 balls"):
        batch.aims(xy[None], on[None], batch.candidates(on[None]))
    with pytest.raises(ValueError, match="at most 63 balls"):
        batch.windows(xy, on, on)
