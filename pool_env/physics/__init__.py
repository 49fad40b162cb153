"""pool_env.physics: exact continuous-time, event-based pool physics."""

from .batch import simulate_batch
from .config import Physics
from .cue import strike
from .kinds import EVENT_KINDS, STATE_NAMES
from .objects import BALL_MASS, BALL_RADIUS, CAROM_MASS, CAROM_RADIUS, SEED_MASS, SEED_RADIUS, Balls, Table, rack
from .pocket_shape import PocketShape
from .result import Event, Result, SimulationError
from .simulate import simulate, warm_up

__all__ = [
    "Balls", "Table", "PocketShape", "Physics", "simulate", "simulate_batch", "strike", "rack", "Event", "Result",
    "SimulationError",
    "EVENT_KINDS", "STATE_NAMES", "warm_up", "BALL_RADIUS", "BALL_MASS", "SEED_RADIUS", "SEED_MASS",
    "CAROM_RADIUS", "CAROM_MASS",
]
