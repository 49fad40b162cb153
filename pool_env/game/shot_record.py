"""What a shot is and did: `StruckShot` (ready to simulate), `ShotRecord` (played), and a game's `GameSnapshot`."""

from __future__ import annotations

from dataclasses import dataclass

from .. import rules
from ..physics import Balls, Result
from .shot import Shot


@dataclass(eq=False, slots=True)
class StruckShot:
    """A shot ready to simulate (`Game.strike`): who shoots, what he meant (`shot`, and the
    `action` it was read from, if any), his ball in hand, the called pocket (and ball), the balls at rest
    with the cue ball placed (`placed`), the cue's force, tip and elevation as executed (noise
    included), and `balls`, the struck balls to simulate, or the ValueError striking raised. Read-only by
    convention (not frozen: it is made for every shot, and a frozen dataclass is slow to make)."""

    shot: Shot
    shooter: int
    ball_in_hand: str | None
    called_pocket: int | None
    placed: Balls
    force: tuple
    tip: tuple
    balls: Balls | Exception
    action: tuple | None = None
    elevation: float = 0.0
    called_ball: int | None = None
    push_out: bool = False


@dataclass(eq=False, slots=True)
class ShotRecord:
    """What one shot did (`Game.play`, `Game.evaluate`).

    `shooter`, `shot`, `action`, `ball_in_hand`, `called_pocket`, `called_ball`, `force`, `tip`
    and `elevation` (executed) as in `StruckShot`; `balls_before` the balls at rest before the strike (the cue ball
    placed) and `state_before` the rules' state then, `balls_after` at rest after it
    (spotted balls back on the table); `result` the
    physics `Result` (events, trajectories, stats); `ruling` the rules' `Ruling` and
    `state_after` the next `rules.GameState` (None in the break and run modes); `over` the
    game ended with this shot; `error` why the shot could not be simulated or settled (then `result` is
    None, the game did not change and the balls are `balls_before`). Read-only by convention."""

    shooter: int
    shot: Shot
    action: tuple | None
    ball_in_hand: str | None
    called_pocket: int | None
    force: tuple
    tip: tuple
    balls_before: Balls
    state_before: rules.GameState | None
    balls_after: Balls
    result: Result | None
    ruling: rules.Ruling | None
    state_after: rules.GameState | None
    over: bool
    error: str | None = None
    judged: rules.ShotOutcome | None = None
    elevation: float = 0.0
    called_ball: int | None = None

    @property
    def outcome(self) -> rules.ShotOutcome | None:
        """What the rules see of the shot (`rules.ShotOutcome`, read once); None for a failed shot."""
        if self.judged is None and self.result is not None:
            self.judged = rules.read_outcome(self.state_before, self.result)
        return self.judged

    @property
    def pocketed(self) -> tuple:
        """The object balls that dropped, in the order they dropped."""
        return () if self.outcome is None else self.outcome.pocketed

    @property
    def scratch(self) -> bool:
        """The cue ball dropped."""
        return bool(self.result is not None and self.result.final.pocketed[0])

    @property
    def foul(self) -> str | None:
        return None if self.ruling is None else self.ruling.foul

    @property
    def events(self) -> list:
        return [] if self.result is None else self.result.events


@dataclass(frozen=True)
class GameSnapshot:
    """A game's whole state (`Game.snapshot`), the noise generator's included; `Game.restore`
    puts it back exactly. `key` names the game it belongs to (mode, table, physics, noise, rules)."""

    key: tuple
    balls: Balls
    state: rules.GameState | None
    shots: int
    over: bool
    rng_state: dict
