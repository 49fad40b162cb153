"""Snooker equipment against the WPBSA Official Rules, Section 1 (Equipment), and 22 balls through the engine.

Figures: WPBSA Section 1 Rule 1 (a) playing area 3569 x 1778 mm, (d) baulk line 737 mm from the
bottom cushion, (e) the D's radius 292 mm, (f) the spots; Rule 2 balls 52.5 mm. The pockets
(pooltool's measured snooker table; the WPBSA templates are unpublished) as physics/snooker.py cites.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env.physics import Balls, Table, simulate, strike
from pool_env.physics.simulate import check_on_table
from pool_env.physics.snooker import SNOOKER_BALL_MASS, SNOOKER_BALL_RADIUS
from pool_env.rules.snooker_spots import (
    BLACK,
    COLOURS,
    baulk_x,
    colour_spots,
    d_radius,
    snooker_rack,
    spot_colours,
)

TABLE = Table.snooker()


def test_table_is_the_wpbsa_playing_area():
    # WPBSA S1 R1(a): 11 ft 8 1/2 in x 5 ft 10 in = 3569 x 1778 mm inside the cushion faces.
    assert TABLE.length == pytest.approx((11 * 12 + 8.5) * 0.0254, abs=0.001)
    assert (TABLE.length, TABLE.width) == (3.569, 1.778)
    assert TABLE.width == pytest.approx(70 * 0.0254, abs=0.001)


def test_pockets_corners_and_middles():
    # WPBSA S1 R1(c)(i): four corner pockets and one in the middle of each long side.
    entries = TABLE.pocket_entries
    L, W = TABLE.length, TABLE.width
    centres = sorted((round(x, 4), round(y, 4)) for x, y, _ in entries)
    assert centres == sorted([(0, 0), (L, 0), (0, W), (L, W), (L / 2, 0), (L / 2, W)])
    corner = [m for x, y, m in entries if x in (0.0, L)]
    middle = [m for x, y, m in entries if x == L / 2]
    assert corner == [0.083] * 4 and middle == [0.087] * 2  # pooltool SnookerTableSpecs
    # Snooker pockets are much tighter than pool's (WPA corner 4.5-4.625 in = 114-117 mm).
    assert max(corner) < 4.5 * 0.0254 - 0.02
    # Rounded jaws (pooltool: 4 in at the corners, 2.5 in at the middles).
    assert TABLE.corner_pocket.jaw_radius == pytest.approx(4 * 0.0254)
    assert TABLE.side_pocket.jaw_radius == pytest.approx(2.5 * 0.0254)


def test_balls_and_cushion_height():
    # WPBSA S1 R2: 52.5 mm (+- 0.05 mm).
    assert 2 * SNOOKER_BALL_RADIUS == pytest.approx(0.0525, abs=0.05e-3)
    assert SNOOKER_BALL_MASS == 0.142
    # The cushion nose must sit below the top of the ball (else it would pass under) and above its centre.
    assert SNOOKER_BALL_RADIUS < TABLE.cushion_height < 2 * SNOOKER_BALL_RADIUS


def test_markings():
    L, W = TABLE.length, TABLE.width
    assert baulk_x(TABLE) == pytest.approx(29 * 0.0254, abs=0.001)  # S1 R1(d): 29 in = 737 mm
    assert d_radius(TABLE) == pytest.approx(11.5 * 0.0254, abs=0.001)  # S1 R1(e): 11 1/2 in = 292 mm
    spots = colour_spots(TABLE)
    yellow, green, brown, blue, pink, black = (spots[c] for c in COLOURS)
    assert brown == pytest.approx((0.737, W / 2))  # the middle of the baulk line
    assert blue == pytest.approx((L / 2, W / 2))  # midway between top and bottom cushions
    assert pink[0] == pytest.approx((blue[0] + L) / 2)  # midway between blue and the top cushion
    assert L - black[0] == pytest.approx(12.75 * 0.0254, abs=0.001)  # 12 3/4 in = 324 mm from the top
    # Yellow and green on the D's corners, yellow on the right seen from baulk (looking along +x: -y).
    assert yellow == pytest.approx((0.737, W / 2 - 0.292)) and green == pytest.approx((0.737, W / 2 + 0.292))


def test_rack_positions():
    # WPBSA S3 R2: reds in a triangle, apex as near the pink as possible without touching,
    # base parallel to the top cushion; colours on their spots.
    balls = snooker_rack(TABLE, seed=3)
    assert len(balls) == 22 and not balls.pocketed.any()
    check_on_table(balls, TABLE)
    spots = colour_spots(TABLE)
    for c in COLOURS:
        assert tuple(balls.xy[c]) == pytest.approx(spots[c])
    reds = balls.xy[1:16]
    d = np.hypot(*(reds - balls.xy[20]).T)
    assert d.min() > 2 * SNOOKER_BALL_RADIUS and d.min() < 2 * SNOOKER_BALL_RADIUS + 1e-3
    assert np.all(reds[:, 0] > balls.xy[20, 0]) and np.all(reds[:, 0] < balls.xy[21, 0] - 2 * SNOOKER_BALL_RADIUS)
    back = reds[np.argsort(reds[:, 0])[-5:]]
    assert np.ptp(back[:, 0]) < 3e-4  # the back row of five: parallel to the top cushion (to the jitter)
    assert not np.array_equal(snooker_rack(TABLE, seed=3).xy, snooker_rack(TABLE, seed=4).xy)
    assert np.array_equal(snooker_rack(TABLE, seed=3).xy, balls.xy)


@pytest.mark.parametrize("pocket", range(6))
def test_a_straight_pot_drops_in_every_pocket(pocket):
    # A ball rolled along the pocket's axis through the middle of the mouth drops into it.
    x, y, _ = TABLE.pocket_entries[pocket]
    L, W = TABLE.length, TABLE.width
    target = np.array([x, y]) - np.sign([x - L / 2, y - W / 2]) * (0.0 if x == L / 2 else 0.25)
    if x == L / 2:
        target = np.array([x, 0.3 if y == 0 else W - 0.3])
    centre = np.array([L / 2, W / 2])
    u = (np.array([x, y]) - target) / np.hypot(*(np.array([x, y]) - target))
    obj = target
    cue = obj - u * 0.3
    if x == L / 2:
        cue, obj = centre - u * 0.2, target
    balls = Balls(np.array([cue, obj]), radius=SNOOKER_BALL_RADIUS, mass=SNOOKER_BALL_MASS)
    struck = strike(balls, u * 2.0 / 0.005 * SNOOKER_BALL_MASS, contact_time=0.005)  # 2 m/s
    result = simulate(struck, TABLE)
    drops = [e for e in result.events if e.kind == "ball_pocket" and e.i == 1]
    assert drops and drops[0].j == pocket


def test_22_balls_run_through_the_engine():
    # The break-off from the D into the reds: every ball is accounted for (on the cloth or in a pocket).
    balls = snooker_rack(TABLE, seed=0).with_ball_at(0, (baulk_x(TABLE) - 0.1, TABLE.width / 2 - 0.1))
    aim = balls.xy[15] - balls.xy[0]
    struck = strike(balls, aim / np.hypot(*aim) * 10.0 / 0.005 * SNOOKER_BALL_MASS, contact_time=0.005)
    result = simulate(struck, TABLE)
    final = result.final
    assert len(final) == 22
    contacts = {e.i for e in result.events if e.kind.startswith("ball_ball")} | \
        {e.j for e in result.events if e.kind.startswith("ball_ball")}
    assert len(contacts) > 10  # the pack opened
    on = ~final.pocketed
    check_on_table(final.__class__(final.xy[on], radius=SNOOKER_BALL_RADIUS), TABLE)
    assert not np.any(final.v) and math.isfinite(result.final.energy())


def test_spotting_colours_rule_6():
    # WPBSA S3 R6: own spot; if occupied the highest-value free spot; if none, nearest its own spot
    # towards the top cushion on the long string.
    spots = colour_spots(TABLE)
    rack = snooker_rack(TABLE, seed=0)
    cls = rack.__class__

    def layout(moves, potted):
        xy, pocketed = rack.xy.copy(), rack.pocketed.copy()
        for ball, spot in moves.items():
            xy[ball] = spot
        pocketed[list(potted)] = True
        return cls(xy, radius=SNOOKER_BALL_RADIUS, mass=SNOOKER_BALL_MASS, pocketed=pocketed)

    # Free own spot: back on it.
    assert tuple(spot_colours(layout({}, [18]), TABLE, [18]).xy[18]) == pytest.approx(spots[18])
    # The blue potted, the cue ball on its spot, the pink knocked off its own: the pink spot is
    # the highest-value free spot (the black's is occupied by the black).
    out = spot_colours(layout({0: spots[19], 20: (1.0, 0.3)}, [19]), TABLE, [19])
    assert tuple(out.xy[19]) == pytest.approx(spots[20])
    # The black potted, the cue ball on its spot, every other spot occupied: as near its own spot
    # as it fits on the long string towards the top cushion (touching the cue ball).
    out2 = spot_colours(layout({0: spots[BLACK]}, [BLACK]), TABLE, [BLACK])
    assert out2.xy[BLACK, 1] == pytest.approx(TABLE.width / 2)
    assert out2.xy[BLACK, 0] == pytest.approx(spots[BLACK][0] + 2 * SNOOKER_BALL_RADIUS, abs=1e-5)
    with pytest.raises(ValueError, match="only pocketed colours"):
        spot_colours(out, TABLE, [5])
