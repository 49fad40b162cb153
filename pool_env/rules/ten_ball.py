"""`TenBall`: 10-ball by the WPA World Standardized Rules (the Ten Ball section, with 1.x and 6.x)."""

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

TEN = 10
TEN_END_REASONS = ("ten_pocketed",)
PUSH_OUT_REPLY = Decision("push_out_reply", ("shoot", "pass"), "shoot")
WRONGLY_POCKETED_REPLY = Decision("wrongly_pocketed_reply", ("shoot", "pass"), "shoot")


@dataclass(frozen=True)
class TenBall:
    """10-ball (WPA Ten Ball rules): balls 1-10, the lowest-numbered ball first, every shot
    but the break called (a ball and a pocket), the 10 pocketed on a legal called shot wins.

    Rule numbers cite the WPA Ten Ball section (2 rack, 3 legal break, 4 push out, 5 call
    shots, 6 safety, 7 wrongly pocketed balls, 8 continuing play, 9 spotting balls, 10
    standard fouls, 11 serious fouls). The 10 pocketed on the break, on a push out, on a foul
    or not as called is spotted (3, 4, 9). A called shot that drops another ball, or the
    called ball in another pocket, ends the inning and the incoming player chooses to shoot
    or pass it back (7: the "wrongly_pocketed_reply" decision); a shot with no called ball is a
    safety (6): balls that drop stay down and the turn passes. `three_foul_rule` (default
    True): three consecutive fouls lose (11), the warning always given (as `NineBall`)."""

    three_foul_rule: bool = True
    n_pockets: int = 6
    name = "ten_ball"
    object_balls = frozenset(range(1, 11))
    money_ball = TEN

    def new_game(self, breaker: int = 0) -> GameState:
        """A racked game: `breaker` breaks with the cue ball in hand behind the head string (3(a))."""
        return GameState(self, self.object_balls, shooter=breaker, ball_in_hand="behind_head_string")

    def legal_targets(self, state: GameState) -> frozenset:
        """The lowest-numbered ball on the table (the break too: the 1)."""
        return frozenset({min(state.on_table)}) if state.on_table else frozenset()

    def judge(self, state: GameState, outcome, called_pocket=None, called_ball=None, push_out=False):
        """(next GameState, Ruling) after `outcome` from `state`: `called_ball` and
        `called_pocket` the call (ignored on the break and a push out; a ball on the table and
        a pocket index below `n_pockets`; no ball called: a safety); `push_out` (only when
        `state.push_out`). ValueError for a bad call or a push out where none is allowed."""
        check_shot(state, outcome)
        self._check_call(state, called_pocket, called_ball)
        if push_out and not state.push_out:
            raise ValueError("no push out now: only the shot right after a break without a foul (WPA Ten Ball 4)")
        lowest = min(state.on_table)
        targets = frozenset() if push_out else {lowest}
        fouls = standard_fouls(outcome, targets, lambda b: f"hit the {b}, lowest is the {lowest}",
                               state.is_break or push_out)
        if state.is_break:
            illegal = break_requirement(outcome)
            fouls += [illegal] if illegal else []
        fouls = ordered(fouls)
        foul = fouls[0][0] if fouls else None
        called = None if (state.is_break or push_out) else (called_ball, called_pocket)
        return self._rule(state, outcome, fouls, foul, called, push_out)

    def _check_call(self, state, called_pocket, called_ball):
        if called_pocket is not None and (isinstance(called_pocket, bool) or not isinstance(called_pocket, int)
                                          or not 0 <= called_pocket < self.n_pockets):
            raise ValueError(f"called_pocket must be None or a pocket index 0..{self.n_pockets - 1}, "
                             f"got {called_pocket!r}")
        if called_ball is not None and (isinstance(called_ball, bool) or not isinstance(called_ball, int)
                                        or called_ball not in state.on_table):
            raise ValueError(f"called_ball must be None or an object ball on the table {sorted(state.on_table)}, "
                             f"got {called_ball!r}")

    def _rule(self, state, outcome, fouls, foul, called, push_out):
        """The ruling of a judged shot: fouls, the call, the 10 spotted or winning, the turn."""
        player, other = state.shooter, 1 - state.shooter
        messages = [m for _, m in fouls]
        ten_gone = TEN in outcome.pocketed or TEN in outcome.off_table
        on_table = state.on_table - set(outcome.pocketed) - set(outcome.off_table)
        counts = list(state.fouls)
        made = not foul and called is not None and _made(outcome, *called)
        winner = end = pending = None
        if foul:
            counts[player] += 1
            if self.three_foul_rule and counts[player] >= 3:  # Ten Ball 11, 6.14
                winner, end = other, "three_fouls"
                messages.append(f"player {player} loses: three consecutive fouls")
        else:
            counts[player] = 0
        if made and called[0] == TEN:  # Ten Ball 5: the 10 on a legal called shot wins
            winner, end = player, "ten_pocketed"
            messages.append(f"player {player} wins: the 10 pocketed in the called pocket")
        spot = ()
        if ten_gone and winner is None:  # Ten Ball 9: otherwise the 10 is spotted
            spot, on_table = (TEN,), on_table | {TEN}
            messages.append("the 10 is spotted")
        wrongly = not foul and called is not None and called[0] is not None and outcome.pocketed and not made
        if winner is None and not foul:
            if push_out:  # Ten Ball 4: the incoming player shoots or passes it back
                pending = PUSH_OUT_REPLY
                messages.append(f"push out: player {other} shoots from here or passes the shot back")
            elif wrongly:  # Ten Ball 7
                pending = WRONGLY_POCKETED_REPLY
                messages.append(f"not as called: player {other} shoots from here or passes the shot back")
        kept = state.is_break and bool(outcome.pocketed) if not foul else False
        turn_passed = winner is None and not (kept or made)
        hand = "anywhere" if foul and winner is None else None  # Ten Ball 10, 1.5
        ruling = quick_ruling(foul, tuple(n for n, _ in fouls), turn_passed, hand, spot, winner, end)
        may_push = state.is_break and not foul and winner is None  # Ten Ball 4
        new = advance(state, ruling, on_table, counts, pending=pending, push_out=may_push)
        if winner is None:
            messages += turn_messages(new, turn_passed, self.three_foul_rule)
        return new, with_messages(ruling, messages)

    def decide(self, state: GameState, option: str) -> GameState:
        """After a push out (Ten Ball 4) or a ball pocketed not as called (7): "shoot" the
        incoming player plays from the position, "pass" the other player must."""
        check_option(state, option)
        shooter = state.shooter if option == "shoot" else 1 - state.shooter
        return GameState.successor(self, state.on_table, shooter, state.ball_in_hand, state.fouls, state.groups,
                                   state.shot, state.winner)

    def describe(self, state: GameState) -> str:
        """One line: whose shot, the ball on, ball in hand, fouls."""
        if state.winner is not None:
            return f"player {state.winner} won"
        if state.pending is not None:
            return f"player {state.shooter} to decide: shoot or pass"
        return (f"player {state.shooter} to shoot{' the break' if state.is_break else ''}, on the "
                f"{min(state.on_table)}{', ball in hand' if state.ball_in_hand else ''}")


def _made(outcome, ball, pocket) -> bool:
    """The called ball dropped in the called pocket (Ten Ball 5)."""
    if ball is None or pocket is None or ball not in outcome.pocketed:
        return False
    if ball not in outcome.pocket_of:
        raise ValueError(f"the called ball {ball} dropped but outcome.pocket_of does not say in which pocket")
    return outcome.pocket_of[ball] == pocket
