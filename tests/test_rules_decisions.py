"""Decision turns against the WPA rules: the 9-ball push out (2.4, 2.6) and 8-ball's choices after
an illegal break (3.3(d)) and after the 8 on the break (3.3(e)-(f), 3.6); `rules.decide` and `Game.decide`."""

from __future__ import annotations

import pytest

from pool_env import rules as R
from pool_env.game import Game, Shot
from pool_env.rules import GameState, NineBall, ShotOutcome, decide, judge, new_game

RAIL4 = frozenset({2, 3, 4, 5})


def shot(first=None, pocketed=(), rail=True, cue=False, to_rail=frozenset(), off=()):
    pocket_of = {b: 0 for b in pocketed} | ({0: 0} if cue else {})
    return ShotOutcome(first, tuple(pocketed), pocket_of, cue, rail and first is not None, frozenset(to_rail),
                       tuple(off))


def after_legal_break():
    """9-ball: player 0 broke legally (four balls to a rail, none pocketed): player 1 to shoot."""
    state, ruling = judge(new_game("nine_ball"), shot(1, to_rail=RAIL4))
    assert ruling.foul is None and state.shooter == 1
    return state


def test_push_out_allowed_only_right_after_a_legal_break():
    # WPA 2.4: "the player who shoots the shot immediately after a legal break may play a push out".
    state = after_legal_break()
    assert state.push_out
    later, _ = judge(state, shot(1))  # a normal shot: no push out after it
    assert not later.push_out
    with pytest.raises(ValueError, match="push out"):
        judge(later, shot(2), push_out=True)
    with pytest.raises(ValueError, match="push out"):
        judge(new_game("nine_ball"), shot(1, to_rail=RAIL4), push_out=True)  # not on the break


def test_no_push_out_after_a_foul_on_the_break():
    # WPA 2.4: "After a player scratches on the break shot, the incoming player cannot play a push out";
    # an illegal break (2.3) is a foul too, so the break was not legal.
    scratched, _ = judge(new_game("nine_ball"), shot(1, (3,), cue=True))
    illegal, _ = judge(new_game("nine_ball"), shot(1, to_rail={2, 3}))
    assert not scratched.push_out and not illegal.push_out


def test_push_out_needs_no_contact_and_no_rail_then_the_opponent_chooses():
    # WPA 2.4: on a push out the cue ball need not contact any object ball nor any rail; after a
    # legal push out the incoming player may shoot from that position or pass the shot back.
    state = after_legal_break()
    new, ruling = judge(state, shot(None, rail=False), push_out=True)
    assert ruling.foul is None and ruling.turn_passed and ruling.ball_in_hand is None
    assert new.shooter == 0 and new.pending is not None and new.pending.name == "push_out_reply"
    assert set(new.pending.options) == {"shoot", "pass"}
    shoots = decide(new, "shoot")
    assert shoots.shooter == 0 and shoots.pending is None and shoots.ball_in_hand is None
    passed = decide(new, "pass")
    assert passed.shooter == 1 and passed.pending is None  # the player who pushed out must shoot


def test_push_out_wrong_ball_first_is_no_foul():
    # WPA 2.4: a push out is no foul as long as no rule except 6.2 (wrong ball first) and 6.3 is broken.
    state = after_legal_break()
    _, ruling = judge(state, shot(5, rail=False), push_out=True)
    assert ruling.foul is None


def test_ball_pocketed_on_a_push_out_stays_down_but_the_nine_is_spotted():
    # WPA 2.4: any ball pocketed on a push out does not count and remains pocketed, except the
    # nine; 2.6: the 9 pocketed on a push out is spotted, and no one wins.
    state = after_legal_break()
    new, ruling = judge(state, shot(5, (4, 9)), push_out=True)
    assert 4 not in new.on_table and 9 in new.on_table and ruling.balls_to_spot == (9,)
    assert ruling.winner is None and ruling.turn_passed and new.shooter == 0  # the pocketed 4 does not keep him on


def test_scratch_on_a_push_out_is_a_foul():
    # WPA 2.4: all other foul rules still apply on a push out; a scratch (6.1) gives ball in hand (2.7).
    state = after_legal_break()
    new, ruling = judge(state, shot(None, cue=True, rail=False), push_out=True)
    assert ruling.foul == "scratch" and new.pending is None and new.ball_in_hand == "anywhere"
    assert new.shooter == 0 and new.fouls[1] == 1


def test_shot_waits_for_the_decision_and_bad_options_raise():
    state, _ = judge(after_legal_break(), shot(None, rail=False), push_out=True)
    with pytest.raises(ValueError, match="decision"):
        judge(state, shot(1))
    with pytest.raises(ValueError, match="not an option"):
        decide(state, "rerack_and_break")
    with pytest.raises(ValueError, match="no decision is pending"):
        decide(after_legal_break(), "shoot")
    with pytest.raises(ValueError, match="Decision"):
        R.Decision("push_out_reply", ("shoot", "spot_eight"), "shoot")


def test_eight_illegal_break_options():
    # WPA 3.3(d): after an illegal break the incoming player may (1) accept the table in position
    # and shoot, or (2) have the balls re-racked and break himself or let the breaker re-break.
    state, ruling = judge(new_game("eight_ball"), shot(1, to_rail={2, 3}))
    assert ruling.foul == "illegal_break" and state.shooter == 1 and state.pending.name == "illegal_break"
    accept = decide(state, "accept_table")
    assert accept.shooter == 1 and accept.ball_in_hand is None and not accept.is_break and accept.pending is None
    mine = decide(state, "rerack_and_break")
    assert mine.is_break and mine.shooter == 1 and mine.on_table == frozenset(range(1, 16))
    assert mine.ball_in_hand == "behind_head_string"  # 3.3(a)
    theirs = decide(state, "rerack_opponent_breaks")
    assert theirs.is_break and theirs.shooter == 0
    kept = decide(state, "ball_in_hand")  # the package's former fixed choice, still an option
    assert kept.ball_in_hand == "anywhere" and kept.shooter == 1


def test_eight_on_a_legal_break_breaker_spots_or_rebreaks():
    # WPA 3.3(e): the 8 pocketed on a legal break: the breaker re-spots it and accepts the balls
    # in position (he shoots on), or re-breaks.
    state, ruling = judge(new_game("eight_ball"), shot(1, (8,)))
    assert ruling.foul is None and state.shooter == 0 and state.pending.name == "eight_on_break"
    spotted = decide(state, "spot_eight")
    assert 8 in spotted.on_table and spotted.shooter == 0 and not spotted.is_break
    again = decide(state, "rebreak")
    assert again.is_break and again.shooter == 0 and again.on_table == frozenset(range(1, 16))


def test_eight_on_the_break_with_a_scratch_opponent_chooses():
    # WPA 3.3(f): the breaker pockets the 8 and scratches: the opponent re-spots the 8 and shoots
    # with the cue ball in hand behind the head string, or re-breaks.
    state, _ = judge(new_game("eight_ball"), shot(1, (8,), cue=True))
    assert state.shooter == 1 and state.pending.name == "eight_on_break"
    spotted = decide(state, "spot_eight")
    assert spotted.ball_in_hand == "behind_head_string" and spotted.shooter == 1
    again = decide(state, "rebreak")
    assert again.is_break and again.shooter == 1


def test_game_without_decisions_takes_the_default():
    # The defaults keep the former behaviour: ball in hand anywhere after an illegal 8-ball break.
    state, _ = judge(new_game("eight_ball"), shot(1, to_rail={2, 3}))
    assert state.pending.default == "ball_in_hand"
    state, _ = judge(new_game("eight_ball", illegal_break="table_in_position"), shot(1, to_rail={2, 3}))
    assert state.pending.default == "accept_table"


def _pushed_game():
    """A 9-ball Game with decisions, from a position right after a legal break: player 1 pushes out."""
    game = Game("nine_ball", seed=1, decisions=True)
    base = after_legal_break()
    game.reset(balls=game.balls, state=GameState(NineBall(), base.on_table, 1, None, push_out=True, is_break=False,
                                                 shot=1))
    assert game.may_push_out
    record = game.play(Shot.aimed((0.0, 1.0), 0.5, push_out=True))
    return game, record


def test_game_push_out_and_decide():
    game, record = _pushed_game()
    assert record.foul is None and game.pending is not None and game.shooter == 0
    with pytest.raises(RuntimeError, match="decision"):
        game.play(Shot.aimed((1.0, 0.0), 2.0))
    with pytest.raises(ValueError, match="not an option"):
        game.decide("spot_eight")
    game.decide("pass")
    assert game.shooter == 1 and game.pending is None and not game.may_push_out
    with pytest.raises(ValueError, match="push out"):
        game.play(Shot.aimed((1.0, 0.0), 2.0, push_out=True))


def test_game_decision_is_deterministic_and_snapshots():
    game, _ = _pushed_game()
    snap = game.snapshot()
    game.decide("shoot")
    a = game.play(Shot.aimed((1.0, 0.2), 3.0))
    game.restore(snap)
    assert game.pending is not None
    game.decide("shoot")
    b = game.play(Shot.aimed((1.0, 0.2), 3.0))
    assert a.state_after == b.state_after and (a.balls_after.xy == b.balls_after.xy).all()


def test_game_rerack_racks_afresh():
    # WPA 3.3(d)(2): a re-rack puts all fifteen balls back in the rack; the balls follow the state.
    game = Game("eight_ball", seed=3, decisions=True)
    record = game.play(Shot.aimed((1.0, 0.0), 0.6, place=(0.5, 0.6)))  # a soft break: illegal
    assert record.foul == "illegal_break" and game.pending.name == "illegal_break"
    game.decide("rerack_opponent_breaks")
    assert game.state.is_break and game.shooter == 0 and not game.balls.pocketed.any()
    assert game.ball_in_hand == "behind_head_string"
