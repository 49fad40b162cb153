"""pool_env.players: the built-in players (random, ghost-ball) and the registry that resolves a player's name."""

from __future__ import annotations

from importlib.metadata import entry_points
from pathlib import Path

from .base import Agent, RandomAgent, game_of
from .carom_search import CaromSearchAgent
from .game_ghost_ball import GameGhostBallAgent
from .ghost_ball import BreakAgent, GhostBallAgent, Pot, cue_action
from .snooker import SnookerPlayer

ENTRY_POINT_GROUP = "pool_env.players"  # other packages register players here (agents: search, model)
MODEL_LOADER = "model"  # the registered name that loads a saved model's path
MODEL_SUFFIXES = (".zip",)
_PLAYERS: dict = {}
_loaded_entry_points = False


def register_player(name: str, factory, overwrite: bool = False) -> None:
    """Register `factory(env, seed=None, **options) -> player` (a player has `act(observation)`)
    under `name`; ValueError if the name is taken (unless `overwrite`)."""
    if not isinstance(name, str) or not name:
        raise ValueError(f"a player's name must be a non-empty string, got {name!r}")
    if name in _PLAYERS and not overwrite:
        raise ValueError(f"a player named {name!r} is already registered")
    _PLAYERS[name] = factory


def _load_entry_points() -> None:
    global _loaded_entry_points
    if _loaded_entry_points:
        return
    _loaded_entry_points = True
    for entry in entry_points(group=ENTRY_POINT_GROUP):
        if entry.name not in _PLAYERS:
            _PLAYERS[entry.name] = entry.load()


def player_names() -> list[str]:
    """Every registered player's name (the built-in ones and those of installed packages)."""
    _load_entry_points()
    return sorted(name for name in _PLAYERS if name != MODEL_LOADER)


def is_model_path(spec: str) -> bool:
    """`spec` names a saved model: a path ending in .zip, or an existing file."""
    path = Path(spec)
    return path.suffix in MODEL_SUFFIXES or path.is_file()


def make_player(name: str, env, seed: int | None = None, **options):
    """The player `name` for `env` (a pool_env env, a two-player env or a `Game`): "random",
    "ghost_ball", "search" (from `agents`), or a saved model's path (loaded by `agents`); it
    has `act(observation) -> action` for that env. ValueError naming the choices for an
    unknown name, or a model path that does not exist."""
    if not isinstance(name, str):
        raise TypeError(f"a player's name must be a string, got {type(name).__name__}")
    if name not in _PLAYERS:
        _load_entry_points()
    if name in _PLAYERS and name != MODEL_LOADER:
        return _PLAYERS[name](env, seed=seed, **options)
    if is_model_path(name):
        if not Path(name).is_file() and not Path(name).with_suffix(".zip").is_file():
            raise ValueError(f"unknown player {name!r}: no player of that name and no such model file")
        if MODEL_LOADER not in _PLAYERS:
            raise ValueError(f"player {name!r} is a model, and no installed package loads models "
                             "(install the project with its 'train' extra)")
        return _PLAYERS[MODEL_LOADER](env, seed=seed, path=name, **options)
    raise ValueError(f"unknown player {name!r}; choose one of {', '.join(player_names())} or a saved model's "
                     "path (runs/<name>/model.zip)")


def _random(env, seed=None):
    return RandomAgent(game_of(env).layout.size, seed=seed)


def _snooker(env, seed=None):
    return SnookerPlayer.from_env(env, seed=seed)


def _ghost_ball(env, seed=None):
    game = game_of(env)
    if game.mode == "snooker":  # the ghost-ball player of snooker
        return SnookerPlayer.from_env(game, seed=seed)
    if game.mode == "three_cushion":  # no ghost ball at carom: its built-in player searches
        return CaromSearchAgent.from_env(env, seed=seed)
    if game.has_rules:
        return GameGhostBallAgent.from_env(game)
    return GhostBallAgent(game.table, game.physics, spin=game.layout.spin)


register_player("random", _random)
register_player("ghost_ball", _ghost_ball)
register_player("carom_search", CaromSearchAgent.from_env)
register_player("snooker", _snooker)

__all__ = ["Agent", "RandomAgent", "CaromSearchAgent", "SnookerPlayer",
           "BreakAgent", "GhostBallAgent", "GameGhostBallAgent", "Pot", "cue_action",
           "game_of", "make_player", "register_player", "player_names", "is_model_path"]
