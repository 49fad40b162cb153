"""pool_env.rules: 9-ball and 8-ball (WPA World Standardized Rules), three-cushion (UMB), pure Python."""

from __future__ import annotations

import dataclasses

from . import codes
from .carom_outcome import CaromOutcome, carom_outcome
from .eight_ball import EightBall
from .nine_ball import NineBall
from .outcome import ShotOutcome, outcome_from_result, outcome_of_facts
from .racks import eight_ball_rack, foot_spot, head_spot, head_string_x, nine_ball_rack, spot_balls, ten_ball_rack
from .snooker import Snooker, SnookerRuling, SnookerState
from .snooker_free_ball import settle as settle_snooker
from .snooker_spots import snooker_rack, spot_colours
from .state import BALL_IN_HAND, DECISIONS, END_REASONS, FOULS, GROUPS, Decision, GameState, Ruling
from .ten_ball import TEN_END_REASONS, TenBall
from .three_cushion import CaromRuling, ThreeCushion, ThreeCushionState, carom_spots, starting_position

KINDS = {"nine_ball": NineBall, "eight_ball": EightBall, "three_cushion": ThreeCushion, "snooker": Snooker,
         "ten_ball": TenBall}
STATES = (GameState, ThreeCushionState, SnookerState)  # every rule set's state class (judge, legal_targets, Game)

__all__ = [
    "new_game", "judge", "legal_targets", "GameState", "Ruling", "ShotOutcome", "outcome_from_result",
    "outcome_of_facts",
    "NineBall", "EightBall", "FOULS", "END_REASONS", "BALL_IN_HAND", "GROUPS", "KINDS",
    "nine_ball_rack", "eight_ball_rack", "spot_balls", "head_string_x", "foot_spot", "head_spot", "codes",
    "ThreeCushion", "ThreeCushionState", "CaromOutcome", "CaromRuling", "carom_outcome", "carom_spots",
    "starting_position", "STATES", "read_outcome", "cue_ball", "settle", "open_table",
    "Snooker", "SnookerState", "SnookerRuling", "snooker_rack", "spot_colours", "decide", "Decision", "DECISIONS",
    "TenBall", "ten_ball_rack", "TEN_END_REASONS",
]


def new_game(kind, breaker: int = 0, **options) -> GameState:
    """A new game: `kind` "nine_ball" or "eight_ball" (with the rule set's options, e.g.
    `three_foul_rule=False`, `illegal_break="table_in_position"`), or a rule set instance;
    `breaker` (0 or 1) breaks with the cue ball in hand behind the head string."""
    if isinstance(kind, tuple(KINDS.values())):
        if options:
            raise TypeError(f"options go to the rule set's constructor, not with an instance: {sorted(options)}")
        rules = kind
    elif kind in KINDS:
        rules = KINDS[kind](**options)
    else:
        raise ValueError(f"unknown game {kind!r}; available: {', '.join(map(repr, KINDS))}")
    if breaker not in (0, 1) or isinstance(breaker, bool):
        raise ValueError(f"breaker must be 0 or 1, got {breaker!r}")
    return rules.new_game(breaker)


def judge(state: GameState | ThreeCushionState, outcome: ShotOutcome | CaromOutcome, called_pocket: int | None = None,
          called_ball: int | None = None, push_out: bool = False) -> tuple[GameState, Ruling]:
    """(the next GameState, the Ruling) after the shot `outcome` played from `state`, by
    `state.rules`. 8-ball only: `called_pocket` names the pocket, `called_ball` the ball
    (read by `EightBall(calling="ball_and_pocket")`; the default "eight_only" calls only the
    8's pocket). `push_out`: the shooter declared a push out (9-ball, when `state.push_out`:
    WPA 2.4). Raises ValueError for a finished game, a decision pending, a shot naming balls
    not on the table, a bad called pocket or ball, or a push out where none is allowed."""
    if not isinstance(state, STATES):
        raise TypeError(f"state must be one of pool_env.rules.STATES (GameState, ThreeCushionState, SnookerState), "
                        f"got {type(state).__name__}")
    if push_out:
        if not getattr(state, "push_out", False):
            raise ValueError("no push out now: only the 9-ball shot right after a legal break may be one (WPA 2.4)")
        return state.rules.judge(state, outcome, called_pocket, called_ball, push_out=True)
    return state.rules.judge(state, outcome, called_pocket, called_ball)


def decide(state: GameState, option: str) -> GameState:
    """The state after the shooter chooses `option` of `state.pending` (a `Decision`): 9-ball's
    reply to a push out ("shoot", "pass"), 8-ball's choices after an illegal break or the 8 on
    the break. ValueError when no decision is pending or `option` is not one of its options."""
    if not isinstance(state, STATES):
        raise TypeError(f"state must be one of pool_env.rules.STATES (GameState, ThreeCushionState, SnookerState), "
                        f"got {type(state).__name__}")
    if getattr(state, "pending", None) is None:
        raise ValueError("no decision is pending: the shooter shoots (rules.judge)")
    return state.rules.decide(state, option)


def legal_targets(state: GameState) -> frozenset:
    """The object balls the shooter may hit first now (9-ball: the lowest on the table; 8-ball:
    any on the break, any but the 8 on an open table, his group, then the 8)."""
    if not isinstance(state, STATES):
        raise TypeError(f"state must be one of pool_env.rules.STATES (GameState, ThreeCushionState, SnookerState), "
                        f"got {type(state).__name__}")
    return state.rules.legal_targets(state)


def read_outcome(state, result):
    """What `state`'s rules read of a simulated shot: a `CaromOutcome` (the shooter's cue ball's
    contacts) for three-cushion, else the `ShotOutcome` (`outcome_from_result`)."""
    if isinstance(state, ThreeCushionState):
        return carom_outcome(result, state.cue_ball)
    return outcome_from_result(result)


def cue_ball(state) -> int:
    """The index of the ball the shooter strikes: his own in three-cushion, else 0 (also without rules)."""
    return state.cue_ball if isinstance(state, ThreeCushionState) else 0


def settle(state, ruling, balls, table):
    """(the balls, the state) after `judge`'s ruling is applied to the balls at rest, `state` the
    state it ruled next: the balls it puts back (pool: `spot_balls`; three-cushion: the starting
    position; snooker: `spot_colours`, the re-spotted black and the free ball)."""
    if isinstance(state, SnookerState):
        return settle_snooker(state, ruling, balls, table)
    if not ruling.balls_to_spot:
        return balls, state
    if isinstance(state, ThreeCushionState):
        return state.rules.respot(state, balls, table), state
    return spot_balls(balls, table, ruling.balls_to_spot), state


def open_table(kind, on_table, shooter: int, ball_in_hand: bool, **options):
    """A game of `kind` under way from a layout: player `shooter` to shoot, no break (the
    pool games: an open table with `on_table` on it, ball in hand anywhere if asked; three-
    cushion: scores 0-0 in the first inning, no starting stroke; snooker: scores 0-0, the ball on
    that a visit starts with, ball in hand in the D if asked)."""
    state = new_game(kind, breaker=0, **options)
    if isinstance(state, SnookerState):
        return state.rules.position(on_table, shooter, ball_in_hand)
    if isinstance(state, ThreeCushionState):
        if ball_in_hand:
            raise ValueError("three-cushion has no ball in hand")
        return ThreeCushionState(state.rules, shooter=shooter, starter=shooter,
                                 innings=(1, 0) if shooter == 0 else (0, 1), is_break=False)
    return dataclasses.replace(state, on_table=on_table, is_break=False, shooter=shooter,
                               ball_in_hand="anywhere" if ball_in_hand else None)
