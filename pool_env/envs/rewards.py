"""The break env's shot reward: balls pocketed, the scratch penalty, the spread of the object balls and the shaping."""

from __future__ import annotations

import math

import numpy as np

from ..game import N_BALLS
from ..physics import Balls, Table

SHAPING_CONTACT = 0.1  # shaping: + for hitting an object ball, - for missing them all
SHAPING_SPREAD = 0.5  # shaping: weight of the spread gain on a table with pockets


def spread(xy, on_table, table: Table) -> float:
    """Mean nearest-neighbour distance of the object balls on the table, in units of
    sqrt(L W / 15) (the spacing of 15 balls on a square grid covering the table); 0 with fewer than two."""
    p = np.asarray(xy)[1:][np.asarray(on_table)[1:]]
    if len(p) < 2:
        return 0.0
    d = np.hypot(p[:, None, 0] - p[None, :, 0], p[:, None, 1] - p[None, :, 1])
    np.fill_diagonal(d, np.inf)
    return float(d.min(axis=1).mean() / math.sqrt(table.length * table.width / (N_BALLS - 1)))


def spread_gain(before: Balls, after: Balls, table: Table) -> float:
    """The spread after a shot minus the spread before it, clipped to [-1, 1]."""
    gain = spread(after.xy, ~after.pocketed, table) - spread(before.xy, ~before.pocketed, table)
    return float(min(1.0, max(-1.0, gain)))


def shot_reward(info: dict, before: Balls, after: Balls, table: Table, scratch_penalty=1.0, shaping=False) -> float:
    """A shot's reward (see PoolBreakEnv) from its `info` and the balls before and after it."""
    pocketless = table.pockets.shape[0] == 0
    if pocketless:
        reward = spread_gain(before, after, table)
    else:
        reward = float(info["pocketed"][1:].sum()) - (scratch_penalty if info["scratch"] else 0.0)
    if shaping:
        reward += SHAPING_CONTACT if info["first_contact"] >= 0 else -SHAPING_CONTACT
        if not pocketless:
            reward += SHAPING_SPREAD * spread_gain(before, after, table)
    return float(reward)
