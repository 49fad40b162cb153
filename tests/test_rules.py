"""pool_env.rules against the WPA World Standardized Rules: one hand-built shot per rule and per foul.

Rule numbers are those of the WPA "Rules of Play" (the World Standardized Rules): 1.x general
rules, 2.x nine ball, 3.x eight ball, 6.x fouls (docs/rules.md lists them and every deviation).
Each test states what the rule text decides and asserts that, never the code's own output.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from pool_env import rules as R
from pool_env.physics import BALL_RADIUS, Balls, Event, Table, simulate, strike
from pool_env.physics.simulate import check_on_table
from pool_env.rules import EightBall, GameState, NineBall, ShotOutcome, judge, legal_targets, new_game
from pool_env.rules.racks import JITTER, foot_spot, head_spot

RAIL4 = frozenset({2, 3, 4, 5})


def shot(first=None, pocketed=(), rail=True, cue=False, to_rail=frozenset(), pocket_of=None, off=()):
    """A ShotOutcome; pocket_of defaults to pocket 0 for every ball that dropped."""
    if pocket_of is None:
        pocket_of = {b: 0 for b in pocketed} | ({0: 0} if cue else {})
    return ShotOutcome(first, tuple(pocketed), pocket_of, cue, rail and first is not None, frozenset(to_rail),
                       tuple(off))


def nine(on_table=range(1, 10), shooter=0, fouls=(0, 0), is_break=False, **kw):
    return GameState(NineBall(**kw), frozenset(on_table), shooter, None, fouls, (None, None), is_break, 5)


def eight(on_table=range(1, 16), shooter=0, groups=(None, None), is_break=False, **kw):
    return GameState(EightBall(**kw), frozenset(on_table), shooter, None, (0, 0), groups, is_break, 5)


# --- 9-ball ------------------------------------------------------------------------------

def test_nine_legal_pot_keeps_the_turn():
    # WPA 2.5: a ball legally pocketed lets the shooter continue, from where the cue ball lies.
    state, ruling = judge(nine(), shot(1, (2,)))
    assert ruling.foul is None and not ruling.turn_passed and ruling.ball_in_hand is None
    assert state.shooter == 0 and state.on_table == frozenset({1, 3, 4, 5, 6, 7, 8, 9})


def test_nine_miss_passes_the_turn_without_ball_in_hand():
    # WPA 2.5: no ball pocketed (and no foul): the other player plays the cue ball from where it lies.
    state, ruling = judge(nine(), shot(1, rail=True))
    assert ruling.foul is None and ruling.turn_passed and ruling.ball_in_hand is None
    assert state.shooter == 1 and state.ball_in_hand is None and state.fouls == (0, 0)


def test_nine_wrong_ball_first():
    # WPA 6.2 (with 2.x: the lowest-numbered ball first): hitting the 5 with the 3 on the table
    # is a foul; 2.7 and 1.5: the incoming player has the cue ball in hand anywhere. A ball it
    # pockets stays down (2.6: only the 9 is ever spotted).
    state, ruling = judge(nine(range(3, 10)), shot(5, (4,)))
    assert ruling.foul == "wrong_ball_first" and ruling.turn_passed and ruling.ball_in_hand == "anywhere"
    assert "foul: wrong ball first (hit the 5, lowest is the 3)" in ruling.messages
    assert state.shooter == 1 and state.ball_in_hand == "anywhere" and 4 not in state.on_table
    assert ruling.balls_to_spot == () and state.fouls == (1, 0)


def test_nine_no_rail():
    # WPA 6.3: no ball pocketed and no ball to a rail after the contact: foul, ball in hand.
    state, ruling = judge(nine(), shot(1, rail=False))
    assert ruling.foul == "no_rail" and ruling.fouls == ("no_rail",) and ruling.ball_in_hand == "anywhere"
    assert state.shooter == 1


def test_nine_pocketing_a_ball_satisfies_the_rail_rule():
    # WPA 6.3 applies only "if no ball is pocketed": a pot without any rail is legal.
    _, ruling = judge(nine(), shot(1, (1,), rail=False))
    assert ruling.foul is None and not ruling.turn_passed


def test_nine_scratch():
    # WPA 6.1: the cue ball pocketed is a foul even on a pot; the potted ball stays down (2.6).
    state, ruling = judge(nine(), shot(1, (1,), cue=True))
    assert ruling.foul == "scratch" and ruling.turn_passed and ruling.ball_in_hand == "anywhere"
    assert 1 not in state.on_table and ruling.balls_to_spot == ()


def test_nine_no_contact():
    # WPA 6.2/6.3: the cue ball must contact the lowest ball; touching none is a foul.
    state, ruling = judge(nine(), shot(None))
    assert ruling.foul == "no_contact" and ruling.ball_in_hand == "anywhere" and state.shooter == 1


def test_nine_illegal_break():
    # WPA 2.3(b): no ball pocketed and fewer than four object balls to a rail: a foul, ball in hand anywhere.
    state, ruling = judge(new_game("nine_ball"), shot(1, to_rail={2, 3, 4}))
    assert ruling.foul == "illegal_break" and ruling.turn_passed and ruling.ball_in_hand == "anywhere"
    assert state.shooter == 1 and not state.is_break


def test_nine_legal_break_with_four_balls_to_a_rail():
    # WPA 2.3(b): four object balls to a rail make the break legal even with nothing pocketed;
    # 2.5: nothing pocketed, so the turn passes with no ball in hand.
    state, ruling = judge(new_game("nine_ball"), shot(1, to_rail=RAIL4))
    assert ruling.foul is None and ruling.turn_passed and ruling.ball_in_hand is None


def test_nine_break_must_hit_the_one_first():
    # WPA 6.2 with 2.x: the lowest ball (the 1) first on every shot, the break included.
    _, ruling = judge(new_game("nine_ball"), shot(2, (5,), to_rail=RAIL4))
    assert ruling.foul == "wrong_ball_first" and ruling.ball_in_hand == "anywhere"


def test_new_game_breaks_from_behind_the_head_string():
    # WPA 2.3(a) and 3.3(a): the cue ball begins in hand behind the head string.
    for kind in ("nine_ball", "eight_ball"):
        state = new_game(kind, breaker=1)
        assert state.is_break and state.shooter == 1 and state.ball_in_hand == "behind_head_string"


def test_nine_on_the_break_wins():
    # WPA 2.5: legally pocketing the 9 on any shot (the break is one) wins.
    state, ruling = judge(new_game("nine_ball"), shot(1, (9,)))
    assert ruling.winner == 0 and ruling.end_reason == "nine_pocketed" and state.winner == 0


def test_nine_on_a_combination_wins():
    # WPA 2.5 (and 2.x: the balls need not be pocketed in order): the 3 hit first into the 9.
    state, ruling = judge(nine(range(3, 10)), shot(3, (9,)))
    assert ruling.foul is None and ruling.winner == 0 and state.over


def test_nine_pocketed_on_a_foul_is_spotted():
    # WPA 2.6: the 9 pocketed on a foul is spotted (1.4), the foul stands, no one wins.
    state, ruling = judge(nine(range(3, 10)), shot(5, (9,)))
    assert ruling.foul == "wrong_ball_first" and ruling.winner is None
    assert ruling.balls_to_spot == (9,) and 9 in state.on_table and state.shooter == 1


def test_nine_on_the_break_with_a_scratch_is_spotted():
    # WPA 2.6 and 6.1: a scratch is a foul, so the 9 dropped with it is spotted.
    state, ruling = judge(new_game("nine_ball"), shot(1, (9,), cue=True))
    assert ruling.foul == "scratch" and ruling.winner is None and ruling.balls_to_spot == (9,)
    assert state.ball_in_hand == "anywhere"


def test_nine_driven_off_the_table_is_spotted():
    # WPA 6.5: driving an object ball off the table is a foul; 2.6: the 9 is spotted.
    state, ruling = judge(nine(), shot(1, off=(9,)))
    assert ruling.foul == "ball_off_table" and ruling.balls_to_spot == (9,) and 9 in state.on_table


def test_three_consecutive_fouls_lose():
    # WPA 6.14 and 2.8: three fouls without a legal shot between them lose the rack; the
    # opponent's shots in between do not break the sequence; the warning is given before the third.
    state = nine()
    for _ in range(2):
        state, _ = judge(state, shot(2))  # player 0: wrong ball first
        state, _ = judge(state, shot(1))  # player 1: a legal miss
    assert state.shooter == 0 and state.fouls == (2, 0)
    state, ruling = judge(state, shot(None))  # player 0's third foul
    assert ruling.winner == 1 and ruling.end_reason == "three_fouls" and state.winner == 1


def test_warning_when_on_two_fouls():
    # WPA 6.14: a player on two fouls is warned when he comes to the table.
    state, _ = judge(nine(shooter=1, fouls=(1, 0)), shot(1))  # player 1 misses: player 0 comes to the table
    assert state.fouls == (1, 0)
    state, ruling = judge(nine(fouls=(1, 0)), shot(2))  # player 0 fouls again: player 1 comes
    assert not any("warning" in m for m in ruling.messages)
    state, ruling = judge(nine(shooter=1, fouls=(2, 0)), shot(1))
    assert "warning: player 0 is on two fouls (a third loses the game)" in ruling.messages


def test_a_legal_shot_clears_the_foul_count():
    # WPA 6.14: the fouls must come without an intervening legal shot.
    state, _ = judge(nine(fouls=(2, 0)), shot(1))
    assert state.fouls == (0, 0)


def test_three_foul_rule_can_be_switched_off():
    _, ruling = judge(nine(fouls=(2, 0), three_foul_rule=False), shot(None))
    assert ruling.winner is None and ruling.foul == "no_contact"


def test_nine_legal_targets():
    # WPA 6.2 in 9-ball: the lowest-numbered ball on the table.
    assert legal_targets(nine(range(4, 10))) == {4}
    assert legal_targets(new_game("nine_ball")) == {1}


# --- 8-ball ------------------------------------------------------------------------------

SOLIDS_ON = ("solids", "stripes")


def test_eight_legal_break_pot_continues_on_an_open_table():
    # WPA 3.3(c): the breaker who pockets a ball without a foul continues; the table stays open.
    state, ruling = judge(new_game("eight_ball"), shot(5, (3,)))
    assert ruling.foul is None and not ruling.turn_passed and state.groups == (None, None)


def test_eight_break_needs_no_particular_ball_first():
    # WPA 3.3(b): no ball is called and the cue ball need not hit a particular ball first.
    _, ruling = judge(new_game("eight_ball"), shot(12, to_rail=RAIL4))
    assert ruling.foul is None and ruling.turn_passed and ruling.ball_in_hand is None


def test_eight_illegal_break():
    # WPA 3.3(d): no ball pocketed and fewer than four to a rail is an illegal break; the
    # incoming player takes over. Default (deviation): the table as it lies with ball in hand
    # anywhere; illegal_break="table_in_position" is 3.3(d)(1) to the letter.
    state, ruling = judge(new_game("eight_ball"), shot(1, to_rail={2, 3}))
    assert ruling.foul == "illegal_break" and ruling.turn_passed and state.shooter == 1
    assert ruling.ball_in_hand == "anywhere"
    _, ruling = judge(new_game("eight_ball", illegal_break="table_in_position"), shot(1, to_rail={2, 3}))
    assert ruling.foul == "illegal_break" and ruling.ball_in_hand is None


def test_eight_scratch_on_the_break_gives_ball_in_hand_behind_the_head_string():
    # WPA 3.3 (scratch on the break): a foul, the table open, the incoming player has the cue
    # ball in hand behind the head string; the balls pocketed stay down.
    state, ruling = judge(new_game("eight_ball"), shot(1, (4,), cue=True))
    assert ruling.foul == "scratch" and ruling.turn_passed
    assert ruling.ball_in_hand == "behind_head_string" and state.ball_in_hand == "behind_head_string"
    assert 4 not in state.on_table and state.groups == (None, None)


def test_eight_on_the_break_is_spotted():
    # WPA 3.3(e): the 8 on a legal break is no foul; the breaker may have it re-spotted and
    # play on (our fixed choice of his option).
    state, ruling = judge(new_game("eight_ball"), shot(1, (8,)))
    assert ruling.foul is None and ruling.winner is None and ruling.balls_to_spot == (8,)
    assert 8 in state.on_table and state.shooter == 0 and not ruling.turn_passed


def test_eight_on_the_break_with_a_scratch():
    # WPA 3.3(f): the 8 spotted and the incoming player shoots with ball in hand behind the head string.
    state, ruling = judge(new_game("eight_ball"), shot(1, (8,), cue=True))
    assert ruling.foul == "scratch" and ruling.winner is None and ruling.balls_to_spot == (8,)
    assert state.shooter == 1 and state.ball_in_hand == "behind_head_string"


def test_open_table_group_assignment():
    # WPA 3.4: on an open table any ball but the 8 may be hit first (a solid into a stripe is
    # legal); a legally pocketed ball decides the groups (here the first ball to drop: the
    # called-ball simplification, calling="eight_only") and the shooter continues (3.5).
    state, ruling = judge(eight(calling="eight_only"), shot(2, (11,)))
    assert ruling.foul is None and not ruling.turn_passed
    assert state.groups == ("stripes", "solids") and state.shooter == 0
    assert "player 0 takes stripes (the 11 dropped first), player 1 solids" in ruling.messages
    state, _ = judge(eight(shooter=1, calling="eight_only"), shot(10, (6, 12)))
    assert state.groups == ("stripes", "solids")  # player 1 made the 6 first: solids for player 1


def test_open_table_stays_open_after_a_foul_or_a_miss():
    # WPA 3.4: groups come only from a legally pocketed ball.
    state, ruling = judge(eight(), shot(2, (11,), cue=True))
    assert ruling.foul == "scratch" and state.groups == (None, None)
    state, _ = judge(eight(), shot(2))
    assert state.groups == (None, None) and state.shooter == 1


def test_open_table_eight_first_is_a_foul():
    # WPA 3.4: on an open table the 8 may not be struck first.
    _, ruling = judge(eight(), shot(8, (3,)))
    assert ruling.foul == "wrong_ball_first" and ruling.ball_in_hand == "anywhere"


def test_eight_wrong_group_first():
    # WPA 6.2 (3.x: the shooter's group first): player 0 on solids hits the 12.
    state, ruling = judge(eight(groups=SOLIDS_ON), shot(12, (3,)))
    assert ruling.foul == "wrong_ball_first" and ruling.turn_passed and state.ball_in_hand == "anywhere"
    assert "foul: wrong ball first (hit the 12, player 0 is on solids)" in ruling.messages


def test_eight_no_rail_no_contact_and_scratch():
    # WPA 6.3, 6.2 and 6.1, each a standard foul with ball in hand anywhere (3.7).
    for outcome, name in ((shot(3, rail=False), "no_rail"), (shot(None), "no_contact"),
                          (shot(3, (3,), cue=True), "scratch")):
        state, ruling = judge(eight(groups=SOLIDS_ON), outcome)
        assert ruling.foul == name and ruling.ball_in_hand == "anywhere" and state.shooter == 1


def test_eight_turn_stays_on_own_ball_and_passes_on_opponents_only():
    # WPA 3.5: the shooter continues after pocketing his own ball; an opponent's ball alone
    # (a legal shot: his own group hit first) ends the turn, and it stays down (the 8-only
    # calling; called shots: tests/test_rules_called.py).
    state, ruling = judge(eight(groups=SOLIDS_ON, calling="eight_only"), shot(3, (3, 12)))
    assert not ruling.turn_passed and state.shooter == 0
    state, ruling = judge(eight(groups=SOLIDS_ON, calling="eight_only"), shot(3, (12,)))
    assert ruling.foul is None and ruling.turn_passed and 12 not in state.on_table and state.shooter == 1


def test_eight_legal_targets():
    # WPA 3.3(b), 3.4, 3.x: any ball on the break; any but the 8 open; own group; then the 8.
    assert legal_targets(new_game("eight_ball")) == frozenset(range(1, 16))
    assert legal_targets(eight()) == frozenset(range(1, 16)) - {8}
    assert legal_targets(eight(groups=("stripes", "solids"))) == frozenset(range(9, 16))
    assert legal_targets(eight({8, 9, 10}, groups=SOLIDS_ON)) == {8}


def test_eight_in_the_called_pocket_wins():
    # WPA 3.x (object of the game) and 1.6: the group cleared, the 8 legally in the called pocket.
    state, ruling = judge(eight({8, 12}, groups=SOLIDS_ON), shot(8, (8,), pocket_of={8: 4}), called_pocket=4)
    assert ruling.winner == 0 and ruling.end_reason == "eight_pocketed" and state.winner == 0


def test_eight_early_loses():
    # WPA 3.8: pocketing the 8 when it is not the shooter's legal object ball loses.
    _, ruling = judge(eight({3, 8, 12}, groups=SOLIDS_ON), shot(3, (8,)), called_pocket=0)
    assert ruling.winner == 1 and ruling.end_reason == "eight_early"
    _, ruling = judge(eight(), shot(3, (8,)))  # on an open table too
    assert ruling.winner == 1 and ruling.end_reason == "eight_early"


def test_eight_with_the_last_ball_of_the_group_loses():
    # WPA 3.8: the 8 on the same stroke as the last ball of the shooter's group loses.
    _, ruling = judge(eight({3, 8, 12}, groups=SOLIDS_ON), shot(3, (3, 8), pocket_of={3: 1, 8: 1}), called_pocket=1)
    assert ruling.winner == 1 and ruling.end_reason == "eight_early"


def test_eight_in_the_wrong_pocket_loses():
    # WPA 3.8: the 8 in a pocket other than the called one loses (and uncalled counts as wrong).
    state, ruling = judge(eight({8, 12}, groups=SOLIDS_ON), shot(8, (8,), pocket_of={8: 2}), called_pocket=3)
    assert ruling.winner == 1 and ruling.end_reason == "eight_wrong_pocket" and state.winner == 1
    _, ruling = judge(eight({8, 12}, groups=SOLIDS_ON), shot(8, (8,), pocket_of={8: 2}))
    assert ruling.winner == 1 and ruling.end_reason == "eight_wrong_pocket"


def test_eight_with_a_scratch_loses():
    # WPA 3.8: a foul on the shot that pockets the 8 loses, even in the called pocket.
    _, ruling = judge(eight({8, 12}, groups=SOLIDS_ON), shot(8, (8,), cue=True, pocket_of={8: 2, 0: 5}),
                      called_pocket=2)
    assert ruling.winner == 1 and ruling.end_reason == "eight_with_foul" and ruling.foul == "scratch"


def test_eight_off_the_table_loses():
    # WPA 3.8: driving the 8 off the table (after the break) loses.
    _, ruling = judge(eight({8, 12}, groups=SOLIDS_ON), shot(8, off=(8,)), called_pocket=2)
    assert ruling.winner == 1 and ruling.end_reason == "eight_off_table"


def test_scratch_on_the_eight_without_pocketing_it_is_only_a_foul():
    # WPA 3.7/3.8: a foul while on the 8 loses only if the 8 drops (or leaves the table).
    state, ruling = judge(eight({8, 12}, groups=SOLIDS_ON), shot(8, cue=True), called_pocket=2)
    assert ruling.winner is None and ruling.foul == "scratch" and state.ball_in_hand == "anywhere"


def test_eight_ball_has_no_three_foul_rule():
    # WPA 6.14: some games, eight ball among them, do not use the three-foul rule.
    state = eight(groups=SOLIDS_ON)
    for _ in range(3):
        state, ruling = judge(state, shot(12))  # player 0 (solids) hits a stripe
        state, _ = judge(state, shot(3))  # player 1 (stripes) hits a solid
    assert state.winner is None and state.fouls == (3, 3)


# --- bad input -----------------------------------------------------------------------------

def test_judging_a_finished_game_raises():
    state, _ = judge(new_game("nine_ball"), shot(1, (9,)))
    with pytest.raises(ValueError, match="game is over"):
        judge(state, shot(1))


@pytest.mark.parametrize("pocket", [6, -1, True, 1.0, "3"])
def test_called_pocket_out_of_range_raises(pocket):
    with pytest.raises(ValueError, match="called_pocket"):
        judge(eight({8, 12}, groups=SOLIDS_ON), shot(8), called_pocket=pocket)


def test_bad_inputs_raise():
    with pytest.raises(ValueError, match="not on the table"):
        judge(nine(range(3, 10)), shot(1))
    with pytest.raises(ValueError, match="unknown game"):
        new_game("straight_pool")
    with pytest.raises(ValueError, match="breaker"):
        new_game("nine_ball", breaker=2)
    with pytest.raises(ValueError, match="illegal_break"):
        new_game("eight_ball", illegal_break="rerack")
    with pytest.raises(TypeError):
        judge("state", shot(1))
    with pytest.raises(ValueError, match="cue ball"):
        ShotOutcome(first_contact=0)
    with pytest.raises(ValueError, match="dropped twice"):
        ShotOutcome(pocketed=(3, 3))
    with pytest.raises(ValueError, match="pocket_of"):
        ShotOutcome(pocketed=(3,), pocket_of={4: 1})
    with pytest.raises(ValueError, match="groups"):
        GameState(EightBall(), frozenset(range(1, 16)), groups=("solids", "solids"))
    with pytest.raises(ValueError, match="no winner"):
        GameState(NineBall(), frozenset(range(1, 9)))
    with pytest.raises(ValueError, match="pocket_of"):
        judge(eight({8, 12}, groups=SOLIDS_ON), ShotOutcome(8, (8,)), called_pocket=1)


# --- outcome_from_result on real shots ------------------------------------------------------

TABLE = Table.eight_foot()
L, W = TABLE.length, TABLE.width
DIAG = np.array([1.0, 1.0]) / math.sqrt(2.0)


def test_outcome_of_a_pot_into_the_corner():
    # The 1 sits 0.3 m from the far corner on the diagonal, the cue ball 0.4 m behind it on the
    # same line: a straight shot sends the 1 into pocket 3 (the corner at (L, W)), no rail.
    p1 = np.array([L - 0.3, W - 0.3])
    balls = Balls([p1 - 0.4 * DIAG, p1])
    out = R.outcome_from_result(simulate(strike(balls, 60 * DIAG), TABLE))
    assert out.first_contact == 1 and out.pocketed == (1,) and out.pocket_of == {1: 3}
    assert not out.cue_pocketed and not out.rail_after_contact and out.object_balls_to_rail == frozenset()
    # With strong follow the cue ball runs after it into the same pocket: a scratch.
    out = R.outcome_from_result(simulate(strike(balls, 60 * DIAG, (0.0, 0.4)), TABLE))
    assert out.pocketed == (1,) and out.cue_pocketed and out.pocket_of == {1: 3, 0: 3}


def test_outcome_of_a_shot_to_the_foot_rail():
    # Cue ball and the 1 on the long string, struck along +x: the 1 goes to the foot rail.
    balls = Balls([(0.5, W / 2), (1.0, W / 2)])
    out = R.outcome_from_result(simulate(strike(balls, (40.0, 0.0)), TABLE))
    assert out.first_contact == 1 and out.pocketed == () and out.rail_after_contact
    assert out.object_balls_to_rail == frozenset({1})


def test_outcome_of_a_miss():
    # The cue ball sent across the table, away from the only object ball: no contact.
    balls = Balls([(0.5, W / 2), (1.5, 0.2)])
    out = R.outcome_from_result(simulate(strike(balls, (0.0, 30.0)), TABLE))
    assert out.first_contact is None and not out.rail_after_contact and out.pocketed == ()


def test_outcome_counts_facings_and_jaw_tips_as_cushions_and_needs_contact_first():
    # Cushion ids past the rail noses (facings, then jaw tips) are cushions too; a cushion
    # touched before the first contact does not count as a rail after contact.
    jaw = len(TABLE.rails) + 1
    events = [Event(0.1, "ball_cushion", 0, 2), Event(0.2, "sliding_rolling", 0, -1),
              Event(0.3, "ball_ball", 3, 0), Event(0.4, "ball_cushion", 3, jaw)]
    out = R.outcome_from_result(SimpleNamespace(events=events))
    assert out.first_contact == 3 and out.rail_after_contact and out.object_balls_to_rail == {3}
    out = R.outcome_from_result(SimpleNamespace(events=events[:3]))
    assert out.first_contact == 3 and not out.rail_after_contact


# --- racks ---------------------------------------------------------------------------------

def _no_overlap(balls):
    on = np.flatnonzero(~balls.pocketed)
    p = balls.xy[on]
    d = np.hypot(*(p[:, None, :] - p[None, :, :]).transpose(2, 0, 1))
    np.fill_diagonal(d, np.inf)
    return d.min() >= 2 * BALL_RADIUS


def test_nine_ball_rack():
    # WPA 2.2: a diamond, the 1 at the apex on the foot spot, the 9 in the middle.
    for seed in range(5):
        balls = R.nine_ball_rack(TABLE, seed)
        assert len(balls) == 10 and not balls.pocketed.any() and _no_overlap(balls)
        check_on_table(balls, TABLE)
        assert np.hypot(*(balls.xy[1] - foot_spot(TABLE))) <= JITTER + 1e-12
        assert np.hypot(*(balls.xy[9] - balls.xy[1:].mean(axis=0))) < 3 * JITTER  # the centre of the diamond
        assert np.allclose(balls.xy[0], head_spot(TABLE))
    assert np.array_equal(R.nine_ball_rack(TABLE, 3).xy, R.nine_ball_rack(TABLE, 3).xy)
    assert not np.array_equal(R.nine_ball_rack(TABLE, 3).xy, R.nine_ball_rack(TABLE, 4).xy)
    padded = R.nine_ball_rack(TABLE, 3, n_balls=16)
    assert padded.pocketed.tolist() == [False] * 10 + [True] * 6


def test_eight_ball_rack():
    # WPA 3.2: a triangle, the apex on the foot spot, the 8 in the centre (third row, middle),
    # a solid and a stripe in the two back corners.
    s = 2 * BALL_RADIUS + 2 * JITTER
    for seed in range(5):
        balls = R.eight_ball_rack(TABLE, seed)
        assert len(balls) == 16 and not balls.pocketed.any() and _no_overlap(balls)
        check_on_table(balls, TABLE)
        fx, fy = foot_spot(TABLE)
        assert np.hypot(balls.xy[8, 0] - (fx + math.sqrt(3) * s), balls.xy[8, 1] - fy) <= JITTER + 1e-12
        back = [b for b in range(1, 16) if balls.xy[b, 0] > fx + 3.9 * s * math.sqrt(3) / 2]
        corners = sorted(back, key=lambda b: balls.xy[b, 1])
        assert len(corners) == 5
        assert {corners[0] < 8, corners[-1] < 8} == {True, False}  # one solid, one stripe
    assert np.array_equal(R.eight_ball_rack(TABLE, 7).xy, R.eight_ball_rack(TABLE, 7).xy)
    assert not np.array_equal(R.eight_ball_rack(TABLE, 7).xy, R.eight_ball_rack(TABLE, 8).xy)


def test_spot_balls_on_the_long_string():
    # WPA 1.4: on the foot spot if free, else on the long string behind it as close as
    # possible; several balls in numerical order, the lowest nearest the foot spot.
    fx, fy = foot_spot(TABLE)
    xy = [(0.5, fy), (fx, fy), (1.0, 0.2), (0.2, 0.2)]
    balls = Balls(xy, pocketed=[False, False, True, True])
    spotted = R.spot_balls(balls, TABLE, [3, 2])
    assert not spotted.pocketed.any() and _no_overlap(spotted)
    check_on_table(spotted, TABLE)
    assert spotted.xy[2, 1] == fy and spotted.xy[3, 1] == fy
    assert fx < spotted.xy[2, 0] < spotted.xy[3, 0]
    assert spotted.xy[2, 0] - fx == pytest.approx(2 * BALL_RADIUS, abs=1e-5)  # touching the ball on the spot
    free = R.spot_balls(Balls(xy, pocketed=[False, True, False, False]), TABLE, [1])
    assert tuple(free.xy[1]) == (fx, fy)
    with pytest.raises(ValueError, match="cannot be spotted"):
        R.spot_balls(balls, TABLE, [1])


def test_head_string():
    # The head string is a quarter of the length from the head rail.
    assert R.head_string_x(TABLE) == pytest.approx(L / 4)
