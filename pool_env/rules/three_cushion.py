"""Three-cushion billiards by the UMB rules: `ThreeCushion`, `ThreeCushionState`, the carom spots and start.

Sources: the UMB Sports Rules (carom), sections 2.1 (table), 2.2 (balls), 3.3 (starting
position), and the 1989 World Rules of Carom Billiard (Art. 27 balls in contact, Art. 28 balls
jumping off the billiard, Art. 29 end of the match, Art. 83 three cushions). docs/games.md lists
what is modelled and every deviation.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..physics.objects import CAROM_MASS, CAROM_RADIUS, Balls, Table
from .carom_outcome import RED, CaromOutcome
from .state import Ruling

# The two starting spots lie on the starting line through the bottom spot, this far to
# either side of it (UMB's marking of the spots: 18.2 cm; the USBA's and house rules' 7 3/16 in
# = 18.26 cm agree).
STARTING_SPOT_OFFSET = 0.182
END_REASONS = ("points_reached", "innings_limit", "equalized")
WHITE, YELLOW = 0, 1


def carom_spots(table: Table) -> dict:
    """The carom spots (UMB 2.3/3.3) on `table`, x along the length from the bottom (head)
    cushion: "top" (x = 3L/4, where the red starts), "centre", "bottom" (x = L/4, the
    opponent's cue ball), "start_right" and "start_left" (the starting spots, the bottom spot
    +- STARTING_SPOT_OFFSET across)."""
    L, W = table.length, table.width
    return {"top": (0.75 * L, 0.5 * W), "centre": (0.5 * L, 0.5 * W), "bottom": (0.25 * L, 0.5 * W),
            "start_right": (0.25 * L, 0.5 * W - STARTING_SPOT_OFFSET),
            "start_left": (0.25 * L, 0.5 * W + STARTING_SPOT_OFFSET)}


def starting_position(table: Table, cue_ball: int = WHITE, radius=None, mass=None) -> Balls:
    """The starting position (UMB 3.3): the red on the top spot, the other player's cue ball on
    the bottom spot, `cue_ball` (0 white, 1 yellow; the player's) on a starting spot (the
    right one: the rule lets him choose; docs/games.md). `radius` and `mass` default to carom balls."""
    if cue_ball not in (WHITE, YELLOW):
        raise ValueError(f"cue_ball must be 0 (white) or 1 (yellow), got {cue_ball!r}")
    spots = carom_spots(table)
    xy = np.zeros((3, 2))
    xy[cue_ball], xy[1 - cue_ball], xy[RED] = spots["start_right"], spots["bottom"], spots["top"]
    return Balls(xy, radius=CAROM_RADIUS if radius is None else radius, mass=CAROM_MASS if mass is None else mass)


def _count(value, name, low=0):
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
        raise ValueError(f"{name} must be an integer >= {low}, got {value!r}")


@dataclass(frozen=True)
class ThreeCushionState:
    """A three-cushion game between shots (immutable; `judge` returns the next one).

    `rules` the `ThreeCushion` rule set; `shooter` 0 or 1; `starter` the player who played the
    first inning, with the white ball (UMB 3.3; the other plays the yellow); `scores` and
    `innings` each player's points and innings begun; `run` the shooter's points in this inning;
    `is_break` the next shot is a starting stroke (the red must be hit first); `shot` shots so
    far; `equalizing` the inning under way is the equalising inning; `winner` 0, 1 or None;
    `ended` the game is over (a draw when `winner` is None)."""

    rules: object
    shooter: int = 0
    starter: int = 0
    scores: tuple = (0, 0)
    innings: tuple = (1, 0)
    run: int = 0
    is_break: bool = True
    shot: int = 0
    equalizing: bool = False
    winner: int | None = None
    ended: bool = False

    def __post_init__(self):
        object.__setattr__(self, "scores", tuple(int(s) for s in self.scores))
        object.__setattr__(self, "innings", tuple(int(n) for n in self.innings))
        _check_state(self)

    @property
    def kind(self) -> str:
        return "three_cushion"

    @property
    def over(self) -> bool:
        return self.ended

    @property
    def cue_ball(self) -> int:
        """The ball the shooter strikes: 0 (white) for the starter, 1 (yellow) for the other."""
        return WHITE if self.shooter == self.starter else YELLOW

    @property
    def on_table(self) -> frozenset:
        """Balls 1 and 2 (the yellow and the red, by number): every ball is always on a carom
        table (a ball that jumps off is put back, UMB Art. 28)."""
        return frozenset({1, 2})

    @property
    def ball_in_hand(self) -> None:
        """Never: three-cushion has no ball in hand."""
        return None


def _check_state(s: ThreeCushionState) -> None:
    """ValueError for a ThreeCushionState no game can reach."""
    if not isinstance(s.rules, ThreeCushion):
        raise ValueError(f"ThreeCushionState: rules must be a ThreeCushion, got {s.rules!r}")
    for name in ("shooter", "starter"):
        if getattr(s, name) not in (0, 1) or isinstance(getattr(s, name), bool):
            raise ValueError(f"ThreeCushionState: {name} must be 0 or 1, got {getattr(s, name)!r}")
    if len(s.scores) != 2 or len(s.innings) != 2:
        raise ValueError(f"ThreeCushionState: scores and innings hold two counts, got {s.scores}, {s.innings}")
    for k in (0, 1):
        _count(s.scores[k], "ThreeCushionState: each score")
        _count(s.innings[k], "ThreeCushionState: each player's innings")
    _count(s.run, "ThreeCushionState: run")
    _count(s.shot, "ThreeCushionState: shot")
    starter, other = s.innings[s.starter], s.innings[1 - s.starter]
    if not (other <= starter <= other + 1) or starter < 1:
        raise ValueError(f"ThreeCushionState: the starter has begun the same number of innings as the other "
                         f"player or one more (and at least one), got innings {s.innings} (starter {s.starter})")
    if s.run > s.scores[s.shooter]:
        raise ValueError(f"ThreeCushionState: run {s.run} exceeds the shooter's score {s.scores[s.shooter]}")
    if s.rules.points is not None and max(s.scores) > s.rules.points:
        raise ValueError(f"ThreeCushionState: a score {s.scores} is past the game's {s.rules.points} points")
    if s.winner not in (None, 0, 1) or not isinstance(s.ended, bool) or (s.winner is not None and not s.ended):
        raise ValueError(f"ThreeCushionState: winner must be None, 0 or 1, and a winner ends the game "
                         f"(winner {s.winner!r}, ended {s.ended!r})")
    if not isinstance(s.is_break, bool) or not isinstance(s.equalizing, bool):
        raise ValueError("ThreeCushionState: is_break and equalizing must be bools")


@dataclass(frozen=True)
class CaromRuling(Ruling):
    """A three-cushion `Ruling`: its fields, and `point` (the shot scored)."""

    point: bool = False


@dataclass(frozen=True)
class ThreeCushion:
    """Three-cushion billiards (UMB): each player's cue ball (white, yellow) and the red.

    `points` the distance (the score that ends the game; None: none, then `innings_limit` is
    needed); `innings_limit` the most innings each player plays (None: no limit); `equalizing`
    (default True) when the starter reaches the distance, the other player gets a last inning
    from the starting position (UMB Art. 29: both players play the same number of innings). A
    tie after it, or at the innings limit, is a draw (winner None): the UMB's penalty shots
    that settle a knock-out match are not modelled."""

    points: int | None = 40
    innings_limit: int | None = None
    equalizing: bool = True
    name = "three_cushion"
    object_balls = frozenset({1, 2})
    money_ball = None

    def __post_init__(self):
        if self.points is None and self.innings_limit is None:
            raise ValueError("ThreeCushion needs points (a distance), an innings_limit, or both: "
                             "otherwise the game never ends")
        for name in ("points", "innings_limit"):
            if getattr(self, name) is not None:
                _count(getattr(self, name), f"ThreeCushion.{name}", low=1)
        if not isinstance(self.equalizing, bool):
            raise ValueError(f"ThreeCushion.equalizing must be a bool, got {self.equalizing!r}")

    def new_game(self, breaker: int = 0) -> ThreeCushionState:
        """A game from the starting position: `breaker` (0 or 1) plays the first inning, with the white."""
        innings = (1, 0) if breaker == 0 else (0, 1)
        return ThreeCushionState(self, shooter=breaker, starter=breaker, innings=innings)

    def legal_targets(self, state: ThreeCushionState) -> frozenset:
        """The balls the cue ball may hit first: the red on a starting stroke (UMB 3.3: "by
        direct attack on the red ball"), else either object ball; none once the game is over."""
        if state.ended:
            return frozenset()
        if state.is_break:
            return frozenset({RED})
        return frozenset({0, 1, 2} - {state.cue_ball})

    def judge(self, state, outcome, called_pocket=None, called_ball=None):
        """(next ThreeCushionState, CaromRuling) after `outcome` (a `CaromOutcome`) played from
        `state`. `called_pocket` and `called_ball` must be None (nothing is called)."""
        _check_shot(state, outcome, called_pocket, called_ball)
        fouls = []
        if outcome.off_table:  # UMB Art. 28: a ball off the billiard ends the inning, no point
            fouls.append(("ball_off_table", f"foul: ball {', '.join(map(str, outcome.off_table))} left the table"))
        if state.is_break and outcome.first_ball not in (None, RED):  # UMB 3.3: the red first
            fouls.append(("wrong_ball_first", "foul: the starting stroke must hit the red first"))
        point = outcome.point and not fouls
        player, other = state.shooter, 1 - state.shooter
        scores, innings = list(state.scores), list(state.innings)
        messages = [m for _, m in fouls]
        if point:
            scores[player] += 1
            messages.append(f"point: player {player} scores ({scores[0]}-{scores[1]})")
        elif not fouls:
            messages.append(_miss_message(outcome))
        nxt = dict(shooter=player, run=state.run + 1 if point else 0, equalizing=state.equalizing)
        winner, end, spot, is_break = None, None, (), False
        reached = point and self.points is not None and scores[player] >= self.points
        if reached:
            winner, end, nxt, spot, is_break = self._distance(state, scores, innings, nxt, messages)
        elif not point:
            winner, end = self._inning_over(state, scores, innings, messages)
            if end is None and winner is None:
                innings[other] += 1
                nxt.update(shooter=other, run=0)
        ended = end is not None
        turn_passed = not ended and nxt["shooter"] != player
        next_ball = WHITE if nxt["shooter"] == state.starter else YELLOW
        if not ended and not spot and (fouls or any(next_ball in pair for pair in outcome.touching)):
            # Art. 28 (a ball off the table) and Art. 27 (the cue ball touching a ball): the balls
            # go back to the starting position, the incoming player's ball on the starting spot.
            spot = (0, 1, 2)
            messages.append("the balls are set up in the starting position")
        new = ThreeCushionState(self, nxt["shooter"], state.starter, tuple(scores), tuple(innings), nxt["run"],
                                is_break, state.shot + 1, nxt["equalizing"], winner, ended)
        if not ended:
            messages.append(f"player {new.shooter} to shoot" + (" (inning passes)" if turn_passed else " again"))
        foul = fouls[0][0] if fouls else None
        ruling = CaromRuling(foul, tuple(n for n, _ in fouls), turn_passed, None, spot, winner, end,
                             tuple(messages), point)
        return new, ruling

    def _distance(self, state, scores, innings, nxt, messages):
        """(winner, end reason, next-state fields, balls to spot, is_break) when the shooter
        reaches the distance (UMB Art. 29)."""
        player, other = state.shooter, 1 - state.shooter
        if state.equalizing:  # the second player drew level in his last inning
            messages.append(f"player {player} equals the distance in the equalising inning: a draw")
            return None, "equalized", nxt, (), False
        if self.equalizing and innings[other] < innings[player]:
            innings[other] += 1
            nxt.update(shooter=other, run=0, equalizing=True)
            messages.append(f"player {player} reaches {self.points}; player {other} has the equalising inning")
            return None, None, nxt, (0, 1, 2), True
        messages.append(f"player {player} wins: {self.points} points ({scores[0]}-{scores[1]})")
        return player, "points_reached", nxt, (), False

    def _inning_over(self, state, scores, innings, messages):
        """(winner, end reason) when the shooter's inning ends on a miss: the end of the
        equalising inning, or of the last inning the innings limit allows; (None, None) otherwise."""
        player = state.shooter
        if state.equalizing:  # the starter reached the distance; the other did not equal it
            messages.append(f"player {state.starter} wins: {self.points} points ({scores[0]}-{scores[1]})")
            return state.starter, "points_reached"
        last = self.innings_limit is not None and player != state.starter and innings[player] >= self.innings_limit
        if not last:
            return None, None
        winner = None if scores[0] == scores[1] else int(np.argmax(scores))
        messages.append(f"innings limit ({self.innings_limit}) reached: "
                        + ("a draw" if winner is None else f"player {winner} wins") + f" ({scores[0]}-{scores[1]})")
        return winner, "innings_limit"

    def respot(self, state: ThreeCushionState, balls: Balls, table: Table) -> Balls:
        """`balls` set up in the starting position for `state`'s shooter (his ball on the
        starting spot), their radius and mass kept."""
        return starting_position(table, state.cue_ball, balls.radius, balls.mass)

    def describe(self, state: ThreeCushionState) -> str:
        """One line: the score, innings, whose shot."""
        score = f"{state.scores[0]}-{state.scores[1]} after innings {state.innings[0]}/{state.innings[1]}"
        if state.ended:
            return ("a draw" if state.winner is None else f"player {state.winner} won") + f", {score}"
        ball = "white" if state.cue_ball == WHITE else "yellow"
        return (f"player {state.shooter} to shoot ({ball}){', starting stroke' if state.is_break else ''}, "
                f"{score}{', equalising inning' if state.equalizing else ''}")


def _miss_message(outcome: CaromOutcome) -> str:
    if outcome.first_ball is None:
        return "no point: the cue ball touched no ball"
    if outcome.second_ball is None:
        return "no point: the cue ball touched one ball"
    return f"no point: {outcome.cushions_before_second} cushion(s) before the second ball, 3 needed"


def _check_shot(state, outcome, called_pocket, called_ball) -> None:
    if not isinstance(state, ThreeCushionState):
        raise TypeError(f"state must be a ThreeCushionState, got {type(state).__name__}")
    if not isinstance(outcome, CaromOutcome):
        raise TypeError(f"outcome must be a CaromOutcome, got {type(outcome).__name__}")
    if state.ended:
        raise ValueError("the game is over; start a new one with new_game")
    if outcome.cue_ball != state.cue_ball:
        raise ValueError(f"the shot struck ball {outcome.cue_ball}, but player {state.shooter}'s cue ball is "
                         f"ball {state.cue_ball}")
    if called_pocket is not None or called_ball is not None:
        raise ValueError("three-cushion calls no pocket and no ball: called_pocket and called_ball must be None")
