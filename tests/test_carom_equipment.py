"""The carom presets against the UMB equipment rules, and a carom ball's run to a cushion against its closed form.

UMB Sports Rules (carom) 2.1: playing surface 2.84 x 1.42 m (+-5 mm), cushion 37 mm (+-1 mm)
high at its nose; 2.2: balls 61-61.5 mm in diameter, 205-220 g. pooltool's three-cushion
cushion (BILLIARD_GENERIC): e_c 0.85, f_c 0.5.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env.physics import CAROM_MASS, CAROM_RADIUS, Balls, Physics, Table, simulate, strike
from pool_env.physics.config import cushion_reach


def test_the_carom_table_is_the_umb_table():
    table = Table.carom()
    assert abs(table.length - 2.84) <= 0.005 and abs(table.width - 1.42) <= 0.005
    assert table.pockets.shape[0] == 0
    assert abs(table.cushion_height - 0.037) <= 0.001
    # The nose sits above the ball's equator and below its top (a cushion the ball can meet).
    assert CAROM_RADIUS < table.cushion_height < 2 * CAROM_RADIUS


def test_carom_balls_are_in_the_umb_ranges():
    assert 0.061 <= 2 * CAROM_RADIUS <= 0.0615
    assert 0.205 <= CAROM_MASS <= 0.220


def test_the_carom_physics_preset():
    p = Physics.carom()
    assert (p.e_c, p.f_c) == (0.85, 0.5)  # pooltool's three-cushion cushion
    assert (p.mu_s, p.mu_r) == (0.2, 0.01)  # Alciatore's cloth
    assert p.cushion == "han2005"
    with pytest.raises(AttributeError):
        p.e_c = 0.9  # frozen


def test_a_carom_ball_reaches_the_cushion_where_and_when_the_closed_form_says():
    """A centre-struck ball slides (deceleration mu_s g) until v = 5/7 v0 at t1 = 2 v0 / (7 mu_s g),
    then rolls (deceleration mu_r g). The han2005 cushion meets it at its nose height h: the
    centre is R cos(theta) from the nose, sin(theta) = h / R - 1."""
    table, physics = Table.carom(), Physics.carom()
    R, h, g = CAROM_RADIUS, table.cushion_height, physics.g
    y0, v0 = 0.5, 2.0
    balls = Balls([[1.42, y0], [0.3, 0.3], [2.5, 0.3]], radius=CAROM_RADIUS, mass=CAROM_MASS)
    force = v0 * CAROM_MASS / 0.005
    result = simulate(strike(balls, (0.0, force), (0.0, 0.0), 0.005), table, physics)
    hits = [e for e in result.events if e.kind == "ball_cushion" and e.i == 0]
    assert hits, "the ball never reached the cushion"
    reach = R * math.sqrt(1.0 - (h / R - 1.0) ** 2)
    assert cushion_reach(R, h, "han2005") == pytest.approx(reach, rel=1e-12)
    distance = table.width - reach - y0
    mu_s, mu_r = physics.mu_s, physics.mu_r
    t1 = 2.0 * v0 / (7.0 * mu_s * g)
    d1 = v0 * t1 - 0.5 * mu_s * g * t1**2
    assert distance > d1  # rolling when it arrives
    v1 = 5.0 / 7.0 * v0
    rest = distance - d1  # v1 t - mu_r g t^2 / 2 = rest
    t2 = (v1 - math.sqrt(v1**2 - 2.0 * mu_r * g * rest)) / (mu_r * g)
    assert hits[0].time == pytest.approx(t1 + t2, rel=1e-9)
    rows, _ = result.sample(np.array([hits[0].time]))
    assert rows[0, 0, 1] == pytest.approx(table.width - reach, abs=1e-9)


def test_a_carom_shot_hits_a_ball_and_three_cushions_in_the_engine():
    """Balls of this radius on this table: the cue ball meets the red and cushions, the run ends."""
    table, physics = Table.carom(), Physics.carom()
    balls = Balls([[0.7, 0.4], [1.8, 1.0], [2.2, 0.5]], radius=CAROM_RADIUS, mass=CAROM_MASS)
    result = simulate(strike(balls, (176.30227694668886, 170.90389885995367), (0.0, 0.0), 0.005), table, physics)
    kinds = [(e.kind, e.i, e.j) for e in result.events if e.kind in ("ball_ball", "ball_cushion") and 0 in (e.i, e.j)]
    assert sum(k == "ball_cushion" for k, _, _ in kinds) >= 3
    assert {j for k, i, j in kinds if k == "ball_ball"} | {i for k, i, j in kinds if k == "ball_ball"} >= {0, 1, 2}
    assert not result.final.v.any()
