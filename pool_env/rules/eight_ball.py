"""`EightBall`: 8-ball by the WPA World Standardized Rules (section 3, with the general rules 1.x and fouls 6.x)."""

from __future__ import annotations

from dataclasses import dataclass

from .state import (
    DECISIONS,
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

EIGHT = 8
SOLIDS = frozenset(range(1, 8))
STRIPES = frozenset(range(9, 16))
GROUP_BALLS = {"solids": SOLIDS, "stripes": STRIPES}
ILLEGAL_BREAK_OPTIONS = ("ball_in_hand", "table_in_position")
# What the shooter calls on a shot after the break: a ball and a pocket (WPA 1.6, 3.4-3.5), or
# only the 8's pocket (the common simplification: every other ball counts wherever it drops).
CALLING_OPTIONS = ("ball_and_pocket", "eight_only")


def group_of(ball: int) -> str | None:
    """"solids" (1-7), "stripes" (9-15) or None (the 8)."""
    return "solids" if ball in SOLIDS else "stripes" if ball in STRIPES else None


@dataclass(frozen=True)
class EightBall:
    """8-ball (WPA rules, section 3): solids 1-7 against stripes 9-15, then the 8 in a called pocket.

    `n_pockets` (default 6): how many pockets a called pocket may name (0 to n_pockets - 1,
    `Table.pockets` order). After an illegal break the incoming player decides (WPA 3.3(d),
    `decide`): "accept_table" (3.3(d)(1): the cue ball where it stopped), "rerack_and_break",
    "rerack_opponent_breaks" (3.3(d)(2)), or "ball_in_hand" (the table as it lies with the cue
    ball in hand anywhere); `illegal_break` names the default a player who does not decide
    gets: "ball_in_hand" (default, so a soft break never pays) or "table_in_position"
    ("accept_table"). After the 8 drops on the break the breaker (after a foul, the incoming
    player) decides (3.3(e)-(f)): "spot_eight" (the default) or "rebreak" (he breaks again).
    `calling`: "ball_and_pocket" (default; WPA 1.6 and 3.4-3.5): every shot after the break
    calls a ball and a pocket (`called_ball`, `called_pocket`), the shooter stays at the table
    only when the called ball drops in the called pocket on a legal shot, and on an open table
    that ball decides the groups (other balls that drop stay down and count for nothing); or
    "eight_only" (the common simplification): only the 8 is called, every other ball counts
    wherever it drops, and on an open table the first ball to drop on a legal shot decides
    the groups.
    See docs/rules.md for every deviation."""

    n_pockets: int = 6
    illegal_break: str = "ball_in_hand"
    calling: str = "ball_and_pocket"
    name = "eight_ball"
    object_balls = frozenset(range(1, 16))
    money_ball = EIGHT

    def __post_init__(self):
        if isinstance(self.n_pockets, bool) or not isinstance(self.n_pockets, int) or self.n_pockets < 1:
            raise ValueError(f"n_pockets must be an integer >= 1, got {self.n_pockets!r}")
        if self.illegal_break not in ILLEGAL_BREAK_OPTIONS:
            raise ValueError(f"illegal_break must be one of {ILLEGAL_BREAK_OPTIONS}, got {self.illegal_break!r}")
        if self.calling not in CALLING_OPTIONS:
            raise ValueError(f"calling must be one of {CALLING_OPTIONS}, got {self.calling!r}")

    def new_game(self, breaker: int = 0) -> GameState:
        """A racked game: `breaker` (0 or 1) breaks with the cue ball in hand behind the head
        string (WPA 3.3(a)); the table is open."""
        return GameState(self, self.object_balls, shooter=breaker, ball_in_hand="behind_head_string")

    def legal_targets(self, state: GameState) -> frozenset:
        """The balls the shooter may hit first: any on the break (WPA 3.3(b)); any but the 8 on
        an open table (3.4); his own group, or the 8 once his group is off the table."""
        if state.is_break:
            return state.on_table
        group = state.groups[state.shooter]
        balls = state.on_table - {EIGHT} if group is None else state.on_table & GROUP_BALLS[group]
        return balls or state.on_table & {EIGHT}

    def judge(self, state: GameState, outcome, called_pocket=None, called_ball=None):
        """(next GameState, Ruling) after `outcome` played from `state`. `called_pocket` is the
        pocket the shooter names (WPA 1.6, 3.8): an index below `n_pockets`, or None;
        `called_ball` the ball he names (read with `calling="ball_and_pocket"`; None at the 8
        means the 8): an object ball on the table, or None (no call: nothing he pockets keeps
        him at the table). The break calls nothing (3.3). ValueError for a pocket or a ball that is
        not there."""
        check_shot(state, outcome)
        if called_pocket is not None and (isinstance(called_pocket, bool) or not isinstance(called_pocket, int)
                                          or not 0 <= called_pocket < self.n_pockets):
            raise ValueError(f"called_pocket must be None or a pocket index 0..{self.n_pockets - 1}, "
                             f"got {called_pocket!r}")
        if called_ball is not None and (isinstance(called_ball, bool) or not isinstance(called_ball, int)
                                        or called_ball not in state.on_table):
            raise ValueError(f"called_ball must be None or an object ball on the table {sorted(state.on_table)}, "
                             f"got {called_ball!r}")
        if state.is_break:
            return self._judge_break(state, outcome)
        return self._judge_shot(state, outcome, called_pocket, called_ball)

    def _judge_break(self, state, outcome):
        """The break (WPA 3.3): an object ball pocketed or four to a rail; no ball need be hit
        first; the 8 that drops (or leaves the table) is spotted; a scratch gives the incoming
        player the cue ball in hand behind the head string; the table stays open."""
        fouls = standard_fouls(outcome, frozenset(), None, True)
        illegal = break_requirement(outcome)
        fouls = ordered(fouls + ([illegal] if illegal else []))
        names = tuple(n for n, _ in fouls)
        player = state.shooter
        messages = [m for _, m in fouls]
        on_table = state.on_table - set(outcome.pocketed) - set(outcome.off_table)
        spot = ()
        eight_gone = EIGHT in outcome.pocketed or EIGHT in outcome.off_table
        if eight_gone:  # 3.3(e)-(f), 3.6: spotted (the default), or a re-break (decide)
            spot, on_table = (EIGHT,), on_table | {EIGHT}
            messages.append("the 8 is spotted")
        counts = list(state.fouls)
        counts[player] = counts[player] + 1 if fouls else 0
        hand = None
        if outcome.scratch or "ball_off_table" in names:  # 3.3(f)-(g)
            hand = "behind_head_string"
        elif illegal and self.illegal_break == "ball_in_hand":
            hand = "anywhere"
        turn_passed = bool(fouls) or not outcome.pocketed  # 3.3(c): a legal break that pockets continues
        ruling = quick_ruling(names[0] if names else None, names, turn_passed, hand, spot, None, None)
        pending = None
        if illegal:  # 3.3(d): the incoming player's choice
            default = "ball_in_hand" if self.illegal_break == "ball_in_hand" else "accept_table"
            pending = Decision("illegal_break", DECISIONS["illegal_break"], default)
        elif eight_gone:  # 3.3(e): the breaker's choice; 3.3(f): after a foul, the incoming player's
            pending = Decision("eight_on_break", DECISIONS["eight_on_break"], "spot_eight")
        new = advance(state, ruling, on_table, counts, pending=pending)
        messages += turn_messages(new, turn_passed, False)
        if pending is not None:
            messages.append(f"player {new.shooter} decides: {' or '.join(pending.options)}")
        return new, with_messages(ruling, messages)

    def decide(self, state: GameState, option: str) -> GameState:
        """The state after the shooter's `option` of the pending decision: after an illegal
        break (WPA 3.3(d)) "accept_table" (the cue ball where it lies), "ball_in_hand"
        (anywhere), "rerack_and_break" (he breaks a new rack), "rerack_opponent_breaks"; after
        the 8 on the break (3.3(e)-(f)) "spot_eight" (the 8 stays spotted) or "rebreak" (he
        breaks a new rack). A cue ball in hand behind the head string (a scratch) stays so."""
        check_option(state, option)
        if option in ("rerack_and_break", "rerack_opponent_breaks", "rebreak"):
            breaker = 1 - state.shooter if option == "rerack_opponent_breaks" else state.shooter
            return GameState(self, self.object_balls, shooter=breaker, ball_in_hand="behind_head_string",
                             shot=state.shot)
        hand = state.ball_in_hand
        if hand != "behind_head_string" and state.pending.name == "illegal_break":
            hand = "anywhere" if option == "ball_in_hand" else None
        return GameState.successor(self, state.on_table, state.shooter, hand, state.fouls, state.groups,
                                   state.shot, None)

    def _judge_shot(self, state, outcome, called_pocket, called_ball=None):
        """Any shot after the break: WPA 3.4 (open table, groups), 3.5 (continuing play), 3.7
        (standard fouls: ball in hand anywhere), 3.8 (losing the rack with the 8)."""
        player, other = state.shooter, 1 - state.shooter
        targets = self.legal_targets(state)
        group = state.groups[player]
        fouls = ordered(standard_fouls(outcome, targets, lambda b: _wrong_ball(b, player, group, targets), False))
        names, messages = (tuple(n for n, _ in fouls), [m for _, m in fouls]) if fouls else ((), [])
        on_table = state.on_table - set(outcome.pocketed) - set(outcome.off_table)
        winner = end = None
        if EIGHT in outcome.pocketed or EIGHT in outcome.off_table:
            end, line = _eight_down(outcome, called_pocket, EIGHT in targets, bool(fouls))
            winner = player if end == "eight_pocketed" else other
            messages.append(f"player {player} {'wins' if winner == player else 'loses'}: {line}")
        counts, groups = list(state.fouls), state.groups
        counts[player] = counts[player] + 1 if fouls else 0
        called = self.calling == "ball_and_pocket"
        scored = called and not fouls and _called_down(outcome, called_ball, called_pocket, targets)
        if winner is None and not fouls and group is None:
            dropped = ((called_ball,) if scored else ()) if called else outcome.pocketed
            groups, line = _assign_groups(player, dropped)
            messages += [line] if line else []
        own = GROUP_BALLS[groups[player]] if groups[player] else frozenset()
        kept = scored if called else any(b in own for b in outcome.pocketed)
        if called and not fouls and not kept and winner is None and outcome.pocketed:
            messages.append("no called ball in its called pocket: the balls that dropped stay down")
        turn_passed = winner is None and (bool(fouls) or not kept)
        hand = "anywhere" if fouls and winner is None else None
        ruling = quick_ruling(names[0] if names else None, names, turn_passed, hand, (), winner, end)
        new = advance(state, ruling, on_table, counts, groups)
        if winner is None:
            messages += turn_messages(new, turn_passed, False)
        return new, with_messages(ruling, messages)

    def describe(self, state: GameState) -> str:
        """One line: whose shot, the group, ball in hand."""
        if state.winner is not None:
            return f"player {state.winner} won"
        group = state.groups[state.shooter]
        on = "the break" if state.is_break else "open table" if group is None else (
            "on the 8" if self.legal_targets(state) == {EIGHT} else f"on {group}")
        return f"player {state.shooter} to shoot, {on}{', ball in hand' if state.ball_in_hand else ''}"


def _eight_down(outcome, called_pocket, on_eight, fouled):
    """(end reason, words) when the 8 drops or leaves the table after the break (WPA 3.8)."""
    if EIGHT in outcome.off_table:
        return "eight_off_table", "the 8 left the table"
    if not on_eight:
        return "eight_early", "the 8 pocketed before his group was cleared"
    if fouled:
        return "eight_with_foul", "the 8 pocketed on a foul"
    if called_pocket is None:
        return "eight_wrong_pocket", "the 8 pocketed with no pocket called"
    if EIGHT not in outcome.pocket_of:
        raise ValueError("the 8 dropped but outcome.pocket_of does not say in which pocket; it is needed "
                         "to check the called pocket")
    pocket = outcome.pocket_of[EIGHT]
    if pocket != called_pocket:
        return "eight_wrong_pocket", f"the 8 pocketed in pocket {pocket}, pocket {called_pocket} was called"
    return "eight_pocketed", f"the 8 pocketed in the called pocket {pocket}"


def _called_down(outcome, ball, pocket, targets):
    """The called ball (a legal target; the 8 when it is the only one and none is named)
    dropped in the called pocket (WPA 1.6: the called shot made)."""
    if ball is None and targets == {EIGHT}:
        ball = EIGHT
    if ball is None or pocket is None or ball not in targets or ball not in outcome.pocketed:
        return False
    if ball not in outcome.pocket_of:
        raise ValueError(f"the called ball {ball} dropped but outcome.pocket_of does not say in which pocket; "
                         "it is needed to check the called pocket")
    return outcome.pocket_of[ball] == pocket


def _assign_groups(player, pocketed):
    """Groups after a legal shot on an open table: the group of the first object ball (not
    the 8) to drop goes to the shooter (WPA 3.4, with "the first to drop" for "the called
    ball"); ((None, None), None) if none dropped."""
    first = next((b for b in pocketed if b != EIGHT), None)
    if first is None:
        return (None, None), None
    mine = group_of(first)
    theirs = "stripes" if mine == "solids" else "solids"
    groups = (mine, theirs) if player == 0 else (theirs, mine)
    return groups, f"player {player} takes {mine} (the {first} dropped first), player {1 - player} {theirs}"


def _wrong_ball(ball, player, group, targets):
    """The wrong-ball-first message's tail."""
    if group is None:
        return f"hit the {ball} on an open table: any ball but the 8 first"
    if targets == {EIGHT}:
        return f"hit the {ball}, player {player} is on the 8"
    return f"hit the {ball}, player {player} is on {group}"
