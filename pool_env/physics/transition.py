"""Motion transitions: sliding to rolling, rolling to spinning or rest, spinning to rest."""

from numba import njit

from .motion import ROLLING, SLIDING, SPINNING, VX, VY, WX, WY, WZ, classify

# Event-kind ids (see engine.EVENT_KINDS).
SLIDING_ROLLING, ROLLING_SPINNING, ROLLING_STATIONARY, SPINNING_STATIONARY = 3, 4, 5, 6
SLIDING_STATIONARY, SLIDING_SPINNING = 7, 8


@njit(cache=True)
def sliding_to_rolling(row, radius):
    """The slip has just vanished: lock the spin to the velocity (removes round-off)."""
    row[WX] = -row[VY] / radius
    row[WY] = row[VX] / radius


@njit(cache=True)
def rolling_to_rest(row):
    """Rolling resistance has just stopped the ball; only z-spin may remain."""
    row[VX] = row[VY] = row[WX] = row[WY] = 0.0


@njit(cache=True)
def spinning_to_rest(row):
    row[WZ] = 0.0


@njit(cache=True)
def resolve(row, state, radius):
    """Apply the transition due for a ball in `state` (its row already at the event time);
    returns the event-kind id."""
    if state == SLIDING:
        sliding_to_rolling(row, radius)
        new = classify(row, radius)
        if new == ROLLING:
            return SLIDING_ROLLING
        return SLIDING_SPINNING if new == SPINNING else SLIDING_STATIONARY
    if state == ROLLING:
        rolling_to_rest(row)
        return ROLLING_SPINNING if classify(row, radius) == SPINNING else ROLLING_STATIONARY
    spinning_to_rest(row)
    return SPINNING_STATIONARY
