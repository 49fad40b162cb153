"""The games `python -m pool_env.play` plays: their envs (against a player, a model or a friend) and names."""

from __future__ import annotations

import gymnasium as gym

from ..players import player_names

GAMES = {"break": ("PoolBreak-v0", {"spin": True}), "run": ("PoolBreakRun-v0", {"spin": True}),
         "nine_ball": ("PoolNineBall-v0", {}), "eight_ball": ("PoolEightBall-v0", {}),
         "ten_ball": ("PoolTenBall-v0", {}), "snooker": ("Snooker-v0", {}), "three_cushion": ("ThreeCushion-v0", {})}
NAMES = {"break": "break", "run": "break and run", "nine_ball": "9-ball", "eight_ball": "8-ball", "ten_ball": "10-ball",
         "snooker": "snooker", "three_cushion": "three-cushion"}
# the games with an opponent (or a friend)
TWO_SIDED = ("nine_ball", "eight_ball", "ten_ball", "snooker", "three_cushion")
TABLE_SIZE = (1120, 630)  # px: the table's frames


def make_env(game, opponent="ghost_ball", two_players=False, size=TABLE_SIZE, render_mode="rgb_array"):
    """The env of a played game: a break env (with spin), or a game env against `opponent` (a
    player's name, `pool_env.make_player`'s, or a saved model's path), or two people taking
    turns (`hotseat`)."""
    if game not in GAMES:
        raise ValueError(f"unknown game {game!r}; choose one of {', '.join(GAMES)}")
    env_id, kwargs = GAMES[game]
    if render_mode is not None:  # (a saved game's env has neither: only names and numbers are saved)
        kwargs = {**kwargs, "render_mode": render_mode, "render_size": tuple(size)}
    if game in ("break", "run"):
        return gym.make(env_id, **kwargs)
    if two_players:
        return gym.make(env_id, opponent=None, hotseat=True, **kwargs)
    return gym.make(env_id, opponent=opponent, **kwargs)


def opponent_names() -> list[str]:
    """The players `--opponent` takes by name."""
    return player_names()
