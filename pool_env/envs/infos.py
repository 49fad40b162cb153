"""The envs' `info` dicts: numeric (numbers, bools, fixed-shape arrays) or rich (with the shot records)."""

from __future__ import annotations

import numpy as np

from ..physics import Balls
from ..physics.facts import DROPS, FIRST, HEAD
from ..physics.kinds import BALL_BALL_KINDS, BALL_CUSHION, BALL_POCKET
from ..rules import codes

NO_WINNER = -1  # `winner` while the game goes on; else the winner's player number (the agent is 0)


def shot_info(result, after: Balls, error: str | None = None) -> dict:
    """A step's numeric `info` (see PoolBreakEnv) from the shot's `Result` and the balls after it;
    for a shot that could not be simulated (or no shot: reset's info), result None and the balls
    as they are. Every value is a number, a bool or an array of a fixed shape."""
    pocketed = np.zeros(len(after.pocketed), dtype=np.bool_)
    first, cushions, events = -1, 0, 0
    facts = None if result is None else result.event_facts()
    if facts is not None:  # the first contact and the drops as the rules read them, in one compiled call
        kinds = result.event_arrays[1]
        events, cushions, first = kinds.shape[0], int(np.count_nonzero(kinds == BALL_CUSHION)), facts[FIRST]
        for k in range(facts[DROPS]):
            pocketed[facts[HEAD + 2 * k]] = True
    elif result is not None:  # a Result without the engine's output (a fixed-step run's): its events
        _, kinds, i_s, j_s = (a.tolist() for a in result.event_arrays)  # lists: a shot has tens of events
        events = len(kinds)
        for kind, i, j in zip(kinds, i_s, j_s):
            if kind == BALL_POCKET:
                pocketed[i] = True
            elif kind == BALL_CUSHION:
                cushions += 1
            elif first < 0 and kind in BALL_BALL_KINDS and (i == 0 or j == 0):  # a settle is a contact too
                first = i + j
    on_table = after.pocketed.tolist()
    return {
        "pocketed": pocketed,
        "first_contact": first,
        "cushion_hits": cushions,
        "scratch": bool(on_table[0]),
        "events": events,
        "shot_duration": 0.0 if result is None else float(result.duration),
        "balls_left": len(on_table) - 1 - sum(on_table[1:]),
        "error": error is not None,
    }


def rich_info(info: dict, records, error: str | None) -> dict:
    """`info` with the rich entries of `info_mode="rich"`: `records` (the step's `ShotRecord`s)
    and `error_message` (why a shot failed, or None)."""
    return {**info, "records": tuple(records), "error_message": error}


INFO_MODES = ("numeric", "rich")


def check_info_mode(info_mode) -> str:
    """`info_mode` checked: "numeric" (the default) or "rich"."""
    if info_mode not in INFO_MODES:
        raise ValueError(f"info_mode must be one of {INFO_MODES}, got {info_mode!r}")
    return info_mode


def rules_info(record) -> dict:
    """The rules' part of a shot's info: `foul` and `ball_in_hand` (the next shooter's) as
    their codes (`pool_env.rules.codes`), `turn_passed`."""
    ruling = record.ruling
    return {"foul": codes.encode("foul", ruling.foul),
            "ball_in_hand": codes.encode("ball_in_hand", ruling.ball_in_hand),
            "turn_passed": bool(ruling.turn_passed)}


def record_info(record) -> dict:
    """A game shot's info: `shot_info`'s entries and the rules' (`rules_info`); `balls_left` is
    the object balls on the table by the rules (spotted balls back)."""
    return {**shot_info(record.result, record.balls_after), **rules_info(record),
            "balls_left": len(record.state_after.on_table)}


def no_shot_info(balls: Balls, ball_in_hand: str | None, error: str | None = None) -> dict:
    """A game env's info for a step (or a reset) without a shot of the stepping player: the keys
    of `record_info`, nothing pocketed, no foul, the ball in hand the shooter has now."""
    return {**shot_info(None, balls, error), "foul": 0, "ball_in_hand": codes.encode("ball_in_hand", ball_in_hand),
            "turn_passed": False}


def winner_code(winner: int | None) -> int:
    """`winner` as the infos give it: the player number, `NO_WINNER` (-1) while the game goes on."""
    return NO_WINNER if winner is None else int(winner)


def score_info(state) -> dict:
    """The frame's score for a game that keeps one (snooker: `scores`, int64 (2,), player 0's
    points first, the fouls' penalty points included); empty for the pool games, which have none."""
    scores = getattr(state, "scores", None)
    return {} if scores is None else {"scores": np.array(scores, dtype=np.int64)}


def sampled_info(game) -> dict:
    """Reset's info entries of a game's randomized equipment (`physics`, `table`, and the
    per-ball `ball_radius` and `ball_mass` when drawn); none without `randomize`."""
    return {} if game.sample is None else game.sample.info()
