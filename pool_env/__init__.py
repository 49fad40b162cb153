"""pool_env: exact, fast pool physics, the games played on it, and Gymnasium and PettingZoo envs."""

import importlib.abc
import importlib.util
import sys

__version__ = "0.1.0"
__all__ = ["Game", "Shot", "make_player", "PoolBreakEnv", "PoolGameEnv", "PoolVectorEnv", "PoolGameVectorEnv",
           "GhostBallAction", "record_video", "record_game", "save_game", "load_game", "replay", "calibrate",
           "__version__"]

# The env ids, one registry: registered by entry-point strings so that `import pool_env` stays
# light (no numba, no physics, and no gymnasium until it is imported: see _register_envs).
# `gymnasium.make_vec(id, num_envs=N, vectorization_mode="vector_entry_point")` makes the
# native vector env (one simulate_batch call per round of shots), with the id's kwargs passed on.
ENV_IDS = {
    "PoolBreak-v0": ("pool_env.envs.break_env:PoolBreakEnv", "pool_env.envs.vector:PoolVectorEnv", {"max_shots": 1}),
    "PoolBreakRun-v0": ("pool_env.envs.break_env:PoolBreakEnv", "pool_env.envs.vector:PoolVectorEnv",
                        {"max_shots": 30}),
    "PoolNineBall-v0": ("pool_env.envs.game_env:PoolGameEnv", "pool_env.envs.vector:PoolGameVectorEnv",
                        {"game": "nine_ball"}),
    "PoolEightBall-v0": ("pool_env.envs.game_env:PoolGameEnv", "pool_env.envs.vector:PoolGameVectorEnv",
                         {"game": "eight_ball"}),
    "PoolTenBall-v0": ("pool_env.envs.game_env:PoolGameEnv", "pool_env.envs.vector:PoolGameVectorEnv",
                       {"game": "ten_ball"}),
    "ThreeCushion-v0": ("pool_env.envs.carom_env:ThreeCushionEnv", "pool_env.envs.carom_vector:ThreeCushionVectorEnv",
                        {}),
    "Snooker-v0": ("pool_env.envs.game_env:PoolGameEnv", "pool_env.envs.vector:PoolGameVectorEnv",
                   {"game": "snooker", "opponent": "snooker", "max_shots": 300}),
}


def _register_envs():
    import gymnasium

    for env_id, (entry, vector, kwargs) in ENV_IDS.items():
        if env_id not in gymnasium.registry:
            gymnasium.register(id=env_id, entry_point=entry, vector_entry_point=vector, kwargs=kwargs)


class _RegisterWithGymnasium(importlib.abc.MetaPathFinder):
    """Registers the env ids right after gymnasium is imported, if it was not yet when pool_env
    was: the physics alone (`from pool_env.physics import ...`) then never imports gymnasium."""

    def find_spec(self, name, path=None, target=None):
        if name != "gymnasium":
            return None
        sys.meta_path.remove(self)
        spec = importlib.util.find_spec(name)
        if spec is not None and spec.loader is not None:
            run = spec.loader.exec_module

            def exec_module(module):
                run(module)
                _register_envs()

            spec.loader.exec_module = exec_module
        return spec


if "gymnasium" in sys.modules:
    _register_envs()
else:
    sys.meta_path.insert(0, _RegisterWithGymnasium())

_LAZY = {  # name: (module, attribute), imported on first use
    "Game": ("pool_env.game", "Game"), "Shot": ("pool_env.game", "Shot"),
    "make_player": ("pool_env.players", "make_player"),
    "PoolBreakEnv": ("pool_env.envs.break_env", "PoolBreakEnv"),
    "PoolGameEnv": ("pool_env.envs.game_env", "PoolGameEnv"),
    "PoolVectorEnv": ("pool_env.envs.vector", "PoolVectorEnv"),
    "PoolGameVectorEnv": ("pool_env.envs.vector", "PoolGameVectorEnv"),
    "GhostBallAction": ("pool_env.envs.wrappers", "GhostBallAction"),
    "record_video": ("pool_env.records.video", "record_video"),
    "record_game": ("pool_env.records.saved", "record_game"), "save_game": ("pool_env.records.saved", "save_game"),
    "load_game": ("pool_env.records.saved", "load_game"), "replay": ("pool_env.records.saved", "replay"),
    "calibrate": ("pool_env.physics.calibrate", "calibrate"),
}


def __getattr__(name):
    if name in _LAZY:
        import importlib

        module, attribute = _LAZY[name]
        return getattr(importlib.import_module(module), attribute)
    raise AttributeError(f"module 'pool_env' has no attribute {name!r}")
