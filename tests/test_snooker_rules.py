"""pool_env.rules.snooker against the WPBSA Official Rules of Snooker, Section 3 (The Game).

Rule numbers: S3 R1 (values), R3 (mode of play: the ball on, the end of the frame, the tie),
R4 (in-hand), R6 (spotting colours), R10 (snookered after a foul: the free ball), R11-12 (fouls
and penalties). Each expectation comes from the rule's text; docs/rules.md lists the deviations.
"""

from __future__ import annotations

import numpy as np
import pytest

from pool_env import rules as R
from pool_env.physics import Table
from pool_env.rules import ShotOutcome, Snooker, SnookerState, judge, legal_targets, new_game
from pool_env.rules.snooker_free_ball import is_snookered
from pool_env.rules.snooker_spots import COLOURS, REDS, colour_spots, snooker_rack, value

ALL = frozenset(range(1, 22))
TABLE = Table.snooker()


def shot(first=None, pocketed=(), cue=False, off=()):
    pocket_of = {b: 0 for b in pocketed} | ({0: 1} if cue else {})
    return ShotOutcome(first, tuple(pocketed), pocket_of, cue, first is not None, frozenset(), tuple(off))


def frame(on_table=ALL, ball_on="red", shooter=0, scores=(0, 0), free_ball=False, **kw):
    return SnookerState(Snooker(), frozenset(on_table), shooter, scores, ball_on, None, free_ball, False, **kw)


def test_values_rule_1():
    assert [value(b) for b in (1, 15, 16, 17, 18, 19, 20, 21)] == [1, 1, 2, 3, 4, 5, 6, 7]


def test_new_frame_rule_3_and_4():
    s = new_game("snooker", breaker=1)
    assert s.on_table == ALL and s.shooter == 1 and s.ball_on == "red" and s.ball_in_hand == "in_d"
    assert legal_targets(s) == REDS  # the first stroke of a turn is on a red


def test_red_then_colour_then_red_rule_3():
    s, r = judge(frame(), shot(5, (5,)))
    assert r.foul is None and not r.turn_passed and s.scores == (1, 0) and s.ball_on == "colour"
    assert legal_targets(s) == frozenset(COLOURS)  # any colour may be nominated
    s, r = judge(s, shot(20, (20,)))  # the pink: 6, re-spotted while reds remain (R6)
    assert s.scores == (7, 0) and r.balls_to_spot == (20,) and 20 in s.on_table and s.ball_on == "red"
    assert s.visit == 7  # the break so far


def test_several_reds_in_one_stroke_score_each_rule_3():
    s, r = judge(frame(), shot(3, (3, 7, 9)))
    assert r.foul is None and s.scores == (3, 0) and s.ball_on == "colour"


def test_missing_everything_passes_the_turn():
    s, r = judge(frame(), shot(4, ()))
    assert r.foul is None and r.turn_passed and s.shooter == 1 and s.ball_on == "red"


def test_fouls_minimum_four_rule_12():
    # Red on: hitting the yellow first is worth 4 (the minimum), the black first 7.
    assert judge(frame(), shot(16))[1].penalty == 4
    assert judge(frame(), shot(21))[1].penalty == 7
    s, r = judge(frame(), shot(None))
    assert r.foul == "no_contact" and r.penalty == 4 and s.scores == (0, 4) and s.shooter == 1
    s, r = judge(frame(), shot(5, (5,), cue=True))  # in-off: the red is not scored
    assert r.foul == "scratch" and s.scores == (0, 4) and s.ball_in_hand == "in_d" and 5 not in s.on_table


def test_potting_a_ball_not_on_rule_12():
    # Red on, a red hit and the pink potted: the pink's value, the pink re-spotted, the reds stay off.
    s, r = judge(frame(), shot(2, (2, 20)))
    assert r.foul == "wrong_ball_potted" and r.penalty == 6 and s.scores == (0, 6)
    assert r.balls_to_spot == (20,) and 2 not in s.on_table and 20 in s.on_table
    # Colour on (the blue nominated by hitting it first), a red potted too: foul, at the blue's 5.
    s, r = judge(frame(ball_on="colour"), shot(19, (19, 4)))
    assert r.foul == "wrong_ball_potted" and r.penalty == 5 and s.scores == (0, 5)
    # Colour on, a red hit first: foul.
    s, r = judge(frame(ball_on="colour"), shot(3))
    assert r.foul == "wrong_ball_first" and r.penalty == 4


def test_ball_forced_off_the_table_rule_12():
    s, r = judge(frame(), shot(7, off=(21,)))
    assert r.foul == "ball_off_table" and r.penalty == 7 and r.balls_to_spot == (21,)


def test_colours_in_ascending_order_after_the_reds_rule_3():
    on = frozenset(COLOURS)
    s = frame(on, ball_on=16)
    assert legal_targets(s) == {16}
    s, r = judge(s, shot(16, (16,)))
    assert r.foul is None and s.scores == (2, 0) and 16 not in s.on_table and s.ball_on == 17 and not r.balls_to_spot
    s2, r2 = judge(s, shot(18, ()))  # the brown hit while the green is on
    assert r2.foul == "wrong_ball_first" and r2.penalty == 4 and s2.scores == (2, 4)
    s3, r3 = judge(s, shot(17, (17, 21)))  # the green and the black: foul, 7, both re-spotted? green too
    assert r3.foul == "wrong_ball_potted" and r3.penalty == 7 and set(r3.balls_to_spot) == {17, 21}


def test_last_red_then_the_colour_is_re_spotted_then_yellow_rule_3():
    on = frozenset({9}) | frozenset(COLOURS)
    s, _ = judge(frame(on), shot(9, (9,)))
    assert s.reds == 0 and s.ball_on == "colour"
    s, r = judge(s, shot(21, (21,)))
    assert s.scores == (8, 0) and r.balls_to_spot == (21,) and s.ball_on == 16


def test_last_red_potted_in_a_foul_leaves_the_yellow_on():
    on = frozenset({9}) | frozenset(COLOURS)
    s, r = judge(frame(on), shot(9, (9,), cue=True))
    assert r.foul == "scratch" and s.reds == 0 and s.ball_on == 16 and s.shooter == 1


def test_frame_ends_on_the_last_black_rule_3():
    s, r = judge(frame({21}, ball_on=21, scores=(40, 30)), shot(21, (21,)))
    assert s.winner == 0 and s.scores == (47, 30) and r.end_reason == "black_potted"
    # A foul on the last black ends the frame too: 7 to the opponent.
    s, r = judge(frame({21}, ball_on=21, scores=(40, 30)), shot(21, (), cue=True))
    assert s.winner == 0 and s.scores == (40, 37) and r.end_reason == "black_fouled"
    s, r = judge(frame({21}, ball_on=21, scores=(30, 35)), shot(None))
    assert s.winner == 1 and s.scores == (30, 42)


def test_tie_re_spots_the_black_rule_3():
    s, r = judge(frame({21}, ball_on=21, scores=(33, 40), breaker=1), shot(21, (21,)))
    assert s.winner is None and s.scores == (40, 40) and s.respotted_black and r.respot_black
    assert s.ball_in_hand == "in_d" and 21 in s.on_table and s.shooter == 1  # the breaker plays it (deviation)
    # Then the first score or foul ends the frame.
    s2, r2 = judge(s, shot(21, ()))
    assert s2.winner is None and s2.shooter == 0  # a miss: the turn passes
    s3, r3 = judge(s2, shot(None))
    assert s3.winner == 1 and s3.scores == (40, 47)


def test_free_ball_rule_10():
    # Red on with a free ball: the nominated colour counts as a red, 1 point, and is re-spotted.
    s, r = judge(frame(free_ball=True), shot(19, (19,)))
    assert r.foul is None and s.scores == (1, 0) and r.balls_to_spot == (19,) and s.ball_on == "colour"
    assert not s.free_ball
    # Free ball and a red potted together: each scores (the ball on was a red).
    s, r = judge(frame(free_ball=True), shot(19, (19, 4)))
    assert r.foul is None and s.scores == (2, 0) and 4 not in s.on_table
    # Colours on (the green), the free ball is the pink: potting it scores the green's 3, the pink
    # goes back, the green is still on.
    on = frozenset(range(17, 22))
    s, r = judge(frame(on, ball_on=17, free_ball=True), shot(20, (20,)))
    assert r.foul is None and s.scores == (3, 0) and r.balls_to_spot == (20,) and s.ball_on == 17
    # Free ball and the ball on both potted: only the ball on scores, it stays off.
    s, r = judge(frame(on, ball_on=17, free_ball=True), shot(20, (20, 17)))
    assert r.foul is None and s.scores == (3, 0) and r.balls_to_spot == (20,) and s.ball_on == 18
    # Potting a ball that is neither: a foul.
    s, r = judge(frame(on, ball_on=17, free_ball=True), shot(20, (21,)))
    assert r.foul == "wrong_ball_potted" and r.penalty == 7


def test_snookered_geometry_section_2():
    # The cue ball behind the blue, the only red straight beyond it: snookered on the red.
    xy = np.array(snooker_rack(TABLE, seed=0).xy)
    pocketed = np.zeros(22, bool)
    pocketed[2:16] = True
    cls = snooker_rack(TABLE, seed=0).__class__
    blue = colour_spots(TABLE)[19]
    xy[0] = (blue[0] - 0.3, blue[1])
    xy[1] = (blue[0] + 0.3, blue[1])
    balls = cls(xy, radius=0.02625, mass=0.142, pocketed=pocketed)
    assert is_snookered(balls, frozenset({1}), TABLE, in_hand=False)
    # Moved 0.1 m across: both edges of the red are clear.
    xy[0] = (blue[0] - 0.3, blue[1] + 0.1)
    xy[1] = (blue[0] + 0.3, blue[1] + 0.1)
    balls = cls(xy, radius=0.02625, mass=0.142, pocketed=pocketed)
    assert not is_snookered(balls, frozenset({1}), TABLE, in_hand=False)
    # Half covered (one edge blocked) is still snookered (wholly or partially obstructed).
    xy[0] = (blue[0] - 0.3, blue[1] + 0.03)
    xy[1] = (blue[0] + 0.3, blue[1] + 0.03)
    balls = cls(xy, radius=0.02625, mass=0.142, pocketed=pocketed)
    assert is_snookered(balls, frozenset({1}), TABLE, in_hand=False)


def test_foul_leaving_a_snooker_gives_a_free_ball():
    # Judge then settle: after the foul the incoming player is snookered on every red.
    rack = snooker_rack(TABLE, seed=0)
    xy = rack.xy.copy()
    pocketed = np.zeros(22, bool)
    pocketed[2:16] = True
    blue = colour_spots(TABLE)[19]
    xy[0], xy[1] = (blue[0] - 0.3, blue[1]), (blue[0] + 0.3, blue[1])
    balls = rack.__class__(xy, radius=0.02625, mass=0.142, pocketed=pocketed)
    state = frame(frozenset({1}) | frozenset(COLOURS))
    new, ruling = judge(state, shot(19))  # hit the blue first: foul
    balls2, settled = R.settle(new, ruling, balls, TABLE)
    assert settled.free_ball and settled.shooter == 1 and legal_targets(settled) == settled.on_table
    new, ruling = judge(state, shot(1))  # a fair miss: no free ball
    assert not R.settle(new, ruling, balls, TABLE)[1].free_ball


def test_bad_states_and_shots():
    with pytest.raises(ValueError, match="not on the table"):
        judge(frame({21}, ball_on=21), shot(5))
    with pytest.raises(ValueError, match="lowest colour"):
        frame(frozenset(COLOURS), ball_on=18)
    with pytest.raises(ValueError, match="no red"):
        frame(frozenset(COLOURS), ball_on="red")
    with pytest.raises(ValueError, match="frame is over"):
        judge(frame(frozenset(), ball_on=21, winner=0), shot(None))
