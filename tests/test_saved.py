"""Saved games: save then load then replay gives identical states; a tampered file is refused."""

import json
from pathlib import Path

import pytest

import pool_env
from agents import GameGhostBallAgent, RandomAgent
from pool_env.records.replay import main as replay_main
from pool_env.records.saved import ReplayMismatch, load_game, record_game, replay, save_game

SAVED_RUN = Path(__file__).parent / "data" / "saved_games" / "run_ghost.json"  # 16 steps


@pytest.fixture(scope="module")
def nine_ball_game(tmp_path_factory):
    import gymnasium as gym

    env = gym.make("PoolNineBall-v0")
    record = record_game(env, GameGhostBallAgent.from_env(env), seed=3)
    return save_game(tmp_path_factory.mktemp("games") / "nine.json", record), record


def test_save_load_replay_gives_identical_states(nine_ball_game):
    path, record = nine_ball_game
    loaded = load_game(path)
    assert loaded == json.loads(json.dumps(record))  # floats written exactly
    env = replay(loaded)  # raises at the first step that differs
    final = loaded["outcomes"][-1]
    assert env.unwrapped.balls.xy.tolist() == final["xy"]
    assert final["terminated"] or final["truncated"]


def test_a_tampered_file_is_refused(nine_ball_game, tmp_path):
    path, record = nine_ball_game
    tampered = json.loads(path.read_text())
    tampered["actions"][0][0] *= 0.9  # a softer break: the outcomes no longer follow
    bad = save_game(tmp_path / "bad.json", tampered)
    with pytest.raises(ReplayMismatch, match="step 0 of the saved game replays differently"):
        replay(load_game(bad))
    assert replay_main([str(bad)]) == 1
    (tmp_path / "junk.json").write_text('{"format": "something else"}')
    with pytest.raises(ValueError, match="not a pool_env saved game"):
        load_game(tmp_path / "junk.json")
    (tmp_path / "old.json").write_text(json.dumps({**record, "version": 99}))
    with pytest.raises(ValueError, match="version 99"):
        load_game(tmp_path / "old.json")


def test_replay_cli_and_a_break_env(tmp_path, capsys):
    record = record_game("PoolBreakRun-v0", RandomAgent(pool_env.PoolBreakEnv(max_shots=3).action_space, seed=0),
                         seed=1)
    path = save_game(tmp_path / "run.json", record)
    assert replay_main([str(path), "--shot", "1"]) == 0
    out = capsys.readouterr()
    assert out.out.startswith("replayed 1 step of PoolBreakRun-v0 (seed 1)")  # one step, not "1 steps"
    # conftest's SDL_VIDEODRIVER=dummy: no window anyone would see, and the replay says so.
    assert "not shown: SDL_VIDEODRIVER=dummy" in out.err and "--video" in out.err
    assert replay_main([str(SAVED_RUN), "--no-window", "--shot", "3"]) == 0
    out = capsys.readouterr()
    assert out.out.startswith("replayed 3 steps of PoolBreakRun-v0") and out.err == ""


def test_replay_shows_every_shot_in_a_window_when_there_is_a_display(tmp_path, monkeypatch, capsys):
    import pool_env.records.replay as replay_module

    shown = []

    class Recorded(replay_module.Window):
        def show(self, frame):
            shown.append(frame.shape)
            return super().show(frame)

    record = {**load_game(SAVED_RUN), "actions": load_game(SAVED_RUN)["actions"][:2]}
    record["outcomes"] = record["outcomes"][:2]
    path = save_game(tmp_path / "run.json", record)
    monkeypatch.setattr(replay_module, "display_problem", lambda: None)  # as if a screen were there
    monkeypatch.setattr(replay_module, "Window", Recorded)  # drawn on the dummy driver: no waits, no hold
    assert replay_main([str(path)]) == 0
    counts = []  # each step's frames, as the replayed env draws them
    replay(record, on_step=lambda k, env: counts.append(len(env.unwrapped.shot_frames())))
    assert len(counts) == 2 and len(shown) == sum(counts) and all(shape == (360, 640, 3) for shape in shown)
    assert "close the window" in capsys.readouterr().out


def test_a_snooker_frame_against_the_snooker_player_saves_and_replays(tmp_path):
    import gymnasium as gym

    record = record_game(gym.make("Snooker-v0", max_shots=15), RandomAgent(6, seed=1), seed=3)
    env = replay(load_game(save_game(tmp_path / "snooker.json", record)))  # raises at a step that differs
    final = record["outcomes"][-1]
    assert env.unwrapped.balls.xy.tolist() == final["xy"] and (final["terminated"] or final["truncated"])
    assert final["info"]["winner"] == (-1 if env.unwrapped.game.winner is None else env.unwrapped.game.winner)


def test_unsavable_opponents_are_named():
    import gymnasium as gym

    env = gym.make("PoolNineBall-v0", opponent=lambda obs: obs[:6])
    with pytest.raises(ValueError, match="cannot be saved"):
        record_game(env, lambda obs: obs[:6], seed=0)


SAVED = sorted((Path(__file__).parent / "data" / "saved_games").glob("*.json"))


@pytest.mark.parametrize("path", SAVED, ids=[p.stem for p in SAVED])
def test_games_saved_by_earlier_versions_replay_exactly(path):
    """Games recorded with an earlier version (9-ball and 8-ball against the ghost-ball player,
    with and without the olympiad noise, the opponent breaking, practice, a run, a spin break):
    every step's reward, flags, rulings and every ball's final position replay to the bit."""
    record = load_game(path)
    env = replay(record)
    assert env.unwrapped.balls.xy.tolist() == record["outcomes"][-1]["xy"]
    env.close()
