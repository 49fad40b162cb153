"""pool_env.rules: 9-ball and 8-ball by the WPA World Standardized Rules, pure Python (docs/rules.md)."""

from __future__ import annotations

from . import codes
from .eight_ball import EightBall
from .nine_ball import NineBall
from .outcome import ShotOutcome, outcome_from_result
from .racks import eight_ball_rack, foot_spot, head_spot, head_string_x, nine_ball_rack, spot_balls
from .state import BALL_IN_HAND, END_REASONS, FOULS, GROUPS, GameState, Ruling

KINDS = {"nine_ball": NineBall, "eight_ball": EightBall}

__all__ = [
    "new_game", "judge", "legal_targets", "GameState", "Ruling", "ShotOutcome", "outcome_from_result",
    "NineBall", "EightBall", "FOULS", "END_REASONS", "BALL_IN_HAND", "GROUPS", "KINDS",
    "nine_ball_rack", "eight_ball_rack", "spot_balls", "head_string_x", "foot_spot", "head_spot", "codes",
]


def new_game(kind, breaker: int = 0, **options) -> GameState:
    """A new game: `kind` "nine_ball" or "eight_ball" (with the rule set's options, e.g.
    `three_foul_rule=False`, `illegal_break="table_in_position"`), or a rule set instance;
    `breaker` (0 or 1) breaks with the cue ball in hand behind the head string."""
    if isinstance(kind, (NineBall, EightBall)):
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


def judge(state: GameState, outcome: ShotOutcome, called_pocket: int | None = None,
          called_ball: int | None = None) -> tuple[GameState, Ruling]:
    """(the next GameState, the Ruling) after the shot `outcome` played from `state`, by
    `state.rules`. 8-ball only: `called_pocket` names the pocket, `called_ball` the ball
    (read by `EightBall(calling="ball_and_pocket")`; the default "eight_only" calls only the
    8's pocket). Raises ValueError for a finished game, a shot naming balls not on the
    table, or a bad called pocket or ball."""
    if not isinstance(state, GameState):
        raise TypeError(f"state must be a pool_env.rules.GameState, got {type(state).__name__}")
    return state.rules.judge(state, outcome, called_pocket, called_ball)


def legal_targets(state: GameState) -> frozenset:
    """The object balls the shooter may hit first now (9-ball: the lowest on the table; 8-ball:
    any on the break, any but the 8 on an open table, his group, then the 8)."""
    if not isinstance(state, GameState):
        raise TypeError(f"state must be a pool_env.rules.GameState, got {type(state).__name__}")
    return state.rules.legal_targets(state)
