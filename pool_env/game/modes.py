"""The game modes `Game` plays: one registry of names, each with its balls, rack, rules and action layout."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from .. import rules
from ..physics import Physics, Table, rack


@dataclass(frozen=True)
class Mode:
    """A mode of play: `balls` in play (the cue ball included, ball k is number k), the rules'
    kind (None: no rules, the shooter keeps the table until a scratch), `one_shot` (the game
    is the break alone), its default action layout (`actions.LAYOUTS`) and a label for captions."""

    name: str
    balls: int
    rules: str | None
    one_shot: bool
    layout: str
    label: str
    table: Callable[[], Table] = Table.eight_foot  # the table a Game of this mode gets when given none
    physics: Callable[[], Physics] = Physics.standard  # ... and its physics
    cue_in_hand: bool = True  # the rules give ball in hand (the layout has placement entries); False: carom
    equipment: str = "pool"  # whose measured ranges randomize="default" draws from (physics.randomize.DEFAULTS)

    @property
    def placement(self) -> bool:
        """The mode's action layouts carry the ball-in-hand entries: a rules game with ball in hand."""
        return self.rules is not None and self.cue_in_hand

    def default_layout(self, rule_options: dict) -> str:
        """The action layout a `Game` of this mode gets when given none: 8-ball's names a ball
        as well as a pocket unless its rules call the 8 only (`calling="eight_only"`)."""
        if self.rules == "eight_ball" and rule_options.get("calling", rules.EightBall.calling) != "eight_only":
            return "eight_ball_call"
        return self.layout

    def rack(self, table, seed, cue_xy=None):
        """The starting balls, racked with `seed` (WPA racking for the rules' games)."""
        if self.rules == "nine_ball":
            return rules.nine_ball_rack(table, seed=seed)
        if self.rules == "eight_ball":
            return rules.eight_ball_rack(table, seed=seed)
        if self.rules == "ten_ball":
            return rules.ten_ball_rack(table, seed=seed)
        if self.rules == "three_cushion":  # the breaker plays the white (UMB 3.3): one starting position
            return rules.starting_position(table)
        if self.rules == "snooker":
            return rules.snooker_rack(table, seed=seed)
        return rack(table, seed=seed, cue_xy=cue_xy)


MODES = {
    "break": Mode("break", 16, None, one_shot=True, layout="cue", label="break"),
    "run": Mode("run", 16, None, one_shot=False, layout="cue", label="break and run"),
    "nine_ball": Mode("nine_ball", 10, "nine_ball", one_shot=False, layout="nine_ball", label="9-ball"),
    # (the layout with `calling="eight_only"`; by default "eight_ball_call": `Mode.default_layout`)
    "eight_ball": Mode("eight_ball", 16, "eight_ball", one_shot=False, layout="eight_ball", label="8-ball"),
    "ten_ball": Mode("ten_ball", 11, "ten_ball", one_shot=False, layout="ten_ball", label="10-ball"),
    "three_cushion": Mode("three_cushion", 3, "three_cushion", one_shot=False, layout="cue_spin", label="three-cushion",
                          table=Table.carom, physics=Physics.carom, cue_in_hand=False, equipment="carom"),
    # 0 the cue ball, 1-15 the reds, 16-21 yellow, green, brown, blue, pink, black (rules.snooker_spots).
    "snooker": Mode("snooker", 22, "snooker", one_shot=False, layout="snooker", label="snooker", table=Table.snooker,
                    equipment="snooker"),
}
RULES_MODES = tuple(name for name, mode in MODES.items() if mode.rules is not None)


def mode_of(name) -> Mode:
    """The registered mode `name`; ValueError naming the choices."""
    if name not in MODES:
        raise ValueError(f"unknown game {name!r}; choose one of {', '.join(MODES)}")
    return MODES[name]
