"""`NineBall`: 9-ball by the WPA World Standardized Rules (section 2, with the general rules 1.x and fouls 6.x)."""

from __future__ import annotations

from dataclasses import dataclass

from .state import (
    Decision,
    GameState,
    advance,
    break_requirement,
    check_option,
    check_shot,
    ordered,
    quick_ruling,
    standard_fouls,
    turn_messages,
    with_messages,
)

NINE = 9
PUSH_OUT_REPLY = Decision("push_out_reply", ("shoot", "pass"), "shoot")


@dataclass(frozen=True)
class NineBall:
    """9-ball (WPA rules, section 2): balls 1-9, the lowest-numbered ball first, the 9 wins.

    `three_foul_rule` (default True): three consecutive fouls by one player lose the game
    (WPA 6.14 and 2.8). The WPA counts a third foul only if the player was warned, on coming
    to the table, that he was on two fouls; here the warning is always given (the state
    tracks the count, and the ruling says "warning: ..." when the next shooter is on two), so
    every third foul loses. The push out (WPA 2.4): the shot right after a legal break may be
    declared one (`judge(..., push_out=True)`); then the incoming player decides (`decide`):
    "shoot" from the position, or "pass" it back."""

    three_foul_rule: bool = True
    name = "nine_ball"
    object_balls = frozenset(range(1, 10))
    money_ball = NINE

    def new_game(self, breaker: int = 0) -> GameState:
        """A racked game: `breaker` (0 or 1) breaks with the cue ball in hand behind the head
        string (WPA 2.3(a))."""
        return GameState(self, self.object_balls, shooter=breaker, ball_in_hand="behind_head_string")

    def legal_targets(self, state: GameState) -> frozenset:
        """The ball the shooter must hit first: the lowest-numbered on the table (WPA 6.2; on
        the break too, the 1)."""
        return frozenset({min(state.on_table)}) if state.on_table else frozenset()

    def judge(self, state: GameState, outcome, called_pocket=None, called_ball=None, push_out=False):
        """(next GameState, Ruling) after `outcome` played from `state`. `called_pocket` and
        `called_ball` are ignored (9-ball calls no shot: WPA section 2), so one env loop can
        pass them for both games; they must still be None or integers >= 0. `push_out` the
        shooter declared a push out (only when `state.push_out`)."""
        check_shot(state, outcome)
        for name, value in (("called_pocket", called_pocket), ("called_ball", called_ball)):
            if value is not None and (isinstance(value, bool) or not isinstance(value, int) or value < 0):
                raise ValueError(f"{name} must be None or an integer >= 0, got {value!r}")
        if push_out and not state.push_out:
            raise ValueError("no push out now: only the shot right after a legal break may be one (WPA 2.4)")
        lowest = min(state.on_table)
        # WPA 2.4: a push out need not hit any ball or a rail (6.2 and 6.3 do not apply); other fouls do.
        targets = frozenset() if push_out else {lowest}
        fouls = standard_fouls(outcome, targets, lambda b: f"hit the {b}, lowest is the {lowest}",
                               state.is_break or push_out)
        if state.is_break:
            illegal = break_requirement(outcome)
            fouls += [illegal] if illegal else []
        fouls = ordered(fouls)
        foul = fouls[0][0] if fouls else None
        player, other = state.shooter, 1 - state.shooter
        messages = [m for _, m in fouls]
        nine_gone = NINE in outcome.pocketed or NINE in outcome.off_table
        on_table = state.on_table - set(outcome.pocketed) - set(outcome.off_table)
        spot, counts = (), list(state.fouls)
        winner = end = None
        if foul:
            counts[player] += 1
            if nine_gone:  # WPA 2.6: the 9 pocketed on a foul, or driven off the table, is spotted
                spot, on_table = (NINE,), on_table | {NINE}
                messages.append("the 9 is spotted")
            if self.three_foul_rule and counts[player] >= 3:  # WPA 6.14, 2.8: loss of the rack
                winner, end = other, "three_fouls"
                messages.append(f"player {player} loses: three consecutive fouls")
        elif push_out:  # WPA 2.4: balls pocketed stay down but the 9 (spotted, 2.6); the turn passes
            counts[player] = 0
            if nine_gone:
                spot, on_table = (NINE,), on_table | {NINE}
                messages.append("the 9 is spotted (pocketed on a push out)")
            messages.append(f"push out: player {other} shoots from here or passes the shot back")
        else:
            counts[player] = 0
            if NINE in outcome.pocketed:  # WPA 2.5: the 9 legally pocketed wins (on the break too)
                winner, end = player, "nine_pocketed"
                messages.append(f"player {player} wins: the 9 pocketed{' on the break' if state.is_break else ''}")
        turn_passed = winner is None and (foul is not None or push_out or not outcome.pocketed)
        hand = "anywhere" if foul and winner is None else None  # WPA 2.7, 1.5: in hand anywhere
        ruling = quick_ruling(foul, tuple(n for n, _ in fouls), turn_passed, hand, spot, winner, end)
        pending = PUSH_OUT_REPLY if push_out and not foul else None
        # WPA 2.4: the shot immediately after a legal break may be a push out (not after a foul on the break).
        may_push = state.is_break and not foul and winner is None
        new = advance(state, ruling, on_table, counts, pending=pending, push_out=may_push)
        if winner is None:
            messages += turn_messages(new, turn_passed, self.three_foul_rule)
        return new, with_messages(ruling, messages)

    def decide(self, state: GameState, option: str) -> GameState:
        """The state after the shooter's `option` of the pending decision (WPA 2.4, after a
        legal push out): "shoot" he plays from the position; "pass" the player who pushed out must."""
        check_option(state, option)
        shooter = state.shooter if option == "shoot" else 1 - state.shooter
        return GameState.successor(self, state.on_table, shooter, state.ball_in_hand, state.fouls, state.groups,
                                   state.shot, state.winner)

    def describe(self, state: GameState) -> str:
        """One line: whose shot, the ball on, ball in hand, fouls."""
        if state.winner is not None:
            return f"player {state.winner} won"
        on = min(state.on_table)
        fouls = state.fouls[state.shooter]
        if state.pending is not None:
            return f"player {state.shooter} to decide after the push out: shoot or pass"
        return (f"player {state.shooter} to shoot{' the break' if state.is_break else ''}, on the {on}"
                f"{', ball in hand' if state.ball_in_hand else ''}{f', {fouls} foul(s)' if fouls else ''}")

