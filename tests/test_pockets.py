"""Pockets as a player sees them: jaws with WPA-angled facings and rounded tips, the opening a
ball drops through, balls hanging in the mouth; each expectation derived from the geometry."""

import json
import math
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the envs)
from pool_env.physics import BALL_RADIUS, Balls, Physics, Table, simulate
from pool_env.physics.config import cushion_reach
from pool_env.physics.invariants import run_checked
from pool_env.physics.simulate import check_on_table

R = BALL_RADIUS
TABLE = Table.eight_foot()
STANDARD = Physics.standard()
INCH = 0.0254
SIDE_MOUTH = 5.0625 * INCH  # 0.1286 m rounded in Table.eight_foot()
DATA = Path(__file__).parent / "data"


def rolling(xy, v):
    """One ball at xy rolling (w = z x v / R) at velocity v."""
    v = np.asarray(v, dtype=np.float64)
    return Balls([xy], v=[v], w=[[-v[1] / R, v[0] / R, 0.0]])


def cushion_hits(result):
    return [e.j for e in result.events if e.kind == "ball_cushion"]


@pytest.mark.parametrize("off", [0.001, 0.005, 0.020])
def test_ball_rolling_along_the_rail_passes_the_side_pocket(off):
    # Centre R + off from the nose line, rolling at 0.4 m/s from x = 0.6 m: it passes the side
    # pocket's mouth (x = 1.12 +- 0.064 m) untouched (the rounded jaw tips sit below the nose
    # line, tangent to it, so a centre above the nose by R or more clears them) and rolls
    # v^2 / (2 mu_r g) = 0.8155 m straight on, to x = 1.4155 m, y unchanged.
    v, mu_r, g = 0.4, STANDARD.mu_r, STANDARD.g
    result = simulate(rolling((0.6, R + off), (v, 0.0)), TABLE, STANDARD)
    assert not result.final.pocketed[0]
    assert cushion_hits(result) == []
    assert result.final.xy[0, 1] == R + off
    assert result.final.xy[0, 0] == pytest.approx(0.6 + v * v / (2 * mu_r * g), rel=1e-9)


@pytest.mark.parametrize("off", [0.0, 0.010, 0.020, 0.030])
def test_straight_in_side_pocket_drops_within_30_mm_of_centre(off):
    # Rolled straight at the side pocket at 1.5 m/s with its path `off` from the pocket's
    # centre line: the ball's edge passes 64.3 - (off + R) >= 5.7 mm inside the jaw points,
    # its centre crosses the opening's edge (3/16 in behind the nose line, 64.3 mm radius)
    # before it reaches the 104 degree facing, so it drops without touching a cushion.
    result = simulate(rolling((1.12 + off, 0.5), (0.0, -1.5)), TABLE, STANDARD)
    assert result.final.pocketed[0]
    assert cushion_hits(result) == []
    assert [e.j for e in result.events if e.kind == "ball_pocket"] == [4]


def test_stun_ball_50_mm_off_centre_meets_the_jaw_and_comes_out():
    # A stun ball (no spin) straight at the side pocket at 1.5 m/s, its path 50 mm off the
    # centre line: its edge reaches 78.6 mm out, 14.3 mm (half a radius) past the jaw point
    # at 64.3 mm, so it meets the rounded jaw tip almost head on (contact normal 34 degrees
    # from its path) and rebounds back onto the table.
    result = simulate(Balls([(1.12 + 0.05, 0.5)], v=[(0.0, -1.5)]), TABLE, STANDARD)
    assert not result.final.pocketed[0]
    first = cushion_hits(result)[0]
    jaws = len(TABLE.rails)
    assert first >= jaws and TABLE.jaw_pockets[first - jaws] == 4  # a jaw tip of the side pocket
    hit = next(e.time for e in result.events if e.kind == "ball_cushion")
    after = result.at(hit + 1e-9)
    assert after.v[0, 1] > 0.0  # heading back up the table
    assert result.final.xy[0, 1] > R


@pytest.mark.parametrize("speed", [0.5, 1.0, 2.0, 3.0])
def test_ball_frozen_to_the_long_rail_drops_in_the_corner(speed):
    # Frozen to the long rail (its centre the cushion reach R cos theta from the nose line,
    # sin theta = h / R - 1), rolling into the corner: it passes its own rail's jaw (the
    # tip sits below the nose line) and drops, at most after brushing the far facing.
    reach = cushion_reach(R, TABLE.cushion_height, STANDARD.cushion)
    result = simulate(rolling((0.6, reach), (-speed, 0.0)), TABLE, STANDARD)
    assert result.final.pocketed[0]
    assert [e.j for e in result.events if e.kind == "ball_pocket"] == [0]


def test_ball_driven_into_a_facing_rattles_out():
    # Rolled at 2 m/s from (0.9, 0.06) m at the corner pocket's mouth, 1.5 degrees off the
    # line to its middle: it meets a facing at a shallow angle, bounces between the two
    # facings of the narrowing throat and comes back out onto the table.
    start = np.array([0.9, 0.06])
    d = np.array([0.041, 0.041]) - start
    d /= np.hypot(*d)
    a = math.radians(-1.5)
    d = np.array([math.cos(a) * d[0] - math.sin(a) * d[1], math.sin(a) * d[0] + math.cos(a) * d[1]])
    result, violations = run_checked(rolling(start, 2.0 * d), TABLE, STANDARD)
    assert not violations
    facings = set(np.flatnonzero(TABLE.rail_pockets == 0))
    hits = cushion_hits(result)
    assert len([h for h in hits[:4] if h in facings]) >= 3 and {hits[0], hits[1]} == facings
    assert not result.final.pocketed[0]


def test_pocketless_table_predicts_no_pocket_or_jaw():
    # Nothing to predict: no pocket, facing or jaw tip exists (rails are the four noses).
    table = Table.seed()
    assert table.jaws.shape == (0, 3) and table.rails.shape == (4, 6)
    result = simulate(Balls([(0.5, 0.5), (1.5, 0.6)], v=[(3.0, 0.4), (0.0, 0.0)]), table, STANDARD)
    assert result.stats["ball_pocket_predictions"] == 0 and result.stats["ball_pocket_rejected"] == 0


def test_ball_hanging_in_the_mouth_is_a_valid_start():
    # The state a random shot sequence left (before real pockets it was refused: ball 4 rests
    # in a corner pocket's mouth, nearer the rail line than R where no rail is). The table
    # check accepts it, and the env plays the next shot from it.
    state = json.loads((DATA / "ball-resting-in-pocket-mouth.json").read_text())
    balls = Balls(state["xy"], pocketed=state["pocketed"])
    check_on_table(balls, TABLE, STANDARD)
    env = gym.make("PoolBreakRun-v0")
    obs, _ = env.reset(seed=0, options={"balls": balls})
    assert env.observation_space.contains(obs)  # positions past the nose line clip to its edge
    action = np.asarray(state["next_action"], dtype=np.float32)
    _, _, _, truncated, info = env.step(action)
    assert not truncated or "error" not in info


@pytest.mark.parametrize("xy, match", [
    # Through the nose of a rail, alongside it: 5 mm short of the reach.
    ((0.5, 0.0225), "outside the rails .* into a rail"),
    # In the side pocket's mouth but pressed into its jaw tip (tip centre at x = 1.1882 m,
    # 5 mm below the nose line; reach R cos theta + 5 mm = 32.5 mm; this centre is 29.2 mm
    # from it, and not alongside the nose rail, which starts at x = 1.1882 m).
    ((1.1882 - 0.015, 0.02), "outside the rails .* into a jaw tip"),
    # Behind the side pocket's jaw, past the nose line but not in the throat.
    ((1.25, -0.01), "outside the rails"),
    # Over the side pocket's opening (its centre 69.06 mm behind the nose line, radius 64.3 mm).
    ((1.12, -0.006), "over pocket 4"),
])
def test_table_check_names_where_a_ball_may_not_be(xy, match):
    with pytest.raises(ValueError, match=match):
        check_on_table(Balls([xy]), TABLE, STANDARD)


def test_observation_stays_in_its_space_with_a_ball_past_the_nose_line():
    # A ball hanging in the side pocket's mouth, its centre 2 mm past the nose line (the
    # opening's edge is 4.76 mm past it): a legal start, observed at the table's edge.
    xy = np.zeros((16, 2))
    xy[0], xy[1] = (0.56, 0.56), (1.12, -0.002)
    balls = Balls(xy, pocketed=[False, False] + [True] * 14)
    check_on_table(balls, TABLE, STANDARD)
    env = gym.make("PoolBreakRun-v0")
    obs, _ = env.reset(seed=0, options={"balls": balls})
    assert env.observation_space.contains(obs)
    assert obs[3 * 1 + 1] == -1.0  # ball 1's y, clipped to the near rail's edge
