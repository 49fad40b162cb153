"""The elevated cue above the physics: `Shot.elevation`, the "+elevation" action layouts, the
envs' `elevation=True`, the noise on an elevated shot, the rules on a ball jumped off the
table and the airborne ball's shadow. (The flight itself: tests/test_elevated.py.)"""

import math

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the ids)
from pool_env.game import ELEVATED, LAYOUTS, Game, Shot, decode_action, encode_action, noise_of, noisy_shot
from pool_env.physics import Balls
from pool_env.physics.cue import MAX_ELEVATION
from pool_env.render.table import SHADOW_SLANT, TableRenderer

IDS = ("PoolBreak-v0", "PoolBreakRun-v0", "PoolNineBall-v0", "PoolEightBall-v0")
LEVEL_SIZES = {"PoolBreak-v0": 2, "PoolBreakRun-v0": 2, "PoolNineBall-v0": 6, "PoolEightBall-v0": 8}
AREA = (0.1, 0.5, 0.1, 1.0)


@pytest.mark.parametrize("elevation", [-0.01, MAX_ELEVATION * 1.001, math.nan, math.inf])
def test_a_shot_elevation_outside_0_to_85_degrees_is_refused(elevation):
    with pytest.raises(ValueError, match="Shot.elevation"):
        Shot((100.0, 0.0), elevation=elevation)


@pytest.mark.parametrize("name", [name for name in LAYOUTS if name.endswith(ELEVATED)])
def test_an_elevated_layout_reads_back_what_it_writes(name):
    layout = LAYOUTS[name]
    level = LAYOUTS[name[:-len(ELEVATED)]]
    assert layout.size == level.size + 1 and layout.elevation and not level.elevation
    shot = Shot.aimed((0.6, -0.8), 7.0, tip=(0.2, -0.1) if layout.spin else (0.0, 0.0),
                      place=(0.3, 0.4) if layout.placement else None,
                      pocket=4 if layout.called_pocket else None, elevation=math.radians(33.0))
    back = decode_action(layout, encode_action(layout, shot, AREA), AREA)
    assert back.elevation == pytest.approx(shot.elevation, rel=1e-6)
    assert back.force == pytest.approx(shot.force, rel=1e-6) and back.tip == pytest.approx(shot.tip, abs=1e-7)
    assert back.pocket == shot.pocket


@pytest.mark.parametrize("entry, degrees",
                         [(-1.0, 0.0), (-0.3, 0.0), (0.0, 0.0), (0.5, 42.5), (1.0, 85.0), (3.0, 85.0)])
def test_the_elevation_entry_is_level_at_or_below_zero_and_linear_above(entry, degrees):
    shot = decode_action(LAYOUTS["nine_ball" + ELEVATED], [0.5, 0.0, 0.0, 0.0, 0.0, 0.0, entry], AREA)
    assert math.degrees(shot.elevation) == pytest.approx(degrees, abs=1e-9)


@pytest.mark.parametrize("env_id", IDS)
def test_elevation_adds_one_last_action_entry(env_id):
    env = gym.make(env_id, elevation=True)
    assert env.action_space.shape == (LEVEL_SIZES[env_id] + 1,)
    assert gym.make(env_id).action_space.shape == (LEVEL_SIZES[env_id],)


@pytest.mark.parametrize("env_id", IDS)
def test_an_elevated_env_cued_level_plays_exactly_as_the_level_env(env_id):
    # An elevation entry <= 0 is a level cue, and the opponent cues level in both: every step
    # (the opponent's shots inside it included) must be the level env's, bit for bit.
    elevated, level = gym.make(env_id, elevation=True), gym.make(env_id)
    o1, _ = elevated.reset(seed=5)
    o2, _ = level.reset(seed=5)
    assert np.array_equal(o1, o2)
    rng = np.random.default_rng(1)
    for _ in range(6):
        a = rng.uniform(-1, 1, LEVEL_SIZES[env_id]).astype(np.float32)
        s1 = elevated.step(np.append(a, np.float32(-rng.uniform())))
        s2 = level.step(a)
        assert np.array_equal(s1[0], s2[0]) and s1[1:4] == s2[1:4]
        if s1[2] or s1[3]:
            break


def test_olympiad_noise_draws_an_elevation_only_for_an_elevated_shot():
    # The noise draws four normals for a level shot (aim, speed, side, top) and a fifth, the
    # elevation's (sd 0.1 deg, FastFiz's theta noise), for an elevated one.
    noise = noise_of("olympiad")
    assert noise["elevation"] == pytest.approx(math.radians(0.1))
    force, tip = np.array((200.0, 0.0)), np.array((0.0, 0.0))
    for elevation, draws in ((0.0, 4), (math.radians(20.0), 5)):
        rng, reference = np.random.default_rng(7), np.random.default_rng(7)
        _, _, noisy = noisy_shot(force, tip, noise, rng, elevation)
        reference.normal(size=draws)
        assert rng.normal() == reference.normal()
        assert (noisy == 0.0) == (elevation == 0.0)
    _, _, noisy = noisy_shot(force, tip, noise, np.random.default_rng(3), math.radians(20.0))
    assert abs(noisy - math.radians(20.0)) < 5 * math.radians(0.1)


def test_a_cue_ball_jumped_off_the_table_is_a_foul_and_ball_in_hand():
    # WPA 6.1: the cue ball driven off the table is a foul; the incoming player has ball in
    # hand anywhere (9-ball). A steep, hard cue 10 cm from the foot rail sends it over.
    game = Game("nine_ball", seed=0)
    xy = np.full((10, 2), np.nan)
    xy[:, 1] = 0.15 + 0.09 * np.arange(10)
    xy[:, 0] = 1.2
    xy[0] = (2.14, 0.56)
    game.reset(balls=Balls(xy))
    record = game.play(Shot.aimed((1.0, 0.0), 6.0, elevation=math.radians(60.0)))
    assert any(e.kind == "ball_off_table" and e.i == 0 for e in record.result.events)
    assert record.outcome.off_table == (0,) and record.ruling.foul
    assert game.shooter == 1 and game.ball_in_hand == "anywhere"


def test_an_airborne_ball_casts_its_shadow_slant_times_its_height_away():
    renderer = TableRenderer(2.24, 1.12, np.empty((0, 3)), 0.028575, size=(640, 360))
    xy, pocketed = np.array([[1.12, 0.56]]), np.array([False])
    resting = renderer.draw(xy, pocketed)
    assert np.array_equal(renderer.draw(xy, pocketed, heights=np.zeros(1)), resting)
    h = 0.1
    flying = renderer.draw(xy, pocketed, heights=np.array([h])).astype(int)
    darker = (resting.astype(int) - flying).sum(axis=2) > 30  # the shadow: darker than the cloth was
    rows, cols = np.nonzero(darker)
    centre = renderer.world_to_pixel(xy)[0]
    shift = SHADOW_SLANT * h * renderer.scale  # down and to the right on the image
    assert cols.mean() == pytest.approx(centre[0] + shift, abs=1.0)
    assert rows.mean() == pytest.approx(centre[1] + shift, abs=1.0)
