"""agents.learned_contact: the ghost-ball model of the cue ball after a pot's contact, against closed forms."""

import numpy as np
import pytest

from agents.learned_contact import CUSHION_HITS, NOT_REACHED, after_contact, cushion_hits
from pool_env.physics import BALL_RADIUS, Physics, Table

PHYS = Physics()
TABLE = Table.eight_foot()  # the games' table
R, G = BALL_RADIUS, PHYS.g


def full_hit(back: float, speed: float, top: float):
    """`after_contact` of a cue ball `back` m short of touching a ball straight ahead along +x."""
    cue, obj = np.array([[0.5, 0.6]]), np.array([[0.5 + back + 2.0 * R, 0.6]])
    return after_contact(cue, obj, np.array([[1.0, 0.0]]), speed, top, PHYS, R)[0]


def test_a_stun_full_hit_leaves_the_cue_ball_the_restitution_share_of_its_speed_then_five_sevenths_of_it_rolling():
    """Touching (no run, no spin): the normal impulse (1 + e)/2 v leaves the cue ball (1 - e)/2 v
    along the line; sliding friction then turns it into a roll at 5/7 of that after
    2 V / (7 mu_s g) s, and rolling friction stops it V_roll^2 / (2 mu_r g) m on."""
    v = 2.0
    out = full_hit(0.0, v, 0.0)
    after = (1.0 - PHYS.e_b) / 2.0 * v
    t = 2.0 * after / (7.0 * PHYS.mu_s * G)
    assert out[0:2] == pytest.approx([0.5, 0.6], abs=1e-12)  # the ghost ball is where the cue ball is
    assert out[2:4] == pytest.approx([after, 0.0], abs=1e-12)
    assert out[4:6] == pytest.approx([0.5 + after * t - 0.5 * PHYS.mu_s * G * t * t, 0.6], abs=1e-12)
    assert out[6:8] == pytest.approx([5.0 / 7.0 * after, 0.0], abs=1e-12)
    assert out[8] == pytest.approx((5.0 / 7.0 * after) ** 2 / (2.0 * PHYS.mu_r * G), rel=1e-12)


def test_a_rolling_full_hit_follows_through_at_five_sevenths_of_the_kept_speed_plus_two_sevenths_of_the_spin():
    """A centre-hit ball rolls after 12 v0^2 / (49 mu_s g) m at 5/7 v0, then slows at mu_r g; at a
    full hit it keeps (1 - e)/2 of its speed and all its roll R w = v, so it rolls on at
    (5 (1 - e)/2 v + 2 v) / 7 once the cloth has taken its slip."""
    v0, back = 2.0, 1.0
    slide = 12.0 * v0 * v0 / (49.0 * PHYS.mu_s * G)
    assert back > slide
    v = np.sqrt((5.0 / 7.0 * v0) ** 2 - 2.0 * PHYS.mu_r * G * (back - slide))
    out = full_hit(back, v0, 0.0)
    assert out[0:2] == pytest.approx([0.5 + back, 0.6], abs=1e-12)
    assert out[2:4] == pytest.approx([(1.0 - PHYS.e_b) / 2.0 * v, 0.0], rel=1e-9, abs=1e-12)
    rolling = (5.0 * (1.0 - PHYS.e_b) / 2.0 * v + 2.0 * v) / 7.0
    assert out[6:8] == pytest.approx([rolling, 0.0], rel=1e-9, abs=1e-12)
    assert out[4] > out[0] and out[5] == pytest.approx(0.6, abs=1e-12)


def test_a_half_ball_stun_cut_sends_the_cue_ball_along_the_tangent_at_half_its_speed_less_the_throw():
    """Aimed R beside the object ball's centre the line of centres is 30 degrees off the aim: the
    object ball takes the normal part, the cue ball keeps the tangent part v sin 30 = v / 2 (and
    (1 - e)/2 of the normal one), less the contact friction's share, which at most stops the
    contact point's slip: 1/7 of the tangent part."""
    travel = 4.0 * R * np.cos(np.pi / 6) - np.sqrt(3.0) * R
    cue, obj = np.array([[0.5, 0.6]]), np.array([[0.5 + 4.0 * R * np.cos(np.pi / 6), 0.6 + R]])
    v0 = 1.0
    v = np.sqrt(v0 * v0 - 2.0 * PHYS.mu_s * G * travel)  # still sliding at the contact
    out = after_contact(cue, obj, np.array([[1.0, 0.0]]), v0, 0.0, PHYS, R)[0]
    n = (obj[0] - out[0:2]) / np.hypot(*(obj[0] - out[0:2]))
    assert np.degrees(np.arccos(n[0])) == pytest.approx(30.0, abs=1e-6)
    tangent = out[2:4] @ np.array([-n[1], n[0]])
    normal = out[2:4] @ n
    assert normal == pytest.approx((1.0 - PHYS.e_b) / 2.0 * v * np.cos(np.pi / 6), rel=1e-9)
    assert tangent < 0.0 and 6.0 / 7.0 * v / 2.0 <= -tangent < v / 2.0  # away from the object ball's side


def straight_hit(cue, speed, top, heading):
    """`cushion_hits` of a full hit: the object ball 3 R ahead of `cue` along `heading`."""
    d = np.asarray([heading], dtype=np.float64)
    d /= np.hypot(*d[0])
    cue = np.asarray([cue], dtype=np.float64)
    return cushion_hits(after_contact(cue, cue + 3.0 * R * d, d, speed, top, PHYS, R), TABLE, PHYS, R)[0]


def test_a_followed_full_hit_up_the_table_meets_the_far_cushion_line_square_at_the_rolling_speed_left():
    """Rolling after the contact along +y from (x0, y_r) at v1, the cue ball meets the line
    y = W - R square on at x0, with v1^2 - 2 mu_r g (W - R - y_r) left; back down the table it meets
    y = R with (W - 2R) / e_c^2 more of its run spent. x0 lies nearer a corner than the side pocket."""
    x0 = 0.4
    cue, d = np.array([[x0, 0.2]]), np.array([[0.0, 1.0]])
    after = after_contact(cue, cue + 3.0 * R * d, d, 3.0, 0.3, PHYS, R)[0]
    assert after[6] == pytest.approx(0.0, abs=1e-12) and after[7] > 0.0  # rolls straight on
    out = straight_hit((x0, 0.2), 3.0, 0.3, (0.0, 1.0))
    assert out.shape == (CUSHION_HITS,)
    spend = 2.0 * PHYS.mu_r * PHYS.g
    first = after[7] ** 2 - spend * (TABLE.width - R - after[5])
    second = first - spend * (TABLE.width - 2.0 * R) / PHYS.e_c**2
    assert first > 0.0 and second > 0.0
    assert out[0:4] == pytest.approx([x0 - R, 0.0, np.sqrt(first), 1.0], rel=1e-9)
    assert out[4:8] == pytest.approx([x0 - R, 0.0, np.sqrt(second), 1.0], rel=1e-9)


def test_a_followed_full_hit_along_the_diagonal_into_a_corner_meets_the_cushion_lines_at_the_pocket():
    """Followed along the line through the corner (R, R) of the cushion lines, the cue ball meets
    them at the corner pocket itself: no distance along the rail, at 45 degrees."""
    out = straight_hit((0.6, 0.6), 2.0, 0.3, (-1.0, -1.0))
    assert out[0] == pytest.approx(0.0, abs=1e-9)
    assert out[1] == 0.0 and out[2] > 0.0
    assert out[3] == pytest.approx(np.sqrt(0.5), rel=1e-9)


def test_a_slow_stun_full_hit_stops_before_any_cushion():
    """A stun full hit leaves the cue ball (1 - e)/2 of its speed: at 0.5 m/s it runs
    ((5/7) 0.0125)^2 / (2 mu_r g) m, well short of the far cushion."""
    out = straight_hit((1.0, 0.3), 0.5, 0.0, (0.0, 1.0))
    assert out[0::4] == pytest.approx([NOT_REACHED] * 3)
    assert out[2::4] == pytest.approx([0.0] * 3)


def test_a_cushion_hit_nearest_the_side_pocket_says_so():
    """Rolling up the table from x = L/2 + 0.05 m, the cue ball meets the long cushion line 0.05 m
    from the side pocket, nearer it than any corner."""
    out = straight_hit((TABLE.length / 2.0 + 0.05, 0.2), 3.0, 0.3, (0.0, 1.0))
    assert out[0] == pytest.approx(0.05, rel=1e-9)
    assert out[1] == 1.0
