"""three_cushion_v0: three-cushion (UMB) between player_0 and player_1, PettingZoo AEC (`ThreeCushionAEC`)."""

from pettingzoo.utils import wrappers

from .carom_aec import ThreeCushionAEC as raw_env


def env(**kwargs):
    """three_cushion_v0, wrapped as PettingZoo's classic envs are (`OrderEnforcingWrapper`)."""
    return wrappers.OrderEnforcingWrapper(raw_env(**kwargs))
