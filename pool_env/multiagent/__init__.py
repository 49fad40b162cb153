"""pool_env.multiagent: 9-ball and 8-ball between two agents through PettingZoo's AEC API (needs `.[multiagent]`)."""

__all__ = ["nine_ball_v0", "eight_ball_v0", "PoolGameAEC"]


def __getattr__(name):
    # Lazy, as `pool_env` itself: importing the package does not load the physics.
    if name in ("nine_ball_v0", "eight_ball_v0"):
        import importlib

        return importlib.import_module(f"{__name__}.{name}")
    if name == "PoolGameAEC":
        from .game_aec import PoolGameAEC

        return PoolGameAEC
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
