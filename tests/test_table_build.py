"""The compiled table build: the recorded tables bit for bit; Table.variant, Physics.variant and Balls.sized
against what they stand for (Table(...), dataclasses.replace, numpy's spread)."""

import dataclasses
import json
import math
import pickle
from pathlib import Path

import numpy as np
import pytest

from pool_env.physics import Balls, Physics, PocketShape, Table, rack
from pool_env.physics.bundles import reach_of
from pool_env.physics.config import cushion_reach

RECORDS = json.loads((Path(__file__).parent / "data" / "tables.json").read_text())
ARRAYS = ("pocket_entries", "rails", "rail_pockets", "jaws", "jaw_pockets", "pockets", "pocket_reach", "mouths")


def made(record):
    shapes = {k: None if record[k] is None else PocketShape(**record[k]) for k in ("corner_pocket", "side_pocket")}
    return Table(record["length"], record["width"], record["pockets"], record["cushion_height"], **shapes)


def test_every_recorded_table_is_built_again_bit_for_bit():
    # tests/data/tables.json: tables (the eight-foot and snooker tables with drawn mouths, other
    # shapes and sizes, pockets along a rail) as the Python pocket builder made them, and the
    # messages of those it refused.
    assert sum("error" in r for r in RECORDS) >= 5 and sum("arrays" in r for r in RECORDS) >= 70
    for record in RECORDS:
        if "error" in record:
            with pytest.raises(ValueError) as caught:
                made(record)
            assert str(caught.value) == record["error"]
            continue
        table = made(record)
        for name in ARRAYS:
            got = getattr(table, name)
            want = np.array(record["arrays"][name], dtype=got.dtype).reshape(got.shape)
            assert got.tobytes() == want.tobytes(), name
            assert not got.flags.writeable and got.flags.c_contiguous


def reference(table, cushion_height, corner, side):
    entries = table.pocket_entries.copy()
    entries[table.corner_pockets, 2] = corner
    entries[~table.corner_pockets, 2] = side
    return Table(table.length, table.width, entries.tolist(), cushion_height, table.corner_pocket, table.side_pocket)


@pytest.mark.parametrize("name", ["eight_foot", "snooker", "shaped"])
def test_a_variant_is_the_table_built_with_its_mouths(name):
    rng = np.random.default_rng(4)
    shaped = Table(2.5, 1.3, [(0.0, 0.0, 0.12), (2.5, 1.3, 0.12), (1.25, 0.0, 0.14), (0.8, 1.3, 0.13)], 0.035,
                   PocketShape(138.0, 0.0, 0.03, 0.1), PocketShape(100.0, 0.012, 0.01))
    table = {"eight_foot": Table.eight_foot(), "snooker": Table.snooker(), "shaped": shaped}[name]
    corner0, side0 = table.pocket_entries[0, 2], table.pocket_entries[~table.corner_pockets][0, 2]
    for _ in range(200):
        height = rng.uniform(0.034, 0.037)
        corner, side = corner0 * rng.uniform(0.97, 1.03), side0 * rng.uniform(0.97, 1.03)
        got, want = table.variant(height, corner, side), reference(table, height, corner, side)
        assert got.cushion_height == height and got.corner_pocket is table.corner_pocket
        for array in ARRAYS:
            a, b = getattr(got, array), getattr(want, array)
            assert a.dtype == b.dtype and a.shape == b.shape and not a.flags.writeable
            if array != "pocket_reach":
                assert a.tobytes() == b.tobytes(), array
        # The broad-phase radius: the C library's hypot, at most one unit in the last place off.
        assert got.pocket_reach[:, :2].tobytes() == want.pocket_reach[:, :2].tobytes()
        off = np.abs(got.pocket_reach[:, 2] - want.pocket_reach[:, 2])
        assert np.all(off <= np.spacing(want.pocket_reach[:, 2]))
    assert table.variant().pocket_entries.tobytes() == table.pocket_entries.tobytes()
    assert table.variant(corner_mouth=corner0 * 0.99).cushion_height == table.cushion_height


@pytest.mark.parametrize("kwargs", [dict(corner_mouth=5.0), dict(side_mouth=-0.1), dict(cushion_height=0.0),
                                    dict(corner_mouth=math.nan), dict(cushion_height=math.inf)])
def test_a_variant_refuses_what_table_refuses(kwargs):
    table = Table.eight_foot()
    values = {"cushion_height": table.cushion_height, "corner_mouth": 0.1159, "side_mouth": 0.1286, **kwargs}
    with pytest.raises(ValueError) as want:
        reference(table, values["cushion_height"], values["corner_mouth"], values["side_mouth"])
    with pytest.raises(ValueError) as got:
        table.variant(**kwargs)
    assert str(got.value) == str(want.value)
    with pytest.raises(ValueError, match="must be numbers"):
        table.variant(corner_mouth="wide")


def test_a_pickled_table_makes_the_same_variants_and_names_its_corner_pockets():
    table = Table.eight_foot()
    again = pickle.loads(pickle.dumps(table))
    assert again.variant(0.036, 0.116, 0.129).rails.tobytes() == table.variant(0.036, 0.116, 0.129).rails.tobytes()
    assert table.corner_pockets.tolist() == [True] * 4 + [False] * 2 and not table.corner_pockets.flags.writeable
    assert Table.carom().corner_pockets.shape == (0,) and Table.carom().variant(0.036).rails.shape == (4, 6)


def test_physics_variant_is_dataclasses_replace():
    base = Physics()
    got = base.variant(mu_s=0.3, e_c=0.7, f_c=0.25)
    want = dataclasses.replace(base, mu_s=0.3, e_c=0.7, f_c=0.25)
    assert got == want and pickle.dumps(got) == pickle.dumps(want)
    assert got.as_array().tobytes() == want.as_array().tobytes()
    assert got.engine_args()[1:] == want.engine_args()[1:] and got.engine_args()[0] is got.as_array()
    assert base.as_array()[0] == 0.2  # the base is left as it was
    for bad in (dict(mu_s=-1.0), dict(e_c=1.5), dict(f_c=math.inf), dict(mu_sp=math.nan)):
        with pytest.raises(ValueError) as caught:
            base.variant(**bad)
        with pytest.raises(ValueError) as expected:
            dataclasses.replace(base, **bad)
        assert str(caught.value) == str(expected.value)
    assert base.variant(cushion="restitution") == dataclasses.replace(base, cushion="restitution")


def spread(balls, radii):
    """Balls.sized's positions as numpy works them out."""
    xy, grow = balls.xy, float(np.max(radii) / np.min(balls.radii))
    if grow > 1.0:
        on = ~balls.pocketed
        centre = xy[on].mean(axis=0)
        xy = xy.copy()
        xy[on] = centre + (xy[on] - centre) * grow
    return xy


def test_sized_balls_spread_as_numpy_spreads_them_with_copies_of_their_sizes():
    rng = np.random.default_rng(8)
    for k in range(60):
        balls = rack(Table.eight_foot(), seed=k)
        if k % 2:
            pocketed = balls.pocketed.copy()
            pocketed[rng.integers(1, 16, 3)] = True
            balls = Balls(balls.xy, radius=balls.radii, mass=balls.masses, pocketed=pocketed)
        radii, masses = rng.uniform(0.0285, 0.0287, 16), rng.uniform(0.155, 0.17, 16)
        sized = balls.sized(radii, masses)
        assert sized.xy.tobytes() == spread(balls, radii).tobytes() and not sized.xy.flags.writeable
        assert sized.radii.tobytes() == radii.tobytes() and sized.masses.tobytes() == masses.tobytes()
        assert sized.radius.tobytes() == radii.tobytes() and not sized.radius.flags.writeable
        assert sized.radii.flags.writeable and sized.radii is not radii and sized.pocketed is balls.pocketed
    smaller = balls.sized(np.full(16, 0.02), np.full(16, 0.1))
    assert smaller.xy is balls.xy  # no ball grew: nothing to spread
    assert balls.sized(0.03, 0.17).radius == 0.03
    with pytest.raises(ValueError, match="ball 3 has mass nan"):
        balls.sized(radii, np.where(np.arange(16) == 3, np.nan, masses))


def test_the_cushion_reach_of_balls_of_their_own_sizes_is_cushion_reach():
    balls = rack(Table.eight_foot(), seed=1).sized(np.linspace(0.0284, 0.0287, 16), np.full(16, 0.17))
    table = Table.eight_foot().variant(cushion_height=0.0365)
    for model in ("han2005", "restitution"):
        reach = reach_of(balls, table, model)
        assert reach.tobytes() == np.asarray(cushion_reach(balls.radii, 0.0365, model), dtype=np.float64).tobytes()
        assert reach_of(balls, table, model) is reach  # one array per set of sizes, nose and model
