"""The envs' obs_type: pixels equal the renderer's frame, dict round-trips the state vector, text names the
shot's events, both checkers silent, SB3 learns from pixels and dict."""

import warnings

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the ids)
from pool_env.envs.dict_obs import BALL_IN_HAND, GROUPS
from pool_env.envs.obs_types import TextCodes, text_codes, text_of
from pool_env.physics import Balls
from pool_env.render.pixels import LUMA_WEIGHTS, grayscale
from pool_env.render.table import TableRenderer, game_palette

IDS = ["PoolBreak-v0", "PoolBreakRun-v0", "PoolNineBall-v0", "PoolEightBall-v0", "PoolTenBall-v0", "Snooker-v0",
       "ThreeCushion-v0"]


def reference_frame(env, size, gray=False):
    """The renderer's frame of the env's balls now at `size`: what a pixel observation must equal."""
    game = env.unwrapped.game
    t = game.table
    frame = TableRenderer(t.length, t.width, t.pockets, float(np.max(game.balls.radii)), size,
                          game_palette(game.mode)).draw(game.balls.xy, game.balls.pocketed)
    return grayscale(frame) if gray else frame


def scene(positions):
    """16 balls at rest with only the given {ball: (x, y)} on the table; the rest pocketed, parked apart."""
    xy = np.array([(0.1 + 0.07 * i, 0.5) for i in range(16)])
    pocketed = np.ones(16, dtype=bool)
    for i, p in positions.items():
        xy[i], pocketed[i] = p, False
    return Balls(xy, pocketed=pocketed)


# --- pixels -------------------------------------------------------------------------------------
@pytest.mark.parametrize("env_id", ["PoolBreakRun-v0", "PoolNineBall-v0", "Snooker-v0", "ThreeCushion-v0"])
@pytest.mark.parametrize("size", [(84, 84), (96, 96)])
@pytest.mark.parametrize("gray", [False, True])
def test_pixels_equal_the_renderers_frame(env_id, size, gray):
    env = gym.make(env_id, obs_type="pixels", obs_size=size, grayscale=gray)
    assert env.observation_space.shape == (size[1], size[0], 1 if gray else 3)
    assert env.observation_space.dtype == np.uint8
    obs, _ = env.reset(seed=1)
    assert np.array_equal(obs, reference_frame(env, size, gray))
    for _ in range(2):
        obs, _, terminated, truncated, _ = env.step(env.action_space.sample())
        assert np.array_equal(obs, reference_frame(env, size, gray))
        if terminated or truncated:
            break


def test_pixels_show_the_balls():
    """A frame with balls differs from the empty table where the balls are (the test above could
    pass on two blank frames)."""
    env = gym.make("PoolBreakRun-v0", obs_type="pixels", obs_size=(96, 96))
    obs, _ = env.reset(seed=0)
    renderer = env.unwrapped.observer.frames.renderer
    changed = np.flatnonzero((obs != renderer.background).any(axis=2).any(axis=1))
    ball_rows = np.floor(renderer.world_to_pixel(env.unwrapped.balls.xy)[:, 1]).astype(int)
    assert len(changed) > 0 and set(ball_rows) <= set(range(changed.min() - 1, changed.max() + 2))


def test_grayscale_is_bt601_luma():
    rgb = np.random.default_rng(0).integers(0, 256, (1, 50, 3), dtype=np.uint8)
    gray = grayscale(rgb)[0, :, 0].astype(float)
    exact = rgb[0].astype(float) @ np.array([0.299, 0.587, 0.114])
    assert np.abs(gray - exact).max() <= 1.0 and sum(LUMA_WEIGHTS) == 256
    assert grayscale(np.full((1, 1, 3), 255, np.uint8))[0, 0, 0] == 255


@pytest.mark.parametrize("env_id", ["PoolBreakRun-v0", "PoolNineBall-v0"])
def test_native_vector_env_renders_every_frame_in_one_batch(env_id):
    envs = gym.make_vec(env_id, num_envs=3, vectorization_mode="vector_entry_point", obs_type="pixels",
                        autoreset_mode="SameStep")
    obs, _ = envs.reset(seed=0)
    assert obs.shape == (3, 84, 84, 3) and envs.observation_space.contains(obs)
    for _ in range(2):
        obs, _, terminated, truncated, infos = envs.step(envs.action_space.sample())
        for k, sub in enumerate(envs.unwrapped.envs):
            assert np.array_equal(obs[k], reference_frame(sub, (84, 84)))
            if terminated[k] or truncated[k]:
                assert infos["final_obs"][k].shape == (84, 84, 3)


def test_bad_obs_type_and_size_are_refused():
    with pytest.raises(ValueError, match="obs_type must be one of"):
        gym.make("PoolBreak-v0", obs_type="image")
    with pytest.raises(ValueError, match="at least 8 x 8"):
        gym.make("PoolBreak-v0", obs_type="pixels", obs_size=(4, 84))


# --- dict ---------------------------------------------------------------------------------------
def state_of(env):
    env = env.unwrapped
    return env.observe() if hasattr(env, "observe") and not hasattr(env, "observation") else env.observation()


@pytest.mark.parametrize("env_id", IDS)
def test_dict_is_the_state_vectors_view(env_id):
    """Positions in metres, on-table flags and the shot counter read back from the state vector."""
    env = gym.make(env_id, obs_type="dict")
    obs, _ = env.reset(seed=0)
    env.action_space.seed(0)  # the same shot every run
    obs, *_ = env.step(env.action_space.sample())
    assert env.observation_space.contains(obs)
    state = state_of(env)
    table = env.unwrapped.game.table
    balls = env.unwrapped.game.balls
    on = ~balls.pocketed
    assert np.array_equal(obs["on_table"].astype(bool), on)
    # a ball hanging in a pocket's mouth has its centre past the cushion line: the view clips it to the edge
    x, y = np.clip(balls.xy[:, 0], 0.0, table.length), np.clip(balls.xy[:, 1], 0.0, table.width)
    assert np.allclose(obs["x"][on], x[on], atol=1e-5) and np.allclose(obs["y"][on], y[on], atol=1e-5)
    assert np.all(obs["x"][~on] == 0.0)
    assert obs["shots"][0] == np.float32(state[-1])
    if env_id != "ThreeCushion-v0" and env_id not in ("PoolBreak-v0", "PoolBreakRun-v0"):
        legal = env.unwrapped.game.legal_targets if env.unwrapped.game.shooter == 0 else frozenset()
        assert set(np.flatnonzero(obs["legal"]) + 1) == set(legal) or env.unwrapped.game.over
    assert table.length > 0


def test_dict_names_the_rules_state():
    env = gym.make("PoolEightBall-v0", obs_type="dict", decisions=True)
    obs, _ = env.reset(seed=0, options={"ball_in_hand": True})
    # The agent breaks: its cue ball is in hand behind the head string (Game.reset).
    assert obs["ball_in_hand"] == BALL_IN_HAND.index("behind_head_string") and obs["group"] == GROUPS.index(None)
    assert obs["pending"] == 0
    assert list(obs["fouls"]) == [0, 0]


# --- text ---------------------------------------------------------------------------------------
def corner_pocket(table, x, y) -> int:
    return int(np.argmin(np.hypot(table.pockets[:, 0] - x, table.pockets[:, 1] - y)))


def test_text_names_a_pot_and_its_pocket():
    """Ball 1 straight into the far corner: the text names the first contact, the ball and its pocket."""
    env = gym.make("PoolBreakRun-v0", obs_type="text", spin=True)
    table = env.unwrapped.table
    d = np.array([2.0, 1.0]) / np.sqrt(5.0)  # towards the corner (L, W) from (1.40, 0.70)
    cue, one = np.array([1.40, 0.70]), np.array([1.40, 0.70]) + 0.30 * d
    env.reset(seed=0, options={"balls": scene({0: cue, 1: one})})
    text, *_ = env.step([0.35 * d[0], 0.35 * d[1], 0.0, -1.0])  # a draw shot: the cue ball comes back
    assert "first contact: ball 1" in text
    assert f"ball 1 in pocket {corner_pocket(table, table.length, table.width)}" in text
    on_table = next(line for line in text.splitlines() if line.startswith("on the table"))
    assert "ball 1 (" not in on_table
    assert env.unwrapped.render_mode is None


def test_text_names_a_scratch_and_no_contact():
    env = gym.make("PoolBreakRun-v0", obs_type="text")
    table = env.unwrapped.table
    env.reset(seed=0, options={"balls": scene({0: (0.30, 0.30), 5: (1.5, 0.9)})})
    d = -np.array([0.30, 0.30]) / np.hypot(0.30, 0.30)  # straight at the corner (0, 0)
    text, *_ = env.step(0.3 * d)
    assert "first contact: none" in text
    assert f"cue ball in pocket {corner_pocket(table, 0.0, 0.0)}" in text
    assert "foul: scratch" in text


def test_text_names_the_rules_foul_and_ansi_renders_it():
    env = gym.make("PoolNineBall-v0", obs_type="text", opponent=None, info_mode="rich", render_mode="ansi")
    env.reset(seed=0)
    text, *_, info = env.step(np.array([-0.3, 0.0, 0.0, 0.0, 0.0, 0.0], dtype=np.float32))  # away from the rack
    record = info["records"][0]
    assert record.ruling.foul is not None  # the rack is ahead: the cue ball runs away from it
    assert f"foul: {', '.join(record.ruling.fouls)}" in text
    assert all(f"referee: {m}" in text for m in record.ruling.messages)
    assert env.render() == text


@pytest.mark.parametrize("env_id", ["PoolBreakRun-v0", "Snooker-v0", "ThreeCushion-v0"])
def test_text_codes_round_trip(env_id):
    env = TextCodes(gym.make(env_id, obs_type="text"))
    codes, _ = env.reset(seed=0)
    assert codes.dtype == np.uint8 and text_of(codes) == env.unwrapped.text_observer.observe(env.unwrapped)
    assert np.array_equal(text_codes(text_of(codes)), codes)


# --- the checkers, silently -----------------------------------------------------------------
@pytest.mark.parametrize("env_id", IDS)
@pytest.mark.parametrize("obs_type", ["pixels", "dict", "text"])
def test_checkers_pass_without_warnings(env_id, obs_type):
    from gymnasium.utils.env_checker import check_env as gym_check
    from stable_baselines3.common.env_checker import check_env as sb3_check

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        env = gym.make(env_id, obs_type=obs_type)
        gym_check(env.unwrapped)
        sb3_check(TextCodes(env) if obs_type == "text" else env, warn=True)
        env.close()
    assert [str(w.message) for w in caught] == []


def test_sb3_checker_refuses_a_bare_text_space():
    """Why "text" goes to SB3 through TextCodes: its checker asks for numpy arrays."""
    from stable_baselines3.common.env_checker import check_env as sb3_check

    with pytest.raises(AssertionError, match="numpy array"):
        sb3_check(gym.make("PoolBreak-v0", obs_type="text"), warn=False)


# --- SB3 learns from them -------------------------------------------------------------------------
@pytest.mark.parametrize("policy, obs_type", [("CnnPolicy", "pixels"), ("MultiInputPolicy", "dict")])
def test_sb3_trains_on(policy, obs_type):
    from stable_baselines3 import PPO

    from pool_env.envs.sb3 import SB3VecEnv

    envs = SB3VecEnv("PoolBreak-v0", num_envs=4, threads=1, obs_type=obs_type)
    model = PPO(policy, envs, n_steps=32, batch_size=64, n_epochs=1, seed=0, device="cpu")
    before = [p.detach().clone() for p in model.policy.parameters()]
    model.learn(256)
    assert model.num_timesteps >= 256
    assert any(not np.array_equal(a.numpy(), p.detach().numpy()) for a, p in zip(before, model.policy.parameters()))
    action, _ = model.predict(envs.reset(), deterministic=True)
    assert action.shape == (4, 2)
