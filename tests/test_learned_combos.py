"""agents.learned_combos: the third ball a shot sends its object ball or the cue ball into, and its line to a pocket."""

import math

import numpy as np
import pytest

from agents import learned_combos as lc
from agents.learned import CANDIDATE_FEATURES, KINDS
from agents.learned_features import GAP_CAP
from agents.search import SearchAgent
from pool_env.game import MAX_SPEED, GameView
from pool_env.physics import BALL_RADIUS, Table
from pool_env.players import geometry

TABLE = Table.eight_foot()
L, W, R = TABLE.length, TABLE.width, BALL_RADIUS
SEARCH = SearchAgent("nine_ball", noise=None)
PHYS = SEARCH.physics
MU_R_G = PHYS.mu_r * PHYS.g
DIAGONAL = np.array([1.0, 1.0]) / math.sqrt(2.0)  # from the corner pocket at the origin up the table


def view(balls: dict, legal=(1,)) -> GameView:
    xy = np.tile([L / 2, W / 2], (10, 1)).astype(np.float64)
    on = np.zeros(10, dtype=bool)
    for b, p in balls.items():
        xy[b], on[b] = p, True
    return GameView(xy, on, frozenset(legal))


def row(cue, direction, speed: float, kind: str = "pot", top: float = 0.0) -> np.ndarray:
    """A `candidate_features` row with what `combo_columns` reads: kind, speed, tip, direction, the cue ball."""
    f = np.zeros(CANDIDATE_FEATURES, dtype=np.float32)
    f[KINDS.index(kind)] = 1.0
    f[4], f[6] = speed / MAX_SPEED, top
    f[7:9] = direction
    f[10:12] = np.asarray(cue) * [2.0 / L, 2.0 / W] - 1.0
    return f


def test_a_straight_combination_into_a_corner_drops_the_nine_at_the_speed_two_collisions_leave_it():
    # cue ball, the 1 and the 9 on the corner pocket's diagonal: the 1 leaves at (1 + e_b) / 2 of
    # the cue ball's speed at the contact (`geometry.speed_after` of its run), the 9 at (1 + e_b) / 2
    # of the 1's, and the 9's line runs through the pocket's centre
    nine, one, cue = 0.4 * DIAGONAL * math.sqrt(2.0), 0.7 * DIAGONAL * math.sqrt(2.0), 1.0 * DIAGONAL * math.sqrt(2.0)
    d = view({0: cue, 1: one, 9: nine})
    cols = lc.combo_columns(SEARCH, row(cue, -DIAGONAL, 3.0)[None], d, 9)[0]
    e = 0.5 * (1.0 + PHYS.e_b)
    v1 = e * geometry.speed_after(3.0, float(np.hypot(*(cue - one))) - 2 * R, PHYS)
    v9 = e * geometry.speed_after(v1, float(np.hypot(*(one - nine))) - 2 * R, PHYS)
    assert cols[:2].tolist() == [1.0, 1.0] and cols[4:6].tolist() == [1.0, 1.0]
    assert cols[2] == pytest.approx(GAP_CAP + 0.05)  # the gap is clipped at -5 cm
    assert cols[3] == pytest.approx(v9 / MAX_SPEED, rel=1e-6)
    assert not cols[6:].any()  # a full hit stops the cue ball's run along the line: it meets nothing new


def test_the_nine_off_the_line_a_blocker_before_the_pocket_or_too_little_speed_do_not_drop_it():
    nine, one, cue = 0.4 * DIAGONAL * math.sqrt(2.0), 0.7 * DIAGONAL * math.sqrt(2.0), 1.0 * DIAGONAL * math.sqrt(2.0)
    shot = row(cue, -DIAGONAL, 3.0)[None]
    aside = lc.combo_columns(SEARCH, shot, view({0: cue, 1: one, 9: nine + [3 * R, -3 * R]}), 9)[0]
    assert not aside[:6].any()
    blocked = lc.combo_columns(SEARCH, shot, view({0: cue, 1: one, 9: nine, 2: 0.15 * DIAGONAL * math.sqrt(2)}), 9)[0]
    assert blocked[:2].tolist() == [1.0, 1.0] and blocked[4] == 0.0
    soft = lc.combo_columns(SEARCH, row(cue, -DIAGONAL, 0.9)[None], view({0: cue, 1: one, 9: nine}), 9)[0]
    assert soft[:2].tolist() == [1.0, 1.0] and soft[4] == 0.0  # the 9 rolls about 0.3 m of its 0.55 m to the pocket
    other = lc.combo_columns(SEARCH, shot, view({0: cue, 1: one, 3: nine}), 9)[0]
    assert other[4] == 1.0 and other[5] == 0.0  # a combination that drops the 3: a pot, not a win


def test_a_stun_cut_sends_the_cue_ball_along_the_tangent_into_a_ball_there():
    # a half-ball cut from 5 cm, the cue ball still sliding without spin: it leaves at about 90
    # degrees to the line of centres (its (1 - e_b) / 2 share of the normal speed and the little
    # spin it picked up tilt it by a degree or two)
    obj, d = np.array([1.0, 0.56 + R]), np.array([1.0, 0.0])
    ghost = obj - 2 * R * np.array([math.cos(math.radians(30)), math.sin(math.radians(30))])
    cue = ghost - 0.05 * d
    n = geometry.unit(obj - ghost)
    tangent = np.array([n[1], -n[0]])  # the side of the line the cue ball's velocity keeps
    third = ghost + 0.3 * tangent
    cols = lc.combo_columns(SEARCH, row(cue, d, 2.0)[None], view({0: cue, 1: obj, 9: third}), 9)[0]
    assert cols[0] == 0.0 and cols[6:8].tolist() == [1.0, 1.0]


def test_breaks_kicks_and_shots_into_a_rail_first_have_zero_columns():
    cue = np.array([0.5, 0.5])
    d = view({0: cue, 1: [1.5, 0.5], 9: [1.8, 0.5]})
    rows = np.stack([row(cue, [1.0, 0.0], 5.0, "break"), row(cue, [0.0, -1.0], 3.0, "kick"),
                     row(cue, [0.0, 1.0], 3.0, "safety")])
    assert not lc.combo_columns(SEARCH, rows, d, 9).any()
    assert lc.combo_columns(SEARCH, row(cue, [1.0, 0.0], 5.0, "safety")[None], d, 9)[0, :2].tolist() == [1.0, 1.0]


def test_the_array_speeds_and_spins_are_the_scalar_closed_forms():
    from agents.learned_features import roll_at_contact

    for v0, dist in [(2.0, 0.1), (2.0, 1.5), (0.5, 2.0)]:
        assert lc.roll_speed(v0, dist, PHYS) == pytest.approx(geometry.speed_after(v0, dist, PHYS), abs=1e-12)
    for v0, dist, top in [(2.0, 0.1, 0.0), (2.0, 1.5, 0.0), (3.0, 0.4, -0.3), (3.0, 2.5, -0.3), (3.0, 0.3, 0.3),
                          (2.0, 1.0, 0.4)]:
        speed, spin = lc.struck_at(np.float64(v0), top, dist, PHYS)
        assert spin == pytest.approx(roll_at_contact(v0, top, dist, PHYS), abs=1e-9)
        if top == 0.0:
            assert speed == pytest.approx(geometry.speed_after(v0, dist, PHYS), abs=1e-9)
    speed, spin = lc.struck_at(np.float64(2.0), 0.4, 1.0, PHYS)  # natural roll: it rolls from the start
    assert speed == spin == pytest.approx(math.sqrt(4.0 - 2.0 * MU_R_G), abs=1e-9)
    assert lc.roll_speed(1.0, lc.reach(1.0, PHYS) + 1e-9, PHYS) == 0.0


def test_the_combo_columns_follow_the_safety_nets_or_are_refused():
    from agents.learned_train import with_pots

    data = {"features": np.zeros((2, 96), dtype=np.float32), "values": np.zeros(2), "decision": np.zeros(2, dtype=int)}
    with pytest.raises(ValueError, match="pass them all"):
        with_pots(data, None, combos=True)
