"""Fixed-step simulation (method="fixed"): convergence to the exact engine, the seed report's behaviours, options."""

import numpy as np
import pytest

from pool_env.physics import (
    BALL_RADIUS,
    SEED_MASS,
    SEED_RADIUS,
    Balls,
    Physics,
    Table,
    rack,
    simulate,
    strike,
)

R = BALL_RADIUS
METHODS = [("posteriori", False), ("priori", False), ("priori", True)]
DTS = [1e-2, 1e-3, 1e-4, 1e-5]


def fixed(balls, table, physics, dt, detection, recheck=False):
    return simulate(balls, table, physics, method="fixed", dt=dt, detection=detection, recheck=recheck)


def final_error(result, exact):
    """Largest distance (m) between where a ball ends in `result` and in the exact run."""
    return float(np.max(np.hypot(*(result.final.xy - exact.final.xy).T)))


# Simple scenes, standard physics. The head-on pair runs on a long table so that it makes
# exactly one contact; the cut and the bank use the pocketless 2.24 x 1.12 m table.
LONG = Table(10.0, 2.0)
HEAD_ON = Balls([[0.4, 1.0], [1.0, 1.0]], v=[[2.0, 0.0], [0.0, 0.0]])
CUT = Balls([[0.4, 0.50], [1.0, 0.56]], v=[[2.0, 0.0], [0.0, 0.0]])
BANK = Balls([[0.4, 0.3]], v=[[1.5, -1.0]])


@pytest.mark.parametrize("detection, recheck", METHODS)
def test_friction_only_is_exact_at_any_step(detection, recheck):
    # With nothing to collide with, the fixed-step run follows the same closed-form laws and
    # applies transitions at their exact times: only detection can make the methods differ.
    big = Table(20.0, 20.0)
    balls = strike(Balls([[10.0, 10.0]]), force=(50.0, 15.0), offset=(0.3, -0.4))
    exact = simulate(balls, big, Physics.standard())
    res = fixed(balls, big, Physics.standard(), 1 / 60, detection, recheck)
    assert [e.kind for e in res.events] == [e.kind for e in exact.events]
    assert np.allclose([e.time for e in res.events], [e.time for e in exact.events], rtol=1e-12)
    assert np.allclose(res.final.xy, exact.final.xy, rtol=0, atol=1e-12)
    for t in (0.003, 0.1, 0.5 * exact.duration):  # at() inside a frame: closed form too
        assert np.allclose(res.at(t).xy, exact.at(t).xy, rtol=0, atol=1e-12)
        assert np.allclose(res.at(t).w, exact.at(t).w, rtol=0, atol=1e-9)


@pytest.mark.slow
def test_posteriori_head_on_error_is_first_order():
    # The overlap is found up to one frame late, delta in [0, dt): the striker has run
    # v delta into the object ball, and the push splits that depth equally, so each ball
    # starts its post-collision path at most v delta / 2 from where the exact one has it at
    # that moment. And the striker has slowed for delta, so the object ball leaves slower by
    # about mu_r g delta and stops short by at most as much again (its run-out scales with
    # the square of its speed, v^2 / (2 mu_r g) times 25/49 for the slide). So the final
    # error is at most v delta <= v0 dt: first order.
    v0 = 2.0
    exact = simulate(HEAD_ON, LONG, Physics.standard())
    assert exact.stats["ball_ball"] == 1 and exact.stats["ball_cushion"] == 0
    errors = []
    for dt in DTS:
        res = fixed(HEAD_ON, LONG, Physics.standard(), dt, "posteriori")
        errors.append(final_error(res, exact))
        assert errors[-1] <= v0 * dt
        assert res.stats["max_overlap_depth"] <= v0 * dt  # the striker's travel in one frame
        assert res.stats["ball_ball"] == 1
    # The trend: two decades of dt buy well over one decade of accuracy (first order: two).
    assert errors[2] < errors[0] / 20 and errors[3] < errors[1] / 20


@pytest.mark.slow
@pytest.mark.parametrize("balls", [CUT, BANK], ids=["cut", "bank"])
def test_posteriori_converges_on_cut_and_bank(balls):
    exact = simulate(balls, Table.seed(), Physics.standard())
    errors = [final_error(fixed(balls, Table.seed(), Physics.standard(), dt, "posteriori"), exact) for dt in DTS]
    assert errors[2] < errors[0] / 20 and errors[3] < errors[1] / 20
    assert errors[3] < 1e-4  # 0.1 mm at dt = 10 us


@pytest.mark.slow
@pytest.mark.parametrize("recheck", [False, True])
@pytest.mark.parametrize("balls, table", [(HEAD_ON, LONG), (CUT, Table.seed()), (BANK, Table.seed())],
                         ids=["head-on", "cut", "bank"])
def test_priori_error_is_second_order(balls, table, recheck):
    # The straight-line prediction ignores friction, so within a frame a ball strays at most
    # a dt^2 / 2 (a <= mu_s g) from the predicted line: contacts are resolved that far from
    # where they happen, and the changed contact speed moves the object ball by less than as
    # much again (its travel scales with v^2 / (2 mu_r g), so the shift is 25/49 of the
    # contact error). Hence final error <= mu_s g dt^2: second order.
    phys = Physics.standard()
    exact = simulate(balls, table, phys)
    errors = []
    for dt in DTS:
        errors.append(final_error(fixed(balls, table, phys, dt, "priori", recheck), exact))
        assert errors[-1] <= phys.mu_s * phys.g * dt**2 + 1e-10
    # Where a contact falls within its frame varies with dt, so compare two decades apart:
    # more than first order's factor 100 (second order gives 10^4 up to that phase).
    assert errors[2] < errors[0] / 300 and errors[3] < errors[1] / 300


def test_seed_preset_rolls_at_five_sevenths_at_60_fps():
    # The report's eq. 2.10: a centre-hit ball starts rolling at 5/7 of its initial speed.
    balls = strike(Balls([[0.3, 0.56]], radius=SEED_RADIUS, mass=SEED_MASS), force=(60.0, 0.0))
    v0 = balls.v[0, 0]
    res = fixed(balls, Table.seed(), Physics.seed(), 1 / 60, "priori")
    roll = res.events[0]
    assert roll.kind == "sliding_rolling"
    at = res.at(roll.time)
    assert at.v[0, 0] == pytest.approx(5 / 7 * v0, rel=1e-12)
    assert at.w[0, 1] == pytest.approx(5 / 7 * v0 / SEED_RADIUS, rel=1e-12)


def cluster():
    """The report's chapter-5 failure: a fast cue ball into two balls 0.5 mm apart. The first
    contact comes 1 ms into the first frame; the second 64 us later, in the same frame."""
    r = SEED_RADIUS
    xy = [[0.5, 0.56], [0.5 + 2 * r + 0.008, 0.56], [0.5 + 4 * r + 0.0085, 0.56]]
    return strike(Balls(xy, radius=r, mass=SEED_MASS), force=(240.0, 0.0))  # 8 m/s


def test_tight_cluster_misses_the_second_collision_unless_rechecked():
    balls = cluster()
    exact = simulate(balls, Table.seed(), Physics.seed())
    second = [e for e in exact.events if e.kind == "ball_ball"][1]
    assert (second.i, second.j) == (1, 2) and second.time < 1 / 60

    missed = fixed(balls, Table.seed(), Physics.seed(), 1 / 60, "priori", recheck=False)
    hits = [e for e in missed.events if e.kind == "ball_ball"]
    assert hits[0].time < 1 / 60 and (hits[0].i, hits[0].j) == (0, 1)
    # Ball 1 runs straight through ball 2 (13 cm in the rest of the frame) and ball 2 is only
    # reached much later, after ball 1 has come back off the far cushion.
    assert next(e for e in hits if (e.i, e.j) == (1, 2)).time > 0.1
    assert missed.at(1 / 60).xy[1, 0] > missed.at(1 / 60).xy[2, 0]

    rechecked = fixed(balls, Table.seed(), Physics.seed(), 1 / 60, "priori", recheck=True)
    hits = [e for e in rechecked.events if e.kind == "ball_ball"]
    assert [(e.i, e.j) for e in hits[:2]] == [(0, 1), (1, 2)]
    assert hits[1].time == pytest.approx(second.time, abs=1e-6)
    assert final_error(rechecked, exact) < 1e-3


@pytest.mark.parametrize("detection, recheck", METHODS)
def test_break_contract(detection, recheck):
    table = Table.eight_foot()
    balls = strike(rack(table, seed=3), force=(272.0, 0.0))
    res = fixed(balls, table, Physics.standard(), 1 / 60, detection, recheck)
    again = fixed(balls, table, Physics.standard(), 1 / 60, detection, recheck)
    assert res.events == again.events  # deterministic
    times = [e.time for e in res.events]
    assert times == sorted(times) and res.duration == times[-1]
    assert not np.any(res.final.v) and not np.any(res.final.w)
    on = ~res.final.pocketed
    x, y = res.final.xy[on].T
    assert np.all((x > -1e-9) & (x < table.length + 1e-9) & (y > -1e-9) & (y < table.width + 1e-9))
    pocketed = {e.i for e in res.events if e.kind == "ball_pocket"}
    assert pocketed == set(np.flatnonzero(res.final.pocketed))
    stats = res.stats
    assert stats["method"] == "fixed" and stats["detection"] == detection and stats["recheck"] == recheck
    last_contact = max(e.time for e in res.events if e.kind in ("ball_ball", "ball_cushion"))
    assert stats["steps"] >= round(last_contact * 60)
    assert stats["wall_time"] > 0 and stats["max_overlap_depth"] >= 0
    # Kinetic energy never rises: friction, the collision models and the pushes only take.
    energy = [res.at(t).energy() for t in np.linspace(0.0, res.duration, 200)]
    assert all(b <= a * (1 + 1e-9) + 1e-12 for a, b in zip(energy, energy[1:]))


@pytest.mark.parametrize("detection", ["posteriori", "priori"])
def test_pockets_at_frame_end(detection):
    t = Table.eight_foot()
    b = Balls([[0.5, 0.5], [1.12, 0.3]], v=[[-2.0, -2.0], [0.0, -2.0]])
    res = fixed(b, t, Physics.standard(), 1 / 60, detection)
    assert {e.i: e.j for e in res.events if e.kind == "ball_pocket"} == {0: 0, 1: 4}
    assert all(round(e.time * 60, 9).is_integer() for e in res.events if e.kind == "ball_pocket")


@pytest.mark.parametrize("options, match", [
    ({"detection": "sideways"}, "unknown detection"),
    ({"dt": 0.0}, "dt must be"),
    ({"dt": -0.01}, "dt must be"),
    ({"dt": float("nan")}, "dt must be"),
    ({"dt": float("inf")}, "dt must be"),
    ({"dt": "fast"}, "dt must be"),
    ({"detection": "posteriori", "recheck": True}, "needs detection='priori'"),
    ({"recheck": "yes"}, "recheck must be"),
])
def test_bad_options(options, match):
    with pytest.raises(ValueError, match=match):
        simulate(HEAD_ON, LONG, method="fixed", **options)


def test_unknown_method_and_option():
    with pytest.raises(ValueError, match="'events', 'fixed'"):
        simulate(HEAD_ON, LONG, method="verlet")
    with pytest.raises(TypeError, match="substeps"):
        simulate(HEAD_ON, LONG, method="fixed", substeps=4)
