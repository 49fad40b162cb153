"""The snooker mode: 22 balls, ball in hand in the D (a half circle), the action and observation round trips."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env.game import Game, Shot, decode_game_observation, game_observation, game_observation_size
from pool_env.game.placement import HalfDisc
from pool_env.rules.snooker_spots import baulk_x, colour_spots, d_radius


@pytest.fixture(scope="module")
def game():
    return Game("snooker", seed=0)


def test_mode_defaults(game):
    assert game.n_balls == 22 and len(game.balls) == 22 and game.table.length == 3.569
    assert game.state.ball_on == "red" and game.ball_in_hand == "in_d"
    assert game.balls.radii[0] == pytest.approx(0.02625)


def test_placement_maps_onto_the_d(game):
    # WPBSA Section 3 Rule 4 / Section 1 Rule 1(e): on or within the D, a half circle of 292 mm
    # on the baulk line's middle, in baulk.
    area = game.placement_area()
    assert isinstance(area, HalfDisc)
    cx, cy, r = baulk_x(game.table), game.table.width / 2, d_radius(game.table)
    rng = np.random.default_rng(0)
    for a in rng.uniform(-1, 1, (200, 2)):
        action = np.array([0.3, 0.1, 0.0, 0.0, *a], dtype=np.float32)
        place = game.decode(action).place
        assert place[0] <= cx + 1e-12 and math.hypot(place[0] - cx, place[1] - cy) <= r + 1e-12
    # The corners of the entries: the D's arc ends are the yellow and green spots, -1 the centre.
    spots = colour_spots(game.table)
    assert game.decode(np.array([0, .1, 0, 0, 1, -1])).place == pytest.approx(spots[16])
    assert game.decode(np.array([0, .1, 0, 0, 1, 1])).place == pytest.approx(spots[17])
    assert game.decode(np.array([0, .1, 0, 0, -1, 0.3])).place == pytest.approx((cx, cy))
    assert game.decode(np.array([0, .1, 0, 0, 1, 0])).place == pytest.approx((cx - r, cy))


def test_action_round_trip(game):
    rng = np.random.default_rng(1)
    for _ in range(100):
        a = rng.uniform(-1, 1, 6).astype(np.float32)
        a[4] = max(a[4], -0.99)  # off the centre, where the direction is undefined
        shot = game.decode(a)
        back = game.decode(game.encode(shot))
        assert back.place == pytest.approx(shot.place, abs=1e-5)
        assert back.force == pytest.approx(shot.force, rel=1e-5) and back.tip == pytest.approx(shot.tip, abs=1e-6)


def test_placed_cue_ball_stays_in_the_d(game):
    g = Game("snooker", seed=2)
    cx, cy, r = baulk_x(g.table), g.table.width / 2, d_radius(g.table)
    record = g.play(Shot.aimed((1.0, 0.0), 0.5, place=(cx + 0.5, cy + 0.5)))  # asked outside: the nearest D spot
    x, y = record.balls_before.xy[0]
    assert x <= cx + 1e-9 and math.hypot(x - cx, y - cy) <= r + 1e-9


def test_observation_round_trip(game):
    g = Game("snooker", seed=3)
    rng = np.random.default_rng(3)
    for _ in range(6):
        if g.over:
            break
        g.play(rng.uniform(-1, 1, 6))
    for viewer in (0, 1):
        obs = game_observation(g.balls, g.state, viewer, g.shots, 100, g.table)
        assert obs.shape == (game_observation_size("snooker"),) == (96,)
        assert obs.dtype == np.float32 and np.all(np.abs(obs) <= 1)
        view = decode_game_observation(obs, "snooker", g.table)
        on = ~g.balls.pocketed
        assert np.array_equal(view.on_table, on)
        assert np.allclose(view.xy[on], g.balls.xy[on], atol=1e-6)
        assert view.scores == (g.state.scores[viewer], g.state.scores[1 - viewer])
        assert view.ball_on == g.state.ball_on and view.visit == g.state.visit
        mine = g.state.shooter == viewer
        assert view.legal == (g.legal_targets if mine else frozenset())
        assert view.in_hand == (mine and g.ball_in_hand == "in_d")
    with pytest.raises(ValueError, match="shape"):
        decode_game_observation(np.zeros(44), "snooker", g.table)


def test_snapshot_restore_and_evaluate_are_exact():
    g = Game("snooker", noise="olympiad", seed=4)
    snap = g.snapshot()
    shot = Shot.aimed((1.0, 0.05), 6.0, place=(0.6, 0.85))
    first = g.play(shot)
    g.restore(snap)
    again = g.play(shot)
    assert np.array_equal(first.balls_after.xy, again.balls_after.xy) and first.ruling == again.ruling
    g.restore(snap)
    (evaluated,) = g.evaluate([shot])
    assert np.array_equal(evaluated.balls_after.xy, first.balls_after.xy)


def test_a_layout_mid_frame():
    g = Game("snooker", seed=5)
    balls = g.balls
    pocketed = balls.pocketed.copy()
    pocketed[1:16] = True
    cls = balls.__class__
    g.reset(balls=cls(balls.xy, radius=balls.radius, mass=balls.mass, pocketed=pocketed), ball_in_hand=True)
    assert g.state.ball_on == 16 and g.ball_in_hand == "in_d" and g.legal_targets == {16}
