"""pool_env: exact, fast pool physics as a Gymnasium environment."""

import gymnasium

__version__ = "0.1.0"
__all__ = ["PoolBreakEnv", "record_video", "__version__"]

# Registered by entry-point string so that `import pool_env` stays light (no numba, no physics).
for _id, _kwargs in (("PoolBreak-v0", {"max_shots": 1}), ("PoolBreakRun-v0", {"max_shots": 30})):
    if _id not in gymnasium.registry:
        gymnasium.register(id=_id, entry_point="pool_env.env:PoolBreakEnv", kwargs=_kwargs)


def __getattr__(name):
    if name == "PoolBreakEnv":
        from .env import PoolBreakEnv

        return PoolBreakEnv
    if name == "record_video":
        from .video import record_video

        return record_video
    raise AttributeError(f"module 'pool_env' has no attribute {name!r}")
