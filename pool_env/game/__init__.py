"""pool_env.game: the game as an object (`Game`), its shots, records, snapshots, action and observation layouts."""

from .actions import (
    ELEVATED,
    LAYOUTS,
    ActionLayout,
    cue_force,
    decode_action,
    decode_decision,
    decode_entries,
    elevation_entry,
    encode_action,
    encode_decision,
    encoded_entries,
    env_layout,
)
from .batch import play_batch, simulate_struck, simulate_struck_batch
from .carom_observation import CAROM_OBSERVATION_SIZE, CaromView, carom_observation, decode_carom_observation
from .core import Game
from .modes import MODES, RULES_MODES, Mode, mode_of
from .observation import (
    GAME_BALLS,
    N_BALLS,
    GameView,
    break_observation,
    break_observations,
    decode_game_observation,
    decode_observation,
    game_observation,
    game_observation_size,
    game_view,
)
from .placement import place_cue_ball, placement_area
from .shot import CONTACT_TIME, MAX_FORCE, MAX_SPEED, MAX_TIP_OFFSET, NOISE_PRESETS, Shot, noise_of, noisy_shot
from .shot_record import GameSnapshot, ShotRecord, StruckShot
from .snooker_observation import SnookerView, decode_snooker_observation, snooker_observation

__all__ = [
    "Game", "Shot", "ShotRecord", "GameSnapshot", "StruckShot", "play_batch", "simulate_struck",
    "simulate_struck_batch", "MODES", "RULES_MODES", "Mode", "mode_of", "LAYOUTS", "ELEVATED", "ActionLayout",
    "cue_force", "elevation_entry", "decode_entries", "encoded_entries", "game_view",
    "decode_action", "encode_action", "N_BALLS", "GameView", "GAME_BALLS", "break_observation", "break_observations",
    "decode_observation", "game_observation", "decode_game_observation", "game_observation_size",
    "place_cue_ball", "placement_area", "CONTACT_TIME", "MAX_FORCE", "MAX_SPEED", "MAX_TIP_OFFSET",
    "NOISE_PRESETS", "noise_of", "noisy_shot", "env_layout", "decode_decision", "encode_decision",
    "CAROM_OBSERVATION_SIZE", "CaromView", "carom_observation", "decode_carom_observation",
    "SnookerView", "decode_snooker_observation", "snooker_observation",
]
