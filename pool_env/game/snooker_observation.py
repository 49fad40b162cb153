"""The snooker observation layout (96 entries): its encoder `snooker_observation`, decoder `decode_snooker_observation`.

| entries | meaning |
| --- | --- |
| 0-65 | the 22 balls by number (0 cue, 1-15 reds, 16-21 yellow..black): x, y onto [-1, 1], +1; potted (0, 0, -1) |
| 66-86 | the object balls 1-21: +1 the viewer (when he is to shoot) may hit it first now, else -1 |
| 87 | +1 the viewer has the cue ball in hand in the D |
| 88 | +1 the viewer has a free ball |
| 89, 90 | +1 a red is on; +1 a colour (any, to nominate) is on |
| 91 | the colour in sequence once the reds are gone: yellow -1 ... black +1 (0 while a red or colour is on) |
| 92, 93 | the viewer's score, the opponent's: points / 100 - 1, clipped (200 and more read as 200) |
| 94 | the shooter's break so far (points this visit) / 100 - 1, clipped |
| 95 | shots taken, 2 * shots / max_shots - 1 |
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import rules

SNOOKER_BALLS = 22
SNOOKER_OBS_SIZE = 3 * SNOOKER_BALLS + (SNOOKER_BALLS - 1) + 9
SCORE_SCALE = 100.0


def _points(p) -> float:
    return min(p, 2 * SCORE_SCALE) / SCORE_SCALE - 1.0


def snooker_observation(balls, state, viewer: int, shots: int, max_shots: int, table) -> np.ndarray:
    """The observation of `viewer` (0 or 1), float32 in [-1, 1] (the table in the module's doc)."""
    n = SNOOKER_BALLS
    out = np.empty(SNOOKER_OBS_SIZE, dtype=np.float32)
    per_ball = out[: 3 * n].reshape(n, 3)
    # Centres scaled onto [-1, 1] (clipped: a ball hanging in a mouth), +1 on the table.
    per_ball[:, 0:2] = np.clip(balls.xy * (2.0 / table.length, 2.0 / table.width) - 1.0, -1.0, 1.0)
    per_ball[:, 2] = 1.0
    per_ball[balls.pocketed] = (0.0, 0.0, -1.0)
    legal = out[3 * n: 4 * n - 1]
    legal[:] = -1.0
    mine = state.shooter == viewer and state.winner is None
    if mine:
        legal[[ball - 1 for ball in rules.legal_targets(state)]] = 1.0
    on = state.ball_on
    sequence = 0.0 if on in ("red", "colour") else (on - 16) / 2.5 - 1.0
    tail = [1.0 if mine and state.ball_in_hand == "in_d" else -1.0, 1.0 if mine and state.free_ball else -1.0,
            1.0 if on == "red" else -1.0, 1.0 if on == "colour" else -1.0, sequence,
            _points(state.scores[viewer]), _points(state.scores[1 - viewer]), _points(state.visit),
            2.0 * min(shots, max_shots) / max_shots - 1.0]
    out[4 * n - 1:] = tail
    return out


@dataclass(frozen=True)
class SnookerView:
    """A snooker observation read back: positions (22, 2) m, on-table flags, the legal first
    contacts (empty when the opponent is to shoot), `in_hand` and `free_ball` (the viewer's),
    `ball_on` ("red", "colour" or 16-21), `scores` (viewer, opponent), `visit`, `counter`."""

    xy: np.ndarray
    on_table: np.ndarray
    legal: frozenset
    in_hand: bool
    free_ball: bool
    ball_on: object
    scores: tuple
    visit: int
    counter: float


def decode_snooker_observation(obs, table) -> SnookerView:
    """The `SnookerView` of a snooker observation; ValueError for a wrong shape."""
    n = SNOOKER_BALLS
    obs = np.asarray(obs, dtype=np.float64)
    if obs.shape != (SNOOKER_OBS_SIZE,):
        raise ValueError(f"a snooker observation has shape ({SNOOKER_OBS_SIZE},), got {obs.shape}")
    per_ball = obs[: 3 * n].reshape(n, 3)
    on_table = per_ball[:, 2] > 0
    xy = np.column_stack([(per_ball[:, 0] + 1.0) * 0.5 * table.length, (per_ball[:, 1] + 1.0) * 0.5 * table.width])
    legal = frozenset(int(b) + 1 for b in np.flatnonzero(obs[3 * n: 4 * n - 1] > 0))
    t = obs[4 * n - 1:]
    ball_on = "red" if t[2] > 0 else "colour" if t[3] > 0 else 16 + int(round((t[4] + 1.0) * 2.5))
    scores = tuple(int(round((v + 1.0) * SCORE_SCALE)) for v in t[5:7])
    return SnookerView(xy, on_table, legal, bool(t[0] > 0), bool(t[1] > 0), ball_on, scores,
                       int(round((t[7] + 1.0) * SCORE_SCALE)), float(t[8]))
