"""randomize=: draws in range and by seed, bad specs refused, per-scene batches, saved games, the checkers."""

import dataclasses
import importlib.util
import json
import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import pool_env  # noqa: F401  (registers the ids)
from pool_env.game import Game, Shot
from pool_env.physics import Physics, Table, simulate, simulate_batch, strike
from pool_env.physics.randomize import DEFAULTS, INCH, OUNCE, PHYSICS_NAMES, Randomization
from pool_env.records.saved import ReplayMismatch, load_game, record_game, replay, save_game

EQUIPMENT = {"nine_ball": "pool", "eight_ball": "pool", "ten_ball": "pool", "break": "pool",
             "three_cushion": "carom", "snooker": "snooker"}


def silent(check, env):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check(env)
    assert not [str(w.message) for w in caught]


def test_the_pool_defaults_are_the_wpa_and_alciatore_figures():
    pool = DEFAULTS["pool"]
    # WPA Equipment Specifications: ball 2.25 +- 0.005 in across, 5.5-6 oz; corner mouth
    # 4.5-4.625 in, side mouth 5-5.125 in.
    assert pool["ball_radius"] == pytest.approx((2.245 / 2 * INCH, 2.255 / 2 * INCH))
    assert pool["ball_mass"] == pytest.approx((0.1559, 0.1701), abs=1e-4)
    assert pool["corner_mouth"] == pytest.approx((0.1143, 0.117475))
    assert pool["side_mouth"] == pytest.approx((0.127, 0.130175))
    # Alciatore: sliding 0.15-0.4, rolling 0.005-0.015, ball-ball restitution 0.92-0.98.
    assert (pool["mu_s"], pool["mu_r"], pool["e_b"]) == ((0.15, 0.4), (0.005, 0.015), (0.92, 0.98))
    # UMB 2.2: carom balls 61-61.5 mm, 205-220 g.
    assert DEFAULTS["carom"]["ball_radius"] == pytest.approx((0.0305, 0.03075))
    assert DEFAULTS["carom"]["ball_mass"] == pytest.approx((0.205, 0.220))
    assert 5.5 * OUNCE == pytest.approx(0.155922, abs=1e-6)


@pytest.mark.parametrize("mode", list(EQUIPMENT))
def test_default_draws_stay_in_their_ranges_for_every_game(mode):
    ranges = DEFAULTS[EQUIPMENT[mode]]
    game = Game(mode, seed=0, randomize="default")
    seen = set()
    for seed in range(20):
        game.reset(seed=seed)
        sample = game.sample
        for name, (low, high) in ranges.items():
            values = np.atleast_1d(sample.values[name])
            assert np.all((values >= low) & (values <= high)), name
        seen.add(game.physics.mu_s)
        info = sample.info()
        assert info["physics"]["mu_s"] == game.physics.mu_s
        assert np.array_equal(game.balls.radii, info["ball_radius"]) and len(info["ball_mass"]) == game.n_balls
        assert np.array_equal(game.balls.masses, info["ball_mass"])
        assert game.table.cushion_height == info["table"]["cushion_height"]
        assert np.all(game.table.cushion_height < 2 * game.balls.radii)
    assert len(seen) == 20  # every reset draws afresh


def test_draws_are_deterministic_by_seed_and_differ_between_seeds():
    def drawn(seed):
        game = Game("nine_ball", seed=seed, randomize="default")
        return game.sample.values, game.balls.xy.tolist()

    assert drawn(5) == drawn(5)
    assert drawn(5)[0] != drawn(6)[0]


@pytest.mark.parametrize("env_id", ["PoolNineBall-v0", "PoolEightBall-v0", "ThreeCushion-v0", "Snooker-v0"])
def test_episodes_against_a_built_in_opponent_repeat_by_seed(env_id):
    # The opponent plans on the equipment the env was made with, never on a draw (a draw made
    # while the env was built came from no seed: two envs of one seed then played apart).
    def episode():
        env = gym.make(env_id, randomize="default")
        env.action_space.seed(3)
        env.reset(seed=100)
        out = []
        for _ in range(3):
            obs, reward, terminated, truncated, _ = env.step(env.action_space.sample())
            out.append((obs.tobytes(), reward))
            if terminated or truncated:
                break
        return out

    assert episode() == episode()


def test_the_equipment_is_drawn_first_from_the_games_generator_as_rng_uniform_draws_it():
    # One call of rng.random for every uniform range: the values rng.uniform(low, high) gives
    # each parameter in turn (NAMES order, a ball's radius and mass one draw per ball).
    game = Game("break", randomize="default")
    game.reset(seed=11)
    rng, expected = np.random.default_rng(11), {}
    for d in game.randomization.draws:
        per_ball = d.name in ("ball_radius", "ball_mass")
        value = rng.uniform(d.low, d.high, game.n_balls if per_ball else None)
        expected[d.name] = tuple(value.tolist()) if per_ball else float(value)
    assert game.sample.values == expected
    assert game.physics.mu_s == expected["mu_s"] and game.table.pocket_entries[0, 2] == expected["corner_mouth"]
    assert game.table.pocket_entries[4, 2] == expected["side_mouth"] and game.balls.masses.tolist() == list(
        expected["ball_mass"])
    scaled = game.randomization.scaled(game.sample)
    assert scaled[0] == np.float32(2.0 * (expected["mu_s"] - 0.15) / (0.4 - 0.15) - 1.0)
    assert scaled.dtype == np.float32 and np.all(np.abs(scaled) <= 1.0)


def test_a_spec_with_a_normal_draws_each_parameter_in_turn():
    spec = {"mu_s": {"normal": (0.2, 0.05), "clip": (0.15, 0.25)}, "e_c": (0.6, 0.9), "ball_mass": (0.16, 0.17)}
    randomization = Randomization(spec, Table.eight_foot(), Physics(), 16)
    sample = randomization.sample(np.random.default_rng(2))
    rng = np.random.default_rng(2)
    assert sample.values["mu_s"] == float(np.clip(rng.normal(0.2, 0.05), 0.15, 0.25))
    assert sample.values["e_c"] == rng.uniform(0.6, 0.9) == sample.physics.e_c
    assert sample.values["ball_mass"] == tuple(rng.uniform(0.16, 0.17, 16).tolist())
    assert sample.radii is None and sample.table is randomization.table


def test_without_randomize_nothing_is_drawn_and_the_rack_is_unchanged():
    plain = Game("nine_ball", seed=4)
    assert plain.sample is None and plain.table is plain.base_table
    again = Game("nine_ball", seed=4)
    assert plain.balls.xy.tolist() == again.balls.xy.tolist()
    env = gym.make("PoolNineBall-v0")
    _, info = env.reset(seed=0)
    assert "physics" not in info and "table" not in info


def test_a_normal_draw_is_clipped_and_the_other_parameters_keep_their_values():
    spec = {"mu_s": {"normal": (0.2, 0.5), "clip": (0.15, 0.25)}}
    game = Game("break", seed=0, randomize=spec)
    values = []
    for seed in range(50):
        game.reset(seed=seed)
        values.append(game.physics.mu_s)
        assert game.physics.e_b == Physics().e_b and game.table is game.base_table
    assert min(values) == 0.15 and max(values) == 0.25  # sd 0.5: many draws hit the clip


@pytest.mark.parametrize("spec, message", [
    ({"mu_q": (0.1, 0.2)}, "unknown parameter 'mu_q'"),
    ({"mu_s": (0.3, 0.2)}, "empty or inverted"),
    ({"mu_s": (0.2, 0.2)}, "empty or inverted"),
    ({"mu_s": (0.2, float("nan"))}, "must be finite"),
    ({"mu_s": 0.2}, "pair of numbers"),
    ({"mu_s": {"normal": (0.2, 0.01)}}, "'normal': (mean, sd), 'clip'"),
    ({"mu_s": {"normal": (0.2, 0.0), "clip": (0.1, 0.3)}}, "sd must be > 0"),
    ({"mu_s": {"normal": (0.5, 0.1), "clip": (0.1, 0.3)}}, "outside its clip"),
    ({"e_b": (0.9, 1.2)}, "Physics.e_b must be in [0, 1]"),
    ({"ball_radius": (0.015, 0.02)}, "pass under a cushion nose"),
    ({"ball_mass": (-0.1, 0.2)}, "every ball's mass must be > 0"),
    ({"corner_mouth": (0.1, 0.9)}, "invalid game"),
    ({}, "non-empty dict"),
    ("measured", "'default'"),
])
def test_bad_specs_are_refused_at_construction_naming_the_problem(spec, message):
    with pytest.raises(ValueError) as caught:
        Game("nine_ball", randomize=spec)
    assert message in str(caught.value)


def test_pocket_sizes_have_nothing_to_size_on_a_carom_table():
    with pytest.raises(ValueError, match="no pockets"):
        Randomization({"corner_mouth": (0.11, 0.12)}, Table.carom(), Physics.carom(), 3)


def test_simulate_batch_with_a_table_and_physics_per_scene_is_bit_identical_to_simulate():
    tables, physics, scenes = [], [], []
    game = Game("break", seed=0, randomize="default")
    for seed in range(4):
        game.reset(seed=seed)
        tables.append(game.table)
        physics.append(game.physics)
        scenes.append(strike(game.balls, (300.0, 4.0), physics=game.physics))
    batch = simulate_batch(scenes, tables, physics, threads=2)
    for k in range(4):
        alone = simulate(scenes[k], tables[k], physics[k])
        assert np.array_equal(batch[k].final.xy, alone.final.xy)
        assert [e.time for e in batch[k].events] == [e.time for e in alone.events]
    with pytest.raises(ValueError, match="3 tables for 4 scenes"):
        simulate_batch(scenes, tables[:3], physics)


@pytest.mark.parametrize("env_id", ["PoolBreak-v0", "PoolNineBall-v0"])
def test_the_native_vector_env_runs_sub_envs_with_different_equipment_in_one_batch(env_id):
    kwargs = dict(randomize="default") if env_id == "PoolBreak-v0" else dict(randomize="default", opponent="random")
    native = gym.make_vec(env_id, 3, vectorization_mode="vector_entry_point", **kwargs)
    _, infos = native.reset(seed=10)
    assert len(set(infos["physics"]["mu_s"].tolist())) == 3
    actions = np.tile(np.linspace(0.9, -0.3, native.single_action_space.shape[0]), (3, 1)).astype(np.float32)
    obs, rewards, *_ = native.step(actions)
    for k in range(3):
        env = gym.make(env_id, **kwargs)
        _, info = env.reset(seed=10 + k)
        assert info["physics"]["mu_s"] == infos["physics"]["mu_s"][k]
        alone = env.step(actions[k])
        assert np.array_equal(alone[0], obs[k]) and alone[1] == rewards[k]


def test_a_randomized_saved_game_replays_and_a_changed_draw_is_refused():
    env = gym.make("PoolBreakRun-v0", randomize={"mu_s": (0.15, 0.4), "ball_mass": (0.16, 0.17)})
    record = record_game(env, lambda obs: np.array([0.9, 0.05], np.float32), seed=7, max_steps=3)
    record = json.loads(json.dumps(record))
    assert record["sampled"]["physics"]["mu_s"] != Physics().mu_s and len(record["sampled"]["ball_mass"]) == 16
    assert record["physics"] == dataclasses.asdict(Physics())  # the base, drawn from at each reset
    replay(record)
    record["sampled"]["physics"]["mu_s"] += 1e-9
    with pytest.raises(ReplayMismatch, match="randomize drew"):
        replay(record)


def test_a_randomized_game_saved_before_version_4_is_refused(tmp_path):
    # Version 3 drew the equipment from a generator of its own: its resets cannot be drawn again.
    env = gym.make("PoolBreak-v0", randomize={"mu_s": (0.15, 0.4)})
    record = json.loads(json.dumps(record_game(env, lambda obs: np.array([0.9, 0.0], np.float32), seed=1)))
    assert record["version"] == 4 and "sampled" in record
    old = {**record, "version": 3}
    path = save_game(tmp_path / "old.json", old)
    with pytest.raises(ValueError, match="old.json: a randomized game saved by saved-game version 3 .* cannot be "
                                         "drawn again"):
        load_game(path)
    with pytest.raises(ValueError, match="cannot be drawn again"):
        replay(old)
    replay(record)


@pytest.mark.parametrize("env_id", ["PoolBreak-v0", "PoolNineBall-v0", "ThreeCushion-v0", "Snooker-v0"])
def test_the_gymnasium_checker_is_silent_with_randomize_on(env_id):
    kwargs = {"opponent": "random"} if env_id != "PoolBreak-v0" else {}
    silent(check_env, gym.make(env_id, randomize="default", **kwargs).unwrapped)


@pytest.mark.skipif(importlib.util.find_spec("stable_baselines3") is None, reason="needs stable-baselines3")
@pytest.mark.parametrize("env_id", ["PoolBreak-v0", "PoolNineBall-v0"])
def test_the_sb3_checker_is_silent_with_randomize_on(env_id):
    from stable_baselines3.common.env_checker import check_env as sb3_check

    kwargs = {"opponent": "random"} if env_id != "PoolBreak-v0" else {}
    silent(sb3_check, gym.make(env_id, randomize="default", **kwargs).unwrapped)


def test_the_drawn_ball_sizes_make_a_rack_without_overlaps_that_plays():
    game = Game("eight_ball", seed=2, randomize={"ball_radius": (0.0285, 0.0287)})
    record = game.play(Shot.aimed((1.0, 0.0), 8.0, place=(0.5, 0.56)))
    assert record.error is None
    assert len(set(game.balls.radii.tolist())) == 16
    assert set(PHYSICS_NAMES) >= {"mu_s", "mu_r", "mu_sp", "e_b", "e_c", "f_c"}


def test_the_equipment_observation_carries_the_draw_and_reads_back():
    from pool_env.envs.equipment import EquipmentObservation

    env = EquipmentObservation(gym.make("PoolBreak-v0", randomize="default"))
    obs, info = env.reset(seed=3)
    randomization = env.randomization
    assert obs.shape == env.observation_space.shape == (49 + randomization.size,)
    assert randomization.size == 6 + 3 + 2 * 16
    assert env.observation_space.contains(obs)
    back = randomization.unscaled(obs[49:])
    assert back["mu_s"] == pytest.approx(info["physics"]["mu_s"], rel=1e-6)
    assert np.allclose(back["ball_mass"], info["ball_mass"], rtol=1e-6)
    assert back.keys() == env.unwrapped.game.sample.values.keys()
    after = env.step(np.array([0.9, 0.1], np.float32))[0]
    assert env.observation_space.contains(after) and np.array_equal(after[49:], obs[49:])  # drawn at reset only
    with pytest.raises(TypeError, match="randomize="):
        EquipmentObservation(gym.make("PoolBreak-v0"))


@pytest.mark.parametrize("env_id", ["PoolBreak-v0", "PoolNineBall-v0", "ThreeCushion-v0"])
def test_the_vector_equipment_observation_gives_each_sub_env_its_own_draw(env_id):
    from pool_env.envs.equipment import EquipmentVectorObservation

    kwargs = {"opponent": "random"} if env_id == "PoolNineBall-v0" else {}
    envs = EquipmentVectorObservation(gym.make_vec(env_id, 3, vectorization_mode="vector_entry_point",
                                                   randomize="default", **kwargs))
    obs, infos = envs.reset(seed=7)
    n = envs.env.single_observation_space.shape[0]
    assert obs.shape == (3, n + envs.randomization.size) and envs.observation_space.contains(obs)
    for k in range(3):  # each row reads back to the physics its sub-env's info reports
        drawn = envs.randomization.unscaled(obs[k, n:])
        assert drawn["mu_s"] == pytest.approx(infos["physics"]["mu_s"][k], abs=1e-6)
    assert len({round(float(v), 6) for v in obs[:, n]}) == 3  # three draws, three rows
    obs, *_ = envs.step(envs.action_space.sample())
    assert envs.observation_space.contains(obs)
    with pytest.raises(TypeError, match="vector_entry_point"):
        EquipmentVectorObservation(gym.make_vec(env_id, 2, vectorization_mode="sync", randomize="default", **kwargs))
    with pytest.raises(TypeError, match="randomize="):
        EquipmentVectorObservation(gym.make_vec(env_id, 2, vectorization_mode="vector_entry_point", **kwargs))


def test_the_two_player_envs_draw_from_their_seed_too():
    from pool_env.multiagent import nine_ball_v0, three_cushion_v0

    env = nine_ball_v0.env(randomize="default")
    env.reset(seed=4)
    first = env.infos["player_0"]["physics"]
    assert env.unwrapped.game.physics.mu_s == first["mu_s"] != Physics().mu_s
    env.reset(seed=4)
    assert env.infos["player_1"]["physics"] == first
    carom = three_cushion_v0.env(randomize="default")
    carom.reset(seed=0)
    assert 0.0305 <= carom.unwrapped.game.balls.radii.min() <= carom.unwrapped.game.balls.radii.max() <= 0.03075
