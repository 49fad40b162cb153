"""The frozen-ball rail rule on real shots: WPA 6.3 (no rail after contact) with 8.4 (driven to a rail).

What the rule text decides (WPA "Rules of Play", wpapool.com/rules): 6.3 makes a shot that
pockets no ball a foul unless, after the cue ball's contact with an object ball, some ball
(the cue ball or any object ball) is driven to a rail; 8.4 says a ball is driven to a rail
only if it was not touching that rail and then touches it, so a ball frozen to a rail is
driven to it only if it leaves it and comes back (or reaches another rail). Pressing a frozen
ball deeper into its cushion is no cushion contact (B. Jewett, "Making Contact", Billiards
Digest, on the ball frozen to the rail). Each scene below is built so that exactly one of
these cases happens, and the test checks the scene is that case before it checks the ruling.
"""

from __future__ import annotations

import math

import numpy as np

from pool_env import rules as R
from pool_env.physics import BALL_RADIUS, Balls, Physics, Table, simulate, strike
from pool_env.physics.config import cushion_reach
from pool_env.rules import EightBall, GameState, NineBall

TABLE = Table.eight_foot()
PHYSICS = Physics.standard()
W = TABLE.width
REACH = cushion_reach(BALL_RADIUS, TABLE.cushion_height, PHYSICS.cushion)  # centre to nose line at contact
TOP_LEFT = 3  # the rail row of the head half of the y = W rail (Table.rails order)
FROZEN = np.array([0.6, W - REACH])  # the 1, frozen to that rail: its gap is 0


def _shot(cue_xy, force, tip=(0.0, 0.0), ball=FROZEN):
    result = simulate(strike(Balls(np.array([cue_xy, ball])), force, tip), TABLE, PHYSICS)
    return result, R.outcome_from_result(result)


def _cushions(result, ball):
    """The (time, cushion) of every ball_cushion event of `ball`."""
    return [(e.time, e.j) for e in result.events if e.kind == "ball_cushion" and e.i == ball]


def _rulings(outcome):
    """The rulings of a 9-ball and an open-table 8-ball shot on the 1 (the legal target of both)."""
    nine = GameState(NineBall(), frozenset(range(1, 10)), 0, None, (0, 0), (None, None), False, 5)
    eight = GameState(EightBall(), frozenset(range(1, 16)), 0, None, (0, 0), (None, None), False, 5)
    return R.judge(nine, outcome)[1], R.judge(eight, outcome)[1]


def test_the_frozen_ball_is_frozen():
    # The scenes' premise: the 1 touches the rail (gap zero within the engine's contact
    # tolerance), and the engine accepts it there.
    x1, y1, _, _, nx, ny = TABLE.rails[TOP_LEFT]
    assert abs(nx * (FROZEN[0] - x1) + ny * (FROZEN[1] - y1) - REACH) < 1e-12


def test_a_soft_hit_that_only_presses_the_frozen_ball_into_its_rail_is_a_foul():
    # Straight up the table into the 1: it is pressed into the rail it touches, rebounds a
    # few mm and stops; the cue ball comes back and stops short of every rail. The engine
    # does report a ball_cushion event for the 1 (the press), but by 8.4 the 1 was not driven
    # to that rail, and no other ball reached one: 6.3 makes it a foul in both games.
    result, out = _shot(FROZEN - (0.0, 0.3), (0.0, 20.0))
    presses = _cushions(result, 1)
    assert presses and all(j == TOP_LEFT for _, j in presses)
    assert _cushions(result, 0) == []
    assert W - REACH - result.final.xy[1, 1] < 0.01  # the 1 never got far from its rail
    assert out.first_contact == 1 and out.pocketed == ()
    assert not out.rail_after_contact and out.object_balls_to_rail == frozenset()
    for ruling in _rulings(out):
        assert ruling.foul == "no_rail" and ruling.turn_passed and ruling.ball_in_hand == "anywhere"


def test_the_frozen_ball_driven_off_its_rail_and_onto_other_rails_is_legal():
    # A full hit at 45 degrees into the rail: the 1 is pressed in, leaves the rail and crosses
    # the table to the foot rail and a long rail; the cue ball touches no rail. The 1 left
    # its rail and then touched a rail: driven to a rail (8.4), a legal shot (6.3).
    d = np.array([math.sin(math.radians(45.0)), math.cos(math.radians(45.0))])
    result, out = _shot(FROZEN - d * (2.0 * BALL_RADIUS + 0.1), tuple(80.0 * d), (0.0, -0.1))
    contacts = _cushions(result, 1)
    first = next(e.time for e in result.events if e.kind == "ball_ball")
    assert contacts[0] == (first, TOP_LEFT)  # pressed at the instant of the hit
    assert any(t > first + 0.1 and j != TOP_LEFT for t, j in contacts)  # then other rails
    assert _cushions(result, 0) == [] and out.pocketed == ()
    assert out.rail_after_contact and out.object_balls_to_rail == frozenset({1})
    for ruling in _rulings(out):
        assert ruling.foul is None and ruling.turn_passed and ruling.ball_in_hand is None


def test_the_cue_ball_reaching_a_rail_after_contact_is_legal():
    # A near-full hit 10 degrees off the rail's normal: the 1 is only pressed in (and rolls
    # off it), but the cue ball rebounds to the far rail. 6.3 is satisfied by any ball.
    d = np.array([math.sin(math.radians(10.0)), math.cos(math.radians(10.0))])
    result, out = _shot(FROZEN - d * (2.0 * BALL_RADIUS + 0.1), tuple(60.0 * d), (0.0, -0.1))
    assert [j for _, j in _cushions(result, 1)] == [TOP_LEFT]  # the press only
    assert _cushions(result, 0)  # the cue ball reaches a rail
    assert out.rail_after_contact and out.object_balls_to_rail == frozenset()
    for ruling in _rulings(out):
        assert ruling.foul is None


def test_a_ball_near_the_rail_but_not_frozen_is_driven_to_it():
    # The same soft straight hit on a 1 that sits 2 mm off the rail: it was not touching the
    # rail and then touched it, which is what 8.4 calls driven to a rail: a legal shot.
    near = FROZEN - (0.0, 0.002)
    result, out = _shot(near - (0.0, 0.3), (0.0, 20.0), ball=near)
    assert [j for _, j in _cushions(result, 1)][:1] == [TOP_LEFT]
    assert out.rail_after_contact and out.object_balls_to_rail == frozenset({1})
    for ruling in _rulings(out):
        assert ruling.foul is None


def test_pressed_cushion_events_flags_only_the_press():
    # The engine's flag marks the press events of the frozen ball, never another event.
    result, _ = _shot(FROZEN - (0.0, 0.3), (0.0, 20.0))
    flags = result.pressed_cushion_events()
    assert flags.shape == (len(result.events),) and flags.any()
    for event, flag in zip(result.events, flags):
        assert not flag or (event.kind == "ball_cushion" and event.i == 1 and event.j == TOP_LEFT)
    near = FROZEN - (0.0, 0.002)
    result, _ = _shot(near - (0.0, 0.3), (0.0, 20.0), ball=near)
    assert not result.pressed_cushion_events().any()
