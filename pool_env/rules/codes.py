"""The integer codes of the rules' names in the numeric infos (foul, end reason, ball in hand) and their decoders."""

from __future__ import annotations

from .snooker import SNOOKER_END_REASONS, SNOOKER_FOULS, SNOOKER_IN_HAND
from .state import BALL_IN_HAND, END_REASONS, FOULS
from .ten_ball import TEN_END_REASONS

# Why a game env's episode stopped without a winner (its `truncation` info): the agent's shot
# limit (`max_shots`, the envs' stand-in for the WPA's stalemate, 1.12, which is not declared:
# docs/rules.md), the opponent's shots in a row reaching it, a shot the simulator could not finish.
TRUNCATIONS = ("shot_limit", "opponent_shot_limit", "shot_error")

# Code k names entry k; code 0 is None (no foul, the game goes on, no ball in hand, not
# truncated), so a code is falsy exactly when its name is None.
# Snooker's names follow the pool ones (codes of the pool names stay as they were), 10-ball's last.
FOUL_CODES = (None, *FOULS, *(f for f in SNOOKER_FOULS if f not in FOULS))
END_REASON_CODES = (None, *END_REASONS, *SNOOKER_END_REASONS, *TEN_END_REASONS)
BALL_IN_HAND_CODES = (*BALL_IN_HAND, *(h for h in SNOOKER_IN_HAND if h not in BALL_IN_HAND))
TRUNCATION_CODES = (None, *TRUNCATIONS)
CODE_TABLES = {"foul": FOUL_CODES, "end_reason": END_REASON_CODES, "ball_in_hand": BALL_IN_HAND_CODES,
               "truncation": TRUNCATION_CODES}


def _table(key: str) -> tuple:
    if key not in CODE_TABLES:
        raise ValueError(f"no code table for {key!r}; the coded keys are {', '.join(map(repr, CODE_TABLES))}")
    return CODE_TABLES[key]


def encode(key: str, name: str | None) -> int:
    """The code of `name` (a foul, an end reason, a ball-in-hand place, or None) in `key`'s table."""
    table = _table(key)
    if name not in table:
        raise ValueError(f"{name!r} is not a {key}; choose one of {table}")
    return table.index(name)


def decode(key: str, code) -> str | None:
    """The name (or None) that code `code` stands for in `key`'s table; ValueError for a code out of range."""
    table = _table(key)
    if int(code) != code or not 0 <= code < len(table):
        raise ValueError(f"{code!r} is not a {key} code: the codes run 0-{len(table) - 1} ({table})")
    return table[int(code)]


def decode_info(info: dict) -> dict:
    """A copy of one env's numeric `info` with every coded entry (`foul`, `end_reason`,
    `ball_in_hand`, `truncation`) replaced by its name, and the `pocketed` mask by the tuple of ball numbers."""
    out = dict(info)
    for key in CODE_TABLES:
        if key in out:
            out[key] = decode(key, out[key])
    if "pocketed" in out:
        out["pocketed"] = tuple(int(k) for k in out["pocketed"].nonzero()[0])
    return out
