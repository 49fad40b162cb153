"""PoolVectorEnv: step for step the same as Gymnasium's SyncVectorEnv of PoolBreakEnvs (both autoreset
modes, both ids), Gymnasium's vector API, rendering, pickling, thread counts; and the env's planner API."""

import copy
import pickle
import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.vector import AutoresetMode, VectorEnv

import pool_env
from pool_env.envs.break_env import PoolBreakEnv
from pool_env.envs.vector import PoolVectorEnv
from pool_env.game import decode_observation
from pool_env.physics import Balls, SimulationError, Table, simulate, simulate_batch

IDS = ("PoolBreak-v0", "PoolBreakRun-v0")
MODES = (AutoresetMode.NEXT_STEP, AutoresetMode.SAME_STEP)
TABLE = Table.eight_foot()


def assert_same(a, b, where="data"):
    """Exactly equal: same types, dict keys (in the same order), array dtypes, shapes and values (object
    arrays element by element)."""
    assert type(a) is type(b), f"{where}: {type(a).__name__} != {type(b).__name__}"
    if isinstance(a, dict):
        assert list(a) == list(b), f"{where}: keys {list(a)} != {list(b)} (in this order)"
        for key in a:
            assert_same(a[key], b[key], f"{where}[{key!r}]")
    elif isinstance(a, (list, tuple)):
        assert len(a) == len(b), f"{where}: lengths {len(a)} != {len(b)}"
        for k, (x, y) in enumerate(zip(a, b)):
            assert_same(x, y, f"{where}[{k}]")
    elif isinstance(a, np.ndarray):
        assert (a.dtype, a.shape) == (b.dtype, b.shape), f"{where}: {a.dtype}{a.shape} != {b.dtype}{b.shape}"
        if a.dtype == object:
            for k, (x, y) in enumerate(zip(a, b)):
                assert_same(x, y, f"{where}[{k}]")
        else:
            assert np.array_equal(a, b), f"{where}: {a} != {b}"
    else:
        assert a == b, f"{where}: {a!r} != {b!r}"


def pocket_aim(obs_row):
    """An action sending the cue ball straight at the nearest pocket (often a scratch)."""
    xy, _ = decode_observation(obs_row, TABLE)
    d = TABLE.pockets[:, :2] - xy[0]
    d = d[np.argmin(np.hypot(d[:, 0], d[:, 1]))]
    return (0.6 * d / np.hypot(*d)).astype(np.float32)


def actions_for(rng, obs, n):
    """Random actions from a seeded generator; about one in five aims the cue ball at a pocket."""
    out = rng.uniform(-1.0, 1.0, (n, 2)).astype(np.float32)
    for k in np.flatnonzero(rng.random(n) < 0.2):
        out[k] = pocket_aim(obs[k])
    return out


def run_both(env_id, mode, num_envs=3, seed=5, min_resets=1, max_steps=60, policy=actions_for, **kwargs):
    """Step ours and SyncVectorEnv with the same seed and actions, asserting every step's outputs
    equal, until every sub-env has been autoreset `min_resets` times and episodes of at least two
    lengths have ended (unless every episode is one shot long). Returns (steps, episode lengths)."""
    ours = gym.make_vec(env_id, num_envs=num_envs, vectorization_mode="vector_entry_point",
                        autoreset_mode=mode, **kwargs)
    ref = gym.make_vec(env_id, num_envs=num_envs, vectorization_mode="sync",
                       vector_kwargs={"autoreset_mode": mode}, **kwargs)
    assert isinstance(ours.unwrapped, PoolVectorEnv) and isinstance(ref, gym.vector.SyncVectorEnv)
    assert ours.metadata["autoreset_mode"] == ref.metadata["autoreset_mode"] == mode
    obs, info = ours.reset(seed=seed)
    ref_obs, ref_info = ref.reset(seed=seed)
    assert_same((obs, info), (ref_obs, ref_info), "reset")
    rng = np.random.default_rng(seed)
    resets = np.zeros(num_envs, dtype=int)
    ended = np.zeros(num_envs, dtype=bool)
    lengths = set()
    shots = np.zeros(num_envs, dtype=int)
    for step in range(max_steps):
        actions = policy(rng, obs, num_envs)
        out, ref_out = ours.step(actions), ref.step(actions)
        assert_same(out, ref_out, f"step {step}")
        obs, _, terminated, truncated, _ = out
        if mode == AutoresetMode.NEXT_STEP:
            resets += ended  # this step reset the sub-envs whose episodes ended on the last one
        shots += ~ended if mode == AutoresetMode.NEXT_STEP else 1
        ended = terminated | truncated
        for k in np.flatnonzero(ended):
            lengths.add(int(shots[k]))
            shots[k] = 0
        if mode == AutoresetMode.SAME_STEP:
            resets += ended
        if resets.min() >= min_resets and (len(lengths) > 1 or env_id == "PoolBreak-v0"):
            break
    assert resets.min() >= min_resets, f"only {resets} autoresets in {max_steps} steps"
    assert len(lengths) > 1 or env_id == "PoolBreak-v0", f"episodes all took {lengths} shots"
    ours.close()
    ref.close()
    return step + 1, lengths


@pytest.mark.parametrize("mode", MODES, ids=lambda m: m.value)
@pytest.mark.parametrize("env_id", IDS)
def test_same_as_sync_vector_env_step_for_step(env_id, mode):
    steps, lengths = run_both(env_id, mode, min_resets=2)
    print(env_id, mode, steps, "steps, episode lengths", sorted(lengths))


def test_same_as_sync_with_spin_and_other_options():
    def actions_with_spin(rng, obs, n):
        return np.concatenate([actions_for(rng, obs, n), rng.uniform(-1, 1, (n, 2)).astype(np.float32)], axis=1)

    for mode in MODES:
        run_both("PoolBreakRun-v0", mode, num_envs=2, seed=11, policy=actions_with_spin, spin=True,
                 randomize_cue=True, shaping=True, max_shots=4)


def test_registered_kwargs_reach_the_sub_envs():
    for env_id, shots in (("PoolBreak-v0", 1), ("PoolBreakRun-v0", 30)):
        envs = gym.make_vec(env_id, num_envs=2, vectorization_mode="vector_entry_point")
        assert isinstance(envs, PoolVectorEnv) and envs.num_envs == 2
        assert [e.max_shots for e in envs.envs] == [shots, shots]
        assert envs.metadata["autoreset_mode"] == AutoresetMode.NEXT_STEP
        assert envs.spec.id == env_id
    envs = gym.make_vec("PoolBreakRun-v0", num_envs=3, max_shots=5, spin=True, threads=1,
                        autoreset_mode="SameStep")  # the vector entry point is the default here
    assert isinstance(envs, PoolVectorEnv) and envs.threads == 1
    assert envs.autoreset_mode == AutoresetMode.SAME_STEP == envs.metadata["autoreset_mode"]
    assert all(e.max_shots == 5 and e.spin for e in envs.envs) and envs.single_action_space.shape == (4,)


# --- Gymnasium's vector API ---------------------------------------------------------------------
def test_vector_api():
    """Gymnasium 1.4 has no checker for vector envs (gymnasium.utils.env_checker.check_env takes a
    gymnasium.Env only, and gymnasium.vector holds none), so the API is checked here."""
    envs = PoolVectorEnv(num_envs=3, max_shots=30)
    assert isinstance(envs, VectorEnv) and envs.unwrapped is envs
    assert envs.single_observation_space == envs.envs[0].observation_space
    assert envs.single_action_space == envs.envs[0].action_space
    assert envs.observation_space == gym.vector.utils.batch_space(envs.single_observation_space, 3)
    assert envs.action_space == gym.vector.utils.batch_space(envs.single_action_space, 3)
    obs, infos = envs.reset(seed=3)
    assert obs in envs.observation_space and obs.dtype == np.float32
    assert infos["pocketed"].shape == (3, 16) and not infos["pocketed"].any() and infos["_pocketed"].all()
    envs.action_space.seed(0)
    for _ in range(4):
        obs, rewards, terminations, truncations, infos = envs.step(envs.action_space.sample())
        assert obs in envs.observation_space
        assert rewards.dtype == np.float64 and rewards.shape == (3,)
        assert terminations.dtype == truncations.dtype == np.bool_ and terminations.shape == (3,)
        for key, value in infos.items():
            if not key.startswith("_"):
                assert infos[f"_{key}"].dtype == np.bool_ and len(value) == 3
    # The returned arrays are the caller's: changing them changes nothing inside.
    obs[:] = 7.0
    assert envs.step(envs.action_space.sample())[0].max() <= 1.0
    # Seeds as Gymnasium's sync env takes them: an int s (sub-env k gets s + k), a list, None.
    by_int = envs.reset(seed=10)[0]
    assert np.array_equal(by_int, envs.reset(seed=[10, 11, 12])[0])
    assert envs.np_random_seed == (10, 11, 12)
    single = PoolBreakEnv(max_shots=30)
    assert np.array_equal(by_int[1], single.reset(seed=11)[0])
    assert not np.array_equal(envs.reset(seed=None)[0], by_int)
    assert np.array_equal(envs.reset(seed=[None, 11, None])[0][1], by_int[1])
    with pytest.raises(ValueError, match="num_envs=3"):
        envs.reset(seed=[1, 2])
    with pytest.raises(ValueError, match="one action per sub-env"):
        envs.step(np.zeros((2, 2), np.float32))
    with pytest.raises(ValueError, match="action must be finite"):
        envs.step(np.array([[1, 0], [np.nan, 0], [1, 0]], np.float32))
    assert envs.call("max_shots") == (30, 30, 30) and envs.get_attr("spin") == (False,) * 3
    envs.set_attr("scratch_penalty", [1.0, 2.0, 3.0])
    assert envs.get_attr("scratch_penalty") == (1.0, 2.0, 3.0)
    assert "num_envs=3" in repr(envs)
    # What Gymnasium 1.4 can check: its env checker takes single envs only (it refuses a vector
    # env), and the sub-envs pass it (its render check needs a spec, which only gym.make gives;
    # tests/test_env.py runs it on made envs).
    from gymnasium.utils.env_checker import check_env

    with pytest.raises(TypeError):
        check_env(envs)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(envs.envs[0], skip_render_check=True)
    assert [str(w.message) for w in caught] == []
    envs.close()
    assert envs.closed


def test_a_bad_action_changes_nothing():
    envs = PoolVectorEnv(num_envs=2, max_shots=30)
    obs, _ = envs.reset(seed=0)
    with pytest.raises(ValueError):
        envs.step(np.array([[1.0, 0.0], [np.inf, 0.0]], np.float32))
    assert [e.shots for e in envs.envs] == [0, 0]
    ref = PoolVectorEnv(num_envs=2, max_shots=30)
    ref.reset(seed=0)
    assert_same(envs.step(np.array([[1.0, 0.0], [1.0, 0.1]], np.float32)),
                ref.step(np.array([[1.0, 0.0], [1.0, 0.1]], np.float32)))


def test_autoreset_disabled_with_reset_mask():
    ours = PoolVectorEnv(num_envs=3, max_shots=30, autoreset_mode=AutoresetMode.DISABLED)
    ref = gym.make_vec("PoolBreakRun-v0", num_envs=3, vectorization_mode="sync",
                       vector_kwargs={"autoreset_mode": AutoresetMode.DISABLED})
    obs, info = ours.reset(seed=2)
    assert_same((obs, info), ref.reset(seed=2))
    rng = np.random.default_rng(2)
    resets = 0
    for step in range(30):
        actions = actions_for(rng, obs, 3)
        out = ours.step(actions)
        assert_same(out, ref.step(actions), f"step {step}")
        obs = out[0]
        done = out[2] | out[3]
        if done.any():
            with pytest.raises(RuntimeError, match="reset_mask"):
                ours.step(actions)
            obs, info = ours.reset(options={"reset_mask": done})
            assert_same((obs, info), ref.reset(options={"reset_mask": done}))
            resets += 1
    assert resets >= 2
    with pytest.raises(ValueError, match="at least one True"):
        ours.reset(options={"reset_mask": np.zeros(3, bool)})


def test_max_episode_steps_truncates_like_time_limit():
    for mode in MODES:
        ours = gym.make_vec("PoolBreakRun-v0", num_envs=2, vectorization_mode="vector_entry_point",
                            autoreset_mode=mode, max_episode_steps=2)
        ref = gym.make_vec("PoolBreakRun-v0", num_envs=2, vectorization_mode="sync", max_episode_steps=2,
                           vector_kwargs={"autoreset_mode": mode})
        assert_same(ours.reset(seed=4), ref.reset(seed=4))
        truncated = False
        for step in range(6):
            actions = np.array([[0.05, 0.01], [-0.04, 0.02]], np.float32)  # gentle: no scratch, no pocket
            out = ours.step(actions)
            assert_same(out, ref.step(actions), f"{mode} step {step}")
            truncated |= out[3].all()
        assert truncated


def test_render_rgb_array_gives_each_sub_envs_frame():
    envs = gym.make_vec("PoolBreakRun-v0", num_envs=2, vectorization_mode="vector_entry_point",
                        render_mode="rgb_array", render_size=(160, 90))
    assert envs.render_mode == "rgb_array"
    envs.reset(seed=0)
    envs.step(np.array([[1.0, 0.0], [0.2, 0.1]], np.float32))
    frames = envs.render()
    assert isinstance(frames, tuple) and len(frames) == 2
    single = PoolBreakEnv(max_shots=30, render_mode="rgb_array", render_size=(160, 90))
    for k, action in enumerate(([1.0, 0.0], [0.2, 0.1])):
        single.reset(seed=k)
        single.step(np.array(action, np.float32))
        assert frames[k].shape == (90, 160, 3) and frames[k].dtype == np.uint8
        assert np.array_equal(frames[k], single.render())
    envs.close()


def test_pickle_and_deepcopy_after_steps_continue_identically():
    envs = PoolVectorEnv(num_envs=3, max_shots=30, autoreset_mode=AutoresetMode.SAME_STEP)
    envs.reset(seed=1)
    rng = np.random.default_rng(1)
    for _ in range(3):
        envs.step(rng.uniform(-1, 1, (3, 2)).astype(np.float32))
    copies = [pickle.loads(pickle.dumps(envs)), copy.deepcopy(envs)]
    actions = rng.uniform(-1, 1, (4, 3, 2)).astype(np.float32)
    expected = [envs.step(a) for a in actions]
    for other in copies:
        assert_same([other.step(a) for a in actions], expected)


def test_threads_do_not_change_results():
    outs = []
    for threads in (1, 2):
        envs = PoolVectorEnv(num_envs=6, max_shots=30, threads=threads, autoreset_mode=AutoresetMode.SAME_STEP)
        rng = np.random.default_rng(9)
        out = [envs.reset(seed=9)]
        obs = out[0][0]
        for _ in range(5):
            out.append(envs.step(actions_for(rng, obs, 6)))
            obs = out[-1][0]
        outs.append(out)
    assert_same(outs[0], outs[1])
    with pytest.raises(ValueError, match="threads"):
        PoolVectorEnv(num_envs=2, threads=0)


def test_a_failed_shot_truncates_only_its_sub_env(monkeypatch):
    import pool_env.game.batch as game_batch

    def second_fails(balls_list, *args, **kwargs):
        out = simulate_batch(balls_list, *args, **kwargs)
        out[1] = SimulationError("simulation exceeded the event cap of 1 events")
        return out

    envs = PoolVectorEnv(num_envs=3, max_shots=30)
    obs0, _ = envs.reset(seed=0)
    ref = PoolVectorEnv(num_envs=3, max_shots=30)
    ref.reset(seed=0)
    actions = np.array([[1.0, 0.0], [1.0, 0.0], [0.3, 0.2]], np.float32)
    ref_out = ref.step(actions)
    monkeypatch.setattr(game_batch, "simulate_batch", second_fails)
    with pytest.warns(UserWarning, match="event cap"):
        obs, rewards, terminations, truncations, infos = envs.step(actions)
    assert (rewards[1], terminations[1], truncations[1]) == (0.0, False, True)
    assert np.array_equal(obs[1, :48], obs0[1, :48])  # its balls stay put
    assert infos["error"].tolist() == [False, True, False] and "event cap" in envs.envs[1].step_records[0].error
    for k in (0, 2):
        assert np.array_equal(obs[k], ref_out[0][k]) and rewards[k] == ref_out[1][k]
        assert np.array_equal(infos["pocketed"][k], ref_out[4]["pocketed"][k])


# --- the planner API of PoolBreakEnv -------------------------------------------------------------
def test_balls_and_strike_give_the_shot_step_plays():
    env = gym.make("PoolBreakRun-v0", spin=True)
    with pytest.raises(RuntimeError, match="reset"):
        env.unwrapped.strike([1.0, 0.0, 0.0, 0.0])
    assert env.unwrapped.balls is None
    env.reset(seed=3)
    base = env.unwrapped
    before = base.balls
    assert isinstance(before, Balls) and not before.xy.flags.writeable
    with pytest.raises(AttributeError):
        base.balls = before
    action = np.array([0.9, 0.1, 0.2, -0.3], np.float32)
    struck = base.strike(action)
    assert base.balls is before and not before.v.any() and struck.v[0].any()
    expected = simulate(struck, base.table, base.physics)
    _, _, _, _, info = env.step(action)
    after = base.balls
    assert np.array_equal(after.xy, expected.final.xy) and np.array_equal(after.pocketed, expected.final.pocketed)
    assert info["events"] == len(expected.events)
    with pytest.raises(ValueError, match="shape"):
        base.strike([1.0, 0.0])


def test_vector_env_is_importable_from_the_package():
    assert pool_env.PoolVectorEnv is PoolVectorEnv


def test_no_warnings_on_make_reset_step():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        envs = gym.make_vec("PoolBreak-v0", num_envs=2, vectorization_mode="vector_entry_point")
        envs.reset(seed=0)
        envs.step(envs.action_space.sample())
        envs.close()
    assert [str(w.message) for w in caught] == []


def _cue_force_numpy(action, spin):
    """cue_force as it was written with numpy arrays (before the vector env made it lean)."""
    import math

    from pool_env.game import MAX_FORCE, MAX_TIP_OFFSET
    from pool_env.game.actions import MIN_MAGNITUDE

    a = np.clip(np.asarray(action, dtype=np.float64), -1.0, 1.0)
    d = a[:2]
    magnitude = math.hypot(d[0], d[1])
    if magnitude == 0.0:
        d = np.array([MIN_MAGNITUDE, 0.0])
    elif magnitude > 1.0:
        d = d / magnitude
    elif magnitude < MIN_MAGNITUDE:
        d = d * (MIN_MAGNITUDE / magnitude)
    offset = np.zeros(2)
    if spin:
        offset = MAX_TIP_OFFSET * a[2:4]
        length = math.hypot(offset[0], offset[1])
        if length > MAX_TIP_OFFSET:
            offset *= MAX_TIP_OFFSET / length
    return MAX_FORCE * d, offset


@pytest.mark.parametrize("spin", [False, True])
def test_cue_force_is_bit_identical_to_the_numpy_version(spin):
    from pool_env.game import cue_force

    rng = np.random.default_rng(0)
    actions = np.concatenate([rng.uniform(-s, s, (500, 4)) for s in (1e-3, 0.015, 0.03, 1.0, 3.0)])
    actions[::7, :2] = 0.0
    actions[::11, 0] = -0.0
    for a in actions:
        a = a if spin else a[:2]
        for x in (a, a.astype(np.float32), a.tolist()):
            force, offset = cue_force(x, spin)
            ref_force, ref_offset = _cue_force_numpy(x, spin)
            for u, v in ((force, ref_force), (offset, ref_offset)):
                assert u.dtype == v.dtype and u.shape == v.shape
                assert np.array_equal(u, v) and np.array_equal(np.signbit(u), np.signbit(v)), (x, u, v)


def test_gymnasium_vector_wrappers_run_on_it():
    """Gymnasium's vector wrappers read the API (infos, masks, final_info) and count episodes."""
    from gymnasium.wrappers.vector import DictInfoToList, RecordEpisodeStatistics

    envs = gym.make_vec("PoolBreakRun-v0", num_envs=3, vectorization_mode="vector_entry_point",
                        autoreset_mode=AutoresetMode.SAME_STEP, max_shots=3)
    wrapped = DictInfoToList(RecordEpisodeStatistics(envs))
    wrapped.reset(seed=0)
    wrapped.action_space.seed(0)
    episodes = []
    for _ in range(6):
        _, _, terminations, truncations, infos = wrapped.step(wrapped.action_space.sample())
        assert isinstance(infos, list) and len(infos) == 3
        episodes += [info["episode"] for info, end in zip(infos, terminations | truncations) if end]
    assert episodes and all(1 <= int(e["l"]) <= 3 for e in episodes)
    wrapped.close()


def test_made_by_make_vec_pickles_with_its_spec():
    envs = gym.make_vec("PoolBreakRun-v0", num_envs=2, vectorization_mode="vector_entry_point",
                        autoreset_mode=AutoresetMode.SAME_STEP)
    envs.reset(seed=0)
    envs.step(np.array([[1.0, 0.0], [0.5, 0.5]], np.float32))
    other = pickle.loads(pickle.dumps(envs))
    assert other.spec == envs.spec and other.spec.kwargs["max_shots"] == 30
    actions = np.array([[0.3, -0.2], [-0.6, 0.1]], np.float32)
    assert_same(other.step(actions), envs.step(actions))


def test_infos_gathered_at_once_equal_gymnasiums_add_info():
    """_gather_infos (key by key) against VectorEnv._add_info (env by env) on infos of every kind:
    Python and numpy scalars, lists, strings, arrays, nested dicts, final_obs, keys some envs lack."""
    envs = PoolVectorEnv(num_envs=4)
    rng = np.random.default_rng(0)
    for trial in range(200):
        entries = []
        for k in range(4):
            info = {}
            for key, make in (("i", lambda: int(rng.integers(9))), ("f", lambda: float(rng.random())),
                              ("b", lambda: bool(rng.random() < 0.5)), ("n", lambda: np.float32(rng.random())),
                              ("nb", lambda: np.bool_(rng.random() < 0.5)), ("s", lambda: "err"),
                              ("l", lambda: list(range(int(rng.integers(3))))),
                              ("a", lambda: rng.random(3)), ("final_obs", lambda: rng.random(2).astype(np.float32)),
                              ("d", lambda: {"x": int(rng.integers(3)), "y": [1]})):
                if rng.random() < (1.0 if trial % 3 == 0 else 0.6):
                    info[key] = make()
            entries.append((k, info))
        expected = {}
        for k, info in entries:
            expected = envs._add_info(expected, info, k)  # noqa: SLF001 (Gymnasium's own, the reference)
        assert_same(envs.gather_infos(entries), expected, f"trial {trial}")


@pytest.mark.parametrize("mode", ["vector_entry_point", "sync"])
def test_same_step_autoreset_spends_no_step_on_a_reset(mode):
    # PoolBreak-v0 is one shot an episode: with SAME_STEP every step plays a break and starts the
    # next episode at once; with Gymnasium's default NEXT_STEP every other step only resets.
    same = AutoresetMode.SAME_STEP
    how = {"autoreset_mode": same} if mode == "vector_entry_point" else {"vector_kwargs": {"autoreset_mode": same}}
    envs = gym.make_vec("PoolBreak-v0", num_envs=2, vectorization_mode=mode, **how)
    assert envs.metadata["autoreset_mode"] == same
    envs.reset(seed=0)
    actions = np.array([[1.0, 0.02], [0.8, -0.03]], np.float32)
    for _ in range(4):
        obs, rewards, terminations, truncations, infos = envs.step(actions)
        assert terminations.all() and not truncations.any()  # every step ended both episodes with a shot
        assert infos["_final_info"].all() and (infos["final_info"]["events"] > 0).all()
        assert (obs[:, 48] == -1.0).all() and not infos["pocketed"].any()  # and the next episodes began
    default = gym.make_vec("PoolBreak-v0", num_envs=2, vectorization_mode=mode)
    default.reset(seed=0)
    shots = [default.step(actions)[4]["events"].tolist() for _ in range(4)]
    assert shots[1] == shots[3] == [0, 0] and min(shots[0] + shots[2]) > 0  # NEXT_STEP: every other step resets
