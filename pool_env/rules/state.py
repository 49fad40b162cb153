"""`GameState` and `Ruling`, the foul names, and the checks and foul tests both rule sets share."""

from __future__ import annotations

from dataclasses import dataclass

from ..physics.frozen import unchecked
from .outcome import CUE, ShotOutcome

# Standard fouls (the shot is a foul: the turn passes, the incoming player gets ball in hand),
# in the order a ruling names them when one shot commits several (Ruling.foul is the first).
FOULS = ("scratch", "no_contact", "wrong_ball_first", "illegal_break", "no_rail", "ball_off_table")
# Why a game ended (Ruling.end_reason).
END_REASONS = ("nine_pocketed", "three_fouls", "eight_pocketed", "eight_early", "eight_wrong_pocket",
               "eight_with_foul", "eight_off_table")
BALL_IN_HAND = (None, "anywhere", "behind_head_string")
# The decisions a player makes instead of a shot (`GameState.pending`): each one's options, the
# first the built-in default (what a player who does not decide gets).
DECISIONS = {
    "push_out_reply": ("shoot", "pass"),  # WPA 2.4: after a legal push out, the incoming player
    "illegal_break": ("ball_in_hand", "accept_table", "rerack_and_break", "rerack_opponent_breaks"),  # 3.3(d)
    "eight_on_break": ("spot_eight", "rebreak"),  # 3.3(e)-(f), 3.6
    "wrongly_pocketed_reply": ("shoot", "pass"),  # WPA Ten Ball 7: a ball pocketed but not as called
}
GROUPS = (None, "solids", "stripes")


@dataclass(frozen=True)
class Decision:
    """A choice the shooter (`GameState.shooter`) makes before the next shot: `name` a key of
    `DECISIONS`, `options` the choices open to him, `default` the one a player who does not
    decide gets (`rules.decide` takes one of `options`)."""

    name: str
    options: tuple
    default: str

    def __post_init__(self):
        if self.name not in DECISIONS:
            raise ValueError(f"Decision: unknown decision {self.name!r}; known: {', '.join(DECISIONS)}")
        object.__setattr__(self, "options", tuple(self.options))
        unknown = [o for o in self.options if o not in DECISIONS[self.name]]
        if unknown or not self.options:
            raise ValueError(f"Decision {self.name!r}: options must be some of {DECISIONS[self.name]}, "
                             f"got {self.options!r}")
        if self.default not in self.options:
            raise ValueError(f"Decision {self.name!r}: default {self.default!r} is not one of {self.options}")


@dataclass(frozen=True)
class GameState:
    """A game between shots (immutable; `judge` returns the next one).

    `rules` the rule set (`NineBall` or `EightBall`, with its options); `on_table` the object
    balls on the table; `shooter` 0 or 1, the player to shoot; `ball_in_hand` where the
    shooter may place the cue ball (None: it plays from where it lies, "anywhere", or
    "behind_head_string": x < `racks.head_string_x(table)`); `fouls` each player's consecutive
    fouls; `groups` each player's 8-ball group (None while the table is open, "solids" 1-7,
    "stripes" 9-15); `is_break` the next shot is the break; `shot` shots taken so far;
    `winner` None while the game goes on, else 0 or 1; `pending` None, or the `Decision` the
    shooter makes before he shoots (`rules.decide`); `push_out` the shooter may declare a push
    out on this shot (9-ball, the shot right after a legal break: WPA 2.4)."""

    rules: object
    on_table: frozenset
    shooter: int = 0
    ball_in_hand: str | None = "behind_head_string"
    fouls: tuple = (0, 0)
    groups: tuple = (None, None)
    is_break: bool = True
    shot: int = 0
    winner: int | None = None
    pending: Decision | None = None
    push_out: bool = False

    def __post_init__(self):
        object.__setattr__(self, "on_table", frozenset(self.on_table))
        object.__setattr__(self, "fouls", tuple(self.fouls))
        object.__setattr__(self, "groups", tuple(self.groups))
        check_state(self)

    @classmethod
    def successor(cls, rules, on_table: frozenset, shooter: int, ball_in_hand, fouls: tuple, groups: tuple,
                  shot: int, winner, pending=None, push_out=False) -> GameState:
        """The state after a shot, built by a rule set from a checked state (`advance`): the
        fields as given (a frozenset and tuples already), without `__post_init__`'s
        conversions and checks, which cost most of a ruling's time."""
        return unchecked(cls, {"rules": rules, "on_table": on_table, "shooter": shooter, "ball_in_hand": ball_in_hand,
                               "fouls": fouls, "groups": groups, "is_break": False, "shot": shot, "winner": winner,
                               "pending": pending, "push_out": push_out})

    @property
    def kind(self) -> str:
        """"nine_ball" or "eight_ball"."""
        return self.rules.name

    @property
    def over(self) -> bool:
        """The game has a winner."""
        return self.winner is not None


@dataclass(frozen=True)
class Ruling:
    """The referee's decision on one shot.

    `foul` the first standard foul of the shot in `FOULS` order (None: a legal shot), `fouls`
    all of them; `turn_passed` the other player shoots next (False when the game ended);
    `ball_in_hand` what the next shooter gets (None, "anywhere", "behind_head_string");
    `balls_to_spot` object balls to put back on the table (`racks.spot_balls`), in spotting
    order; `winner` None, 0 or 1; `end_reason` why the game ended (`END_REASONS`), else None;
    `messages` short human-readable lines for overlays and logs."""

    foul: str | None = None
    fouls: tuple = ()
    turn_passed: bool = False
    ball_in_hand: str | None = None
    balls_to_spot: tuple = ()
    winner: int | None = None
    end_reason: str | None = None
    messages: tuple = ()


def _is_int(value) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def check_state(s: GameState) -> None:
    """ValueError for a GameState no game can reach."""
    balls = s.rules.object_balls
    if not s.on_table <= balls:
        raise ValueError(f"GameState: on_table holds {sorted(s.on_table - balls)}, not object balls of "
                         f"{s.rules.name} (1-{max(balls)})")
    if s.shooter not in (0, 1) or not _is_int(s.shooter):
        raise ValueError(f"GameState: shooter must be 0 or 1, got {s.shooter!r}")
    if s.ball_in_hand not in BALL_IN_HAND:
        raise ValueError(f"GameState: ball_in_hand must be one of {BALL_IN_HAND}, got {s.ball_in_hand!r}")
    if len(s.fouls) != 2 or not all(_is_int(f) and f >= 0 for f in s.fouls):
        raise ValueError(f"GameState: fouls must be two integers >= 0 (one per player), got {s.fouls!r}")
    if len(s.groups) != 2 or not all(g in GROUPS for g in s.groups):
        raise ValueError(f"GameState: groups must be two of {GROUPS}, got {s.groups!r}")
    if (s.groups[0] is None) != (s.groups[1] is None) or (s.groups[0] is not None and s.groups[0] == s.groups[1]):
        raise ValueError(f"GameState: groups are both None (open table) or one 'solids' and one 'stripes', "
                         f"got {s.groups!r}")
    if s.groups[0] is not None and s.rules.name != "eight_ball":
        raise ValueError(f"GameState: {s.rules.name} has no groups, got {s.groups!r}")
    if not isinstance(s.is_break, bool) or not _is_int(s.shot) or s.shot < 0:
        raise ValueError(f"GameState: is_break must be a bool and shot an integer >= 0, got {s.is_break!r}, {s.shot!r}")
    if s.winner not in (None, 0, 1):
        raise ValueError(f"GameState: winner must be None, 0 or 1, got {s.winner!r}")
    if s.pending is not None and (not isinstance(s.pending, Decision) or s.winner is not None):
        raise ValueError(f"GameState: pending must be None or a Decision of a game under way, got {s.pending!r}")
    if not isinstance(s.push_out, bool) or (s.push_out and (s.pending is not None or s.is_break)):
        raise ValueError(f"GameState: push_out must be a bool, and False on the break or with a decision pending, "
                         f"got {s.push_out!r}")
    if s.winner is None and s.rules.money_ball not in s.on_table:
        raise ValueError(f"GameState: the {s.rules.money_ball} is off the table but the game has no winner")


def check_shot(state, outcome) -> None:
    """ValueError unless `outcome` can follow `state`: a game under way, and every ball the
    shot names (first contact, dropped, to a rail, off the table) on the table before it."""
    if not isinstance(state, GameState):
        raise TypeError(f"state must be a pool_env.rules.GameState, got {type(state).__name__}")
    if not isinstance(outcome, ShotOutcome):
        raise TypeError(f"outcome must be a pool_env.rules.ShotOutcome, got {type(outcome).__name__}")
    if state.winner is not None:
        raise ValueError(f"the game is over (player {state.winner} won); start a new one with new_game")
    if state.pending is not None:
        raise ValueError(f"player {state.shooter} has a decision to make first ({state.pending.name}: one of "
                         f"{state.pending.options}); call rules.decide(state, option)")
    named = set().union(outcome.pocketed, outcome.object_balls_to_rail, outcome.off_table)
    if outcome.first_contact is not None:
        named.add(outcome.first_contact)
    named.discard(CUE)  # the cue ball may leave the table (the others never name it: _check_outcome)
    if not named <= state.on_table:
        missing = sorted(named - state.on_table)
        raise ValueError(f"the shot names ball {missing[0]}, which is not on the table "
                         f"(on the table: {sorted(state.on_table)})")


def standard_fouls(outcome, targets, describe, is_break) -> list:
    """The standard fouls of a shot (WPA 6.1 scratch, 6.2 wrong ball first, 6.3 no rail after
    contact, 6.5 ball driven off the table) as (name, message) pairs; `targets` the balls it
    may hit first (an empty set skips the test, e.g. an 8-ball break), `describe(ball)` the
    wrong-ball message's tail. On the break the break rule replaces 6.3 (the caller tests it)."""
    out = []
    if outcome.scratch:
        how = "was pocketed" if outcome.cue_pocketed else "left the table"
        out.append(("scratch", f"foul: scratch (the cue ball {how})"))
    if targets:
        if outcome.first_contact is None:
            out.append(("no_contact", "foul: the cue ball touched no object ball"))
        elif outcome.first_contact not in targets:
            out.append(("wrong_ball_first", f"foul: wrong ball first ({describe(outcome.first_contact)})"))
    if (not is_break and outcome.first_contact is not None and not outcome.pocketed
            and not outcome.cue_pocketed and not outcome.rail_after_contact):
        out.append(("no_rail", "foul: no ball pocketed and no ball reached a rail after contact"))
    gone = [b for b in outcome.off_table if b != CUE] if outcome.off_table else None
    if gone:
        out.append(("ball_off_table", f"foul: ball {', '.join(map(str, gone))} left the table"))
    return out


def break_requirement(outcome):
    """(name, message) of an illegal break, or None: a break must pocket an object ball or
    drive at least four object balls to a rail (WPA 2.3(b) nine ball, 3.3(d) eight ball)."""
    if outcome.pocketed or len(outcome.object_balls_to_rail) >= 4:
        return None
    n = len(outcome.object_balls_to_rail)
    return ("illegal_break", f"foul: illegal break (no ball pocketed, {n} object ball{'s' * (n != 1)} "
                             "reached a rail, 4 needed)")


def ordered(fouls) -> list:
    """The (name, message) fouls in FOULS order, each name once."""
    if len(fouls) < 2:  # most shots: none or one
        return list(fouls)
    seen, out = set(), []
    for name, message in sorted(fouls, key=lambda f: FOULS.index(f[0])):
        if name not in seen:
            seen.add(name)
            out.append((name, message))
    return out


def advance(state, ruling, on_table, fouls, groups=None, pending=None, push_out=False):
    """The GameState after a shot ruled `ruling`: the next shooter, ball in hand, fouls,
    groups and the balls left (`on_table`, spotted balls included); the decision he makes
    first (`pending`), whether he may push out."""
    shooter = 1 - state.shooter if ruling.turn_passed else state.shooter
    # Built directly (dataclasses.replace costs several times as much, and a game judges every shot).
    return GameState.successor(state.rules, frozenset(on_table), shooter, ruling.ball_in_hand, tuple(fouls),
                               state.groups if groups is None else tuple(groups), state.shot + 1, ruling.winner,
                              pending, push_out)


def check_option(state, option) -> None:
    """ValueError unless `state` has a decision pending and `option` is one of its options."""
    if not isinstance(state, GameState):
        raise TypeError(f"state must be a pool_env.rules.GameState, got {type(state).__name__}")
    if state.pending is None:
        raise ValueError("no decision is pending: the shooter shoots (rules.judge)")
    if option not in state.pending.options:
        raise ValueError(f"{option!r} is not an option of the pending {state.pending.name!r} decision; "
                         f"choose one of {state.pending.options}")


def turn_messages(new, turn_passed, warn_two_fouls) -> list:
    """The overlay lines after a shot: who shoots next, ball in hand, and (with the three-foul
    rule) the warning to a player on two fouls (WPA 6.14)."""
    lines = [f"player {new.shooter} to shoot" + (" (turn passes)" if turn_passed else " again")]
    if new.ball_in_hand is not None:
        where = "anywhere" if new.ball_in_hand == "anywhere" else "behind the head string"
        lines.append(f"player {new.shooter} has ball in hand {where}")
    if warn_two_fouls and new.fouls[new.shooter] == 2:
        lines.append(f"warning: player {new.shooter} is on two fouls (a third loses the game)")
    return lines


def quick_ruling(foul, fouls, turn_passed, ball_in_hand, balls_to_spot, winner, end_reason) -> Ruling:
    """`Ruling(foul, ..., end_reason)` (no messages yet: `with_messages`) without the frozen
    dataclass's __init__, which sets each field through object.__setattr__ (every shot's
    ruling is made this way)."""
    return unchecked(Ruling, {"foul": foul, "fouls": fouls, "turn_passed": turn_passed, "ball_in_hand": ball_in_hand,
                              "balls_to_spot": balls_to_spot, "winner": winner, "end_reason": end_reason,
                              "messages": ()})


def with_messages(ruling, messages):
    """`ruling` (a `Ruling`) with its messages: a copy of its fields, without the frozen
    dataclass's __init__, which costs more (every shot's ruling is made twice)."""
    return unchecked(Ruling, {**ruling.__dict__, "messages": tuple(messages)})
