"""Ball-pocket events: a ball drops when its centre enters the pocket's capture circle."""

from numba import njit

from .cushion import point_time
from .motion import VX, VY, WX, WY, WZ


@njit(cache=True)
def capture_time(row, state, t, horizon, radius, params, pocket):
    """Earliest tau in [0, horizon] at which the centre enters pocket [cx, cy, r] (or inf)."""
    return point_time(row, state, t, horizon, radius, params, pocket[0], pocket[1], pocket[2])


@njit(cache=True)
def capture(row):
    """The ball is off the table: it keeps the position where it dropped, and stops."""
    row[VX] = row[VY] = row[WX] = row[WY] = row[WZ] = 0.0
