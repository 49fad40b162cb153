"""Ball-pocket events: a ball drops when its centre enters the pocket's opening (pocket_shape.py)."""


from .geometry import distance_entry
from .jit import helper
from .kinds import VX, VY, WX, WY, WZ


@helper
def capture_time(path, horizon, pocket):
    """Earliest tau in [0, horizon] at which the centre of the ball on `path` (its trajectory
    now, as motion.trajectory gives it) enters the opening [cx, cy, r] (or inf)."""
    x, y, vx, vy, ax, ay = path
    return distance_entry(x - pocket[0], y - pocket[1], vx, vy, ax, ay, pocket[2], horizon)


@helper
def capture(row):
    """The ball is off the table: it keeps the position where it dropped, and stops."""
    row[VX] = row[VY] = row[WX] = row[WY] = row[WZ] = 0.0
