"""The built-in snooker player, and random frames checked shot by shot (the fuzz harness, agents/snooker_match.py)."""

from __future__ import annotations

import numpy as np
import pytest

from agents.snooker_match import fuzz, play_frame, random_player
from pool_env.game import Game
from pool_env.physics import Balls
from pool_env.players.snooker import SnookerPlayer
from pool_env.rules.snooker_spots import colour_spots


def test_player_pots_a_red_over_the_pocket():
    # One red 0.3 m from the top-left corner on its diagonal, the cue ball 0.5 m behind it on the
    # same line, the colours on their spots: a straight pot worth 1 (WPBSA Section 3 Rule 1).
    game = Game("snooker", seed=0)
    table = game.table
    xy = game.balls.xy.copy()
    pocketed = np.ones(22, bool)
    pocketed[0] = pocketed[16:] = False
    for c, spot in colour_spots(table).items():
        xy[c] = spot
    corner = np.array([table.length, table.width])
    u = np.array([1.0, 1.0]) / np.sqrt(2.0)
    xy[1] = corner - 0.3 * u
    xy[0] = xy[1] - 0.5 * u
    pocketed[1] = False
    game.reset(balls=Balls(xy, radius=game.balls.radius, mass=game.balls.mass, pocketed=pocketed))
    record = game.play(SnookerPlayer(game, seed=0).decide())
    assert record.pocketed == (1,) and record.foul is None and game.state.scores == (1, 0)
    assert game.shooter == 0 and game.state.ball_on == "colour"


def test_player_outscores_the_random_player():
    game = Game("snooker", noise="olympiad", seed=1)
    player = SnookerPlayer(game, seed=1)
    result = play_frame(game, (lambda g: player.decide(), random_player(1)), 0, 1, max_shots=120)
    assert result["scores"][0] > result["scores"][1] and result["winner"] == 0


def test_random_frames_stay_sound():
    # 200 random frames of up to 50 shots each, with and without noise: every state valid, every
    # ball accounted for, the scores grown by exactly the points and penalties (check_shot).
    for noise in (None, "olympiad"):
        out = fuzz(100, noise, seed=7, max_shots=50)
        assert out["frames"] == 100 and sum(out["ended"].values()) == 100


def test_a_tight_row_rounded_to_float32_is_separated_to_touching_balls():
    from pool_env.players.geometry import separated

    r = 0.02625
    xy = np.array([(1.0 + k * 2.0 * r * (1.0 - 2e-7), 0.5) for k in range(6)])  # each pair 21 nm too close
    out = separated(xy, np.zeros(6, dtype=bool), r)
    gaps = [np.hypot(*(out[j] - out[i])) - 2.0 * r for i in range(6) for j in range(i + 1, 6)]
    assert min(gaps) >= 0.0  # no two balls overlap (one pass leaves the middle pairs pressed together)
    assert np.max(np.abs(out - xy)) < 1e-6  # moved by rounding's scale, not more
    with pytest.raises(ValueError, match="overlap"):
        separated(np.array([(1.0, 0.5), (1.0 + r, 0.5)]), np.zeros(2, dtype=bool), r, passes=0)
