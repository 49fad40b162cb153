"""ten_ball_v0: 10-ball by the WPA rules between player_0 and player_1 (PettingZoo AEC; see `PoolGameAEC`)."""

from .game_aec import aec_module

env, raw_env = aec_module("ten_ball", "ten_ball_v0")
