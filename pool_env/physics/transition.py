"""Motion transitions: sliding to rolling, rolling to spinning or rest, spinning to rest."""


from .geometry import roll
from .jit import helper
from .kinds import (
    ROLLING,
    ROLLING_SPINNING,
    ROLLING_STATIONARY,
    SLIDING,
    SLIDING_ROLLING,
    SLIDING_SPINNING,
    SLIDING_STATIONARY,
    SPINNING,
    SPINNING_STATIONARY,
    VX,
    VY,
    WX,
    WY,
    WZ,
)
from .motion import classify


@helper
def rolling_to_rest(row):
    """Rolling resistance has just stopped the ball; only z-spin may remain."""
    row[VX] = row[VY] = row[WX] = row[WY] = 0.0


@helper
def resolve(row, state, radius):
    """Apply the transition due for a ball in `state` (its row already at the event time);
    returns the event-kind id. Sliding to rolling: the slip has just vanished, so the spin is
    locked to the velocity (which removes round-off)."""
    if state == SLIDING:
        roll(row, radius)
        new = classify(row, radius)
        if new == ROLLING:
            return SLIDING_ROLLING
        return SLIDING_SPINNING if new == SPINNING else SLIDING_STATIONARY
    if state == ROLLING:
        rolling_to_rest(row)
        return ROLLING_SPINNING if classify(row, radius) == SPINNING else ROLLING_STATIONARY
    row[WZ] = 0.0
    return SPINNING_STATIONARY
