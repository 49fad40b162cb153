"""The "dict" observations: the state vector's decoded view as named arrays (a gymnasium Dict space), per layout."""

from __future__ import annotations

import numpy as np
from gymnasium import spaces

from .. import rules
from ..game import GAME_BALLS, decode_game_observation, decode_observation
from ..game.carom_observation import caps, decode_carom_observation
from ..game.snooker_observation import SCORE_SCALE

BALL_IN_HAND = (None, "anywhere", "behind_head_string")  # "ball_in_hand": its index here
GROUPS = (None, "solids", "stripes")  # 8-ball's "group": None while the table is open
SNOOKER_ON = ("red", "colour", 16, 17, 18, 19, 20, 21)  # snooker's "ball_on": its index here
MAX_POINTS = 2 * SCORE_SCALE  # snooker's scores as the state vector keeps them (200 and more read as 200)


def flag(value) -> np.ndarray:
    return np.array([bool(value)], dtype=np.int8)


def counter_box():
    return spaces.Box(-1.0, 1.0, (1,), np.float32)


def ball_spaces(n: int, table) -> dict:
    """x, y (metres from the corner at x = y = 0; 0 for a pocketed ball) and on_table of n balls."""
    return {"x": spaces.Box(0.0, np.float32(table.length), (n,), np.float32),
            "y": spaces.Box(0.0, np.float32(table.width), (n,), np.float32),
            "on_table": spaces.MultiBinary(n)}


def ball_arrays(xy, on_table) -> dict:
    xy = np.where(np.asarray(on_table)[:, None], np.nan_to_num(np.asarray(xy, dtype=np.float64)), 0.0)
    return {"x": xy[:, 0].astype(np.float32), "y": xy[:, 1].astype(np.float32),
            "on_table": np.asarray(on_table, dtype=np.int8)}


class DictLayout:
    """The Dict space of one state layout and its encoder: `encode(state_vector)` decodes the
    vector (the layout's own decoder) and names its parts; every key is a flat array or an
    integer, as SB3's MultiInputPolicy takes them."""

    def __init__(self, mode: str, table, decisions: bool = False, carom_rules=None):
        self.mode, self.table, self.decisions, self.carom_rules = mode, table, bool(decisions), carom_rules
        if mode in ("break", "run"):
            parts = {**ball_spaces(16, table), "shots": counter_box()}
        elif mode == "three_cushion":
            score_cap, innings_cap = caps(carom_rules)
            parts = {**ball_spaces(3, table), "own_ball": spaces.Discrete(2), "to_shoot": spaces.MultiBinary(1),
                     "is_break": spaces.MultiBinary(1), "equalizing": spaces.MultiBinary(1),
                     "scores": spaces.Box(0.0, float(score_cap), (2,), np.float32),
                     "innings": spaces.Box(0.0, float(innings_cap), (2,), np.float32), "shots": counter_box()}
        elif mode == "snooker":
            n = GAME_BALLS[mode]
            parts = {**ball_spaces(n, table), "legal": spaces.MultiBinary(n - 1), "in_hand": spaces.MultiBinary(1),
                     "free_ball": spaces.MultiBinary(1), "ball_on": spaces.Discrete(len(SNOOKER_ON)),
                     "scores": spaces.Box(0.0, MAX_POINTS, (2,), np.float32),
                     "visit": spaces.Box(0.0, MAX_POINTS, (1,), np.float32), "shots": counter_box()}
        else:
            n = GAME_BALLS[mode]
            parts = {**ball_spaces(n, table), "legal": spaces.MultiBinary(n - 1),
                     "ball_in_hand": spaces.Discrete(len(BALL_IN_HAND)), "fouls": spaces.MultiDiscrete([3, 3])}
            if mode == "eight_ball":
                parts["group"] = spaces.Discrete(len(GROUPS))
            if self.decisions:
                parts["pending"] = spaces.Discrete(len(rules.DECISIONS) + 1)  # 0: none, k: DECISIONS[k - 1]
                parts["push_out"] = spaces.MultiBinary(1)
            parts["shots"] = counter_box()
        self.space = spaces.Dict(parts)

    def encode(self, state) -> dict:
        """The named arrays of a state vector of this layout (keys in the space's order)."""
        state = np.asarray(state)
        if self.mode in ("break", "run"):
            xy, on_table = decode_observation(state, self.table)
            out = {**ball_arrays(xy, on_table), "shots": state[-1:].astype(np.float32)}
        elif self.mode == "three_cushion":
            view = decode_carom_observation(state, self.table, self.carom_rules)
            out = {**ball_arrays(view.xy, np.ones(3, dtype=bool)), "own_ball": np.int64(view.own_ball),
                   "to_shoot": flag(view.to_shoot), "is_break": flag(view.is_break),
                   "equalizing": flag(view.equalizing), "scores": np.array(view.scores, dtype=np.float32),
                   "innings": np.array(view.innings, dtype=np.float32)}
        elif self.mode == "snooker":
            view = decode_game_observation(state, self.mode, self.table)
            out = {**ball_arrays(view.xy, view.on_table), "legal": self.mask(view.legal, len(view.on_table) - 1),
                   "in_hand": flag(view.in_hand), "free_ball": flag(view.free_ball),
                   "ball_on": np.int64(SNOOKER_ON.index(view.ball_on)),
                   "scores": np.array(view.scores, dtype=np.float32),
                   "visit": np.array([view.visit], dtype=np.float32)}
        else:
            view = decode_game_observation(state, self.mode, self.table)
            out = {**ball_arrays(view.xy, view.on_table), "legal": view.legal_mask.astype(np.int8),
                   "ball_in_hand": np.int64(BALL_IN_HAND.index(view.ball_in_hand)),
                   "fouls": np.array(view.fouls, dtype=np.int64)}
            if self.mode == "eight_ball":
                out["group"] = np.int64(GROUPS.index(view.group))
            if self.decisions:
                out["pending"] = np.int64(0 if view.pending is None else 1 + rules.DECISIONS.index(view.pending))
                out["push_out"] = flag(view.push_out)
        out.setdefault("shots", np.array([view.counter if self.mode not in ("break", "run") else state[-1]],
                                         dtype=np.float32))
        return {key: out[key] for key in self.space}

    @staticmethod
    def mask(balls, n: int) -> np.ndarray:
        out = np.zeros(n, dtype=np.int8)
        out[[b - 1 for b in balls]] = 1
        return out
