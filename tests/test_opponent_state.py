"""The built-in opponent reading the game (`game_view`, `Game.strike_encoded`) plays as the observation player."""

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the ids)
from pool_env import rules
from pool_env.game import (
    Game,
    Shot,
    decode_action,
    decode_entries,
    decode_game_observation,
    encode_action,
    encoded_entries,
    game_observation,
    game_view,
    placement_area,
)
from pool_env.physics import BALL_RADIUS
from pool_env.players import GameGhostBallAgent
from pool_env.players import geometry as geo
from pool_env.players import plan_kernels as pk
from pool_env.players import position_kernels as positions_k

IDS = ("PoolNineBall-v0", "PoolEightBall-v0")


def positions(env_id, seed, steps=40):
    """(balls, state, agent shots) after each step of random actions: real positions, pocketed
    balls, ball in hand and (8-ball) groups among them."""
    env = gym.make(env_id)
    env.reset(seed=seed)
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(steps):
        _, _, terminated, truncated, _ = env.step(rng.uniform(-1, 1, env.action_space.shape).astype(np.float32))
        if terminated or truncated:
            env.reset()
        base = env.unwrapped
        out.append((base.balls, base.state, base.shots, base.table))
    return out


@pytest.mark.parametrize("env_id", IDS)
def test_game_view_is_the_observation_read_back_bit_for_bit(env_id):
    game = "nine_ball" if env_id == "PoolNineBall-v0" else "eight_ball"
    seen_hand = seen_pocketed = False
    for balls, state, shots, table in positions(env_id, seed=4):
        for viewer in (0, 1):
            want = decode_game_observation(game_observation(balls, state, viewer, shots, 100, table), game, table)
            got = game_view(balls, state, viewer, shots, 100, table)
            assert got.xy.tobytes() == want.xy.tobytes() and got.xy.dtype == want.xy.dtype
            assert got.on_table.tolist() == want.on_table.tolist()
            assert (got.legal, got.ball_in_hand, got.fouls, got.group, got.counter) == \
                (want.legal, want.ball_in_hand, want.fouls, want.group, want.counter)
            seen_hand |= got.ball_in_hand is not None
        seen_pocketed |= bool(balls.pocketed.any())
    assert seen_hand and seen_pocketed


def test_a_ball_hanging_in_a_mouth_is_clipped_in_the_view_as_in_the_observation():
    game = Game("nine_ball", seed=0)
    xy = game.balls.xy.copy()
    xy[3] = (game.table.length + 0.01, -0.02)  # past the foot rail and the side rail: clipped to the edges
    balls = pool_env.physics.Balls(xy, pocketed=game.balls.pocketed)
    view = game_view(balls, game.state, 0, 0, 100, game.table)
    assert view.xy[3].tolist() == [game.table.length, 0.0]
    want = decode_game_observation(game_observation(balls, game.state, 0, 0, 100, game.table), "nine_ball", game.table)
    assert view.xy.tobytes() == want.xy.tobytes()


@pytest.mark.parametrize("layout", ["nine_ball", "eight_ball_call", "eight_ball_call+elevation"])
def test_strike_encoded_is_strike_of_the_encoded_action(layout):
    mode = "eight_ball" if layout.startswith("eight_ball") else layout.split("+")[0]
    game = Game(mode, seed=1, layout=layout)
    rng = np.random.default_rng(2)
    for k in range(40):
        area = game.placement_area()
        place = None if area is None or k % 3 == 0 else (rng.uniform(area[0], area[1]), rng.uniform(area[2], area[3]))
        shot = Shot.aimed((rng.normal(), rng.normal()), rng.uniform(0.01, 12.0), (rng.uniform(-0.3, 0.3), 0.1),
                          place=place, pocket=int(rng.integers(6)) if k % 2 else None)
        targets = game.called_targets  # 8-ball's called-ball entry chooses among them (WPA 1.6)
        entries = encoded_entries(game.layout, shot, area, 6, targets)
        action = encode_action(game.layout, shot, area, 6, targets)
        assert entries == action.astype(np.float64).tolist()  # the float32 entries, as Python floats
        assert decode_entries(game.layout, entries, area, 6, targets) == decode_action(game.layout, action, area, 6,
                                                                                       targets)
        snapshot = game.snapshot()
        direct = game.strike_encoded(shot)
        game.restore(snapshot)
        vector = game.strike(action)
        for field in ("shot", "action", "shooter", "ball_in_hand", "called_pocket", "elevation"):
            assert getattr(direct, field) == getattr(vector, field), field
        assert np.asarray(direct.force).tobytes() == np.asarray(vector.force).tobytes()
        assert direct.placed.xy.tobytes() == vector.placed.xy.tobytes()
        game.resolve(vector, pool_env.game.simulate_struck(vector, game.table, game.physics))
        if game.over:
            game.reset()


@pytest.mark.parametrize("env_id", IDS)
@pytest.mark.parametrize("kwargs", [{}, {"noise": "olympiad", "agent_breaks": False}])
def test_the_opponent_reading_the_game_plays_the_observation_players_game(env_id, kwargs):
    """opponent="ghost_ball" reads the Game (game_view, strike_encoded); the same player given
    as an agent plays from its observations through act: the same episodes, bit for bit."""
    direct = gym.make(env_id, **kwargs)
    player = GameGhostBallAgent.from_env(direct)  # an agent: the env hands it observations, decodes its actions
    observing = gym.make(env_id, opponent=player, **kwargs)
    for seed in (0, 1):
        a, b = direct.reset(seed=seed), observing.reset(seed=seed)
        assert a[0].tobytes() == b[0].tobytes()
        rng = np.random.default_rng(seed)
        for _ in range(25):
            action = rng.uniform(-1, 1, direct.action_space.shape).astype(np.float32)
            x, y = direct.step(action), observing.step(action)
            assert x[0].tobytes() == y[0].tobytes() and x[1:4] == y[1:4]
            assert {k: np.asarray(v).tolist() for k, v in x[4].items()} == \
                {k: np.asarray(v).tolist() for k, v in y[4].items()}
            mine, theirs = direct.unwrapped.step_records, observing.unwrapped.step_records
            assert [(r.shot, r.action) for r in mine] == [(r.shot, r.action) for r in theirs]
            if x[2] or x[3]:
                direct.reset()
                observing.reset()


def test_the_safety_goes_at_the_nearest_legal_ball_with_a_clear_line():
    """safety_ball against the scalar geometry: sort by distance, then geometry.path_clear."""
    rng = np.random.default_rng(5)
    clearance = 2.0 * BALL_RADIUS * pk.PATH_CLEARANCE
    checked = 0
    for _ in range(300):
        n = 10
        xy = rng.uniform(0.1, 1.0, (n, 2)) * (2.2, 1.1)
        on = rng.uniform(size=n) < 0.8
        legal = on & (rng.uniform(size=n) < 0.6)
        on[0] = legal[0] = False
        balls = [b for b in range(1, n) if legal[b]]
        balls.sort(key=lambda b: float(np.hypot(*(xy[b] - xy[0]))))
        want = -1 if not balls else next(
            (b for b in balls if geo.path_clear(xy[0], xy[b], xy[[j for j in range(1, n) if on[j] and j != b]],
                                                clearance)), balls[0])
        got = positions_k.safety_ball(xy[None], on[None], legal, clearance, np.empty(n, dtype=np.int64), np.empty(n))
        assert got == want
        checked += want > 0
    assert checked > 200


def test_one_position_planned_in_one_call_is_the_batch_plan():
    """ShotPlanner.plan_lie and plan_from give candidates, aims, plan and first_best's rows; best_lie
    plan_lie's choice, best_from plan_from's."""
    agent = GameGhostBallAgent("eight_ball")
    batch = agent.planner.batch
    for balls, state, _, table in positions("PoolEightBall-v0", seed=3, steps=30):
        if state.winner is not None:
            continue
        xy = np.ascontiguousarray(balls.xy)[None]
        on = (~balls.pocketed)[None].copy()
        on[0, 0] = False
        legal = np.zeros_like(on)
        legal[0, list(rules.legal_targets(state))] = True
        legal &= on
        index = batch.candidates(legal)
        aims = batch.aims(xy, on, index)
        rows = batch.plan(np.repeat(xy[0, :1], len(index), axis=0), xy, on, index, aims, np.full(len(index), 0.3))
        best = pool_env.players.planner.first_best(rows, np.zeros(len(index)), 1)[0]
        got_index, got_rows, got_best = batch.plan_lie(xy[0], on[0], legal[0], 0.3)
        assert got_index.tolist() == index.tolist() and got_rows.tobytes() == rows.tobytes() and got_best == best
        # best_lie plans only the candidates its bound leaves in: plan_lie's choice and row
        lie_index, found, k = batch.best_lie(xy[0], on[0], legal[0], 0.3)
        assert lie_index.tolist() == index.tolist() and k == best
        assert (found is None) == (best < 0) and (found is None or found.tobytes() == rows[best].tobytes())
        spots = np.array([xy[0, 0], xy[0, 0] + 0.05, placement_area(table, "anywhere", BALL_RADIUS)[::2]])
        many, spot, row = batch.plan_from(xy, on, index, aims, spots, 0.3)
        assert many[:len(index)].tobytes() == rows.tobytes()
        scores = [max((r[pk.SCORE] for r in many[s * len(index):(s + 1) * len(index)] if r[pk.OK] > 0),
                      default=-np.inf) for s in range(3)]
        assert spot == (-1 if max(scores) == -np.inf else int(np.argmax(scores)))
        # best_from skips the candidates its bound rules out: the same spot, candidate and row
        found, best_spot, k = batch.best_from(xy, on, index, aims, spots, 0.3)
        assert best_spot == spot and (found is None) == (spot < 0)
        if spot >= 0:
            assert best_spot * len(index) + k == row and found.tobytes() == many[row].tobytes()


def test_the_straight_in_spots_are_behind_each_open_window_and_free():
    """straight_in_spots against the formula in numpy: 2 R + back behind the ball on the line
    from its aim point, inside the area and 2.2 R from every object ball."""
    agent = GameGhostBallAgent("eight_ball")
    backs = np.array([0.15, 0.35])
    checked = 0
    for balls, state, _, table in positions("PoolEightBall-v0", seed=6, steps=30):
        if state.winner is not None:
            continue
        on = ~balls.pocketed
        on[0] = False
        legal = np.zeros_like(on)
        legal[list(rules.legal_targets(state))] = True
        index, aims = agent.planner.batch.windows(balls.xy, on, legal & on)
        area = placement_area(table, "anywhere", BALL_RADIUS)
        open_ = aims[:, 2] > 0
        ball, target, share = balls.xy[index[open_, 1]], aims[open_, :2], aims[open_, 2]
        d2 = np.hypot(*(target - ball).T)
        u = (target - ball) / np.where(d2 > 0, d2, 1.0)[:, None]
        want = (ball[:, None, :] - u[:, None, :] * (2.0 * BALL_RADIUS + backs)[None, :, None]).reshape(-1, 2)
        rank = (share[:, None] / ((d2[:, None] + 0.5) * (backs[None, :] + 0.5))).reshape(-1)
        gap = np.hypot(balls.xy[on][None, :, 0] - want[:, None, 0], balls.xy[on][None, :, 1] - want[:, None, 1])
        keep = (area[0] <= want[:, 0]) & (want[:, 0] <= area[1]) & (area[2] <= want[:, 1]) & (want[:, 1] <= area[3]) \
            & (gap.min(axis=1, initial=np.inf) >= 2.2 * BALL_RADIUS)
        spots, ranks = np.empty((2 * len(index), 2)), np.empty(2 * len(index))
        limits = np.array([*area, 2.2 * BALL_RADIUS, BALL_RADIUS])
        m = positions_k.straight_in_spots(np.ascontiguousarray(balls.xy), on, index, aims, backs, limits, spots, ranks)
        assert spots[:m].tobytes() == want[keep].tobytes() and ranks[:m].tobytes() == rank[keep].tobytes()
        flags = np.empty(len(want), dtype=bool)
        positions_k.free_spots(np.ascontiguousarray(balls.xy), on, want, limits, flags)
        assert flags.tolist() == keep.tolist()
        checked += m
    assert checked > 20


def test_best_from_matches_planning_every_spot_on_random_layouts():
    """best_from against plan_from's exhaustive rows on random 8-ball layouts, each planned
    from a grid of cue-ball spots: the same spot, candidate and row (ties and near-ties
    included: the grid repeats spots, and the first of equal pots must win)."""
    agent = GameGhostBallAgent("eight_ball")
    batch, table = agent.planner.batch, agent.table
    rng = np.random.default_rng(11)
    area = placement_area(table, "anywhere", BALL_RADIUS)
    grid = np.array([(x, y) for x in np.linspace(area[0], area[1], 5) for y in np.linspace(area[2], area[3], 3)])
    spots = np.vstack([grid, grid[:3]])  # repeated spots tie exactly
    chosen = 0
    for _ in range(60):
        xy = np.column_stack([rng.uniform(area[0], area[1], 16), rng.uniform(area[2], area[3], 16)])[None]
        on = rng.random((1, 16)) < 0.7
        on[0, 0] = False
        legal = on & (rng.random((1, 16)) < 0.6)
        index = batch.candidates(legal)
        aims = batch.aims(xy, on, index)
        many, spot, row = batch.plan_from(xy, on, index, aims, spots, 0.3)
        found, best_spot, k = batch.best_from(xy, on, index, aims, spots, 0.3)
        assert best_spot == spot and (found is None) == (spot < 0)
        if spot >= 0:
            chosen += 1
            assert best_spot * len(index) + k == row and found.tobytes() == many[row].tobytes()
    assert chosen > 30


def test_plan_from_and_best_from_refuse_windows_or_spots_that_are_not_finite():
    batch = GameGhostBallAgent("eight_ball").planner.batch
    xy = np.column_stack([np.linspace(0.3, 2.0, 16), np.full(16, 0.6)])[None]
    on = np.ones((1, 16), dtype=bool)
    on[0, 0] = False
    index = batch.candidates(on)
    aims = batch.aims(xy, on, index)
    spots = np.array([[0.5, 0.4], [0.7, 0.9]])
    for bad_aims, bad_spots in ((aims, np.array([[0.5, np.nan]])), (np.where(aims == aims[0, 0], np.inf, aims), spots)):
        for plan in (batch.plan_from, batch.best_from):
            with pytest.raises(ValueError, match="aims and spots must be finite"):
                plan(xy, on, index, bad_aims, bad_spots, 0.3)


def test_the_ball_in_hand_call_is_the_windows_the_spots_and_best_from_one_by_one():
    """ShotPlanner.plan_in_hand (one compiled call) against its steps made one by one: the
    windows, the player's spots (`spots`: numpy's lexsort of the straight-in spots, or the
    grid's free ones) and best_from of them; crowded layouts (the grid's turn) and open ones."""
    agent = GameGhostBallAgent("eight_ball")
    batch, table = agent.planner.batch, agent.table
    rng = np.random.default_rng(4)
    kinds = set()
    for trial in range(80):
        where = "anywhere" if trial % 2 else "behind_head_string"
        area = placement_area(table, where, BALL_RADIUS)
        xy = np.column_stack([rng.uniform(0.1, table.length - 0.1, 16), rng.uniform(0.1, table.width - 0.1, 16)])
        if trial % 5 == 0:  # the kitchen crowded: few or no straight-in spots are free
            xy[1:9] = np.column_stack([rng.uniform(area[0], area[1], 8), rng.uniform(area[2], area[3], 8)])
        on = rng.random(16) < 0.8
        on[0] = False
        legal = on & (rng.random(16) < 0.5)
        index, aims = batch.windows(xy, on, legal)
        spots = np.array(agent.spots(xy, on, index, aims, area)).reshape(-1, 2)
        found, spot, k = batch.best_from(xy[None], on[None], index, aims, spots, 0.3)
        got_index, got_aims, tried, got_spot, got_k, got_row = batch.plan_in_hand(xy, on, legal, 0.3,
                                                                                  agent.hand_tables(area), 6)
        assert got_index.tolist() == index.tolist() and got_aims.tobytes() == aims.tobytes()
        assert tried.tobytes() == spots.tobytes() and (got_spot, got_k) == (spot, k)
        assert (got_row is None) == (found is None) and (found is None or got_row.tobytes() == found.tobytes())
        on_grid = len(spots) and all((agent.hand_tables(area)[2] == s).all(axis=1).any() for s in spots)
        kinds.add(("grid" if on_grid else "straight-in" if len(spots) else "none", spot >= 0))
    assert {("straight-in", True), ("grid", True)} <= kinds
