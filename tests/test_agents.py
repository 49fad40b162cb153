"""Agents: the shared interface, the geometry the heuristics rest on, and that the heuristics play well."""

import math

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the env ids)
from agents import (
    BreakAgent,
    GhostBallAgent,
    RandomAgent,
    SB3Agent,
    algorithm_of,
    evaluate,
    format_table,
    load_model,
    paired_difference,
)
from pool_env.physics import BALL_RADIUS, Balls, Physics, Table, simulate, strike
from pool_env.players import geometry as geo

R = BALL_RADIUS
TABLE = Table.eight_foot()
PHYSICS = Physics.standard()


def quiet_make(env_id, **kwargs):
    gym.logger.min_level = gym.logger.ERROR  # a rare simulator failure warns; evaluate() counts them
    return gym.make(env_id, **kwargs)


def layout(*xy):
    """16 balls at rest: the given ones on the table (cue ball first), the rest pocketed."""
    positions = np.zeros((16, 2))
    pocketed = np.ones(16, dtype=bool)
    for i, p in enumerate(xy):
        positions[i], pocketed[i] = p, False
    for i in range(len(xy), 16):  # park pocketed balls apart so the overlap check ignores them
        positions[i] = (0.1 + 0.07 * i, 0.5)
    return Balls(positions, pocketed=pocketed)


# --- the interface ------------------------------------------------------------------------------
@pytest.mark.parametrize("env_id", ["PoolBreak-v0", "PoolBreakRun-v0"])
@pytest.mark.parametrize("spin", [False, True])
def test_every_agent_acts_in_the_action_space(env_id, spin):
    from stable_baselines3 import PPO

    env = quiet_make(env_id, spin=spin)
    obs, _ = env.reset(seed=3)
    agents = [RandomAgent(env.action_space, seed=0), BreakAgent.from_env(env), GhostBallAgent.from_env(env),
              SB3Agent(PPO("MlpPolicy", env, n_steps=16, batch_size=16, device="cpu", seed=0))]
    for agent in agents:
        agent.reset(seed=1)
        for action in (agent.act(obs), agent(obs)):
            assert isinstance(action, np.ndarray) and action.dtype == np.float32
            assert action.shape == env.action_space.shape
            assert env.action_space.contains(action), (type(agent).__name__, action)
        obs2, *_ = env.step(agent.act(obs))
        obs, _ = env.reset(seed=3)


def test_random_agent_is_reproducible_and_uniform():
    space = gym.spaces.Box(-1, 1, (4,), np.float32)
    agent = RandomAgent(space, seed=5)
    first = [agent.act(None) for _ in range(3)]
    agent.reset(seed=5)
    assert all(np.array_equal(a, b) for a, b in zip(first, [agent.act(None) for _ in range(3)]))
    sample = np.array([agent.act(None) for _ in range(4000)])
    assert np.all(sample >= -1) and np.all(sample <= 1)
    assert np.allclose(sample.mean(axis=0), 0.0, atol=0.05)
    assert np.allclose(sample.std(axis=0), 1 / math.sqrt(3), atol=0.03)


def test_break_agent_strikes_full_power_at_the_rack():
    env = quiet_make("PoolBreak-v0")
    obs, _ = env.reset(seed=0)
    head_on = BreakAgent.from_env(env, row=1, offset=0.0)
    action = head_on.act(obs)
    assert np.hypot(*action) == pytest.approx(1.0, abs=1e-6)  # full power: 12 m/s
    assert action[1] == pytest.approx(0.0, abs=1e-3)  # straight up the table at the head ball
    side_cut = BreakAgent.from_env(env).act(obs)
    _, _, _, _, info = env.step(side_cut)
    assert info["first_contact"] == 3  # the left ball of the rack's third row (rack order 10, 8, 3)


def test_heuristic_break_beats_random_on_fixed_seeds():
    seeds = range(500, 700)
    env = quiet_make("PoolBreak-v0")
    heuristic = evaluate(BreakAgent.from_env(env), "PoolBreak-v0", seeds)
    random = evaluate(RandomAgent(env.action_space, seed=0), "PoolBreak-v0", seeds)
    naive = evaluate(BreakAgent.from_env(env, row=1, offset=0.0), "PoolBreak-v0", seeds)
    print(format_table({"heuristic": heuristic, "random": random, "head-on": naive}))
    margin = paired_difference(heuristic, random)
    # Beats random by more than a ball per break, and by far more than the noise.
    assert margin["mean"] > 1.0 and margin["mean"] - margin["ci95"] > 0.5 * margin["mean"]
    assert heuristic["pocketed_per_shot"]["mean"] > random["pocketed_per_shot"]["mean"] + 1.0
    assert heuristic["scratch_rate"]["mean"] < random["scratch_rate"]["mean"]
    # ... and the naive full-power hit at the head ball, which it replaces.
    better = paired_difference(heuristic, naive)
    assert better["mean"] - better["ci95"] > 0


# --- the ghost-ball player ----------------------------------------------------------------------
def test_ghost_ball_pots_a_straight_shot_and_a_cut():
    env = quiet_make("PoolBreakRun-v0")
    agent = GhostBallAgent.from_env(env)
    # Ball 1 in line with the corner pocket at (L, W); then the cue ball moved off the line for a cut.
    for cue in [(1.50, 0.40), (1.40, 0.75)]:
        obs, _ = env.reset(options={"balls": layout(cue, (1.90, 0.78), (0.5, 0.3))})
        shot = agent.best_shot(*geo_decode(obs))
        assert shot is not None and shot.ball == 1 and shot.pocket == 3
        _, reward, _, _, info = env.step(agent.act(obs))
        assert 1 in info["pocketed"] and not info["scratch"], info


def geo_decode(obs):
    from pool_env.game import decode_observation

    return decode_observation(obs, TABLE)


def test_ghost_ball_skips_blocked_shots():
    agent = GhostBallAgent(TABLE, PHYSICS)
    on = np.ones(3, dtype=bool)
    # Ball 2 sits between the cue ball and ball 1: every ghost ball of ball 1 is hidden behind it.
    hidden = np.array([[0.6, 0.56], [1.2, 0.56], [0.9, 0.56]])
    shots = agent.shots(hidden, on)
    assert shots and all(shot.ball == 2 for shot in shots)
    # Ball 1 into the corner pocket at (L, W) (pocket 3) is on, until ball 2 sits on its path.
    cue, ball = [1.5, 0.5], [1.9, 0.8]
    assert (1, 3) in {(s.ball, s.pocket) for s in agent.shots(np.array([cue, ball, [1.0, 0.2]]), on)}
    assert (1, 3) not in {(s.ball, s.pocket) for s in agent.shots(np.array([cue, ball, [2.097, 0.985]]), on)}


def test_ghost_ball_player_clears_tables():
    seeds = range(5)
    result = evaluate(GhostBallAgent.from_env(quiet_make("PoolBreakRun-v0")), "PoolBreakRun-v0", seeds)
    random = evaluate(RandomAgent(quiet_make("PoolBreakRun-v0").action_space, seed=0), "PoolBreakRun-v0", seeds)
    assert result["pocketed_per_episode"]["mean"] >= 8 > random["pocketed_per_episode"]["mean"]
    assert result["pocketed_per_shot"]["mean"] > 0.6


# --- geometry against the simulator ---------------------------------------------------------------
@pytest.mark.parametrize("v0", [0.5, 2.0, 6.0])
@pytest.mark.parametrize("distance", [0.05, 0.4, 1.5])
def test_speed_formulas_invert_and_match_the_simulator(v0, distance):
    v = geo.speed_after(v0, distance, PHYSICS)
    if v > 0:
        assert geo.start_speed(v, distance, PHYSICS) == pytest.approx(v0, rel=1e-9)
    # A lone ball struck along +x: its speed when its centre has moved `distance`.
    result = simulate(strike(layout((0.3, 0.56)), force=(v0 * 0.170097 / 0.005, 0.0)), TABLE, PHYSICS)
    if v > 0:
        first_cushion = min((e.time for e in result.events if e.kind == "ball_cushion"), default=result.duration)
        times = np.linspace(0, first_cushion, 20001)
        rows, _ = result.sample(times)
        k = np.searchsorted(rows[:, 0, 0], 0.3 + distance)
        assert v == pytest.approx(rows[k, 0, 2], abs=2e-3)


@pytest.mark.parametrize("cut_deg", [0.0, 15.0, 30.0, 50.0])
@pytest.mark.parametrize("speed", [1.0, 4.0])
def test_collision_formula_predicts_the_throw(cut_deg, speed):
    """The object ball leaves in the direction `collision` predicts, throw included."""
    obj = np.array([1.5, 0.56])
    n = geo.rotate(np.array([1.0, 0.0]), math.radians(cut_deg))  # line of centres at contact
    ghost = obj - 2 * R * n
    cue = ghost - 0.5 * np.array([1.0, 0.0])  # cue ball travels along +x, 0.5 m to contact
    result = simulate(strike(layout(cue, obj), force=(speed * 0.170097 / 0.005, 0.0)), TABLE, PHYSICS)
    contact = next(e for e in result.events if e.kind == "ball_ball")
    after = result.at(contact.time + 1e-9)
    v_obj = after.v[1]
    roll = geo.forward_spin_after(speed, 0.5, PHYSICS)
    impact = geo.speed_after(speed, 0.5, PHYSICS)
    d = np.array([1.0, 0.0])
    t = np.array([-n[1], n[0]])
    on, ot, _, _ = geo.collision(impact, roll, float(d @ n), float(d @ t), PHYSICS)
    predicted = on * n + ot * t
    assert np.hypot(*(v_obj - predicted)) < 1e-3 * max(impact, 1.0)
    assert math.degrees(math.atan2(ot, on)) == pytest.approx(
        math.degrees(math.atan2(v_obj @ t, v_obj @ n)), abs=0.05)


# --- SB3 models ---------------------------------------------------------------------------------
@pytest.mark.parametrize("algo", ["PPO", "SAC"])
def test_load_model_reads_the_algorithm_from_the_file(tmp_path, algo):
    import stable_baselines3

    env = quiet_make("PoolBreak-v0")
    kwargs = {"n_steps": 16, "batch_size": 16} if algo == "PPO" else {"buffer_size": 100}
    model = getattr(stable_baselines3, algo)("MlpPolicy", env, device="cpu", seed=0, **kwargs)
    model.save(tmp_path / "model.zip")
    assert algorithm_of(tmp_path / "model.zip") == algo
    loaded = load_model(tmp_path / "model")
    assert type(loaded) is type(model)
    obs, _ = env.reset(seed=0)
    assert np.allclose(SB3Agent(loaded).act(obs), SB3Agent(model).act(obs))


def test_evaluation_is_deterministic_and_complete():
    env = quiet_make("PoolBreak-v0")
    first = evaluate(RandomAgent(env.action_space, seed=1), "PoolBreak-v0", range(30))
    second = evaluate(RandomAgent(env.action_space, seed=1), "PoolBreak-v0", range(30))
    assert first == second
    for key in ("reward", "pocketed_per_shot", "scratch_rate", "shots_per_episode"):
        assert np.isfinite(first[key]["mean"])
    assert first["episodes"] == 30 and len(first["per_episode"]) == 30
