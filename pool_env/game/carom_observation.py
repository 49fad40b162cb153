"""The three-cushion observation layout, one player's side: one encoder and one decoder."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..physics import Balls, Table

CAROM_OBSERVATION_SIZE = 15
# Scores and innings map onto [-1, 1] over [0, cap]: the game's distance (points) or innings
# limit, else this many (a count past the cap reads as the cap).
DEFAULT_CAP = 50


@dataclass(frozen=True)
class CaromView:
    """A three-cushion observation read back, from the viewer's side: the balls' positions
    (3, 2) in metres by ball (0 white, 1 yellow, 2 red); `own_ball` the viewer's cue ball;
    `to_shoot` the viewer shoots next; `is_break` a starting stroke; `equalizing` the
    equalising inning; `scores` and `innings` (viewer, opponent); `counter` the shot counter entry."""

    xy: np.ndarray
    own_ball: int
    to_shoot: bool
    is_break: bool
    equalizing: bool
    scores: tuple
    innings: tuple
    counter: float


def caps(rules) -> tuple:
    """(score cap, innings cap) of a `ThreeCushion` rule set."""
    return (rules.points or DEFAULT_CAP, rules.innings_limit or DEFAULT_CAP)


def position_entry(v: float, scale: float) -> np.float32:
    """A centre's coordinate scaled onto [-1, 1] and rounded to float32, as the pool games'
    observations keep it (observation.position_entry, which is compiled-only)."""
    return np.float32(min(max(v * scale - 1.0, -1.0), 1.0))


def _scaled(count, cap) -> float:
    return 2.0 * min(count, cap) / cap - 1.0


def carom_observation(balls: Balls, state, viewer: int, shots: int, max_shots: int, table: Table) -> np.ndarray:
    """The observation (15,) float32 in [-1, 1] of `viewer` (0 or 1):

    | entries | meaning |
    | --- | --- |
    | 0-5 | x, y of the viewer's cue ball, the opponent's cue ball, the red: scaled onto [-1, 1] over the table |
    | 6 | +1 the viewer plays the white (ball 0), -1 the yellow (ball 1) |
    | 7 | +1 the viewer shoots next |
    | 8 | +1 a starting stroke (the red must be hit first) |
    | 9 | +1 the equalising inning |
    | 10, 11 | the viewer's and the opponent's score, over [0, the distance] (else [0, 50]) |
    | 12, 13 | the viewer's and the opponent's innings, over [0, the innings limit] (else [0, 50]) |
    | 14 | shots taken, over [0, max_shots] |
    """
    own = state.cue_ball if state.shooter == viewer else 1 - state.cue_ball
    order = (own, 1 - own, 2)
    sx, sy = 2.0 / table.length, 2.0 / table.width
    out = np.empty(CAROM_OBSERVATION_SIZE, dtype=np.float32)
    for k, ball in enumerate(order):
        out[2 * k] = position_entry(float(balls.xy[ball, 0]), sx)
        out[2 * k + 1] = position_entry(float(balls.xy[ball, 1]), sy)
    score_cap, innings_cap = caps(state.rules)
    flags = (own == 0, state.shooter == viewer and not state.ended, state.is_break, state.equalizing)
    out[6:10] = [1.0 if f else -1.0 for f in flags]
    out[10:14] = [_scaled(state.scores[viewer], score_cap), _scaled(state.scores[1 - viewer], score_cap),
                  _scaled(state.innings[viewer], innings_cap), _scaled(state.innings[1 - viewer], innings_cap)]
    out[14] = _scaled(shots, max_shots)
    return out


def decode_carom_observation(obs, table: Table, rules) -> CaromView:
    """The `CaromView` of a three-cushion observation on `table` under `rules` (a `ThreeCushion`,
    for the score and innings caps). ValueError for a wrong shape."""
    obs = np.asarray(obs, dtype=np.float64)
    if obs.shape != (CAROM_OBSERVATION_SIZE,):
        raise ValueError(f"a three-cushion observation has shape ({CAROM_OBSERVATION_SIZE},), got {obs.shape}")
    own = 0 if obs[6] > 0 else 1
    xy = np.empty((3, 2))
    for k, ball in enumerate((own, 1 - own, 2)):
        xy[ball] = ((obs[2 * k] + 1.0) * 0.5 * table.length, (obs[2 * k + 1] + 1.0) * 0.5 * table.width)
    score_cap, innings_cap = caps(rules)
    count = [int(round((obs[10 + k] + 1.0) * 0.5 * (score_cap if k < 2 else innings_cap))) for k in range(4)]
    return CaromView(xy, own, bool(obs[7] > 0), bool(obs[8] > 0), bool(obs[9] > 0), (count[0], count[1]),
                     (count[2], count[3]), float(obs[14]))
