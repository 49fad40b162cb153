"""pool_env.rules.TenBall against the WPA Ten Ball rules (section numbers of the WPA's Ten Ball rules:
2 rack, 3 legal break, 4 push out, 5 call shots, 6 safety, 7 wrongly pocketed balls, 9 spotting, 10-11 fouls)."""

from __future__ import annotations

import numpy as np
import pytest

from pool_env.physics import Table
from pool_env.physics.simulate import check_on_table
from pool_env.rules import ShotOutcome, decide, judge, new_game, ten_ball_rack
from pool_env.rules.racks import foot_spot

RAIL4 = frozenset({2, 3, 4, 5})


def shot(first=None, pocketed=(), rail=True, cue=False, to_rail=frozenset(), pocket_of=None):
    if pocket_of is None:
        pocket_of = {b: 0 for b in pocketed} | ({0: 0} if cue else {})
    return ShotOutcome(first, tuple(pocketed), pocket_of, cue, rail and first is not None, frozenset(to_rail))


def after_break():
    state, ruling = judge(new_game("ten_ball"), shot(1, to_rail=RAIL4))
    assert ruling.foul is None and state.shooter == 1
    return state


def test_rack():
    # Ten Ball 2: a triangle, the 1 at the apex on the foot spot, the 10 in the middle of the triangle.
    table = Table.eight_foot()
    balls = ten_ball_rack(table, seed=3)
    assert len(balls) == 11 and not balls.pocketed.any()
    assert np.allclose(balls.xy[1], foot_spot(table), atol=3e-4)
    centre = balls.xy[1:].mean(axis=0)  # the triangle's centroid: the 10 sits nearest it
    assert int(np.argmin(np.hypot(*(balls.xy[1:] - centre).T))) + 1 == 10
    check_on_table(balls, table)


def test_ten_on_the_break_is_spotted_and_the_breaker_continues():
    # Ten Ball intro and 3: the 10 pocketed on a legal break is spotted and the player continues.
    state, ruling = judge(new_game("ten_ball"), shot(1, (10,)))
    assert ruling.winner is None and ruling.balls_to_spot == (10,) and 10 in state.on_table
    assert state.shooter == 0 and not ruling.turn_passed


def test_illegal_break_is_a_foul():
    # Ten Ball 3(b): no ball pocketed and fewer than four object balls to a rail: a foul (ball in hand, 10).
    state, ruling = judge(new_game("ten_ball"), shot(1, to_rail={2, 3}))
    assert ruling.foul == "illegal_break" and state.shooter == 1 and state.ball_in_hand == "anywhere"
    assert not state.push_out  # Ten Ball 4: a push out only if no foul on the break


def test_push_out_then_shoot_or_pass():
    # Ten Ball 4: 6.2 and 6.3 suspended; then the other player chooses who shoots; the 10 on it is spotted.
    state = after_break()
    assert state.push_out
    new, ruling = judge(state, shot(7, (10,), rail=False), push_out=True)
    assert ruling.foul is None and 10 in new.on_table and new.shooter == 0 and new.pending.name == "push_out_reply"
    assert decide(new, "pass").shooter == 1 and decide(new, "shoot").shooter == 0


def test_the_ten_on_a_legal_called_shot_wins():
    # Ten Ball 5: the shooter legally pocketing the called 10 in the called pocket wins the rack.
    state, _ = judge(after_break(), shot(None, rail=False))  # a foul: player 0 has ball in hand
    assert state.shooter == 0 and state.pending is None
    _, ruling = judge(state, shot(1, (10,), pocket_of={10: 4}), called_pocket=4, called_ball=10)
    assert ruling.winner == state.shooter and ruling.end_reason == "ten_pocketed"


def test_called_ball_made_continues_and_other_balls_stay_down():
    # Ten Ball 5, 8: the called ball in the called pocket: the shooter continues; other balls pocketed stay down.
    state = after_break()
    new, ruling = judge(state, shot(1, (1, 4), pocket_of={1: 2, 4: 5}), called_pocket=2, called_ball=1)
    assert ruling.foul is None and not ruling.turn_passed and new.shooter == 1 and 4 not in new.on_table


def test_ten_dropped_with_the_called_ball_is_spotted():
    # Ten Ball 9: the 10 pocketed other than on a legal called shot of the 10 is spotted.
    state = after_break()
    new, ruling = judge(state, shot(1, (1, 10), pocket_of={1: 2, 10: 3}), called_pocket=2, called_ball=1)
    assert ruling.winner is None and 10 in new.on_table and not ruling.turn_passed


def test_wrongly_pocketed_ball_gives_the_opponent_the_choice():
    # Ten Ball 7: a ball pocketed not as called (wrong ball or wrong pocket): no foul, the inning
    # ends, the balls stay down (the 10 spotted), and the incoming player shoots or passes it back.
    state = after_break()
    new, ruling = judge(state, shot(1, (1,), pocket_of={1: 5}), called_pocket=2, called_ball=1)
    assert ruling.foul is None and ruling.turn_passed and 1 not in new.on_table
    assert new.shooter == 0 and new.pending.name == "wrongly_pocketed_reply"
    assert decide(new, "pass").shooter == 1


def test_safety_no_call_passes_without_a_choice():
    # Ten Ball 6: a safety: a ball pocketed stays down and the turn passes (no option for the opponent).
    state = after_break()
    new, ruling = judge(state, shot(1, (3,)))
    assert ruling.foul is None and ruling.turn_passed and new.pending is None and 3 not in new.on_table


def test_fouls_and_the_ten_spotted_on_a_foul():
    # Ten Ball 10 (6.2 wrong ball first) and 9: ball in hand anywhere; the 10 pocketed on a foul is spotted.
    state = after_break()
    new, ruling = judge(state, shot(5, (10,), pocket_of={10: 1}), called_pocket=1, called_ball=10)
    assert ruling.foul == "wrong_ball_first" and ruling.winner is None and 10 in new.on_table
    assert new.ball_in_hand == "anywhere" and new.shooter == 0


def test_three_fouls_lose():
    # Ten Ball 11, 6.14: three consecutive fouls lose the rack.
    state = after_break()
    for _ in range(2):
        state, _ = judge(state, shot(None, rail=False))
        state, _ = judge(state, shot(1))
    state, ruling = judge(state, shot(None, rail=False))
    assert ruling.end_reason == "three_fouls" and ruling.winner == 0


def test_bad_calls_raise():
    state = after_break()
    with pytest.raises(ValueError, match="called_pocket"):
        judge(state, shot(1), called_pocket=6, called_ball=1)
    with pytest.raises(ValueError, match="called_ball"):
        judge(state, shot(1), called_pocket=0, called_ball=11)
    later, _ = judge(state, shot(1))
    with pytest.raises(ValueError, match="push out"):
        judge(later, shot(2), push_out=True)
