"""`python -m pool_env.bench stability --multi-shot`: random shot sequences from wherever the balls stop.

Every shot starts from the state the previous one left (balls hanging in a pocket's jaws,
frozen to rails or to each other, in clusters), so it tests what a single random break does
not: that every state the engine leaves is a valid start. A sequence starts from a jittered
rack on `Table.eight_foot()` with a break; each later shot strikes the cue ball at 0.2-8 m/s
in a random direction (half of them aimed at a random object ball) with a random tip offset
within the miscue limit. A pocketed cue ball is put back on a random free spot (ball in
hand); a sequence ends after `length` shots or when no object ball is left.

Per shot: the engine must finish (no SimulationError), the final state must pass
`check_on_table` (so the next shot may start from it); every `check_every`-th shot is also
simulated under `invariants.run_checked` (every invariant at every event, and an identical
rerun). Shot k of sequence s draws from numpy.random.default_rng([seed, s, k]).
"""

from __future__ import annotations

import collections
import math
import time

import numpy as np

MAX_OFFSET = 0.5  # tip offset, in R: the miscue limit
last_failure = []  # the struck balls of the last failing shot (to save it as a regression)


def _shot(rng, balls, table, physics, first):
    """The struck balls of one random shot (the break when `first`)."""
    from pool_env.physics import BALL_MASS, strike

    xy = balls.xy
    on = np.flatnonzero(~balls.pocketed[1:]) + 1
    if first:
        angle, speed = math.atan2(*(xy[1] - xy[0])[::-1]) + rng.normal(0.0, 0.02), rng.uniform(4.0, 10.0)
    elif on.size and rng.random() < 0.5:
        target = xy[rng.choice(on)] - xy[0]
        angle, speed = math.atan2(target[1], target[0]) + rng.normal(0.0, 0.03), rng.uniform(0.2, 8.0)
    else:
        angle, speed = rng.uniform(0.0, 2.0 * math.pi), rng.uniform(0.2, 8.0)
    r, a = MAX_OFFSET * math.sqrt(rng.random()), rng.uniform(0.0, 2.0 * math.pi)
    force = speed * BALL_MASS / 0.005
    return strike(balls, force=(force * math.cos(angle), force * math.sin(angle)),
                  offset=(r * math.cos(a), r * math.sin(a)))


def _ball_in_hand(rng, balls, table):
    """The balls with a pocketed cue ball put back on a random free spot."""
    from pool_env.bench.stability import _free_spot
    from pool_env.physics import BALL_RADIUS, Balls

    on = ~balls.pocketed
    on[0] = False
    spot = _free_spot(rng, balls.xy[on], table, BALL_RADIUS)
    xy, pocketed = balls.xy.copy(), balls.pocketed.copy()
    xy[0], pocketed[0] = spot, False
    return Balls(xy, pocketed=pocketed)


def run(sequences, length, seed=0, physics=None, check_every=100, first=0):
    """Run the sweep; returns a summary dict: shots, failures [(sequence, shot, message)],
    events per shot, balls hanging in a mouth at the end of a shot, wall time."""
    from pool_env.physics import Physics, SimulationError, Table, rack, simulate
    from pool_env.physics.invariants import run_checked
    from pool_env.physics.simulate import check_on_table

    table, physics = Table.eight_foot(), physics or Physics.standard()
    failures, events, hanging, shots = [], [], 0, 0
    last_failure.clear()
    wall = time.perf_counter()
    for s in range(first, first + sequences):
        balls = rack(table, seed=int(np.random.default_rng([seed, s]).integers(2**31)))
        for k in range(length):
            rng = np.random.default_rng([seed, s, k])
            if balls.pocketed[0]:
                balls = _ball_in_hand(rng, balls, table)
            struck = _shot(rng, balls, table, physics, k == 0)
            shots += 1
            try:
                if shots % check_every == 0:
                    result, violations = run_checked(struck, table, physics, rerun=True)
                    for v in violations:
                        failures.append((s, k, f"{v.kind}: {v.detail}"))
                else:
                    result = simulate(struck, table, physics)
                check_on_table(result.final, table, physics)
            except (SimulationError, ValueError) as exc:
                failures.append((s, k, f"{type(exc).__name__}: {exc}"))
                last_failure[:] = [struck]
                break
            balls = result.final
            events.append(len(result.event_times))
            hanging += int(np.count_nonzero(~balls.pocketed & _in_a_mouth(balls.xy, table)))
            if balls.pocketed[1:].all():
                break
    return {"shots": shots, "failures": failures, "events": np.array(events), "hanging": hanging,
            "wall": time.perf_counter() - wall}


def _in_a_mouth(xy, table):
    """Which centres are past a nose line (in a pocket's throat)."""
    x, y = xy[:, 0], xy[:, 1]
    return (x < 0.0) | (y < 0.0) | (x > table.length) | (y > table.width)


def report(summary, show=5):
    """Print the sweep's summary; returns the number of failures."""
    from pool_env.bench.stability import distribution

    s = summary
    counts = collections.Counter(message.split(":")[0] for _, _, message in s["failures"])
    print(f"{s['shots']} shots in {s['wall']:.0f} s ({1e6 * s['wall'] / max(s['shots'], 1):.0f} us a shot)")
    print(f"failures: {len(s['failures'])}" + (f" ({dict(counts)})" if counts else ""))
    for seq, k, message in s["failures"][:show]:
        print(f"  sequence {seq}, shot {k}: {message}")
    print(f"events per shot: {distribution(s['events'])}")
    print(f"balls left with their centre past a nose line (hanging in a pocket's mouth): {s['hanging']}")
    return len(s["failures"])
