"""A struck shot's record: its simulation's outcome judged by the rules from the state it was played in."""

from __future__ import annotations

from .. import rules
from ..physics import Table
from .batch import SHOT_ERRORS
from .modes import Mode
from .shot_record import ShotRecord, StruckShot


def shot_record(struck: StruckShot, result, state, table: Table, mode: Mode, decisions: bool,
                rulings: dict | None = None) -> ShotRecord:
    """The record of `struck`'s simulation `result` (its `Result`, or the error simulating it
    raised) from the rules' `state` (None without rules) of a `mode` game on `table`. A choice
    the rules leave waits when `decisions`, else its default is taken. `rulings` caches the
    rules' judgements from `state`, by outcome, called pocket, called ball and push out."""
    head = (struck.shooter, struck.shot, struck.action, struck.ball_in_hand, struck.called_pocket, struck.force,
            struck.tip, struck.placed, state)
    if isinstance(result, Exception):
        if not isinstance(result, SHOT_ERRORS):
            raise result
        return failed(head, struck, state, f"{type(result).__name__}: {result}")
    if mode.rules is None:
        final = result.final
        cleared = table.pockets.shape[0] > 0 and bool(final.pocketed[1:].all())
        over = mode.one_shot or bool(final.pocketed[0]) or cleared
        return ShotRecord(*head, final, result, None, None, over, elevation=struck.elevation)
    outcome = rules.read_outcome(state, result)  # first: a Result reads its facts and final state in one call
    final = result.final
    key = (outcome, struck.called_pocket, struck.called_ball, struck.push_out)
    judged = None if rulings is None else rulings.get(key)
    if judged is None:
        judged = rules.judge(state, outcome, struck.called_pocket, struck.called_ball, struck.push_out)
        if rulings is not None:
            rulings[key] = judged
    after, ruling = judged
    try:
        balls, after = rules.settle(after, ruling, final, table)
    except ValueError as exc:  # the rules cannot put a ball back (no room left to spot it)
        return failed(head, struck, state, f"ValueError: the rules could not settle the shot: {exc}")
    if not decisions and getattr(after, "pending", None) is not None:  # no re-rack is a default
        after = rules.decide(after, after.pending.default)
    return ShotRecord(*head, balls, result, ruling, after, after.over, judged=outcome,
                      elevation=struck.elevation, called_ball=struck.called_ball)


def failed(head: tuple, struck: StruckShot, state, error: str) -> ShotRecord:
    """The record of a shot from the rules' `state` that could not be simulated or settled
    (`error` says why): no result, the balls as they were before it (the cue ball where it was
    placed), the state unchanged."""
    return ShotRecord(*head, struck.placed, None, None, state, False, error, elevation=struck.elevation,
                      called_ball=struck.called_ball)
