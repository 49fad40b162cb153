"""Starting a game: the random cue-ball start, and the checks of a given layout and rules' state."""

from __future__ import annotations

import numpy as np

from .. import rules
from ..physics import BALL_RADIUS, Balls, Table
from ..physics.simulate import check_on_table
from .actions import ActionLayout
from .modes import Mode

CUE_AREA = ((0.05, 0.25), (0.1, 0.9))  # randomize_cue: the cue ball's start, as fractions of L and W
CUE_TRIES = 1000  # draws of a random cue spot before falling back to the head spot
LAST_BALL = {"nine_ball": 9, "eight_ball": 8, "snooker": 21, "ten_ball": 10}  # on the table while the game goes on


def objects_on(balls: Balls) -> frozenset:
    """The object balls (by number) on the table."""
    return frozenset(int(k) for k in np.flatnonzero(~balls.pocketed[1:]) + 1)


def random_cue_start(table: Table, rng: np.random.Generator) -> tuple:
    """A cue-ball spot drawn uniformly in `CUE_AREA`, clear of the pockets' mouths (the head
    spot's row at a quarter of the length if `CUE_TRIES` draws find none)."""
    (x0, x1), (y0, y1) = CUE_AREA
    L, W, r = table.length, table.width, BALL_RADIUS
    pockets = table.pockets
    for _ in range(CUE_TRIES):
        x = rng.uniform(max(x0 * L, r), x1 * L)
        y = rng.uniform(max(y0 * W, r), min(y1 * W, W - r))
        if not pockets.shape[0] or np.all(np.hypot(pockets[:, 0] - x, pockets[:, 1] - y) > pockets[:, 2] + r):
            return (x, y)
    return (0.25 * L, 0.5 * W)


def check_layout(mode: Mode, balls, table: Table, physics, position: bool = False) -> Balls:
    """A starting layout of `mode` checked; a planner's `position` (with its state) may have the
    cue ball in hand off the table, and its balls are checked as `simulate` checks them, when a
    shot is played from it."""
    n = mode.balls
    if not isinstance(balls, Balls) or len(balls) != n:
        raise ValueError(f"balls must be pool_env.physics.Balls with {n} balls (ball k is number k), got {balls!r}")
    if np.any(balls.v) or np.any(balls.w):
        raise ValueError("balls must be at rest (zero velocities and spins)")
    if position:
        return balls
    if balls.pocketed[0]:
        raise ValueError("balls: the cue ball (ball 0) must be on the table")
    last = LAST_BALL.get(mode.rules)
    if last is not None and balls.pocketed[last]:
        raise ValueError(f"balls: the {last} must be on the table (the game would be over)")
    check_on_table(balls, table, physics)
    return balls


def check_state(mode: Mode, state, balls: Balls) -> None:
    """A planner's rules' state for a layout: of `mode`'s rules, with the layout's balls on the table."""
    if mode.rules is None:
        raise ValueError(f"the {mode.name} mode has no rules' state")
    if not isinstance(state, rules.STATES) or state.kind != mode.rules:
        raise ValueError(f"state must be a {mode.rules} rules.GameState, got {state!r}")
    on_table = objects_on(balls)
    if state.on_table != on_table:
        raise ValueError(f"state.on_table {sorted(state.on_table)} is not the layout's {sorted(on_table)}")


def check_calling(mode: Mode, layout: ActionLayout, rule_options: dict) -> None:
    """8-ball: the layout has a called-ball entry exactly when every shot calls a ball (the
    rules' `calling`); else actions could never call one (or would call one the rules ignore)."""
    if mode.rules != "eight_ball":
        return
    calling = rule_options.get("calling", rules.EightBall.calling)
    if layout.called_ball != (calling == "ball_and_pocket"):
        fit = "an eight_ball_call" if calling == "ball_and_pocket" else "an eight_ball layout without the ball"
        raise ValueError(f"layout {layout.name!r} does not fit 8-ball with calling={calling!r}: it takes {fit} "
                         "layout (pool_env.game.env_layout names it)")
