"""pool_env: exact, fast pool physics as a Gymnasium environment."""

import gymnasium

__version__ = "0.1.0"
__all__ = ["PoolBreakEnv", "PoolGameEnv", "PoolVectorEnv", "record_video", "record_game", "save_game", "load_game",
           "__version__"]

# Registered by entry-point strings so that `import pool_env` stays light (no numba, no physics).
# `gymnasium.make_vec(id, num_envs=N, vectorization_mode="vector_entry_point")` makes a
# PoolVectorEnv (one simulate_batch call per step), with the id's kwargs (max_shots) passed on.
for _id, _kwargs in (("PoolBreak-v0", {"max_shots": 1}), ("PoolBreakRun-v0", {"max_shots": 30})):
    if _id not in gymnasium.registry:
        gymnasium.register(id=_id, entry_point="pool_env.env:PoolBreakEnv",
                           vector_entry_point="pool_env.vector:PoolVectorEnv", kwargs=_kwargs)
# The games (pool_env/games.py): 9-ball and 8-ball by the WPA rules against an opponent.
for _id, _game in (("PoolNineBall-v0", "nine_ball"), ("PoolEightBall-v0", "eight_ball")):
    if _id not in gymnasium.registry:
        gymnasium.register(id=_id, entry_point="pool_env.games:PoolGameEnv",
                           vector_entry_point="pool_env.vector:PoolGameVectorEnv", kwargs={"game": _game})


def __getattr__(name):
    if name == "PoolBreakEnv":
        from .env import PoolBreakEnv

        return PoolBreakEnv
    if name == "PoolGameEnv":
        from .games import PoolGameEnv

        return PoolGameEnv
    if name == "PoolVectorEnv":
        from .vector import PoolVectorEnv

        return PoolVectorEnv
    if name in ("record_game", "save_game", "load_game"):
        from . import saved

        return getattr(saved, name)
    if name == "record_video":
        from .video import record_video

        return record_video
    raise AttributeError(f"module 'pool_env' has no attribute {name!r}")
