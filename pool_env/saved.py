"""Saved games: actions and outcomes in JSON (`record_game`, `save_game`, `load_game`), replayed exactly (`replay`)."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import gymnasium as gym
import numpy as np

FORMAT = "pool_env.saved_game"
VERSION = 1
CHECKED_INFO = ("foul", "pocketed", "winner", "end_reason", "turn_passed", "scratch")  # per step, when present


class ReplayMismatch(ValueError):
    """A replayed step did not give the recorded outcome: the physics, the rules or the file changed."""


def describe_table(table) -> dict:
    """The table's parameters, as `Table(**...)` takes them."""
    return {"length": table.length, "width": table.width, "pockets": table.pocket_entries.tolist(),
            "cushion_height": table.cushion_height, "corner_pocket": dataclasses.asdict(table.corner_pocket),
            "side_pocket": dataclasses.asdict(table.side_pocket)}


def record_game(env, policy, seed=None, max_steps=10_000) -> dict:
    """Play one episode of `env` (an id, or a made env whose spec has its id and kwargs) with
    `policy` (a callable or an agent with `act`) and return the saved-game record."""
    owned = isinstance(env, str)
    env = gym.make(env) if owned else env
    act = policy.act if hasattr(policy, "act") else policy
    record = _header(env, seed)  # refuses what cannot be saved before anything is played
    obs, _ = env.reset(seed=seed)
    actions, steps = [], []
    for _ in range(max_steps):
        action = np.asarray(act(obs), dtype=np.float32)
        obs, reward, terminated, truncated, info = env.step(action)
        actions.append([float(a) for a in action])
        steps.append(_outcome(env, reward, terminated, truncated, info))
        if terminated or truncated:
            break
    record.update(actions=actions, outcomes=steps)
    if owned:
        env.close()
    return record


def _header(env, seed) -> dict:
    spec, base = env.spec, env.unwrapped
    kwargs = dict(spec.kwargs) if spec is not None else {}
    for key, value in kwargs.items():
        if not isinstance(value, (str, int, float, bool, type(None))):
            raise ValueError(f"env kwarg {key}={value!r} cannot be saved: only names and numbers replay "
                             "(an opponent must be a built-in player's name)")
    from . import __version__

    return {"format": FORMAT, "version": VERSION, "pool_env": __version__, "env_id": spec.id if spec else None,
            "env_kwargs": kwargs, "seed": seed, "table": describe_table(base.table),
            "physics": dataclasses.asdict(base.physics)}


def _outcome(env, reward, terminated, truncated, info) -> dict:
    """What a step is checked against on replay: reward, flags, key info, every ball's final position."""
    balls = env.unwrapped.balls
    out = {"reward": float(reward), "terminated": bool(terminated), "truncated": bool(truncated),
           "xy": balls.xy.tolist(), "pocketed": balls.pocketed.tolist()}
    out["info"] = {key: info[key] for key in CHECKED_INFO if key in info}
    return out


def save_game(path, record: dict) -> Path:
    """Write a record from `record_game` as JSON (floats written exactly) and return the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(record, indent=1) + "\n")
    return path


def load_game(path) -> dict:
    """Read a saved game, checking its format and version (ValueError naming what is wrong)."""
    try:
        record = json.loads(Path(path).read_text())
    except json.JSONDecodeError as exc:
        raise ValueError(f"{path} is not a saved game: {exc}") from None
    if not isinstance(record, dict) or record.get("format") != FORMAT:
        raise ValueError(f"{path} is not a pool_env saved game (no format {FORMAT!r})")
    if record.get("version") != VERSION:
        raise ValueError(f"{path} has saved-game version {record.get('version')!r}; "
                         f"this pool_env reads version {VERSION}")
    keys = ("env_id", "env_kwargs", "seed", "actions", "outcomes", "table", "physics")
    missing = [k for k in keys if k not in record]
    if missing or len(record["actions"]) != len(record["outcomes"]):
        raise ValueError(f"{path} is damaged: missing {missing} or the actions and outcomes differ in number")
    return record


def replay(record: dict, env=None, on_step=None, until=None):
    """Play a saved game again and check every step against its recorded outcome; raises
    ReplayMismatch at the first difference (naming the step and what differs). `on_step(k,
    env)` is called after step k (e.g. to film it); `until` stops after that many steps.
    Returns the env, at the end of the replayed steps."""
    env = gym.make(record["env_id"], **record["env_kwargs"]) if env is None else env
    base = env.unwrapped
    if describe_table(base.table) != record["table"] or dataclasses.asdict(base.physics) != record["physics"]:
        raise ReplayMismatch("the env's table or physics differ from the saved game's")
    env.reset(seed=record["seed"])
    steps = record["actions"] if until is None else record["actions"][:until]
    for k, action in enumerate(steps):
        obs, reward, terminated, truncated, info = env.step(np.asarray(action, dtype=np.float32))
        got = json.loads(json.dumps(_outcome(env, reward, terminated, truncated, info)))
        want = record["outcomes"][k]
        if got != want:
            diff = [key for key in want if got.get(key) != want[key]]
            raise ReplayMismatch(f"step {k} of the saved game replays differently ({', '.join(diff)} differ): "
                                 "the physics, the rules or the file changed")
        if on_step is not None:
            on_step(k, env)
    return env
