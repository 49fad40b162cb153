"""Saved games: actions and outcomes in JSON (`record_game`, `save_game`, `load_game`), replayed exactly (`replay`)."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import gymnasium as gym
import numpy as np

from .. import __version__
from ..physics import Physics

FORMAT = "pool_env.saved_game"
# 2: the numeric infos (codes, the pocketed mask); 3: 8-ball calls a ball and a pocket by default;
# 4: randomize draws the equipment from the game's generator (before: from one of its own).
VERSION = 4
READS = (2, 3, 4)  # the versions load_game reads (an older one upgraded: `upgrade`)
DRAWS_FROM_THE_GAME = 4  # the first version whose randomized resets this pool_env draws again
CHECKED_INFO = ("foul", "pocketed", "winner", "end_reason", "turn_passed", "scratch")  # per step, when present


class ReplayMismatch(ValueError):
    """A replayed step did not give the recorded outcome: the physics, the rules or the file changed."""


def describe_table(table) -> dict:
    """The table's parameters, as `Table(**...)` takes them."""
    return {"length": table.length, "width": table.width, "pockets": table.pocket_entries.tolist(),
            "cushion_height": table.cushion_height, "corner_pocket": dataclasses.asdict(table.corner_pocket),
            "side_pocket": dataclasses.asdict(table.side_pocket)}


def base_equipment(base) -> tuple:
    """(table, physics) an env was made with: its game's before randomization draws, else its own."""
    game = getattr(base, "game", None)
    if game is not None and hasattr(game, "base_table"):
        return game.base_table, game.base_physics
    return base.table, base.physics


def sampled_equipment(base) -> dict | None:
    """The equipment an env's randomization drew at its last reset, as JSON keeps it; None without."""
    sample = getattr(getattr(base, "game", None), "sample", None)
    return None if sample is None else json.loads(json.dumps(sample.info(), default=np.ndarray.tolist))


RECORDED = "recorded"  # env_kwargs["opponent"] of a game whose opponent's actions are in the file


class ScriptedOpponent:
    """An opponent that plays recorded actions in order (a saved game's `opponent_actions`)."""

    def __init__(self, actions):
        self.actions, self.played = [np.asarray(a, dtype=np.float64) for a in actions], 0

    def __call__(self, observation):
        if self.played >= len(self.actions):
            raise ReplayMismatch(f"the opponent shoots more often than the {len(self.actions)} recorded times: "
                                 "the physics, the rules or the file changed")
        self.played += 1
        return self.actions[self.played - 1]


class GameRecorder:
    """Records one episode of `env` as a saved game while something else plays it: `action(a)`
    gives the action to step (float32, as the file keeps it), `stepped(...)` notes each step's
    outcome, `record()` returns the saved-game dict. The header (and the refusal of what cannot
    be saved) comes first, before `env.reset(seed=seed)`. With `record_opponent`, a game's
    opponent that is not a built-in name (an agent, a callable) has its actions recorded too
    (`opponent_actions`, read from the env's shot records; env_kwargs["opponent"] is
    "recorded") and replays from them.
    `env_id`/`env_kwargs` stand in for an env made without `gym.make` (no spec)."""

    def __init__(self, env, seed=None, record_opponent=False, env_id=None, env_kwargs=None):
        self.env, self.actions, self.outcomes = env, [], []
        self.base = env.unwrapped
        kwargs = dict(env.spec.kwargs) if env_kwargs is None and env.spec is not None else dict(env_kwargs or {})
        opponent = kwargs.get("opponent", "the default")  # absent: the env's default, a built-in name
        unnamed = not isinstance(opponent, str) or opponent == RECORDED
        self.opponent_actions = None
        if record_opponent and getattr(self.base, "opponent", None) is not None and unnamed:
            kwargs["opponent"] = RECORDED
            self.opponent_actions = []
        self.header = _header(env, seed, env_id, kwargs)  # refuses what cannot be saved

    def _note_opponent(self, records):
        """The opponent's actions of these shot records (the env's `reset_records`, `step_records`)."""
        if self.opponent_actions is not None:
            self.opponent_actions += [list(r.action) for r in records if r.shooter == 1 and r.action is not None]

    def action(self, action) -> np.ndarray:
        action = np.asarray(action, dtype=np.float32)
        self.actions.append([float(a) for a in action])
        return action

    def stepped(self, reward, terminated, truncated, info):
        if not self.outcomes:  # the opponent's turn inside reset (when it broke) came first
            self._note_opponent(getattr(self.base, "reset_records", ()))
        self._note_opponent(getattr(self.base, "step_records", ()))
        self.outcomes.append(_outcome(self.env, reward, terminated, truncated, info))

    def record(self) -> dict:
        """The saved game."""
        out = {**self.header, "actions": self.actions, "outcomes": self.outcomes}
        sampled = sampled_equipment(self.base)
        if sampled is not None:  # randomize: what the seed drew, checked on replay
            out["sampled"] = sampled
        if self.opponent_actions is not None:
            out["opponent_actions"] = self.opponent_actions
        return out


def record_game(env, policy, seed=None, max_steps=10_000, record_opponent=False) -> dict:
    """Play one episode of `env` (an id, or a made env whose spec has its id and kwargs) with
    `policy` (a callable or an agent with `act`) and return the saved-game record. A game's
    opponent that is an agent or a callable is refused, unless `record_opponent` (its actions
    are then saved: see `GameRecorder`)."""
    owned = isinstance(env, str)
    env = gym.make(env) if owned else env
    act = policy.act if hasattr(policy, "act") else policy
    recorder = GameRecorder(env, seed, record_opponent)
    obs, _ = env.reset(seed=seed)
    for _ in range(max_steps):
        obs, reward, terminated, truncated, info = env.step(recorder.action(act(obs)))
        recorder.stepped(reward, terminated, truncated, info)
        if terminated or truncated:
            break
    record = recorder.record()
    if owned:
        env.close()
    return record


def _header(env, seed, env_id=None, kwargs=None) -> dict:
    spec, base = env.spec, env.unwrapped
    if kwargs is None:
        kwargs = dict(spec.kwargs) if spec is not None else {}
    scalar = (str, int, float, bool, type(None))
    for key, value in kwargs.items():
        if key == "randomize" and isinstance(value, dict):
            try:
                json.dumps(value)
            except (TypeError, ValueError):
                raise ValueError(f"env kwarg randomize={value!r} cannot be saved: only names and numbers") from None
            continue
        if not (isinstance(value, scalar) or isinstance(value, (tuple, list)) and all(isinstance(v, scalar)
                                                                                    for v in value)):
            raise ValueError(f"env kwarg {key}={value!r} cannot be saved: only names and numbers replay "
                             "(an opponent must be a built-in player's name, or record its actions: "
                             "record_opponent=True)")
    env_id = env_id if env_id is not None else (spec.id if spec else None)
    table, physics = base_equipment(base)
    return {"format": FORMAT, "version": VERSION, "pool_env": __version__, "env_id": env_id,
            "env_kwargs": json.loads(json.dumps(kwargs)), "seed": seed, "table": describe_table(table),
            "physics": dataclasses.asdict(physics)}


def make_env(record: dict, **kwargs):
    """The env a saved game was played on (`gym.make` of its id and kwargs; an opponent whose
    actions were recorded plays them back)."""
    env_kwargs = {**record["env_kwargs"], **kwargs}
    if env_kwargs.get("opponent") == RECORDED:
        env_kwargs["opponent"] = ScriptedOpponent(record.get("opponent_actions", []))
    return gym.make(record["env_id"], **env_kwargs)


def _outcome(env, reward, terminated, truncated, info) -> dict:
    """What a step is checked against on replay: reward, flags, key info, every ball's final position."""
    balls = env.unwrapped.balls
    out = {"reward": float(reward), "terminated": bool(terminated), "truncated": bool(truncated),
           "xy": balls.xy.tolist(), "pocketed": balls.pocketed.tolist()}
    out["info"] = {key: np.asarray(info[key]).tolist() for key in CHECKED_INFO if key in info}  # JSON: no arrays
    return out


def save_game(path, record: dict) -> Path:
    """Write a record from `record_game` as JSON (floats written exactly) and return the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(record, indent=1) + "\n")
    return path


def load_game(path) -> dict:
    """Read a saved game, checking its format and version (ValueError naming what is wrong; OSError
    when the file cannot be read)."""
    try:
        text = Path(path).read_text()
        record = json.loads(text)
    except UnicodeDecodeError:
        raise ValueError(f"{path} is not a saved game: not text (a saved game is JSON)") from None
    except json.JSONDecodeError as exc:
        what = "the file is empty" if not text.strip() else f"not JSON ({exc})"
        raise ValueError(f"{path} is not a saved game: {what}") from None
    if not isinstance(record, dict) or record.get("format") != FORMAT:
        raise ValueError(f"{path} is not a pool_env saved game (no format {FORMAT!r})")
    if record.get("version") not in READS:
        raise ValueError(f"{path} has saved-game version {record.get('version')!r}; "
                         f"this pool_env reads versions {', '.join(map(str, READS))}")
    keys = ("env_id", "env_kwargs", "seed", "actions", "outcomes", "table", "physics")
    missing = [k for k in keys if k not in record]
    if missing:
        raise ValueError(f"{path} is damaged: missing {', '.join(missing)}")
    if len(record["actions"]) != len(record["outcomes"]):
        raise ValueError(f"{path} is damaged: {len(record['actions'])} actions but {len(record['outcomes'])} "
                         "outcomes (one outcome per action)")
    try:
        return upgrade(record)
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from None


def upgrade(record: dict) -> dict:
    """A loaded record in this version's terms: a version-2 8-ball game was played when 8-ball
    called only the 8 (`EightBall(calling="eight_only")`), so it gets that rule option, unless
    it names a calling of its own. A randomized game of a version before 4 drew its equipment
    from a generator of its own, which this version does not: ValueError."""
    _check_draws(record)
    if record["version"] == 2 and record["env_kwargs"].get("game") == "eight_ball":
        options = {"calling": "eight_only", **(record["env_kwargs"].get("rule_options") or {})}
        record = {**record, "env_kwargs": {**record["env_kwargs"], "rule_options": options}}
    return {**record, "version": VERSION}


def _check_draws(record):
    """ValueError for a randomized game saved before version 4 (its resets cannot be drawn again)."""
    if record.get("sampled") is not None and record.get("version", VERSION) < DRAWS_FROM_THE_GAME:
        raise ValueError(f"a randomized game saved by saved-game version {record['version']} drew its equipment "
                         "from a generator of its own, as this pool_env no longer does: its resets cannot be "
                         "drawn again (replay it with the pool_env that saved it)")


def replay(record: dict, env=None, on_step=None, until=None):
    """Play a saved game again and check every step against its recorded outcome; raises
    ReplayMismatch at the first difference (naming the step and what differs). `on_step(k,
    env)` is called after step k (e.g. to film it); `until` stops after that many steps.
    Returns the env, at the end of the replayed steps."""
    _check_draws(record)
    env = make_env(record) if env is None else env
    base = env.unwrapped
    # A field the saved game predates (the slate's e_t and mu_t) was played at its default.
    saved_physics = {**dataclasses.asdict(Physics()), **record["physics"]}
    table, physics = base_equipment(base)
    if describe_table(table) != record["table"] or dataclasses.asdict(physics) != saved_physics:
        raise ReplayMismatch("the env's table or physics differ from the saved game's")
    env.reset(seed=record["seed"])
    if record.get("sampled") is not None and sampled_equipment(base) != record["sampled"]:
        raise ReplayMismatch("the equipment randomize drew at reset differs from the saved game's")
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
