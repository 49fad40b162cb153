"""Tests for pool_env.render: table renderer, ball sprites, spin markers, orientation."""

import numpy as np
import pytest

from pool_env.render.table import (
    CLOTH_RGB,
    TableRenderer,
    identity_orientation,
    integrate_orientation,
)

L, W, R = 2.54, 1.27, 0.028575  # 9-ft table, standard ball
PR = 0.06
POCKETS = np.array(
    [
        [0.0, 0.0, PR],
        [L / 2, 0.0, PR],
        [L, 0.0, PR],
        [0.0, W, PR],
        [L / 2, W, PR],
        [L, W, PR],
    ]
)
NO_POCKETS = np.zeros((0, 3))
SPOT = (1.0, 0.6)  # somewhere on open cloth


def make(size=(640, 360), pockets=POCKETS):
    return TableRenderer(L, W, pockets, R, size=size)


def one_ball(idx, xy=SPOT, n=None):
    """Positions/pocketed arrays with only ball `idx` on the table at `xy`."""
    n = max(16, idx + 1) if n is None else n
    pos = np.zeros((n, 2))
    pos[idx] = xy
    pocketed = np.ones(n, dtype=bool)
    pocketed[idx] = False
    return pos, pocketed


def pixel_at(img, renderer, xy):
    col, row = renderer.world_to_pixel(np.array([xy]))[0]
    return img[int(row), int(col)].astype(int)


def ball_pixels(img, renderer, xy, r_lo, r_hi):
    """Pixels whose centres lie at r_lo*R <= distance < r_hi*R from the ball centre."""
    col, row = renderer.world_to_pixel(np.array([xy]))[0]
    rows, cols = np.mgrid[0 : img.shape[0], 0 : img.shape[1]]
    dist = np.hypot(cols + 0.5 - col, rows + 0.5 - row) / (R * renderer.scale)
    return img[(dist >= r_lo) & (dist < r_hi)].astype(int)


def is_red(p):
    return (p[..., 0] > 140) & (p[..., 1] < 90) & (p[..., 2] < 90)


def is_yellow(p):
    return (p[..., 0] > 170) & (p[..., 1] > 130) & (p[..., 2] < 90)


def is_blue(p):
    return (p[..., 2] > 120) & (p[..., 0] < 90) & (p[..., 1] < 110)


def is_black(p):
    return p.max(axis=-1) < 70


def is_white(p):
    return p.min(axis=-1) > 180


def is_cloth(p):
    return np.all(p == np.array(CLOTH_RGB), axis=-1)


# --- image format -------------------------------------------------------------


@pytest.mark.parametrize("size", [(640, 360), (320, 240), (1280, 720), (200, 400)])
def test_output_shape_and_dtype(size):
    r = make(size)
    xy = np.array([[0.5 + 0.1 * i, 0.6] for i in range(16)])
    img = r.draw(xy, np.zeros(16, dtype=bool), identity_orientation(16))
    assert img.shape == (size[1], size[0], 3)
    assert img.dtype == np.uint8


def test_table_centre_is_cloth_and_y_axis_points_up():
    r = make()
    img = r.draw(np.zeros((0, 2)), np.zeros(0, dtype=bool))
    assert is_cloth(pixel_at(img, r, (L / 2, W / 2)))
    # y = 0 is the bottom rail, y = width the top one: image rows increase downward.
    (c0, r0), (c1, r1) = r.world_to_pixel(np.array([[0.0, 0.0], [L, W]]))
    assert r0 > r1 and c1 > c0
    # The table fits in the image with the rail around it.
    assert 0 < c0 and c1 < 640 and 0 < r1 and r0 < 360


# --- ball colours -------------------------------------------------------------


@pytest.mark.parametrize("size", [(640, 360), (1280, 720)])
@pytest.mark.parametrize(
    "idx, predicate",
    [(0, is_white), (1, is_yellow), (2, is_blue), (3, is_red), (8, is_black)],
)
def test_solid_ball_colour_where_placed(size, idx, predicate):
    r = make(size)
    xy, pocketed = one_ball(idx)
    img = r.draw(xy, pocketed)
    ring = ball_pixels(img, r, SPOT, 0.72, 0.85)  # outside number disc, inside limb
    assert len(ring) >= 20
    assert predicate(ring).mean() > 0.8
    # The same place without the ball is plain cloth.
    empty = r.draw(xy, np.ones_like(pocketed))
    assert is_cloth(ball_pixels(empty, r, SPOT, 0.0, 1.0)).all()
    # Far from the ball nothing changed.
    assert np.array_equal(img[:, :20], empty[:, :20])


def test_stripe_ball_has_white_and_colour():
    r = make((1280, 720))
    xy, pocketed = one_ball(11)  # red stripe
    disc = ball_pixels(r.draw(xy, pocketed), r, SPOT, 0.0, 0.9)
    assert is_red(disc).sum() >= 10
    assert is_white(disc).sum() >= 10
    solid = ball_pixels(r.draw(*one_ball(3)), r, SPOT, 0.72, 0.85)
    stripe = ball_pixels(r.draw(xy, pocketed), r, SPOT, 0.72, 0.85)
    assert is_white(stripe).sum() > is_white(solid).sum() + 5


def test_ball_number_is_drawn():
    r = make((1280, 720))
    centre = ball_pixels(r.draw(*one_ball(3)), r, SPOT, 0.0, 0.45)
    # White number disc with dark digit pixels on it.
    assert is_white(centre).sum() >= 5
    assert is_black(centre).sum() >= 3
    # Different numbers give different centres (same colour ball 3 vs 11 aside).
    centre_5 = ball_pixels(r.draw(*one_ball(5)), r, SPOT, 0.0, 0.45)
    assert not np.array_equal(centre, centre_5)
    # The cue ball has no number: no dark pixels.
    cue = ball_pixels(r.draw(*one_ball(0)), r, SPOT, 0.0, 0.9)
    assert not is_black(cue).any()


def test_extra_balls_beyond_15_are_drawn_deterministically():
    r = make()
    xy, pocketed = one_ball(17, n=20)
    img = r.draw(xy, pocketed)
    inner = ball_pixels(img, r, SPOT, 0.0, 0.85)
    assert not is_cloth(inner).any()
    img2 = make().draw(xy, pocketed)
    assert np.array_equal(img, img2)


# --- pocketed balls and pockets --------------------------------------------------


def test_pocketed_balls_not_drawn():
    r = make()
    n = 16
    xy = np.array([[0.3 + 0.13 * i, 0.3 + 0.04 * i] for i in range(n)])
    empty = r.draw(np.zeros((0, 2)), np.zeros(0, dtype=bool))
    all_in = r.draw(xy, np.ones(n, dtype=bool), identity_orientation(n))
    assert np.array_equal(all_in, empty)
    pocketed = np.zeros(n, dtype=bool)
    pocketed[3] = True
    img = r.draw(xy, pocketed)
    assert is_cloth(ball_pixels(img, r, xy[3], 0.0, 1.0)).all()
    assert not is_cloth(ball_pixels(img, r, xy[4], 0.0, 0.85)).any()


def test_non_finite_and_off_image_balls_are_skipped():
    r = make()
    xy = np.array([[np.nan, 0.5], [1e9, -1e9], [-5.0, 0.5]])
    img = r.draw(xy, np.zeros(3, dtype=bool), identity_orientation(3))
    assert np.array_equal(img, r.draw(np.zeros((0, 2)), np.zeros(0, dtype=bool)))


def test_ball_clipped_at_image_border():
    r = make()
    col0, _ = r.world_to_pixel(np.array([[0.0, 0.6]]))[0]
    x_edge = -col0 / r.scale  # world x of the image's left border
    xy = np.array([[x_edge, 0.6], [x_edge + 640 / r.scale, 0.6]])
    img = r.draw(xy, np.zeros(2, dtype=bool), identity_orientation(2))
    empty = r.draw(np.zeros((0, 2)), np.zeros(0, dtype=bool))
    diff = np.any(img != empty, axis=-1)
    assert diff[:, :3].any() and diff[:, -3:].any()
    assert not diff[:, 20:-20].any()


@pytest.mark.parametrize("size", [(640, 360), (1280, 720)])
def test_pockets_dark_when_given_and_absent_when_empty(size):
    with_p = make(size, POCKETS)
    without = make(size, NO_POCKETS)
    img_p = with_p.draw(np.zeros((0, 2)), np.zeros(0, dtype=bool))
    img_n = without.draw(np.zeros((0, 2)), np.zeros(0, dtype=bool))
    for cx, cy, pr in POCKETS:
        # Pocket centre and a point inside the hole reaching into the rail.
        out = np.array([cx - L / 2, cy - W / 2])
        out = out / np.abs(out).max()
        for pt in [(cx, cy), (cx + 0.5 * pr * out[0], cy + 0.5 * pr * out[1])]:
            assert pixel_at(img_p, with_p, pt).max() < 40
            assert pixel_at(img_n, without, pt).max() > 60
    # Cloth in the middle is unaffected either way.
    assert is_cloth(pixel_at(img_p, with_p, (L / 2, W / 2)))
    assert is_cloth(pixel_at(img_n, without, (L / 2, W / 2)))


def test_draw_is_deterministic_and_pure():
    r = make()
    rng = np.random.default_rng(1)
    n = 16
    xy = rng.uniform([0.1, 0.1], [L - 0.1, W - 0.1], (n, 2))
    pocketed = rng.random(n) < 0.3
    ori = integrate_orientation(identity_orientation(n), rng.normal(size=(n, 3)), 1.0)
    xy0, ori0 = xy.copy(), ori.copy()
    a = r.draw(xy, pocketed, ori)
    b = r.draw(xy, pocketed, ori)
    assert np.array_equal(a, b)
    assert a is not b
    assert np.array_equal(xy, xy0) and np.array_equal(ori, ori0)
    assert np.array_equal(make().draw(xy, pocketed, ori), a)


# --- orientation integration ----------------------------------------------------


def rz(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def random_rotations(n, seed=0):
    q, _ = np.linalg.qr(np.random.default_rng(seed).normal(size=(n, 3, 3)))
    return q * np.sign(np.linalg.det(q))[:, None, None]  # make det = +1


def test_half_turn_about_z_matches_closed_form():
    out = integrate_orientation(identity_orientation(1), np.array([[0, 0, np.pi]]), 1.0)
    np.testing.assert_allclose(out[0], np.diag([-1.0, -1.0, 1.0]), atol=1e-12)
    o0 = random_rotations(4)
    w = np.tile([0.0, 0.0, np.pi], (4, 1))
    np.testing.assert_allclose(integrate_orientation(o0, w, 1.0), rz(np.pi) @ o0, atol=1e-12)
    # Arbitrary angle too.
    out = integrate_orientation(identity_orientation(1), np.array([[0, 0, 0.7]]), 2.0)
    np.testing.assert_allclose(out[0], rz(1.4), atol=1e-12)


def test_integration_exact_for_constant_w_and_returns_new_array():
    o0 = random_rotations(5, seed=3)
    w = np.random.default_rng(4).normal(size=(5, 3)) * 4
    one = integrate_orientation(o0, w, 0.8)
    many = o0
    for _ in range(16):
        many = integrate_orientation(many, w, 0.05)
    np.testing.assert_allclose(many, one, atol=1e-10)
    assert one is not o0
    np.testing.assert_array_equal(o0, random_rotations(5, seed=3))  # input untouched
    # Zero and tiny angular velocity are well behaved.
    np.testing.assert_allclose(integrate_orientation(o0, np.zeros((5, 3)), 1.0), o0, atol=1e-15)
    tiny = integrate_orientation(o0, np.full((5, 3), 1e-12), 1.0)
    assert np.isfinite(tiny).all()
    np.testing.assert_allclose(tiny, o0, atol=1e-11)


def test_integration_stays_orthonormal():
    rng = np.random.default_rng(5)
    o = identity_orientation(8)
    for _ in range(2000):
        o = integrate_orientation(o, rng.normal(size=(8, 3)) * 30, 1 / 60)
    eye = np.broadcast_to(np.eye(3), o.shape)
    np.testing.assert_allclose(o @ np.swapaxes(o, 1, 2), eye, atol=1e-12)
    np.testing.assert_allclose(np.linalg.det(o), 1.0, atol=1e-12)


def test_rolling_in_plus_x_moves_top_point_forward():
    v, dt = 1.0, 0.01
    w = np.array([[0.0, v / R, 0.0]])  # rolling without slipping along +x
    # Contact point velocity v + w x (0,0,-R) is zero: the sign convention is right.
    np.testing.assert_allclose(np.array([v, 0, 0]) + np.cross(w[0], [0, 0, -R]), 0, atol=1e-12)
    top = integrate_orientation(identity_orientation(1), w, dt)[0][:, 2]
    assert top[0] > 0
    np.testing.assert_allclose(top, [np.sin(v / R * dt), 0.0, np.cos(v / R * dt)], atol=1e-12)


# --- rotation marker on the image -----------------------------------------------


def marker_centroid(img, r, xy, predicate):
    """Centroid (col, row) of marker-coloured pixels on the ball, or None if none."""
    col, row = r.world_to_pixel(np.array([xy]))[0]
    rows, cols = np.mgrid[0 : img.shape[0], 0 : img.shape[1]]
    on_ball = np.hypot(cols + 0.5 - col, rows + 0.5 - row) < 0.9 * R * r.scale
    hit = on_ball & predicate(img.astype(int))
    if not hit.any():
        return None
    return np.array([cols[hit].mean() + 0.5 - col, rows[hit].mean() + 0.5 - row])


@pytest.mark.parametrize(
    "w, expected_unit_offset",
    [
        ([0.0, 0.0, 0.0], [0.0, 0.0]),
        ([0.0, 0.6, 0.0], [np.sin(0.6), 0.0]),  # roll toward +x: marker to the right
        ([0.6, 0.0, 0.0], [0.0, np.sin(0.6)]),  # top goes to -y: marker moves down
        ([0.0, -0.6, 0.0], [-np.sin(0.6), 0.0]),
    ],
)
def test_top_marker_follows_rotation(w, expected_unit_offset):
    r = make((1280, 720))
    xy, pocketed = one_ball(0)  # cue ball: no number, so dark pixels are the marker
    ori = integrate_orientation(identity_orientation(16), np.tile(w, (16, 1)), 1.0)
    img = r.draw(xy, pocketed, ori)
    offset = marker_centroid(img, r, SPOT, is_black)
    assert offset is not None
    r_px = R * r.scale
    np.testing.assert_allclose(offset, np.array(expected_unit_offset) * r_px, atol=0.75)
    assert marker_centroid(img, r, SPOT, is_red) is None  # antipode hidden


def test_antipode_marker_when_top_marker_is_underneath():
    r = make((1280, 720))
    xy, pocketed = one_ball(0)
    theta = np.pi - 0.6  # body +z now points down and forward
    ori = integrate_orientation(identity_orientation(16), np.tile([0, theta, 0], (16, 1)), 1.0)
    img = r.draw(xy, pocketed, ori)
    assert marker_centroid(img, r, SPOT, is_black) is None
    offset = marker_centroid(img, r, SPOT, is_red)
    assert offset is not None
    np.testing.assert_allclose(offset, [-np.sin(0.6) * R * r.scale, 0.0], atol=0.75)


def test_marker_stays_inside_ball():
    r = make((1280, 720))
    xy, pocketed = one_ball(3)
    ori = integrate_orientation(identity_orientation(16), np.tile([0.0, np.pi / 2 - 0.01, 0.0], (16, 1)), 1.0)
    plain = r.draw(xy, pocketed)
    marked = r.draw(xy, pocketed, ori)
    changed = np.any(plain != marked, axis=-1)
    assert changed.any()
    col, row = r.world_to_pixel(np.array([SPOT]))[0]
    rows, cols = np.nonzero(changed)
    dist = np.hypot(cols + 0.5 - col, rows + 0.5 - row)
    assert dist.max() < R * r.scale + 1.0
    assert (cols + 0.5 > col).all()  # marker near the +x limb
