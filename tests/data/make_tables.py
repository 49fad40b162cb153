"""Write tests/data/tables.json: the arrays (or the error) of tables with many mouths, cushion heights
and pocket shapes, as `Table` built them (run only after a deliberate change of the pockets' geometry):

    PYTHONPATH=$PWD python tests/data/make_tables.py

tests/test_table_build.py checks that `Table` builds every one of them again, bit for bit (floats
kept exactly: JSON writes the shortest repr that reads back the same). The file was written by the
Python pocket builder that the compiled one (physics/table_build.py) replaced.
"""

import dataclasses
import json
from pathlib import Path

import numpy as np

from pool_env.physics import PocketShape, Table

PATH = Path(__file__).parent / "tables.json"
ARRAYS = ("pocket_entries", "rails", "rail_pockets", "jaws", "jaw_pockets", "pockets", "pocket_reach", "mouths")
INCH = 0.0254


def shape(cut, jaw, shelf, opening=None):
    """A PocketShape's fields, as JSON keeps them."""
    return {"cut_angle": cut, "jaw_radius": jaw, "shelf": shelf, "opening_radius": opening}


def six(L, W, corner, side):
    """Six pockets: four corners and two in the middle of the long rails."""
    return [(0.0, 0.0, corner), (L, 0.0, corner), (0.0, W, corner), (L, W, corner), (L / 2, 0.0, side),
            (L / 2, W, side)]


def cases():
    """(length, width, pockets, cushion_height, corner shape, side shape) of each table."""
    rng = np.random.default_rng(20240611)
    out = [(2.24, 1.12, six(2.24, 1.12, 0.1159, 0.1286), 0.036291, None, None), (2.24, 1.12, [], 0.0363, None, None)]
    for _ in range(40):  # the eight-foot table with mouths and noses drawn in (and past) the WPA ranges
        corner, side = rng.uniform(4.4 * INCH, 4.7 * INCH), rng.uniform(4.9 * INCH, 5.2 * INCH)
        out.append((2.24, 1.12, six(2.24, 1.12, corner, side), rng.uniform(0.035, 0.037), None, None))
    snooker = Table.snooker()
    for _ in range(10):
        corner, side = rng.uniform(0.08, 0.095), rng.uniform(0.09, 0.11)
        out.append((snooker.length, snooker.width, six(snooker.length, snooker.width, corner, side),
                    snooker.cushion_height, dataclasses.asdict(snooker.corner_pocket),
                    dataclasses.asdict(snooker.side_pocket)))
    for _ in range(30):  # other shapes, openings of their own, other sizes
        L, W = rng.uniform(1.5, 3.0), rng.uniform(0.8, 1.6)
        corner_shape = shape(rng.uniform(130, 150), rng.choice([0.0, rng.uniform(0.001, 0.02)]), rng.uniform(0.0, 0.05),
                             rng.choice([None, rng.uniform(0.07, 0.12)]))
        side_shape = shape(rng.uniform(95, 115), rng.choice([0.0, rng.uniform(0.001, 0.02)]), rng.uniform(0.0, 0.02),
                           rng.choice([None, rng.uniform(0.07, 0.12)]))
        pockets = six(L, W, rng.uniform(0.08, 0.16), rng.uniform(0.08, 0.16))
        if rng.random() < 0.3:  # more pockets along a rail, a table with only some corners
            pockets = pockets[:2] + [(rng.uniform(0.3, 0.6) * L, W, 0.1), (0.0, rng.uniform(0.4, 0.6) * W, 0.1)]
        out.append((L, W, pockets, rng.uniform(0.03, 0.04), corner_shape, side_shape))
    # Refused: a mouth too wide, mouths that overlap, an opening short of its facings, facings that cross.
    out += [(2.0, 1.0, [(0.0, 0.0, 5.0)], 0.0363, None, None),
            (2.0, 1.0, [(1.0, 0.0, 0.3), (1.2, 0.0, 0.3)], 0.0363, None, None),
            (2.24, 1.12, six(2.24, 1.12, 0.1159, 0.1286), 0.0363, shape(142, 0.005, 0.2, 0.03), None),
            (2.24, 1.12, six(2.24, 1.12, 0.1159, 0.1286), 0.0363, None, shape(104, 0.005, 0.05, 0.22))]
    return out


def build(L, W, pockets, height, corner, side):
    kwargs = {"corner_pocket": None if corner is None else PocketShape(**corner),
              "side_pocket": None if side is None else PocketShape(**side)}
    return Table(L, W, pockets, height, **kwargs)


def main():
    records = []
    for L, W, pockets, height, corner, side in cases():
        pockets = [[float(v) for v in p] for p in pockets]
        corner = None if corner is None else {k: (None if v is None else float(v)) for k, v in corner.items()}
        side = None if side is None else {k: (None if v is None else float(v)) for k, v in side.items()}
        record = {"length": float(L), "width": float(W), "pockets": pockets, "cushion_height": float(height),
                  "corner_pocket": corner, "side_pocket": side}
        try:
            table = build(L, W, pockets, height, corner, side)
        except ValueError as exc:
            record["error"] = str(exc)
        else:
            record["arrays"] = {name: getattr(table, name).tolist() for name in ARRAYS}
        records.append(record)
    PATH.write_text(json.dumps(records) + "\n")
    print(f"{PATH}: {len(records)} tables, {sum('error' in r for r in records)} refused")


if __name__ == "__main__":
    main()
