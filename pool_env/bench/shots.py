"""The speed benchmarks' two shots (the 16-ball break at 8 m/s, the 2-ball cut) and `fmt_time` for durations."""

from __future__ import annotations

import math


def break_shot(seed):
    """The benchmark's 16-ball break: cue ball at 8 m/s, centre hit on the head ball."""
    from pool_env.physics import BALL_MASS, Table, rack, strike

    table = Table.eight_foot()
    balls = rack(table, seed=seed)
    aim = balls.xy[1] - balls.xy[0]
    force = aim / math.hypot(*aim) * 8.0 * BALL_MASS / 0.005
    return strike(balls, force=force), table


def two_ball_shot():
    """2 m/s stun shot into an object ball 0.5 m away at a 15 degree cut."""
    from pool_env.physics import BALL_MASS, BALL_RADIUS, Balls, Table, strike

    cut = math.radians(15.0)
    balls = Balls([[0.5, 0.56], [1.0, 0.56 + 2 * BALL_RADIUS * math.sin(cut)]])
    return strike(balls, force=(2.0 * BALL_MASS / 0.005, 0.0)), Table.eight_foot()


def fmt_time(seconds, us_digits=1):
    """A duration in us, ms or s, whichever reads best."""
    if seconds < 1e-3:
        return f"{seconds * 1e6:.{us_digits}f} us"
    if seconds < 1.0:
        return f"{seconds * 1e3:.2f} ms"
    return f"{seconds:.2f} s"
