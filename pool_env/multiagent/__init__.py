"""pool_env.multiagent: 9-ball and 8-ball between two agents through PettingZoo's AEC API (needs `.[multiagent]`)."""

from . import eight_ball_v0, nine_ball_v0, three_cushion_v0
from .carom_aec import ThreeCushionAEC
from .game_aec import PoolGameAEC

__all__ = ["nine_ball_v0", "eight_ball_v0", "PoolGameAEC", "three_cushion_v0", "ThreeCushionAEC"]
