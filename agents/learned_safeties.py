"""A learned safety and kick model: the menu's safeties and kicks simulated with two balls; a net of what each does."""

from __future__ import annotations

import dataclasses
import time

import numpy as np

from pool_env import rules
from pool_env.game import MAX_SPEED
from pool_env.physics import Table

from .learned_mlp import NumpyMLP, fit_outputs
from .learned_pots import BALL, CHUNK, mirrored, parallel_chunks, random_positions, two_ball_records
from .search import SearchAgent
from .search_position import legal_mask

SAFE_INPUTS = 13  # see `safe_inputs`
SAFE_OUTPUTS = 7  # logits of a foul, of the object ball dropping, of a scratch; both balls' rests (x, y in [-1, 1])
SAFE_COLUMNS = 10  # see `SafetyNet.columns`
SAFE_PREFIX = "safe_"  # a saved value net's arrays of its safety net
KINDS = ("safety", "kick")


def quadrant(obj, table: Table) -> np.ndarray:
    """(N, 2) signs that mirror each shot into its frame: the object ball in the quarter of the
    table nearest the origin (the table's two mirror symmetries)."""
    half = np.array([table.length, table.width]) / 2.0
    return np.where(np.asarray(obj, dtype=np.float64).reshape(-1, 2) > half, -1.0, 1.0)


def safe_inputs(cue, obj, direction, speed, top, kick, table: Table, radius: float) -> np.ndarray:
    """(N, SAFE_INPUTS) float32 of N safeties or kicks (cue and object ball centres (N, 2) in m,
    unit directions, cue speeds m/s, tips `top` R, is it a kick), in the frame of `quadrant`:
    the cue ball and the object ball (x, y in [-1, 1]), the direction, speed / MAX_SPEED, top,
    kick, the cosine and sine of the direction's angle from the line to the object ball, the
    distance between the balls (m), and the direction's miss of the object ball's centre (in
    ball radii, capped at 3)."""
    cue, obj, d = (np.asarray(a, dtype=np.float64).reshape(-1, 2) for a in (cue, obj, direction))
    flip = quadrant(obj, table)
    c, o, d = mirrored(cue, flip, table), mirrored(obj, flip, table), d * flip
    to = o - c
    dist = np.maximum(np.hypot(to[:, 0], to[:, 1]), 1e-9)
    u = to / dist[:, None]
    sin = d[:, 0] * u[:, 1] - d[:, 1] * u[:, 0]
    scale = np.array([2.0 / table.length, 2.0 / table.width])
    out = np.zeros((len(c), SAFE_INPUTS), dtype=np.float32)
    out[:, 0:2], out[:, 2:4], out[:, 4:6] = c * scale - 1.0, o * scale - 1.0, d
    out[:, 6] = np.asarray(speed, dtype=np.float64) / MAX_SPEED
    out[:, 7] = top
    out[:, 8] = kick
    out[:, 9] = (d * u).sum(axis=1)
    out[:, 10] = sin
    out[:, 11] = dist
    out[:, 12] = np.clip(dist * np.abs(sin) / radius, 0.0, 3.0) * np.sign((d * u).sum(axis=1))
    return out


def planned_shots(search: SearchAgent, positions) -> tuple[np.ndarray, list]:
    """The safeties and kicks the learned player's menu plans at the object ball BALL alone
    from each position: (rows (M, 2): position, is it a kick; candidates (M,))."""
    rows, cands = [], []
    for q, (cue, obj) in enumerate(positions):
        xy = np.zeros((search.n_balls, 2))
        xy[0], xy[BALL] = cue, obj
        for c in search.safeties(xy, None, {BALL}) + search.kicks(xy, {BALL}):
            rows.append([q, c.kind == "kick"])
            cands.append(c)
    return np.array(rows, dtype=np.float64).reshape(-1, 2), cands


def simulate_shots(search: SearchAgent, positions, rows, cands) -> np.ndarray:
    """(M, 7) float32 labels of the planned shots (`learned_pots.two_ball_records`): a foul,
    the object ball dropped, the cue ball dropped, the cue ball's and the object ball's rests
    (x, y in m)."""
    out = np.zeros((len(rows), 7), dtype=np.float32)
    for i, r in two_ball_records(search, positions, rows, cands):
        o = r.outcome
        if o is None:  # a shot the simulator could not play: counted a foul
            out[i, 0] = 1.0
            continue
        out[i, 0] = r.ruling is not None and r.ruling.foul is not None
        out[i, 1] = BALL in o.pocketed
        out[i, 2] = o.cue_pocketed
        out[i, 3:5], out[i, 5:7] = r.balls_after.xy[0], r.balls_after.xy[BALL]
    return out


def make_safe_data(positions: int = 1000, seed: int = 1, log=print, first_chunk: int = 0) -> dict:
    """`positions` random positions (`learned_pots.random_positions`) in chunks of CHUNK, chunk c
    drawn from a generator seeded (seed, c), every planned safety and kick of each simulated:
    inputs (M, SAFE_INPUTS) and labels (M, 7) (the rests mirrored into the shot's frame, x, y
    in [-1, 1])."""
    search = SearchAgent("nine_ball", noise=None, seed=seed)
    start, inputs, labels = time.perf_counter(), [], []
    scale = np.array([2.0 / search.table.length, 2.0 / search.table.width])
    for first in range(0, positions, CHUNK):
        rng = np.random.default_rng([seed, first_chunk + first // CHUNK])
        pos = random_positions(rng, min(CHUNK, positions - first), search.table, search.radius)
        rows, cands = planned_shots(search, pos)
        q = rows[:, 0].astype(int)
        inputs.append(safe_inputs(pos[q, 0], pos[q, 1], [c.direction for c in cands], [c.speed for c in cands],
                                  [c.tip[1] for c in cands], rows[:, 1], search.table, search.radius))
        y = simulate_shots(search, pos, rows, cands)
        flip = quadrant(pos[q, 1], search.table)
        for k in (3, 5):
            y[:, k:k + 2] = mirrored(y[:, k:k + 2], flip, search.table) * scale - 1.0
        labels.append(y)
        if log is not None:
            log(f"safeties: {first + len(pos)}/{positions} positions, {sum(map(len, labels))} shots, "
                f"{time.perf_counter() - start:.0f} s")
    return {"inputs": np.concatenate(inputs), "labels": np.concatenate(labels)}


def parallel_safe_data(positions: int, seed: int = 1, workers: int = 2) -> dict:
    """`make_safe_data` on `workers` processes (`learned_pots.parallel_chunks`)."""
    return parallel_chunks(make_safe_data, positions, seed, workers)


def fit_safeties(data: dict, hidden=(128, 128), epochs: int = 20, seed: int = 0, lr: float = 2e-3,
                 log=print) -> SafetyNet:
    """The safety net fitted with torch on one thread (`fit_outputs`): cross-entropies of the
    foul, the drop and the scratch, and the squared error of each ball's rest where it stayed
    on the table."""
    import torch

    bce = torch.nn.functional.binary_cross_entropy_with_logits

    def loss(out, t):
        total = sum(bce(out[:, k], t[:, k]) for k in range(3))
        for k, dropped in ((3, t[:, 2]), (5, t[:, 1])):
            kept = 1.0 - dropped
            err = ((out[:, k:k + 2] - t[:, k:k + 2]) ** 2).sum(axis=1) * kept
            total = total + err.sum() / kept.sum().clamp(min=1.0)
        return total

    return SafetyNet(fit_outputs(data["inputs"], data["labels"], SAFE_OUTPUTS, loss, hidden, epochs, seed, lr, log,
                                 "safety fit"))


def aimed_balls(features, d, radius: float, table: Table) -> np.ndarray:
    """(K,) the legal ball each safety or kick row (`learned.candidate_features`) is aimed at:
    the legal ball whose line (a safety) or rail image's line (a kick) is nearest its direction."""
    legal = sorted(int(b) for b in d.legal) or [0]
    f = np.asarray(features, dtype=np.float64)
    size = np.array([table.length, table.width])
    cue, direction = (f[:, 10:12] + 1.0) * size / 2.0, f[:, 7:9]
    lo, hi = radius, size - radius
    best, out = np.full(len(f), -np.inf), np.full(len(f), legal[0])
    for ball in legal:
        x, y = d.xy[ball]
        targets = [(x, y)] + [(2 * lo - x, y), (2 * hi[0] - x, y), (x, 2 * lo - y), (x, 2 * hi[1] - y)]
        for k, target in enumerate(targets):
            to = np.asarray(target) - cue
            cos = (to * direction).sum(axis=1) / np.maximum(np.hypot(to[:, 0], to[:, 1]), 1e-9)
            cos = np.where((f[:, 2] == 1.0) == (k > 0), cos, -np.inf)  # a kick aims at an image
            out = np.where(cos > best, ball, out)
            best = np.maximum(best, cos)
    return out


class SafetyNet(NumpyMLP):
    """The safety model in NumPy (`NumpyMLP`): `__call__` of `safe_inputs` rows gives
    (N, SAFE_OUTPUTS); `columns` the value net's features."""

    def columns(self, search: SearchAgent, features, d, state) -> np.ndarray:
        """(K, SAFE_COLUMNS) float32 of a menu's rows (`learned.candidate_features` leading): for a
        safety or kick at its aimed ball (`aimed_balls`) alone, the predicted chances of a foul,
        of the ball dropping and of a scratch, both balls' predicted rests (x, y in [-1, 1]),
        the opponent's best ghost-ball score with the balls moved there (`opponent_quality`),
        that times the chance of neither a foul nor a drop, and the chance of a drop without a
        foul; zeros for other shots."""
        f = np.asarray(features, dtype=np.float32)
        out = np.zeros((len(f), SAFE_COLUMNS), dtype=np.float32)
        rows = np.flatnonzero((f[:, 1] == 1.0) | (f[:, 2] == 1.0))
        if not len(rows):
            return out
        g = f[rows].astype(np.float64)
        size = np.array([search.table.length, search.table.width])
        balls = aimed_balls(g, d, search.radius, search.table)
        cue, obj = (g[:, 10:12] + 1.0) * size / 2.0, d.xy[balls]
        x = safe_inputs(cue, obj, g[:, 7:9], g[:, 4] * MAX_SPEED, g[:, 6], g[:, 2], search.table, search.radius)
        y = self(x)
        p = 1.0 / (1.0 + np.exp(-y[:, :3].astype(np.float64)))
        flip = quadrant(obj, search.table)
        rests = [mirrored((y[:, k:k + 2].astype(np.float64) + 1.0) * size / 2.0, flip, search.table) for k in (3, 5)]
        q = opponent_quality(search, d, state, balls, *rests)
        calm = (1.0 - p[:, 0]) * (1.0 - p[:, 1])
        out[rows] = np.column_stack([p, rests[0] * 2.0 / size - 1.0, rests[1] * 2.0 / size - 1.0,
                                     q, q * calm, p[:, 1] * (1.0 - p[:, 0])])
        return out

    def save_arrays(self) -> dict:
        return {SAFE_PREFIX + k: v for k, v in self.arrays.items()}


def opponent_quality(search: SearchAgent, d, state, balls, cue_rests, ball_rests) -> np.ndarray:
    """(K,): the opponent's best ghost-ball score (capped at 1) with the cue ball at each
    `cue_rests` and ball `balls[k]` at `ball_rests[k]`, the other balls where they lie."""
    if state is None or not len(balls):
        return np.zeros(len(balls))
    try:
        legal = rules.legal_targets(dataclasses.replace(state, shooter=1, is_break=False))
    except (ValueError, KeyError, IndexError):  # a state the rules cannot hand over: our own legal balls
        legal = rules.legal_targets(state)
    on = np.asarray(d.on_table, dtype=bool).copy()
    on[0] = True
    mask = legal_mask(legal, len(on)) & on
    xys = np.repeat(np.asarray(d.xy, dtype=np.float64)[None], len(balls), axis=0)
    xys[:, 0] = cue_rests
    xys[np.arange(len(balls)), balls] = ball_rests
    n = len(balls)
    return search.plans.qualities(xys, np.repeat(on[None], n, axis=0), np.repeat(mask[None], n, axis=0), 1.0)
