"""pool_env.multiagent: the games between two agents, PettingZoo AEC envs (`.[multiagent]`)."""

from . import eight_ball_v0, nine_ball_v0, snooker_v0, ten_ball_v0, three_cushion_v0
from .carom_aec import ThreeCushionAEC
from .game_aec import PoolGameAEC

__all__ = ["nine_ball_v0", "eight_ball_v0", "ten_ball_v0", "PoolGameAEC", "three_cushion_v0", "ThreeCushionAEC",
           "snooker_v0"]
