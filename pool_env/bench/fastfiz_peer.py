"""The 2-ball benchmark shot through FastFiz's `TableState.executeShot`, run by FastFiz's own Python.

`python -m pool_env.bench speed` runs this file as a script with an interpreter that can import
`fastfiz` (a separate environment: FastFiz builds from source with SWIG and GSL), so it
imports nothing from pool_env, nor numpy. Arguments: the ball radius (m), the cue and object
ball centres in our frame (x along the table's length, y across), the cue ball's speed (m/s)
and the number of timed shots. Prints one JSON line: the seconds of each timed shot, the
events of one shot and the speed the cue ball left at.

Same shot: FastFiz's table runs x across and y along the length, so our (x, y) is its (y, x)
(a mirror, which keeps every distance and angle); the cue points along our +x. FastFiz takes
the cue's speed, not the ball's, so a first strike measures the ratio and the cue speed is
scaled to give the ball our speed. Its cue cannot be level here (the butt would pass through
the end rail behind the ball): it is raised to the lowest whole degree that FastFiz accepts,
and hits the centre of the ball.
"""

import json
import sys
import time

import fastfiz


def table_with(cue_xy, object_xy):
    """A fresh FastFiz table with the cue ball and the one ball at rest (our frame given)."""
    state = fastfiz.TableState()
    state.setBall(fastfiz.Ball.CUE, fastfiz.Ball.STATIONARY, fastfiz.Point(cue_xy[1], cue_xy[0]))
    state.setBall(fastfiz.Ball.ONE, fastfiz.Ball.STATIONARY, fastfiz.Point(object_xy[1], object_xy[0]))
    return state


def lowest_elevation(cue_xy, object_xy):
    """The lowest whole-degree cue elevation FastFiz accepts for this shot, and its shot."""
    for theta in range(0, 30):
        params = fastfiz.ShotParams(0.0, 0.0, float(theta), 90.0, 1.0)
        state = table_with(cue_xy, object_xy)
        try:
            shot = state.executeShot(params)
        except ValueError:  # FastFiz refuses a cue that would hit a rail or a ball
            continue
        return theta, shot
    raise SystemExit("FastFiz accepts no cue elevation below 30 degrees for this shot")


def ball_speed(shot):
    """The cue ball's speed just after the cue strike (the first event)."""
    event = shot.getEventList()[0]
    v = event.getBall1Data().getVelocity()
    return (v.x * v.x + v.y * v.y) ** 0.5


def main(argv):
    radius, cx, cy, ox, oy, speed, repeats = (float(a) for a in argv)
    cue_xy, object_xy = (cx, cy), (ox, oy)
    theta, probe = lowest_elevation(cue_xy, object_xy)
    params = fastfiz.ShotParams(0.0, 0.0, float(theta), 90.0, speed / ball_speed(probe))
    shot = table_with(cue_xy, object_xy).executeShot(params)
    seconds = []
    for _ in range(int(repeats)):
        state = table_with(cue_xy, object_xy)  # untimed: a fresh table for every shot
        start = time.perf_counter()
        state.executeShot(params)
        seconds.append(time.perf_counter() - start)
    state = table_with(cue_xy, object_xy)  # kept alive: getBall returns a view into it
    theirs = state.getBall(fastfiz.Ball.CUE).getRadius()
    if abs(theirs - radius) > 1e-9:
        raise SystemExit(f"FastFiz's balls have radius {theirs} m, ours {radius} m: not the same shot")
    print(json.dumps({"seconds": seconds, "events": len(shot.getEventList()), "speed": ball_speed(shot),
                      "theta": theta}))


if __name__ == "__main__":
    main(sys.argv[1:])
