"""Videos a viewer understands: the overlay, cue lines, result cards, readable numbers, saved games from filming."""

import gymnasium as gym
import numpy as np
import pytest

import pool_env
from pool_env.envs.break_env import PoolBreakEnv
from pool_env.records.saved import load_game, replay
from pool_env.records.video import HOLD_SECONDS, video_frames
from pool_env.records.video_overlay import CARD_SECONDS, CUE_SECONDS
from pool_env.render.overlay import overlay
from pool_env.render.overlay import overlay as games_overlay
from pool_env.render.playback import frame_times

SHOT = np.array([0.6, 0.02], dtype=np.float32)
FPS = 20


def play_once(fps=FPS):
    """The break on seed 3 with SHOT: its frames from `shot_frames` and its duration."""
    env = PoolBreakEnv()
    env.reset(seed=3)
    info = env.step(SHOT)[4]
    return env.shot_frames(fps), info


def test_overlay_false_gives_the_old_frames_exactly():
    frames, _ = play_once()
    got = list(video_frames(PoolBreakEnv(), lambda obs: SHOT, fps=FPS, seed=3, overlay=False))
    assert len(got) == len(frames) + round(HOLD_SECONDS * FPS)
    assert all(np.array_equal(a, b) for a, b in zip(got, frames, strict=False))
    assert np.array_equal(got[-1], frames[-1])


def test_cue_line_frames_come_before_the_first_moving_frame():
    frames, info = play_once()
    got = list(video_frames(PoolBreakEnv(), lambda obs: SHOT, fps=FPS, seed=3))
    cue = round(CUE_SECONDS * FPS)
    moving = len(frame_times(info["shot_duration"], FPS)) - 1
    assert len(got) == cue + moving + round(CARD_SECONDS * FPS)
    # The cue frames are all the same still, the starting table with the cue line drawn on it.
    assert all(np.array_equal(got[0], got[k]) for k in range(cue))
    band = slice(0, 300)  # above the bottom caption band
    assert not np.array_equal(got[0][band], frames[0][band])  # the cue line
    assert not np.array_equal(got[cue - 1][band], got[cue][band])  # then the balls move
    # Frame cue + k is the shot's frame k + 1, with the caption at the bottom only.
    assert np.array_equal(got[cue][band], frames[1][band])
    assert not np.array_equal(got[cue][320:], frames[1][320:])


def test_the_overlay_draws_text_in_its_band():
    frames, _ = play_once()
    frame = frames[-1]
    top, bottom = overlay(frame, ["episode 1  shot 1"]), overlay(frame, ["x"], where="bottom")
    assert not np.array_equal(top[:20, :120], frame[:20, :120]) and np.array_equal(top[40:], frame[40:])
    assert not np.array_equal(bottom[-20:, :40], frame[-20:, :40]) and np.array_equal(bottom[:-40], frame[:-40])
    assert games_overlay is overlay  # the games' old import still works
    assert overlay(frame, []) is frame


def test_scratch_and_result_card_are_told():
    from pool_env.records.video_overlay import episode_result, shot_summary

    assert shot_summary({"pocketed": [3], "scratch": True}) == "pocketed 3; cue ball pocketed (scratch)"
    assert shot_summary({"pocketed": [], "foul": "wrong_ball_first"}) == "nothing pocketed; foul: wrong ball first"
    lines = episode_result(PoolBreakEnv(), 2, {}, 2.0, 3, 3, 1)
    assert lines[:2] == ["episode 2", "3 balls in 3 shots, 1 scratch"]


def test_numbers_are_drawn_at_the_ball_centre():
    from pool_env.render.table import TEXT_RGB

    renderer = PoolBreakEnv().playback.renderer  # the default table at 640 x 360
    xy = np.array([[0.2 + 0.14 * k, 0.6] for k in range(16)])
    frame = renderer.draw(xy, np.zeros(16, dtype=bool))
    for ball in (0, 1, 9, 12):
        col, row = (int(v) for v in renderer.world_to_pixel(xy[ball])[0])
        patch = frame[row - 3 : row + 4, col - 3 : col + 4].astype(int)
        dark = np.all(np.abs(patch - TEXT_RGB) < 40, axis=2).sum()
        assert (dark >= 5) if ball else (dark == 0), ball  # digits on the numbered balls, none on the cue ball
    # One-digit numbers use the tall 4x7 digits at 640 x 360: 7 rows of ink.
    col, row = (int(v) for v in renderer.world_to_pixel(xy[1])[0])
    ink = np.all(np.abs(frame[row - 6 : row + 7, col - 6 : col + 7].astype(int) - TEXT_RGB) < 40, axis=2)
    assert np.ptp(np.flatnonzero(ink.any(axis=1))) + 1 == 7


@pytest.mark.parametrize("env_id, kwargs", [("PoolBreakRun-v0", {}), ("PoolNineBall-v0", {"opponent": "random"}),
                                            ("PoolNineBall-v0", {"opponent": lambda obs: np.full(6, 0.3)})])
def test_record_video_saves_games_that_replay(tmp_path, env_id, kwargs):
    env = gym.make(env_id, render_size=(160, 90), max_shots=3, **kwargs)
    rng = np.random.default_rng(0)
    policy = lambda obs: rng.uniform(-1, 1, env.action_space.shape)  # float64: saved as the float32 stepped
    written = pool_env.record_video(env, policy, tmp_path / "v.mp4", episodes=2, seed=5, save_games=tmp_path / "g")
    assert written > 0
    for k in range(2):
        record = load_game(tmp_path / "g" / f"v-episode-{k}.json")
        assert record["seed"] == 5 + k and record["actions"]
        replay(record)  # raises ReplayMismatch at any difference


def test_tournament_saves_games_that_replay(tmp_path):
    from agents.tournament import tournament

    tournament("nine_ball", ("random", "ghost_ball"), games=2, noise="none", seed=0, save_games=tmp_path)
    paths = sorted((tmp_path / "nine_ball" / "none").glob("*.json"))
    assert [p.name for p in paths] == ["ghost_ball-vs-random-seed1.json", "random-vs-ghost_ball-seed0.json"]
    for path in paths:
        record = load_game(path)
        assert record["env_kwargs"]["opponent"] == "recorded" and record["players"][0] in path.name
        replay(record)


def test_the_title_card_and_captions_number_episodes_as_the_saved_files_do(tmp_path, monkeypatch):
    import pool_env.records.video_overlay as video_overlay

    cards, captions = [], []
    monkeypatch.setattr(video_overlay, "card", lambda frame, lines: cards.append(lines) or frame)
    real_overlay = video_overlay.overlay
    monkeypatch.setattr(video_overlay, "overlay",
                        lambda frame, lines, **kw: captions.append(lines[0]) or real_overlay(frame, lines, **kw))
    env = gym.make("PoolBreak-v0", render_size=(160, 90))
    frames = list(video_frames(env, lambda obs: SHOT, episodes=2, fps=FPS, seed=5, save_games=tmp_path, name="v"))
    assert frames and sorted(p.name for p in tmp_path.iterdir()) == ["v-episode-0.json", "v-episode-1.json"]
    assert {lines[0] for lines in cards} == {"episode 0", "episode 1"}  # as the files: from 0
    assert captions[0].startswith("episode 0") and captions[-1].startswith("episode 1")


def test_the_caption_of_a_640_x_360_video_stays_off_the_cloth():
    from pool_env.records.video_overlay import Story

    env = gym.make("PoolBreak-v0")  # one shot a step: its frames are the caption's, one to one
    base = env.unwrapped
    env.reset(seed=3)
    info = env.step(SHOT)[4]
    story = Story(base, 0, FPS)
    frames = base.shot_frames(FPS)
    told = story.step(frames, info, 0.0, True)
    left, top, right, bottom = base.playback.renderer.cloth_box()
    cloth = (slice(int(top) + 1, int(bottom)), slice(int(left) + 1, int(right)))  # whole pixels of cloth
    assert frames[0].shape == (360, 640, 3) and story.caption_rows(frames[0]) == 360 - int(np.ceil(bottom))
    # Every captioned frame is the env's frame on the cloth: the caption sits under it, on the rail.
    bare = frames[1:]  # the moving frames (the first one is the cue line's)
    moving = told[round(CUE_SECONDS * FPS):]
    assert len(moving) == len(bare)
    assert len(story.last) >= 1  # what the last shot did is told, so the band has text to fit
    assert all(np.array_equal(a[cloth], b[cloth]) for a, b in zip(moving, bare, strict=True))
    assert any(not np.array_equal(a[int(np.ceil(bottom)):], b[int(np.ceil(bottom)):]) for a, b in zip(moving, bare))
