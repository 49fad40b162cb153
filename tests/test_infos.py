"""The envs' infos: numbers, bools and fixed-shape arrays only, the same keys, types and shapes
after reset and every step, in every env; the rules' code tables and their decoders; rich mode."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import pool_env
from pool_env import rules
from pool_env.rules import codes
from pool_env.rules.snooker import SNOOKER_END_REASONS, SNOOKER_FOULS

BREAK_KEYS = {"pocketed", "first_contact", "cushion_hits", "scratch", "events", "shot_duration", "balls_left",
              "error"}
GAME_KEYS = BREAK_KEYS | {"foul", "ball_in_hand", "turn_passed", "opponent_shots", "winner", "end_reason",
                          "truncation"}


def signature(info: dict) -> dict:
    """Each key's type, and an array's dtype and shape: what must not change from step to step."""
    out = {}
    for key, value in info.items():
        assert isinstance(value, (bool, int, float, np.ndarray)), (key, value)
        out[key] = (np.ndarray, value.dtype, value.shape) if isinstance(value, np.ndarray) else type(value)
    return out


GAME_IDS = ("PoolNineBall-v0", "PoolEightBall-v0", "PoolTenBall-v0", "Snooker-v0")
CAROM_KEYS = {"points", "opponent_points", "scores", "innings", "opponent_shots", "winner", "draw", "error",
              "pocketed"}  # ThreeCushion-v0's


CASES = [(env_id, False) for env_id in pool_env.ENV_IDS] + [(env_id, True) for env_id in GAME_IDS]


@pytest.mark.parametrize("env_id, opponent_breaks", CASES)
def test_every_info_is_numeric_with_the_same_keys_and_shapes(env_id, opponent_breaks):
    game = env_id in GAME_IDS
    env = gym.make(env_id, **({"agent_breaks": False} if opponent_breaks else {}))
    n = env.unwrapped.game.n_balls
    rng = np.random.default_rng(1)
    infos = []
    for seed in range(3):
        infos.append(env.reset(seed=seed)[1])
        for _ in range(6):
            *_, terminated, truncated, info = env.step(rng.uniform(-1, 1, env.action_space.shape))
            infos.append(info)
            if terminated or truncated:
                break
    first = signature(infos[0])
    keys = CAROM_KEYS if env_id == "ThreeCushion-v0" else GAME_KEYS if game else BREAK_KEYS
    assert set(first) == (keys | {"scores"} if env_id == "Snooker-v0" else keys)  # snooker keeps a score
    assert first["pocketed"] == (np.ndarray, np.dtype(bool), (n,))
    for info in infos[1:]:
        assert signature(info) == first
    if opponent_breaks:  # the opponent's break is counted in reset's info
        assert infos[0]["opponent_shots"] >= 1
    for info in infos:
        if game:
            assert -1 <= info["winner"] <= 1 and (info["end_reason"] > 0) == (info["winner"] >= 0)
            assert info["pocketed"][1:].sum() + info["balls_left"] <= n - 1
        decoded = codes.decode_info(info)  # every code is in its table
        assert all(0 <= b < n for b in decoded["pocketed"])


def test_reset_info_describes_no_shot():
    for env_id in ("PoolBreakRun-v0", "PoolNineBall-v0"):
        _, info = gym.make(env_id).reset(seed=0)
        assert not info["pocketed"].any() and info["first_contact"] == -1 and info["events"] == 0
        assert info["cushion_hits"] == 0 and info["shot_duration"] == 0.0 and info["error"] is False
    assert (info["foul"], info["winner"], info["end_reason"], info["opponent_shots"], info["truncation"]) == \
        (0, -1, 0, 0, 0)
    assert codes.decode("ball_in_hand", info["ball_in_hand"]) == "behind_head_string"  # the breaker's


def test_code_tables_follow_the_rules_names_with_none_first():
    # the pool games' names keep their codes; snooker's own names follow them, each name once
    snooker_fouls = tuple(f for f in SNOOKER_FOULS if f not in rules.FOULS)
    assert codes.FOUL_CODES == (None, *rules.FOULS, *snooker_fouls) and "wrong_ball_potted" in snooker_fouls
    assert codes.END_REASON_CODES == (None, *rules.END_REASONS, *SNOOKER_END_REASONS, *rules.TEN_END_REASONS)
    assert codes.BALL_IN_HAND_CODES == (None, "anywhere", "behind_head_string", "in_d")  # snooker: in the D
    assert codes.TRUNCATION_CODES == (None, "shot_limit", "opponent_shot_limit", "shot_error")
    for key, table in codes.CODE_TABLES.items():
        for code, name in enumerate(table):
            assert codes.encode(key, name) == code and codes.decode(key, code) == name
        with pytest.raises(ValueError, match=f"not a {key} code: the codes run 0-{len(table) - 1}"):
            codes.decode(key, len(table))
        with pytest.raises(ValueError, match=f"not a {key} code"):
            codes.decode(key, -1)
    with pytest.raises(ValueError, match="'push_out' is not a foul"):
        codes.encode("foul", "push_out")
    with pytest.raises(ValueError, match="no code table for 'winner'"):
        codes.decode("winner", 0)


@pytest.mark.parametrize("env_id", ["PoolBreak-v0", "PoolNineBall-v0"])
def test_rich_mode_adds_the_records(env_id):
    env = gym.make(env_id, info_mode="rich")
    _, info = env.reset(seed=0)
    assert info["records"] == () and info["error_message"] is None
    *_, info = env.step(np.full(env.action_space.shape, 0.5, np.float32))
    assert info["records"] == env.unwrapped.step_records and len(info["records"]) >= 1
    assert info["records"][0].shooter == 0 and info["error_message"] is None
    numeric = gym.make(env_id)
    numeric.reset(seed=0)
    *_, plain = numeric.step(np.full(env.action_space.shape, 0.5, np.float32))
    assert set(info) - set(plain) == {"records", "error_message"}  # the numeric keys are the same
    assert all(np.array_equal(info[k], plain[k]) for k in plain)
    with pytest.raises(ValueError, match="info_mode must be one of"):
        gym.make(env_id, info_mode="verbose")


def test_the_pettingzoo_env_infos_are_numeric_too():
    pytest.importorskip("pettingzoo")
    from pool_env.multiagent import nine_ball_v0

    env = nine_ball_v0.env()
    env.reset(seed=0)
    first = signature(env.infos["player_0"])
    assert set(first) == (GAME_KEYS - {"opponent_shots"}) | {"shooter", "shots"}
    rng = np.random.default_rng(0)
    for _ in range(6):
        agent = env.agent_selection
        if env.terminations[agent] or env.truncations[agent]:
            break
        env.step(rng.uniform(-1, 1, 6).astype(np.float32))
        assert signature(env.infos["player_0"]) == signature(env.infos["player_1"]) == first
    rich = nine_ball_v0.env(info_mode="rich")
    rich.reset(seed=0)
    rich.step(np.zeros(6, np.float32))
    assert rich.infos["player_1"]["records"] == (rich.unwrapped.last_record,)
