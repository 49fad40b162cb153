"""8-ball with called ball and pocket (`EightBall(calling="ball_and_pocket")`): WPA 1.6, 3.4, 3.5.

What the rule text decides (WPA "Rules of Play"): 1.6, every shot but the break names a ball
and a pocket, and only the named ball in the named pocket counts as a ball made; balls that
drop besides it stay down and count for no one. 3.4, the table is open after the break and
the groups are settled when a player legally pockets a called ball: its group becomes his.
3.5, the shooter stays at the table while he legally pockets called balls; otherwise his
inning ends (without a foul, if there is none). 3.8 at the 8 is unchanged (its pocket called).
"""

from __future__ import annotations

import pytest

from pool_env.rules import EightBall, GameState, ShotOutcome, judge

CALLED = EightBall(calling="ball_and_pocket")


def state(groups=(None, None), on_table=range(1, 16)):
    return GameState(CALLED, frozenset(on_table), 0, None, (0, 0), groups, False, 5)


def shot(first, drops, rail=True, cue=False):
    """A ShotOutcome: `drops` the (ball, pocket) pairs in the order they dropped."""
    pocket_of = dict(drops) | ({0: 0} if cue else {})
    return ShotOutcome(first, tuple(b for b, _ in drops), pocket_of, cue, rail, frozenset())


def test_the_called_ball_in_the_called_pocket_keeps_the_table_and_decides_the_group():
    new, ruling = judge(state(), shot(3, [(3, 2)]), called_pocket=2, called_ball=3)
    assert ruling.foul is None and not ruling.turn_passed and new.shooter == 0
    assert new.groups == ("solids", "stripes") and 3 not in new.on_table


def test_the_called_ball_in_another_pocket_ends_the_inning_and_leaves_the_table_open():
    new, ruling = judge(state(), shot(3, [(3, 4)]), called_pocket=2, called_ball=3)
    assert ruling.foul is None and ruling.turn_passed and new.shooter == 1
    assert new.groups == (None, None) and 3 not in new.on_table  # it stays down
    assert new.ball_in_hand is None


def test_the_called_ball_decides_the_group_not_the_first_ball_to_drop():
    # A stripe drops first, then the called solid in its pocket: the shooter has solids.
    new, ruling = judge(state(), shot(3, [(12, 5), (3, 2)]), called_pocket=2, called_ball=3)
    assert not ruling.turn_passed and new.groups == ("solids", "stripes")
    assert not {3, 12} & new.on_table


def test_extra_balls_stay_down_and_the_shooter_continues_on_his_called_ball():
    groups = ("stripes", "solids")
    new, ruling = judge(state(groups), shot(10, [(10, 1), (3, 0)]), called_pocket=1, called_ball=10)
    assert ruling.foul is None and not ruling.turn_passed and not {3, 10} & new.on_table


def test_an_opponents_ball_called_and_made_is_no_ball_made():
    # On stripes, the 10 hit first pushes the called 3 (his opponent's) into the called pocket.
    new, ruling = judge(state(("stripes", "solids")), shot(10, [(3, 2)]), called_pocket=2, called_ball=3)
    assert ruling.foul is None and ruling.turn_passed


def test_no_call_means_no_ball_made():
    new, ruling = judge(state(), shot(3, [(3, 2)]))
    assert ruling.foul is None and ruling.turn_passed and new.groups == (None, None)


def test_a_foul_with_the_called_ball_made_is_a_foul():
    new, ruling = judge(state(), shot(3, [(3, 2)], cue=True), called_pocket=2, called_ball=3)
    assert ruling.foul == "scratch" and ruling.turn_passed and new.ball_in_hand == "anywhere"
    assert new.groups == (None, None)


def test_the_eight_is_called_by_its_pocket():
    on_the_eight = state(("solids", "stripes"), on_table=[8, 9, 10])
    new, ruling = judge(on_the_eight, shot(8, [(8, 3)]), called_pocket=3)
    assert ruling.winner == 0 and ruling.end_reason == "eight_pocketed"
    new, ruling = judge(on_the_eight, shot(8, [(8, 4)]), called_pocket=3, called_ball=8)
    assert ruling.winner == 1 and ruling.end_reason == "eight_wrong_pocket"


def test_a_called_ball_not_on_the_table_is_refused():
    with pytest.raises(ValueError, match="called_ball must be None or an object ball on the table"):
        judge(state(on_table=[1, 2, 8]), shot(1, []), called_pocket=0, called_ball=5)
    with pytest.raises(ValueError, match="calling must be one of"):
        EightBall(calling="everything")


def test_the_default_calls_ball_and_pocket_and_eight_only_calls_only_the_eight():
    # WPA 1.6 is the default: an uncalled ball of the group in a pocket does not keep the table.
    # With calling="eight_only" (the simplification) it does, uncalled.
    groups = ("solids", "stripes")
    called = GameState(EightBall(), frozenset(range(1, 16)), 0, None, (0, 0), groups, False, 5)
    assert EightBall().calling == "ball_and_pocket" and judge(called, shot(3, [(3, 4)]))[1].turn_passed
    plain = GameState(EightBall(calling="eight_only"), frozenset(range(1, 16)), 0, None, (0, 0), groups, False, 5)
    assert not judge(plain, shot(3, [(3, 4)]))[1].turn_passed


def test_a_game_with_called_shots_judges_the_shots_call():
    # The 1 sits 0.3 m from the corner pocket 3 (at (L, W)) on its diagonal, the cue ball 0.4 m
    # behind it: a straight shot drops the 1 in pocket 3 (tests/test_rules.py checks the drop).
    import numpy as np

    from pool_env.game import Game, Shot
    from pool_env.physics import Balls, Table

    table = Table.eight_foot()
    diag = np.array([1.0, 1.0]) / np.sqrt(2.0)
    p1 = np.array([table.length - 0.3, table.width - 0.3])
    xy = np.tile([0.5, 0.3], (16, 1))
    xy[0], xy[1], xy[8] = p1 - 0.4 * diag, p1, (0.5, 0.3)
    pocketed = np.ones(16, dtype=bool)
    pocketed[[0, 1, 8]] = False
    balls = Balls(xy, pocketed=pocketed)
    game = Game("eight_ball", calling="ball_and_pocket")
    for pocket, kept in ((3, True), (2, False)):
        game.reset(seed=0, balls=balls)
        record = game.play(Shot.aimed(diag, 2.0, pocket=pocket, ball=1))
        assert record.pocketed == (1,) and record.foul is None and record.called_ball == 1
        assert (not record.ruling.turn_passed) == kept
        assert game.state.groups == (("solids", "stripes") if kept else (None, None))
    game.reset(seed=0, balls=balls)
    with pytest.raises(ValueError, match="Shot.ball 5 is not on the table"):
        game.play(Shot.aimed(diag, 2.0, pocket=3, ball=5))
    # The same call as an action of the eight_ball_call layout (entry 7: the called ball among
    # the legal targets, here the 1 alone: the 8 is not on while the table is open).
    acting = Game("eight_ball", layout="eight_ball_call", calling="ball_and_pocket").reset(seed=0, balls=balls)
    action = acting.encode(Shot.aimed(diag, 2.0, pocket=3, ball=1))
    assert action.shape == (8,) and acting.decode(action).ball == 1
    record = acting.play(action)
    assert record.called_ball == 1 and record.pocketed == (1,) and not record.ruling.turn_passed


def test_the_ghost_ball_player_calls_the_ball_it_pots_as_the_env_reads_it():
    # WPA 1.6: a called shot names its ball. The player's action must decode, in the env's game,
    # to the ball of the pot it planned (its decide), among the legal targets.
    import gymnasium as gym

    from pool_env.game import decode_game_observation
    from pool_env.players import GameGhostBallAgent

    env = gym.make("PoolEightBall-v0", opponent="random")
    player = GameGhostBallAgent.from_env(env)
    game = env.unwrapped.game
    called = 0
    for seed in range(6):
        obs, _ = env.reset(seed=seed)
        for _ in range(12):
            action = player.act(obs)
            planned = player.decide(decode_game_observation(obs, "eight_ball", game.table))
            shot = game.decode(action)
            if not game.state.is_break and planned.ball is not None:
                assert shot.ball == planned.ball and shot.ball in game.legal_targets
                assert shot.pocket == planned.pocket
                called += 1
            obs, *_, terminated, truncated, _ = env.step(action)
            if terminated or truncated:
                break
    assert called >= 1


def test_a_saved_game_from_before_called_shots_replays_calling_the_eight_only():
    from pathlib import Path

    from pool_env.records.saved import load_game, replay

    path = Path(__file__).parent / "data" / "saved_games" / "eight_ball_ghost_vs_ghost.json"
    record = load_game(path)  # saved-game version 2: 8-ball then called the 8 only
    assert record["env_kwargs"]["rule_options"] == {"calling": "eight_only"}
    env = replay(record)  # raises ReplayMismatch at any difference
    assert env.unwrapped.action_space.shape == (7,)
