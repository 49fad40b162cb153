"""pool_env.multiagent: 9-ball, 8-ball, three-cushion and snooker for two agents, PettingZoo AEC (`.[multiagent]`)."""

from . import eight_ball_v0, nine_ball_v0, snooker_v0, three_cushion_v0
from .carom_aec import ThreeCushionAEC
from .game_aec import PoolGameAEC

__all__ = ["nine_ball_v0", "eight_ball_v0", "PoolGameAEC", "three_cushion_v0", "ThreeCushionAEC", "snooker_v0"]
