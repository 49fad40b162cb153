"""Ball-pocket events: a ball drops when its centre enters the pocket's opening (pocket_shape.py)."""


from .geometry import distance_entry
from .jit import helper
from .kinds import VX, VY, WX, WY, WZ
from .motion import trajectory


@helper
def capture_time(row, state, t, horizon, radius, params, pocket):
    """Earliest tau in [0, horizon] at which the centre enters the opening [cx, cy, r] (or inf)."""
    x, y, vx, vy, ax, ay = trajectory(row, state, t, radius, params)
    return distance_entry(x - pocket[0], y - pocket[1], vx, vy, ax, ay, pocket[2], horizon)


@helper
def capture(row):
    """The ball is off the table: it keeps the position where it dropped, and stops."""
    row[VX] = row[VY] = row[WX] = row[WY] = row[WZ] = 0.0
