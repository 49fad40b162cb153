"""`Game.evaluate(records=False)` and `simulate_level_batch` against evaluate's records and `simulate`, bit for bit."""

import math

import numpy as np
import pytest

from pool_env import rules
from pool_env.game import Game, Shot
from pool_env.game.evaluation import DrawnNormals, JudgedShot
from pool_env.physics import BALL_RADIUS, Balls, Physics, Table, simulate, strike
from pool_env.physics.batch_run import balls_at, simulate_level_batch
from pool_env.physics.config import cushion_reach
from pool_env.physics.kinds import DONE, MISPLACED

TABLE = Table.eight_foot()


class EventsOnly:
    """A Result's events and pressed-cushion flags without its compiled facts: what the rules
    read of it in Python (`rules.outcome_from_result`)."""

    def __init__(self, result):
        self.event_arrays, self.pressed_cushion_events = result.event_arrays, result.pressed_cushion_events


def layout(n, places):
    """n balls, those in `places` (number -> xy) on the table, the rest pocketed out of the way."""
    xy = np.array([(0.1 + 0.1 * k, 2.0) for k in range(n)], dtype=float)
    pocketed = np.ones(n, dtype=bool)
    for k, p in places.items():
        xy[k], pocketed[k] = p, False
    return Balls(xy, pocketed=pocketed)


def mid_game(mode="nine_ball", noise="olympiad", seed=3):
    game = Game(mode, noise=noise, seed=seed)
    head = rules.head_spot(TABLE)
    game.play(Shot.aimed(game.balls.xy[1] - np.array(head), 9.0, place=head))
    return game


def fan(count, speed=2.5, **options):
    return [Shot.aimed((math.cos(a), math.sin(a)), speed, (0.0, 0.2), **options)
            for a in np.linspace(0.0, 2.0 * math.pi, count, endpoint=False)]


def same(judged: JudgedShot, record):
    assert judged.error == record.error and judged.outcome == record.outcome and judged.ruling == record.ruling
    assert judged.state_after == record.state_after and judged.over == record.over
    assert judged.pocketed == record.pocketed
    assert np.array_equal(judged.balls_after.xy, record.balls_after.xy)
    assert np.array_equal(judged.balls_after.pocketed, record.balls_after.pocketed)


def compare(game, shots, draws=3, seed=5, threads=1):
    snap = game.snapshot()
    records = game.evaluate(shots, draws=draws, seed=seed)
    judged = game.evaluate(shots, draws=draws, seed=seed, threads=threads, records=False)
    assert game.snapshot().balls is snap.balls and game.state == snap.state
    assert len(judged) == len(records)
    for j, r in zip(judged, records):
        same(j, r)
    return records


@pytest.mark.parametrize("threads", [1, 2])
def test_lean_evaluate_judges_every_shot_as_the_records_do(threads):
    records = compare(mid_game(), fan(24) + fan(12, 6.0), threads=threads)
    assert len({(r.outcome, r.ruling.foul) for r in records}) > 3  # misses, fouls and pots alike


def test_lean_evaluate_with_ball_in_hand_and_spotting():
    # The cue ball hits the 9 first (a foul) and drops it in corner pocket 0: the 9 is spotted.
    game = Game("nine_ball", noise="olympiad", seed=1)
    game.reset(balls=layout(10, {0: (0.7, 0.7), 1: (1.6, 0.8), 9: (0.35, 0.35)}), ball_in_hand=True)
    shots = [Shot.aimed((-1.0, -1.0), 2.0, place=(0.7, 0.7)), Shot.aimed((1.0, 0.1), 1.5, place=(0.5, 0.5))]
    records = compare(game, shots, draws=4)
    assert any(r.ruling.balls_to_spot for r in records)


@pytest.mark.parametrize("mode", ["eight_ball", "ten_ball", "snooker", "three_cushion"])
def test_lean_evaluate_in_the_other_games(mode):
    game = Game(mode, noise="olympiad", seed=2)
    if mode in ("eight_ball", "ten_ball"):
        game = mid_game(mode, seed=2)
        shots = [Shot.aimed(s.force, 3.0, pocket=k % 6, ball=min(game.legal_targets)) for k, s in enumerate(fan(8))]
    else:
        shots = fan(6, 4.0, place=(0.5, 0.7)) if game.ball_in_hand else fan(6, 4.0)
    compare(game, shots, draws=2)


def struck_scenes(game, shots):
    balls = game.balls
    return [strike(balls, s.force, s.tip, physics=game.physics) for s in shots]


def test_level_batch_is_simulate_and_reads_the_events_as_the_rules_do():
    game = mid_game(noise=None)
    scenes = struck_scenes(game, fan(20, 3.0) + fan(10, 7.0))
    like = scenes[0]
    S, st, codes, facts = simulate_level_batch(like, [b.xy for b in scenes], [b.v for b in scenes],
                                               [b.w for b in scenes], game.table, game.physics)
    assert (codes == DONE).all()
    for k, balls in enumerate(scenes):
        result = simulate(balls, game.table, game.physics)
        final, mine = result.final, balls_at(balls, S[k], st[k])
        for name in ("xy", "v", "w", "pocketed"):
            assert np.array_equal(getattr(final, name), getattr(mine, name))
        assert rules.outcome_of_facts(facts[k].tolist()) == rules.outcome_from_result(EventsOnly(result))


def test_level_batch_reads_a_frozen_ball_pressed_into_its_rail_as_not_driven_to_it():
    # The 1 frozen to the y = W rail, the cue ball sent softly up the table into it: the 1 is
    # only pressed into its rail (WPA 8.4), which the facts must not count as a rail.
    physics = Physics.standard()
    frozen = np.array([0.6, TABLE.width - cushion_reach(BALL_RADIUS, TABLE.cushion_height, physics.cushion)])
    struck = strike(Balls(np.array([frozen - (0.0, 0.3), frozen])), (0.0, 20.0), physics=physics)
    result = simulate(struck, TABLE, physics)
    assert result.pressed_cushion_events().any()
    _, _, codes, facts = simulate_level_batch(struck, [struck.xy], [struck.v], [struck.w], TABLE, physics)
    assert codes[0] == DONE
    outcome = rules.outcome_of_facts(facts[0].tolist())
    assert outcome == rules.outcome_from_result(EventsOnly(result)) and outcome.object_balls_to_rail == frozenset()


def test_a_results_compiled_facts_read_as_its_events_do():
    # Result.event_facts (one compiled call) against the events read in Python, on a fan of
    # 8-ball shots mid-game and on a frozen ball pressed into its rail: the same outcome, its
    # balls to a rail in the same order (the frozenset built alike), the press not a rail.
    game = mid_game("eight_ball", noise=None)
    physics = Physics.standard()
    frozen = np.array([0.6, TABLE.width - cushion_reach(BALL_RADIUS, TABLE.cushion_height, physics.cushion)])
    results = [simulate(game.strike(shot).balls, game.table, game.physics) for shot in fan(24, 3.0)]
    pressed = strike(Balls(np.array([frozen - (0.0, 0.3), frozen])), (0.0, 20.0), physics=physics)
    results.append(simulate(pressed, TABLE, physics))
    assert simulate(pressed, TABLE, physics).pressed_cushion_events().any()
    for result in results:
        assert result.event_facts() is not None
        mine, python = rules.outcome_from_result(result), rules.outcome_from_result(EventsOnly(result))
        assert mine == python and repr(mine) == repr(python)
        assert list(mine.object_balls_to_rail) == list(python.object_balls_to_rail)
    assert any(len(rules.outcome_from_result(r).object_balls_to_rail) >= 3 for r in results)
    assert rules.outcome_from_result(results[-1]).object_balls_to_rail == frozenset()


def test_level_batch_stops_a_misplaced_scene_and_runs_the_others():
    physics = Physics.standard()
    good = strike(layout(10, {0: (1.0, 0.5), 1: (1.5, 0.5)}), (2.0, 0.0), physics=physics)
    xys = np.array([good.xy, good.xy])
    xys[1, 1] = (-0.5, 0.5)  # off the table
    _, _, codes, _ = simulate_level_batch(good, xys, [good.v, good.v], [good.w, good.w], TABLE, physics)
    assert codes.tolist() == [DONE, MISPLACED]
    with pytest.raises(ValueError, match="threads"):
        simulate_level_batch(good, xys, [good.v, good.v], [good.w, good.w], TABLE, physics, threads=0)


def test_drawn_normals_are_the_generators_normals_one_by_one():
    scales = [0.01, 0.2, 0.0, 3.0, 0.5] * 3
    ours, theirs = DrawnNormals(np.random.default_rng(7)), np.random.default_rng(7)
    ours.arm(len(scales))
    assert [ours.normal(0.0, s) for s in scales] == [theirs.normal(0.0, s) for s in scales]
    assert ours.rng.bit_generator.state == theirs.bit_generator.state
    ours.arm(2)
    ours.normal(0.0, 1.0)
    with pytest.raises(RuntimeError, match="1 normals unused"):
        ours.arm(2)


def test_evaluate_of_an_elevated_shot_under_noise_equals_playing_it():
    # An elevated cue draws a fifth normal per draw (its elevation): the draws after it line up.
    game = mid_game()
    snap = game.snapshot()
    shots = [Shot.aimed((1.0, 0.3), 3.0, elevation=0.3), Shot.aimed((-1.0, 0.2), 2.0)]
    records = game.evaluate(shots, draws=2, seed=4)
    draws, own = np.random.default_rng(4), game.rng
    for k, shot in enumerate(shots):
        for j in range(2):
            game.rng = own
            game.restore(snap)
            game.rng = draws
            played = game.play(shot)
            record = records[2 * k + j]
            assert np.array_equal(played.force, record.force) and played.elevation == record.elevation
            assert np.array_equal(played.balls_after.xy, record.balls_after.xy)
    game.rng = own
    game.restore(snap)
    compare(game, shots, draws=2, seed=4)
