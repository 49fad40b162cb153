"""snooker_v0: snooker by the WPBSA rules between player_0 and player_1 (PettingZoo AEC; see `PoolGameAEC`)."""

from .game_aec import aec_module

env, raw_env = aec_module("snooker", "snooker_v0")
