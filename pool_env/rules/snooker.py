"""Snooker by the WPBSA Official Rules: `SnookerState`, the `Snooker` rule set and its `judge` (docs/rules.md).

Rule numbers are those of the WPBSA Official Rules of Snooker, Section 3 (The Game): Rule 1
(description, values), 3 (mode of play: the ball on, scoring, the end of the frame, the
re-spotted black), 4 (play from in-hand), 6 (spotting colours), 10 (snookered after a foul: the
free ball), 11-12 (fouls and their penalties). The colour "nominated" is the first ball the cue
ball touches (the nomination is implicit); the referee's calls (miss, play again) are not made:
docs/rules.md lists the deviations.
"""

from __future__ import annotations

from dataclasses import dataclass

from .outcome import CUE, ShotOutcome
from .snooker_spots import BLACK, COLOURS, REDS, name, value
from .state import Ruling

ON = ("red", "colour")  # besides a colour's number (the colours' sequence)
SNOOKER_FOULS = ("scratch", "no_contact", "wrong_ball_first", "wrong_ball_potted", "ball_off_table")
SNOOKER_END_REASONS = ("black_potted", "black_fouled")
SNOOKER_IN_HAND = (None, "in_d")
MIN_PENALTY = 4  # Section 3 Rule 12: every foul is worth at least 4 points


class Snooker:
    """The snooker rule set (no options). Ball numbers: 0 the cue ball, 1-15 reds, 16-21 yellow..black."""

    name = "snooker"
    object_balls = frozenset(range(1, 22))

    def __repr__(self):
        return "Snooker()"

    def __eq__(self, other):
        return isinstance(other, Snooker)

    def __hash__(self):
        return hash("Snooker")

    def new_game(self, breaker: int = 0) -> SnookerState:
        """The frame's start: every ball on the table, `breaker` in hand in the D, on a red (Section 3 Rule 3)."""
        return SnookerState(self, self.object_balls, shooter=breaker, breaker=breaker)

    def position(self, on_table, shooter: int, in_hand: bool = False) -> SnookerState:
        """A frame in progress from a layout: `on_table` the object balls, `shooter` to play at the
        ball on a visit starts with (a red while reds remain, else the lowest colour), scores 0-0;
        `in_hand` the cue ball in hand in the D. ValueError if the layout cannot be a frame's
        (a colour missing while reds remain, the black gone)."""
        on_table = frozenset(on_table)
        return SnookerState(self, on_table, shooter=shooter, ball_on=next_ball_on(on_table),
                            ball_in_hand="in_d" if in_hand else None, is_break=False)

    def legal_targets(self, state) -> frozenset:
        return targets(state)

    def judge(self, state, outcome, called_pocket=None, called_ball=None):
        return judge(state, outcome)


@dataclass(frozen=True)
class SnookerState:
    """A frame between shots (immutable; `judge` returns the next one).

    `on_table` the object balls on the table; `shooter` 0 or 1; `scores` each player's points;
    `ball_on` "red", "colour" (any colour, after a red), or the colour's number (16-21) once
    the reds are gone (Section 3 Rule 3); `ball_in_hand` None or "in_d" (Rule 4); `free_ball` the
    shooter may play any ball as the ball on (Rule 10); `is_break` the break-off is next;
    `breaker` who broke off; `respotted_black` the frame is in its re-spotted black (a tie,
    Rule 3); `visit` the shooter's points in this visit so far (his break); `shot` shots taken;
    `winner` None, 0 or 1."""

    rules: Snooker
    on_table: frozenset
    shooter: int = 0
    scores: tuple = (0, 0)
    ball_on: object = "red"
    ball_in_hand: str | None = "in_d"
    free_ball: bool = False
    is_break: bool = True
    breaker: int = 0
    respotted_black: bool = False
    visit: int = 0
    shot: int = 0
    winner: int | None = None

    def __post_init__(self):
        object.__setattr__(self, "on_table", frozenset(self.on_table))
        object.__setattr__(self, "scores", tuple(self.scores))
        check_state(self)

    @property
    def kind(self) -> str:
        return "snooker"

    @property
    def over(self) -> bool:
        return self.winner is not None

    @property
    def reds(self) -> int:
        """Reds on the table."""
        return len(self.on_table & REDS)

    @property
    def fouls(self) -> tuple:  # snooker has no consecutive-foul rule; the pool observations read this
        return (0, 0)


def check_state(s: SnookerState) -> None:
    """ValueError for a SnookerState no frame can reach."""
    if not isinstance(s.rules, Snooker):
        raise ValueError(f"SnookerState: rules must be Snooker(), got {s.rules!r}")
    if not s.on_table <= s.rules.object_balls:
        raise ValueError(f"SnookerState: on_table holds {sorted(s.on_table - s.rules.object_balls)}, not 1-21")
    if s.shooter not in (0, 1) or isinstance(s.shooter, bool) or s.breaker not in (0, 1):
        raise ValueError(f"SnookerState: shooter and breaker must be 0 or 1, got {s.shooter!r}, {s.breaker!r}")
    if len(s.scores) != 2 or not all(isinstance(p, int) and p >= 0 for p in s.scores):
        raise ValueError(f"SnookerState: scores must be two integers >= 0, got {s.scores!r}")
    if s.ball_in_hand not in SNOOKER_IN_HAND:
        raise ValueError(f"SnookerState: ball_in_hand must be one of {SNOOKER_IN_HAND}, got {s.ball_in_hand!r}")
    if s.winner not in (None, 0, 1):
        raise ValueError(f"SnookerState: winner must be None, 0 or 1, got {s.winner!r}")
    colours_left = sorted(s.on_table & set(COLOURS))
    if s.ball_on in ON:
        if s.ball_on == "red" and s.reds == 0:
            raise ValueError("SnookerState: ball_on is 'red' but no red is on the table")
        if len(colours_left) != 6 and s.winner is None:
            raise ValueError("SnookerState: every colour is on the table while a red or 'colour' is on")
    elif s.ball_on in COLOURS:
        if s.reds or (s.winner is None and colours_left and colours_left[0] != s.ball_on):
            raise ValueError(f"SnookerState: ball_on {s.ball_on} must be the lowest colour left, with no reds, "
                             f"got colours {colours_left} and {s.reds} reds")
    else:
        raise ValueError(f"SnookerState: ball_on must be 'red', 'colour' or a colour 16-21, got {s.ball_on!r}")
    if s.winner is None and BLACK not in s.on_table:
        raise ValueError("SnookerState: the black is off the table but the frame has no winner")


@dataclass(frozen=True)
class SnookerRuling(Ruling):
    """A snooker ruling: `Ruling`'s fields, plus `points` the shooter scored, `penalty` the points
    his foul gave the opponent, `nominated` the ball the shot played as the ball on (the first
    ball hit), and `respot_black` (a tie: the black goes back on its spot, Section 3 Rule 3)."""

    points: int = 0
    penalty: int = 0
    nominated: int | None = None
    respot_black: bool = False


def targets(state: SnookerState) -> frozenset:
    """The balls the shooter may hit first: a red, any colour, the colour in sequence; any ball with a free ball."""
    if state.winner is not None:
        return frozenset()
    if state.free_ball:
        return state.on_table
    if state.ball_on == "red":
        return state.on_table & REDS
    if state.ball_on == "colour":
        return state.on_table & set(COLOURS)
    return frozenset({state.ball_on})


def next_ball_on(on_table) -> object:
    """The ball on at the start of a visit: a red while reds remain, else the lowest colour (Rule 3)."""
    if on_table & REDS:
        return "red"
    left = sorted(on_table & set(COLOURS))
    return left[0] if left else BLACK


def _on_value(state, nominated) -> int:
    """The value of the ball on for a penalty: a red 1, the colour in sequence, the nominated colour (0: none yet)."""
    if state.ball_on == "red":
        return 1
    if state.ball_on == "colour":
        return value(nominated) if nominated in COLOURS else 0
    return value(state.ball_on)


def _fouls(state, o: ShotOutcome, legal_pots, on_value):
    """(name, penalty, message) of each foul of the shot (Section 3 Rules 11-12)."""
    out = []
    if o.scratch:
        out.append(("scratch", on_value, "foul: the cue ball " + ("was potted (in-off)" if o.cue_pocketed
                                                                    else "left the table")))
    first = o.first_contact
    if first is None:
        out.append(("no_contact", on_value, "foul: the cue ball hit no ball"))
    elif first not in targets(state):
        out.append(("wrong_ball_first", max(on_value, value(first)), f"foul: {name(first)} hit first, not on"))
    for b in o.pocketed:
        if b not in legal_pots:
            out.append(("wrong_ball_potted", max(on_value, value(b)), f"foul: {name(b)} potted, not on"))
    for b in o.off_table:
        if b != CUE:
            out.append(("ball_off_table", max(on_value, value(b)), f"foul: {name(b)} forced off the table"))
    return out


def _legal_pots(state, nominated) -> frozenset:
    """The balls the shot may pot: the reds (red on), the nominated colour, the colour in sequence;
    with a free ball the nominated ball too (Rule 10(c)-(e))."""
    if state.ball_on == "red":
        legal = set(REDS)
    elif state.ball_on == "colour":
        legal = {nominated} if nominated in COLOURS else set()
    else:
        legal = {state.ball_on}
    if state.free_ball and nominated is not None:
        legal.add(nominated)
    return frozenset(legal)


def _score(state, o, nominated) -> int:
    """The points of a fair shot (Rules 1, 3, 10): a red each, the colour's value; a free ball
    scores as the ball on, and with the ball on potted too only the ball on scores (unless reds)."""
    if state.ball_on == "red":
        return len(o.pocketed)  # reds, and a free ball counted as a red
    if state.ball_on == "colour":
        return value(nominated) if o.pocketed else 0
    return value(state.ball_on) if o.pocketed else 0


def _to_spot(state, o, fair) -> tuple:
    """Colours to put back (Rule 6): every potted or forced-off colour but the colour in sequence
    potted fairly (a free ball is always put back, Rule 10(c))."""
    gone = [b for b in (*o.pocketed, *(b for b in o.off_table if b != CUE)) if b in COLOURS]
    keep_off = state.ball_on if (fair and state.ball_on in COLOURS) else None
    if keep_off is not None and keep_off not in o.pocketed:
        keep_off = None
    return tuple(sorted(b for b in gone if b != keep_off))


def judge(state: SnookerState, outcome: ShotOutcome):
    """(the next SnookerState, the SnookerRuling) after the shot `outcome` played from `state`."""
    _check(state, outcome)
    o = outcome
    nominated = o.first_contact
    on_value = _on_value(state, nominated)
    legal_pots = _legal_pots(state, nominated)
    fouls = _fouls(state, o, legal_pots, on_value)
    fair = not fouls
    spot = _to_spot(state, o, fair)
    gone = set(o.pocketed) | {b for b in o.off_table if b != CUE}
    on_table = (state.on_table - gone) | set(spot)
    scores = list(state.scores)
    shooter, other = state.shooter, 1 - state.shooter
    if fouls:
        penalty = max(MIN_PENALTY, *(p for _, p, _ in fouls))
        points = 0
        scores[other] += penalty
    else:
        penalty, points = 0, _score(state, o, nominated)
        scores[shooter] += points
    messages = [m for _, _, m in fouls]
    frame_ends = state.ball_on == BLACK and (fouls or BLACK in o.pocketed)
    if frame_ends:
        return _end_frame(state, o, fouls, points, penalty, nominated, scores, on_table, spot, messages)
    continues = fair and points > 0
    if continues:
        ball_on = _after_pot(state, o, on_table)
    else:
        ball_on = next_ball_on(on_table)
    in_hand = "in_d" if o.scratch else None
    ruling = SnookerRuling(fouls[0][0] if fouls else None, tuple(f for f, _, _ in fouls), not continues, in_hand,
                           spot, None, None, (), points, penalty, nominated)
    new = SnookerState(state.rules, frozenset(on_table), shooter if continues else other, tuple(scores), ball_on,
                       in_hand, False, False, state.breaker, state.respotted_black,
                       state.visit + points if continues else 0, state.shot + 1, None)
    messages += _lines(new, points, penalty, shooter)
    return new, _with(ruling, messages)


def _after_pot(state, o, on_table):
    """The ball on after a scoring shot: a colour after a red; a red after a colour while reds
    remain; then the lowest colour left (Rule 3)."""
    if state.ball_on == "red":
        return "colour"
    return next_ball_on(on_table)


def _end_frame(state, o, fouls, points, penalty, nominated, scores, on_table, spot, messages):
    """The last black potted or fouled (Rule 3): the higher score wins; level scores re-spot the
    black, the cue ball in hand, the breaker to play it (the toss: a deviation)."""
    shooter = state.shooter
    kind = "black_fouled" if fouls else "black_potted"
    foul_names = tuple(f for f, _, _ in fouls)
    if scores[0] != scores[1]:
        winner = 0 if scores[0] > scores[1] else 1
        ruling = SnookerRuling(fouls[0][0] if fouls else None, foul_names, False, None, (), winner, kind, (),
                               points, penalty, nominated)
        new = SnookerState(state.rules, frozenset(on_table - {BLACK}), shooter, tuple(scores), BLACK, None, False,
                           False, state.breaker, state.respotted_black, 0, state.shot + 1, winner)
        messages = [*messages, f"player {winner} wins the frame {scores[winner]}-{scores[1 - winner]}"]
        return new, _with(ruling, messages)
    ruling = SnookerRuling(fouls[0][0] if fouls else None, foul_names, state.breaker != shooter, "in_d", (), None,
                           None, (), points, penalty, nominated, respot_black=True)
    new = SnookerState(state.rules, frozenset(on_table | {BLACK}), state.breaker, tuple(scores), BLACK, "in_d",
                       False, False, state.breaker, True, 0, state.shot + 1, None)
    messages = [*messages, f"scores level {scores[0]}-{scores[1]}: the black is re-spotted",
                f"player {state.breaker} plays the re-spotted black from the D"]
    return new, _with(ruling, messages)


def _lines(new, points, penalty, shooter):
    out = []
    if points:
        out.append(f"player {shooter} scores {points} (break {new.visit if new.shooter == shooter else points})")
    if penalty:
        out.append(f"{penalty} points to player {1 - shooter}")
    out.append(f"score {new.scores[0]}-{new.scores[1]}; player {new.shooter} on "
               + ("a red" if new.ball_on == "red" else "a colour" if new.ball_on == "colour" else name(new.ball_on)))
    if new.ball_in_hand:
        out.append(f"player {new.shooter} has the cue ball in hand in the D")
    return out


def _with(ruling, messages):
    return SnookerRuling(ruling.foul, ruling.fouls, ruling.turn_passed, ruling.ball_in_hand, ruling.balls_to_spot,
                         ruling.winner, ruling.end_reason, tuple(messages), ruling.points, ruling.penalty,
                         ruling.nominated, ruling.respot_black)


def _check(state, outcome):
    if not isinstance(state, SnookerState):
        raise TypeError(f"state must be a SnookerState, got {type(state).__name__}")
    if not isinstance(outcome, ShotOutcome):
        raise TypeError(f"outcome must be a pool_env.rules.ShotOutcome, got {type(outcome).__name__}")
    if state.winner is not None:
        raise ValueError(f"the frame is over (player {state.winner} won); start a new one with new_game")
    named = set(outcome.pocketed) | (set(outcome.off_table) - {CUE})
    if outcome.first_contact is not None:
        named.add(outcome.first_contact)
    missing = sorted(named - state.on_table)
    if missing:
        raise ValueError(f"the shot names ball {missing[0]}, which is not on the table "
                         f"(on the table: {sorted(state.on_table)})")
