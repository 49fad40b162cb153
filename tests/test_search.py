"""SearchAgent: pots what is on, places the cue ball, plays safe, keeps its budget, decodes and repeats exactly."""

import gymnasium as gym
import numpy as np
import pytest
from scenes import layout

import pool_env  # noqa: F401  (registers the envs)
from agents import GameGhostBallAgent, SearchAgent
from agents.search import balls_of, decode, game_state, head_to_head
from agents.stats import wilson
from pool_env import rules
from pool_env.game import GameView, game_observation
from pool_env.physics import BALL_RADIUS, Table

TABLE = Table.eight_foot()


@pytest.mark.parametrize("cue, ball", [((1.12, 0.30), (1.12, 0.80)), ((1.40, 0.40), (1.80, 0.80)),
                                       ((0.60, 0.60), (0.30, 0.30))])
def test_pots_a_straight_in_ball(cue, ball):
    env = gym.make("PoolNineBall-v0", opponent="ghost_ball")
    agent = SearchAgent.from_env(env)
    obs, _ = env.reset(seed=0, options={"balls": layout(10, {0: cue, 1: ball, 9: (0.25, 1.0)})})
    _, _, _, _, info = env.step(agent.act(obs))
    assert info["pocketed"].nonzero()[0].tolist() == [1] and info["foul"] == 0 and not info["turn_passed"]
    assert agent.last_stats["kind"] == "pot"


def test_ball_in_hand_goes_to_a_spot_that_makes_a_shot():
    env = gym.make("PoolNineBall-v0", opponent="ghost_ball")
    agent = SearchAgent.from_env(env)
    # The cue ball lies behind the 9, which blocks the 1: only a placement makes the pot.
    balls = layout(10, {0: (0.40, 0.56), 1: (1.60, 0.56), 9: (1.00, 0.56)})
    obs, _ = env.reset(seed=0, options={"balls": balls, "ball_in_hand": True})
    _, _, _, _, info = env.step(agent.act(obs))
    # From where it lay the cue ball would hit the 9 first; placed, it pots (the 1, or the 9 off it: a win).
    assert info["pocketed"][1:].any() and info["foul"] == 0 and (not info["turn_passed"] or info["winner"] == 0)


def test_plays_a_safety_when_every_pot_is_blocked():
    env = gym.make("PoolNineBall-v0", opponent="ghost_ball")
    agent = SearchAgent.from_env(env)
    # The 1 frozen in the middle of the foot rail, hidden behind the 9 from a cue ball far up the table.
    balls = layout(10, {0: (0.50, 0.56), 1: (2.24 - 0.0290, 0.56), 9: (1.60, 0.56), 2: (2.10, 0.40),
                        3: (2.10, 0.72)})
    obs, _ = env.reset(seed=0, options={"balls": balls})
    d = decode(obs, 10, TABLE)
    assert not [c for c in agent.shot_candidates(d.xy, d.on_table, d.legal) if c.kind == "pot"]
    _, _, _, _, info = env.step(agent.act(obs))
    assert agent.last_stats["kind"] in ("safety", "kick")
    assert info["foul"] == 0  # no foul


@pytest.mark.parametrize("env_id", ["PoolNineBall-v0", "PoolEightBall-v0", "PoolBreakRun-v0"])
def test_actions_stay_in_the_space_and_the_budget_holds(env_id):
    kwargs = {} if env_id == "PoolBreakRun-v0" else {"noise": "olympiad"}
    env = gym.make(env_id, **kwargs)
    agent = SearchAgent.from_env(env, budget=60, noise_samples=3)
    obs, _ = env.reset(seed=3)
    for _ in range(4):
        action = agent.act(obs)
        assert env.action_space.contains(action)
        assert agent.last_stats["simulations"] <= 60 and agent.last_stats["candidates"] <= 60 // agent.noise_samples
        obs, _, terminated, truncated, _ = env.step(action)
        if terminated or truncated:
            obs, _ = env.reset(seed=4)


def test_decoding_round_trips_a_known_state():
    balls = layout(16, {0: (0.5, 0.5), 3: (1.0, 0.3), 8: (1.5, 0.9), 12: (2.0, 0.2)})
    state = rules.new_game("eight_ball")
    state = state.__class__(state.rules, on_table=frozenset({3, 8, 12}), shooter=0, ball_in_hand="anywhere",
                            fouls=(1, 2), groups=("stripes", "solids"), is_break=False, shot=7)
    obs = game_observation(balls, state, 0, 7, 100, TABLE)
    d = decode(obs, 16, TABLE)
    np.testing.assert_allclose(d.xy[~balls.pocketed], balls.xy[~balls.pocketed], atol=1e-6)
    assert np.array_equal(d.on_table, ~balls.pocketed)
    back = game_state(d, "eight_ball")
    assert (back.on_table, back.ball_in_hand, back.fouls, back.groups, back.is_break) == \
        (state.on_table, "anywhere", (1, 2), ("stripes", "solids"), False)
    assert d.legal == rules.legal_targets(state) == rules.legal_targets(back) == frozenset({12})
    assert np.array_equal(balls_of(d).pocketed, balls.pocketed)
    rack = rules.nine_ball_rack(TABLE, seed=1)
    nine = game_state(decode(game_observation(rack, rules.new_game("nine_ball"), 0, 0, 100, TABLE), 10, TABLE),
                      "nine_ball")
    assert nine.is_break and nine.ball_in_hand == "behind_head_string"


def test_balls_the_observation_rounding_made_overlap_are_pushed_apart():
    xy = np.array([[0.5, 0.5], [0.5 + 2 * BALL_RADIUS - 1e-9, 0.5], [1.0, 0.3]])
    balls = balls_of(GameView(xy, np.ones(3, dtype=bool), frozenset()))  # Balls raises on an overlap
    gap = np.hypot(*(balls.xy[1] - balls.xy[0])) - 2 * BALL_RADIUS
    assert 0.0 <= gap < 1e-8 and np.array_equal(balls.xy[2], xy[2])


def test_the_same_seed_gives_the_same_actions():
    env = gym.make("PoolNineBall-v0", noise="olympiad")
    obs, _ = env.reset(seed=2)
    obs, *_ = env.step(GameGhostBallAgent.from_env(env).act(obs))
    first = [SearchAgent.from_env(env, seed=5, budget=80).act(obs) for _ in range(2)]
    assert np.array_equal(first[0], first[1])
    agent = SearchAgent.from_env(env, seed=5, budget=80)
    a = agent.act(obs)
    agent.reset(5)
    assert np.array_equal(agent.act(obs), a)


def test_wilson_interval_holds_the_estimate():
    lo, hi = wilson(7, 10)
    assert 0.3 < lo < 0.7 < hi < 1.0


def ghost_vs_ghost(games, seed):
    """The ghost-ball player's wins against itself (alternating breaks, same seeds as head_to_head)."""
    wins = 0
    for k in range(games):
        env = gym.make("PoolNineBall-v0", opponent="ghost_ball", agent_breaks=k % 2 == 0)
        agent = GameGhostBallAgent.from_env(env)
        obs, _ = env.reset(seed=seed + k)
        done, info = False, {}
        while not done:
            obs, _, terminated, truncated, info = env.step(agent.act(obs))
            done = terminated or truncated
        wins += info["winner"] == 0  # the agent is player 0
    return wins


@pytest.mark.slow
def test_beats_the_ghost_ball_player_more_than_it_beats_itself():
    result = head_to_head(10, seed=100)
    assert result["wins"] > ghost_vs_ghost(10, seed=100)
    assert result["wins"] >= 7


def test_seconds_caps_the_whole_decision():
    env = gym.make("PoolNineBall-v0", noise="olympiad")
    obs, _ = env.reset(seed=5)
    obs, *_ = env.step(GameGhostBallAgent.from_env(env).act(obs))  # the break; then a mid-game position
    free = SearchAgent.from_env(env, seed=1)
    capped = SearchAgent.from_env(env, seed=1, seconds=0.0)  # the time is up after the first batch
    free.act(obs)
    action = capped.act(obs)
    assert env.action_space.contains(action)
    from agents.search import SIMULATION_CHUNK
    assert capped.last_stats["simulations"] == min(SIMULATION_CHUNK, capped.last_stats["candidates"]) * 6
    assert free.last_stats["candidates"] > SIMULATION_CHUNK
    assert capped.last_stats["simulations"] < free.last_stats["simulations"] == 6 * free.last_stats["candidates"]
    generous = SearchAgent.from_env(env, seed=1, seconds=1e9)  # never reached: the same decision as without
    assert np.array_equal(generous.act(obs), SearchAgent.from_env(env, seed=1).act(obs))


def test_quality_is_the_best_ghost_ball_score_of_the_pots_it_filters():
    from pool_env.players import GhostBallAgent
    from pool_env.players import geometry as geo

    agent, scalar = SearchAgent("nine_ball"), GhostBallAgent(TABLE)
    rng = np.random.default_rng(2)
    for _ in range(12):
        xy = rng.uniform([0.1, 0.1], [2.14, 1.02], (10, 2))
        on = rng.uniform(size=10) < 0.7
        on[0] = True
        legal = {int(b) for b in np.flatnonzero(on[1:]) + 1 if rng.uniform() < 0.5}
        objects = np.flatnonzero(on[1:]) + 1
        best = 0.0
        for ball in legal:
            for pocket in scalar.pockets:
                u = geo.unit(pocket.centre - xy[ball])
                to = xy[ball] - 2.0 * BALL_RADIUS * u - xy[0]
                if float(to @ u) <= np.cos(np.radians(80.0)) * float(np.hypot(*to)):
                    continue  # the search's quick cut filter
                pot = scalar.plan(xy[0], ball, xy[ball], pocket, xy[objects[objects != ball]])
                best = max(best, pot.score if pot is not None else 0.0)
        assert agent.quality(xy, on, legal) == pytest.approx(min(best, 1.0), abs=1e-12)
    assert agent.quality(xy, np.r_[False, on[1:]], legal) == 1.0  # the cue ball in hand: IN_HAND_QUALITY


def test_rounds_spend_no_more_simulations_than_one_pass_and_choose_among_the_most_sampled():
    env = gym.make("PoolNineBall-v0", noise="olympiad")
    obs, _ = env.reset(seed=5)
    obs, *_ = env.step(GameGhostBallAgent.from_env(env).act(obs))  # the break; then a mid-game position
    one = SearchAgent.from_env(env, seed=1)
    one.act(obs)
    halving = SearchAgent.from_env(env, seed=1, rounds=3)
    action = halving.act(obs)
    assert env.action_space.contains(action)
    n = halving.last_stats["candidates"]
    assert n == one.last_stats["candidates"] > 4
    # Round 1: every candidate, 2n draws in all (6n / 3 rounds); rounds 2-3: ceil(n/4), then ceil(n/16) of them.
    kept = -(-n // 4)
    last = -(-kept // 4)
    assert halving.last_stats["simulations"] == n * 2 + kept * (2 * n // kept) + last * (2 * n // last)
    assert halving.last_stats["simulations"] <= one.last_stats["simulations"] == 6 * n
    again = SearchAgent.from_env(env, seed=1, rounds=3)
    assert np.array_equal(again.act(obs), action)  # deterministic by seed
    with pytest.raises(ValueError, match="rounds must be >= 1, and 1 with a time budget"):
        SearchAgent.from_env(env, rounds=2, seconds=1.0)
    with pytest.raises(ValueError, match="rounds must be >= 1"):
        SearchAgent.from_env(env, rounds=0)
