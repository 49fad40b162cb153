"""Three-cushion rules against the UMB rule text, on hand-built outcomes and on scenes the engine plays.

UMB Sports Rules (carom) 3.3: the starting position (red on the top spot, the opponent's ball
on the bottom spot, the player's on a starting spot) and the starting stroke "by direct attack
on the red ball"; three cushions (1989 World Rules Art. 83): a point when the cue ball touches
both object balls and the cushions at least three times before it touches the second; the
shooter plays on after a point, the inning passes on a miss; Art. 27 (balls in contact) and
Art. 28 (balls off the billiard: a foul, the inning ends, the balls set up again); Art. 29 (end
of the match: the distance, and the equalising inning).
"""

from __future__ import annotations

import numpy as np
import pytest

from pool_env import rules as R
from pool_env.game import Game, Shot
from pool_env.physics import CAROM_MASS, CAROM_RADIUS, Balls, Table
from pool_env.rules import CaromOutcome, ThreeCushion, ThreeCushionState

SCENE = [[0.7, 0.4], [1.8, 1.0], [2.2, 0.5]]  # white, yellow, red


def hit(first=None, second=None, before=0, total=None, cue=0, off=(), touching=()):
    return CaromOutcome(cue, first, second, before, before if total is None else total, tuple(off),
                        frozenset(touching))


def state(**kw):
    rules = kw.pop("rules", ThreeCushion())
    kw.setdefault("is_break", False)
    return ThreeCushionState(rules, **kw)


def test_a_point_needs_both_balls_and_three_cushions_before_the_second():
    assert hit(2, 1, before=3).point
    assert hit(2, 1, before=5).point
    assert not hit(2, 1, before=2, total=4).point  # the third cushion after the second ball
    assert not hit(2, None, before=4).point  # one ball only
    assert not hit(None, None, before=6).point


def test_the_starting_position_and_the_starting_stroke():
    table = Table.carom()
    balls = R.starting_position(table)
    spots = R.carom_spots(table)
    assert tuple(balls.xy[2]) == spots["top"] == (0.75 * 2.84, 0.71)  # the red on the top spot
    assert tuple(balls.xy[1]) == spots["bottom"] == (0.25 * 2.84, 0.71)  # the opponent's ball
    assert abs(balls.xy[0, 1] - 0.71) == pytest.approx(0.182) and balls.xy[0, 0] == 0.25 * 2.84
    s = R.new_game("three_cushion", breaker=1)
    assert s.shooter == 1 and s.cue_ball == 0  # the starter plays the white (3.3)
    assert R.legal_targets(s) == frozenset({2})
    # The starting stroke must attack the red: a valid carom off the yellow first is a foul.
    new, ruling = R.judge(s, hit(1, 2, before=3))
    assert ruling.foul == "wrong_ball_first" and not ruling.point and new.scores == (0, 0)
    assert new.shooter == 0 and ruling.turn_passed


def test_a_point_keeps_the_table_and_a_miss_passes_the_inning():
    s = state(scores=(4, 2), innings=(3, 2), run=1)
    after, ruling = R.judge(s, hit(2, 1, before=3))
    assert ruling.point and after.scores == (5, 2) and after.shooter == 0 and after.run == 2
    assert after.innings == (3, 2) and not ruling.turn_passed
    missed, ruling = R.judge(after, hit(2, 1, before=2, total=3))
    assert not ruling.point and ruling.turn_passed and missed.shooter == 1
    assert missed.innings == (3, 3) and missed.scores == (5, 2) and missed.cue_ball == 1 and missed.run == 0


def test_a_ball_off_the_table_is_a_foul_and_the_balls_are_set_up_again():
    s = state(scores=(1, 0))
    after, ruling = R.judge(s, hit(2, 1, before=3, off=(2,)))
    assert ruling.foul == "ball_off_table" and not ruling.point and after.scores == (1, 0)
    assert ruling.turn_passed and ruling.balls_to_spot == (0, 1, 2)
    balls, settled = R.settle(after, ruling, R.starting_position(Table.carom()), Table.carom())
    assert settled == after
    assert tuple(balls.xy[1]) == R.carom_spots(Table.carom())["start_right"]  # the incoming player's yellow


def test_a_cue_ball_left_touching_a_ball_is_set_up_again():
    after, ruling = R.judge(state(), hit(2, None, before=1, touching=[(1, 2)]))  # yellow frozen to the red
    assert after.cue_ball == 1 and ruling.balls_to_spot == (0, 1, 2) and ruling.foul is None


def test_the_distance_wins_for_the_second_player_at_once():
    s = state(shooter=1, scores=(10, 14), innings=(8, 8), rules=ThreeCushion(points=15))
    after, ruling = R.judge(s, hit(0, 2, before=3, cue=1))
    assert after.over and after.winner == 1 and ruling.end_reason == "points_reached"


def test_the_starter_reaching_the_distance_gives_the_equalising_inning():
    rules = ThreeCushion(points=15)
    s = state(scores=(14, 9), innings=(8, 7), rules=rules)
    after, ruling = R.judge(s, hit(2, 1, before=3))
    assert not after.over and after.equalizing and after.shooter == 1 and after.innings == (8, 8)
    assert after.is_break and ruling.balls_to_spot == (0, 1, 2)  # from the starting position
    done, ruling = R.judge(after, hit(2, None, before=1, cue=1))  # he misses: the starter wins
    assert done.over and done.winner == 0 and ruling.end_reason == "points_reached"
    level = state(shooter=1, scores=(15, 14), innings=(8, 8), equalizing=True, rules=rules)
    done, ruling = R.judge(level, hit(0, 2, before=3, cue=1))
    assert done.over and done.winner is None and ruling.end_reason == "equalized"  # a draw
    no_eq = ThreeCushion(points=15, equalizing=False)
    done, _ = R.judge(state(scores=(14, 9), innings=(8, 7), rules=no_eq), hit(2, 1, before=3))
    assert done.over and done.winner == 0


def test_the_innings_limit_ends_the_game_after_both_players_have_played_it():
    rules = ThreeCushion(points=None, innings_limit=5)
    s = state(shooter=0, scores=(3, 2), innings=(5, 4), rules=rules)
    after, _ = R.judge(s, hit())  # the starter's 5th inning ends: the other plays his 5th
    assert not after.over and after.innings == (5, 5)
    done, ruling = R.judge(after, hit(cue=1))
    assert done.over and done.winner == 0 and ruling.end_reason == "innings_limit"
    tied, _ = R.judge(state(shooter=1, scores=(2, 2), innings=(5, 5), rules=rules), hit(cue=1))
    assert tied.over and tied.winner is None


def test_bad_rules_states_and_shots_are_refused():
    with pytest.raises(ValueError, match="never ends"):
        ThreeCushion(points=None)
    with pytest.raises(ValueError, match="starter"):
        state(innings=(1, 3))
    with pytest.raises(ValueError, match="cue ball"):
        R.judge(state(), hit(2, 0, before=3, cue=1))
    with pytest.raises(ValueError, match="second ball"):
        CaromOutcome(0, None, 1, 0, 0)
    with pytest.raises(ValueError, match="over"):
        R.judge(state(winner=0, ended=True), hit())


def scene(force):
    """The engine's ruling of a shot of the white with `force` from SCENE (no starting stroke)."""
    game = Game("three_cushion", seed=0)
    game.reset(balls=Balls(SCENE, radius=CAROM_RADIUS, mass=CAROM_MASS))
    record = game.play(Shot(force, (0.0, 0.0)))
    sequence = "".join("C" if e.kind == "ball_cushion" else str(e.j if e.i == 0 else e.i) for e in record.events
                       if 0 in (e.i, e.j) and e.kind in ("ball_cushion", "ball_ball", "ball_ball_settle")
                       and not (e.kind == "ball_cushion" and e.i != 0))
    return record, sequence


def test_scene_three_cushions_then_both_balls_is_a_point():
    record, sequence = scene((176.30227694668886, 170.90389885995367))
    assert sequence == "CCC21"
    assert record.ruling.point and record.state_after.scores == (1, 0) and record.state_after.shooter == 0


def test_scene_a_ball_then_three_cushions_then_the_other_is_a_point():
    record, sequence = scene((248.43302767349513, 11.227090336721632))
    assert sequence == "2CCC1"
    assert record.ruling.point


def test_scene_only_two_cushions_is_no_point():
    record, sequence = scene((131.1295610261204, 208.51034109608554))
    assert sequence == "CC21"
    assert not record.ruling.point and record.state_after.shooter == 1


def test_scene_the_second_ball_before_the_third_cushion_is_no_point():
    record, sequence = scene((161.8508163051054, -80.16792061775168))
    assert sequence.startswith("C2C1") and sequence.count("C") >= 3  # three cushions, the third too late
    assert not record.ruling.point and record.ruling.turn_passed


def test_the_shooter_strikes_his_own_cue_ball():
    game = Game("three_cushion", seed=0)
    assert game.table.length == 2.84 and game.balls.radii[0] == CAROM_RADIUS
    game.reset(balls=Balls(SCENE, radius=CAROM_RADIUS, mass=CAROM_MASS))
    assert game.state.cue_ball == 0
    missed = game.play(Shot((0.0, -60.0), (0.0, 0.0)))  # the white, across the table and back: no ball
    assert missed.ruling.turn_passed and game.shooter == 1 and game.state.cue_ball == 1
    white = game.balls.xy[0].copy()
    record = game.play(Shot((0.0, -60.0), (0.0, 0.0)))  # player 1 strikes the yellow
    first = next(e for e in record.events if e.kind == "ball_cushion")
    assert first.i == 1 and np.array_equal(record.balls_after.xy[0], white)


def test_a_game_ends_and_its_scores_add_up():
    game = Game("three_cushion", seed=3, points=2, innings_limit=3)
    rng = np.random.default_rng(0)
    points = 0
    while not game.over:
        record = game.play(rng.uniform(-1, 1, 4))
        points += bool(record.ruling.point)
    assert sum(game.state.scores) == points
    assert game.state.ended and max(game.state.innings) <= 3
