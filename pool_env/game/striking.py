"""A `Game`'s shot struck from its state: checked, the cue ball placed, the call read, the noise drawn, the strike."""

from __future__ import annotations

import numpy as np

from .. import rules
from ..physics import strike
from .actions import decode_entries, encoded_entries
from .modes import Mode
from .placement import cue_ball_placed
from .shot import CONTACT_TIME, Shot, noisy_shot
from .shot_record import StruckShot

CALLING_RULES = ("eight_ball", "ten_ball")  # the games whose shots call a pocket (and a ball)


def check_can_shoot(game) -> None:
    """RuntimeError unless `game`'s shooter may shoot now: the game is over, or a decision waits."""
    if game.over:
        raise RuntimeError("the game is over; reset() it")
    if game.pending is not None:
        raise RuntimeError(f"player {game.shooter} has a decision to make first ({game.pending.name}: one of "
                           f"{game.pending.options}); call decide(option)")


def shot_and_action(game, shot) -> tuple:
    """(the `Shot`, the action vector's entries as a tuple or None) of a Shot or an action of `game`'s layout."""
    if isinstance(shot, Shot):
        return shot, None
    a = np.asarray(shot, dtype=np.float64)
    return game.decode(a), (tuple(a.tolist()) if a.ndim == 1 else None)


def struck_shot(game, mode: Mode, shot: Shot, action, rng, placements: dict | None = None) -> StruckShot:
    """`Game.strike` of a decoded shot from `game`'s state (`mode` its mode; `action` the shot's
    vector's entries, or None; `rng` the noise's generator, None the game's); `placements`
    keeps the cue ball's placements from this state by the spot asked for (evaluate's shots
    share their spots). ValueError for a call or a push out the state does not allow."""
    placed, hand, state, table = game.balls, game.ball_in_hand, game.state, game.table
    if hand is not None:
        placed = cue_ball_placed(placed, table, game.physics, hand, shot.place, placements)
    called = shot.pocket if mode.rules in CALLING_RULES else None
    if called is not None and called >= table.pockets.shape[0]:
        raise ValueError(f"Shot.pocket {called} names no pocket (the table has {table.pockets.shape[0]})")
    ball = shot.ball if mode.rules in CALLING_RULES else None
    if ball is not None and ball not in state.on_table:
        raise ValueError(f"Shot.ball {ball} is not on the table (on it: {sorted(state.on_table)})")
    if shot.push_out and not game.may_push_out:
        raise ValueError("Shot.push_out: no push out now (only the 9-ball shot right after a legal break: WPA 2.4)")
    force, tip, elevation = shot.force, shot.tip, shot.elevation
    if game.noise is not None:
        force, tip, elevation = noisy_shot(force, tip, game.noise, game.rng if rng is None else rng, elevation)
    try:  # the physics for an elevated cue: the slate's e_t and mu_t
        struck = strike(placed, force, tip, CONTACT_TIME, ball=rules.cue_ball(state), elevation=elevation,
                        physics=game.physics)
    except ValueError as exc:
        struck = exc
    return StruckShot(shot, game.shooter, hand, called, placed, force, tip, struck, action, elevation, ball,
                      shot.push_out)


def struck_or_failed(game, mode: Mode, shot: Shot, action, rng, placements=None) -> StruckShot:
    """`struck_shot`, a placement that finds no free spot recorded as the shot's failure."""
    try:
        return struck_shot(game, mode, shot, action, rng, placements)
    except ValueError as exc:
        zero = (0.0, 0.0)
        return StruckShot(shot, game.shooter, game.ball_in_hand, None, game.balls, zero, zero, exc)


def struck_encoded(game, mode: Mode, shot: Shot, rng) -> StruckShot:
    """`Game.strike_encoded`: `struck_shot` of `shot` as the float32 entries of the action that
    `game.encode` would make of it read it back, those entries its `action`."""
    area, pockets = game.placement_area(), game.table.pockets.shape[0]
    targets = game.called_targets
    entries = encoded_entries(game.layout, shot, area, pockets, targets)
    decoded = decode_entries(game.layout, entries, area, pockets, targets, game.may_push_out, clipped=True)
    return struck_shot(game, mode, decoded, tuple(entries), rng)
