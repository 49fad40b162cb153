"""pool_env.multiagent: 9-ball, 8-ball and 10-ball between two agents (PettingZoo AEC; needs `.[multiagent]`)."""

from . import eight_ball_v0, nine_ball_v0, ten_ball_v0, three_cushion_v0
from .carom_aec import ThreeCushionAEC
from .game_aec import PoolGameAEC

__all__ = ["nine_ball_v0", "eight_ball_v0", "ten_ball_v0", "PoolGameAEC", "three_cushion_v0", "ThreeCushionAEC"]
