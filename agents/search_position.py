"""What the search player reads from an observation: the position (`decode`), its rules' state, its balls."""

from __future__ import annotations

import dataclasses

import numpy as np

from pool_env import rules
from pool_env.game import GAME_BALLS, GameView, decode_game_observation, decode_observation
from pool_env.physics import BALL_RADIUS, Balls, Table

SEPARATION, SEPARATION_PASSES = 1e-9, 5  # m: overlaps the observation's rounding leaves, undone


def legal_mask(legal, n_balls: int) -> np.ndarray:
    """(n_balls,) bool of a set of legal ball numbers (the cue ball's entry False)."""
    mask = np.zeros(n_balls, dtype=bool)
    mask[[int(b) for b in legal]] = True
    return mask


def decode(observation, n_balls: int, table: Table, game: bool = True) -> GameView:
    """Read a game observation (`pool_env.game.decode_game_observation`, n_balls 10, 11 or 16) or,
    with `game=False`, a `PoolBreakEnv` observation (16 balls, every object ball legal)."""
    if game:
        game_of_size = {n: name for name, n in GAME_BALLS.items()}  # 10 nine_ball, 11 ten_ball, 16 eight_ball
        return decode_game_observation(observation, game_of_size[n_balls], table)
    xy, on_table = decode_observation(observation, table)
    xy = np.where(on_table[:, None], xy, 0.5 * np.array([table.length, table.width]))
    return GameView(xy, on_table, frozenset(int(b) for b in np.flatnonzero(on_table[1:]) + 1))


def racked(xy, on_table, radius: float = BALL_RADIUS) -> bool:
    """Every object ball on the table, each touching (within 10 %) another: the break is next."""
    p = xy[1:][on_table[1:]]
    if len(p) < len(xy) - 1 or len(p) < 2:
        return False
    d = np.hypot(p[:, None, 0] - p[None, :, 0], p[:, None, 1] - p[None, :, 1])
    np.fill_diagonal(d, np.inf)
    return bool(np.all(d.min(axis=1) < 2.2 * radius))


def game_state(decoded: GameView, game: str, rule_options: dict | None = None) -> rules.GameState:
    """The `rules.GameState` of a decoded game observation, the shooter as player 0."""
    state = rules.new_game(game, breaker=0, **(rule_options or {}))
    groups = (None, None)
    if decoded.group is not None:
        groups = (decoded.group, "stripes" if decoded.group == "solids" else "solids")
    on = frozenset(int(b) for b in np.flatnonzero(decoded.on_table[1:]) + 1)
    is_break = decoded.ball_in_hand == "behind_head_string" and racked(decoded.xy, decoded.on_table)
    return dataclasses.replace(state, on_table=on, shooter=0, ball_in_hand=decoded.ball_in_hand,
                               fouls=decoded.fouls, groups=groups, is_break=is_break, shot=0 if is_break else 1,
                               push_out=bool(decoded.push_out and not is_break))


def balls_of(decoded: GameView, radius: float = BALL_RADIUS) -> Balls:
    """The balls of a decoded observation (pocketed balls parked at the origin). Touching balls
    that the observation's float32 rounding made overlap are pushed apart to touch."""
    xy = np.where(decoded.on_table[:, None], decoded.xy, 0.0)
    on = np.flatnonzero(decoded.on_table)
    p = xy[on]
    d = np.hypot(p[:, None, 0] - p[None, :, 0], p[:, None, 1] - p[None, :, 1]) + 3.0 * radius * np.eye(len(on))
    for _ in range(SEPARATION_PASSES if np.any(d < 2.0 * radius + SEPARATION) else 0):
        moved = False
        for a in range(len(on)):
            for b in range(a + 1, len(on)):
                gap = xy[on[b]] - xy[on[a]]
                dist = float(np.hypot(*gap))
                if dist < 2.0 * radius + SEPARATION and dist > 0.0:
                    push = gap / dist * (2.0 * radius + SEPARATION - dist) * 0.5
                    xy[on[a]] -= push
                    xy[on[b]] += push
                    moved = True
        if not moved:
            break
    return Balls(xy, radius=radius, pocketed=~decoded.on_table)

