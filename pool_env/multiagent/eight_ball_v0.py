"""eight_ball_v0: 8-ball by the WPA rules between player_0 and player_1 (PettingZoo AEC; see `PoolGameAEC`)."""

from gymnasium.utils import EzPickle
from pettingzoo.utils import wrappers

from .game_aec import PoolGameAEC


def env(render_mode=None, **kwargs):
    """The AEC env wrapped as PettingZoo's classic envs are: `OrderEnforcingWrapper` (reset
    before step, no stepping a finished game). PettingZoo's action wrappers do not apply: every
    action is legal (no `TerminateIllegalWrapper`), the space is a Box (no
    `AssertOutOfBoundsWrapper`), and the env clips out-of-range entries itself as PoolGameEnv
    does, so `ClipOutOfBoundsWrapper` would only warn on float64 actions within the box."""
    return wrappers.OrderEnforcingWrapper(raw_env(render_mode=render_mode, **kwargs))


class raw_env(PoolGameAEC):
    """`PoolGameAEC` with `game="eight_ball"`; keyword arguments as PoolGameAEC's."""

    metadata = {**PoolGameAEC.metadata, "name": "eight_ball_v0"}

    def __init__(self, render_mode=None, **kwargs):
        if "game" in kwargs:
            raise TypeError(f"eight_ball_v0 plays eight_ball; got "
                            f"game={kwargs['game']!r} (use pool_env.multiagent.PoolGameAEC)")
        super().__init__(game="eight_ball", render_mode=render_mode, **kwargs)
        EzPickle.__init__(self, render_mode=render_mode, **kwargs)  # pickles rebuild this class, without game
