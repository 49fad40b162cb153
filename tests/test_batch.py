"""simulate_batch: the same Results as a loop of simulate, whatever the threads; failures stay per scene."""

import numpy as np
import pytest

from pool_env.bench.speed import break_shot, two_ball_shot
from pool_env.physics import Balls, Physics, SimulationError, Table, simulate, simulate_batch

TABLE = Table.eight_foot()


def _scenes():
    """Breaks on different racks, a 2-ball cut and a ball struck into a pocket: short and long
    shots mixed, so the threads finish their scenes out of order."""
    scenes = [break_shot(seed)[0] for seed in range(9)]
    scenes.append(two_ball_shot()[0])
    scenes.append(Balls([[1.0, 0.56]], v=[[1.2, -0.6]]))
    return scenes


def _same(a, b):
    return (np.array_equal(a.final.xy, b.final.xy) and np.array_equal(a.final.pocketed, b.final.pocketed)
            and all(np.array_equal(x, y) for x, y in zip(a.event_arrays, b.event_arrays)))


@pytest.mark.parametrize("threads", [1, 2])
@pytest.mark.parametrize("physics", [Physics.standard(), Physics.seed()], ids=["standard", "seed"])
def test_batch_equals_a_loop_of_simulate(threads, physics):
    scenes = _scenes()
    loop = [simulate(b, TABLE, physics) for b in scenes]
    batch = simulate_batch(scenes, TABLE, physics, threads=threads)
    assert len(batch) == len(scenes)
    assert all(_same(a, b) for a, b in zip(loop, batch))
    assert any(r.final.pocketed.any() for r in batch)


def test_failing_scenes_are_reported_and_the_others_kept():
    scenes = _scenes()
    outside = Balls([[0.01, 0.5]])  # centre closer to the rail than R
    batch = scenes[:2] + [outside] + scenes[2:4] + ["not balls"]
    out = simulate_batch(batch, TABLE, Physics.standard(), threads=2)
    assert isinstance(out[2], ValueError) and "outside the rails" in str(out[2])
    assert isinstance(out[5], TypeError)
    for k, scene in ((0, scenes[0]), (1, scenes[1]), (3, scenes[2]), (4, scenes[3])):
        assert _same(out[k], simulate(scene, TABLE, Physics.standard()))
    # The event cap: a break cannot finish in 20 events; a 2-ball cut can (11).
    capped = simulate_batch([scenes[0], two_ball_shot()[0]], TABLE, Physics.standard(), max_events=20, threads=2)
    assert isinstance(capped[0], SimulationError) and "event cap of 20" in str(capped[0])
    assert capped[1].stats["events"] == 11


def test_threads_must_be_positive():
    with pytest.raises(ValueError, match="threads must be >= 1"):
        simulate_batch(_scenes(), TABLE, threads=0)
    assert simulate_batch([], TABLE) == []
