"""A learned pot model: ghost-ball pots simulated alone; a net of whether each drops, scratches, where the cue stops."""

from __future__ import annotations

import time
from concurrent.futures import ProcessPoolExecutor
from multiprocessing import get_context

import numpy as np

from pool_env.game import MAX_SPEED, GameView
from pool_env.physics import Balls, Physics, Table
from pool_env.players.planner import DN, DX, DY, OK, SPEED

from .learned_contact import AFTER_CONTACT, CUSHION_HITS, after_contact, cushion_hits
from .learned_mlp import NumpyMLP, fit_outputs
from .search import SearchAgent
from .search_candidates import ARRIVALS, Candidate
from .search_position import game_state

POT_INPUTS = 17 + AFTER_CONTACT + CUSHION_HITS  # see `pot_inputs`
POT_OUTPUTS = 4  # logit of the pot, logit of a scratch, the cue ball's rest (x, y in the pot's frame, [-1, 1])
POT_COLUMNS = 6  # see `PotNet.columns`
POT_PREFIX = "pot_"  # a saved value net's arrays of its pot net
ERROR_PREFIX = "err_"  # a pot net's arrays of its rest-error net (`fit_rest_errors`)
ERROR_FLOOR = 0.02  # m: the rest-error net fits log(error + ERROR_FLOOR), finite where a rest is exact
BALL = 9  # the one object ball of a simulated pot (alone on the table: the rules' legal ball)
RAIL_SHARE = 0.3  # share of the simulated positions with the object ball within RAIL_BAND of a cushion
RAIL_BAND = 0.08  # m
CHUNK = 200  # positions planned and drawn at a time (each chunk its own seeded generator)


def frames(obj, pocket_xy, is_side, table: Table) -> np.ndarray:
    """(N, 2) signs (+1 or -1) that mirror each pot into its frame: the pocket at the table's
    origin corner, or the side pocket on the y = 0 rail with the object ball on its x <= L / 2
    side (the table's mirror symmetries)."""
    half = np.array([table.length, table.width]) / 2.0
    flip = np.where(pocket_xy > half, -1.0, 1.0)
    flip[:, 0] = np.where(is_side, np.where(obj[:, 0] > half[0], -1.0, 1.0), flip[:, 0])
    return flip


def pocket_frames(obj, pocket, table: Table) -> tuple:
    """(the pockets' places (N, 2), side pockets (N,), `frames`) of pots of the balls at `obj`
    into the pockets of indices `pocket`."""
    pocket = np.asarray(pocket, dtype=int)
    pocket_xy = np.asarray(table.pocket_entries, dtype=np.float64)[pocket, :2]
    is_side = ~np.asarray(table.corner_pockets, dtype=bool)[pocket]
    return pocket_xy, is_side, frames(np.asarray(obj, dtype=np.float64).reshape(-1, 2), pocket_xy, is_side, table)


def mirrored(points, flip, table: Table) -> np.ndarray:
    """Points (N, 2) in metres mirrored by `flip` (an involution: it maps them back too)."""
    size = np.array([table.length, table.width])
    return np.where(flip > 0, points, size - points)


def pot_inputs(cue, obj, pocket, direction, speed, top, arrival, table: Table, physics: Physics,
               radius: float) -> np.ndarray:
    """(N, POT_INPUTS) float32 of N ghost-ball pots (cue and object ball centres (N, 2) in m,
    pocket indices, the unit directions, cue speeds m/s, tips `top` R, arrival-speed indices),
    all in the pot's mirrored frame (`frames`): the cue ball and the object ball (x, y in
    [-1, 1]), the direction, the unit line from the object ball to the pocket, a side pocket,
    speed / MAX_SPEED, top, the arrival index / 2, the cosine of the cut, the cue-object and
    object-pocket distances (m), the object ball's and the cue ball's distances to the nearer
    long and short rail lines (m) beside the pocket; then the ghost-ball model of the cue ball
    after the contact (`learned_contact.after_contact`): the ghost ball and where the cue ball
    starts to roll (x, y in [-1, 1]), its velocities after the contact and when it rolls
    (m/s), and log(1 + its rolling run in m); then where its path first meets the cushions
    (`learned_contact.cushion_hits`: the scratches it risks)."""
    cue, obj, direction = (np.asarray(a, dtype=np.float64).reshape(-1, 2) for a in (cue, obj, direction))
    pocket_xy, is_side, flip = pocket_frames(obj, pocket, table)
    c, o, p = mirrored(cue, flip, table), mirrored(obj, flip, table), mirrored(pocket_xy, flip, table)
    d = direction * flip
    to_pocket = p - o
    d2 = np.hypot(to_pocket[:, 0], to_pocket[:, 1])
    u = to_pocket / np.maximum(d2, 1e-9)[:, None]
    scale = np.array([2.0 / table.length, 2.0 / table.width])
    out = np.zeros((len(cue), POT_INPUTS), dtype=np.float32)
    out[:, 0:2], out[:, 2:4] = c * scale - 1.0, o * scale - 1.0
    out[:, 4:6], out[:, 6:8] = d, u
    out[:, 8] = is_side
    out[:, 9] = np.asarray(speed, dtype=np.float64) / MAX_SPEED
    out[:, 10] = top
    out[:, 11] = np.asarray(arrival, dtype=np.float64) / 2.0
    out[:, 12] = (d * u).sum(axis=1)
    out[:, 13] = np.hypot(*(o - c).T)
    out[:, 14] = d2
    out[:, 15] = o[:, 1]
    out[:, 16] = c[:, 1]
    after = after_contact(c, o, d, speed, top, physics, radius)
    out[:, 17:19], out[:, 19:21] = after[:, 0:2] * scale - 1.0, after[:, 2:4]
    out[:, 21:23], out[:, 23:25] = after[:, 4:6] * scale - 1.0, after[:, 6:8]
    out[:, 25] = np.log1p(after[:, 8])
    out[:, 26:] = cushion_hits(after, table, physics, radius)
    return out


def random_positions(rng, n: int, table: Table, radius: float) -> np.ndarray:
    """(n, 2, 2): the cue ball and the object ball uniformly on the cloth, apart; a share
    RAIL_SHARE with the object ball within RAIL_BAND of a cushion line."""
    lo, hi = np.array([radius, radius]), np.array([table.length - radius, table.width - radius])
    out = np.empty((n, 2, 2))
    for k in range(n):
        while True:
            cue, obj = rng.uniform(lo, hi), rng.uniform(lo, hi)
            if rng.random() < RAIL_SHARE:
                axis, side = int(rng.integers(2)), int(rng.integers(2))
                band = rng.uniform(0.0, RAIL_BAND)
                obj[axis] = lo[axis] + band if side == 0 else hi[axis] - band
            if np.hypot(*(obj - cue)) > 2.0 * radius + 1e-3:
                break
        out[k] = cue, obj
    return out


def planned_pots(search: SearchAgent, positions) -> tuple[np.ndarray, list]:
    """Every ghost-ball pot the learned player's menu would plan from each position (the
    object ball BALL alone; each pocket, arrival speed and tip): (rows (M, 6): position, pocket,
    arrival index, speed, top, cos of the cut; candidates (M,))."""
    q = len(positions)
    xy = np.zeros((q, search.n_balls, 2))
    xy[:, 0], xy[:, BALL] = positions[:, 0], positions[:, 1]
    on = np.zeros((q, search.n_balls), dtype=bool)
    on[:, [0, BALL]] = True
    legal = np.zeros_like(on)
    legal[:, BALL] = True
    index, plan = search.plans.pots(xy, on, legal, ARRIVALS)
    rows, cands = [], []
    for i in np.flatnonzero(plan[:, OK] > 0):
        direction, speed = np.array([plan[i, DX], plan[i, DY]]), float(plan[i, SPEED])
        for tip in search.tips():
            rows.append([index[i, 0], index[i, 2], i % len(ARRIVALS), speed, tip[1], plan[i, DN]])
            cands.append(Candidate(direction, speed, tip, pocket=int(index[i, 2]), ball=BALL))
    return np.array(rows).reshape(-1, 6), cands


def two_ball_records(search: SearchAgent, positions, rows, cands):
    """(k, the `JudgedShot` of cands[k]) of planned shots (rows[:, 0]: the index of each one's
    position, the rows grouped by it), each simulated without noise from its own position:
    the cue ball and the object ball BALL alone on the table."""
    sim = search.sim
    on = np.zeros(search.n_balls, dtype=bool)
    on[[0, BALL]] = True
    starts = np.flatnonzero(np.r_[True, rows[1:, 0] != rows[:-1, 0]]) if len(rows) else []
    for a, b in zip(starts, [*starts[1:], len(rows)]):
        xy = np.zeros((search.n_balls, 2))
        xy[0], xy[BALL] = positions[int(rows[a, 0])]
        view = GameView(xy, on, frozenset({BALL}))
        sim.reset(balls=Balls(xy, radius=search.radius, pocketed=~on), state=game_state(view, search.game))
        shots = [sim.decode(search.action(c, None)) for c in cands[a:b]]
        for k, r in enumerate(sim.evaluate(shots, draws=1, seed=0, records=False)):
            yield a + k, r


def simulate_pots(search: SearchAgent, positions, rows, cands) -> np.ndarray:
    """(M, 4) float32 labels of the planned pots (`two_ball_records`): the ball dropped in the
    planned pocket, the cue ball dropped, the cue ball's rest (x, y in m; where it dropped, its
    last place on the cloth). `make_pot_data` turns the rests into the pot's frame, as
    `pot_inputs` sees it."""
    out = np.zeros((len(rows), 4), dtype=np.float32)
    for i, r in two_ball_records(search, positions, rows, cands):
        o = r.outcome
        if o is None:
            continue
        out[i, 0] = BALL in o.pocketed and o.pocket_of.get(BALL) == int(rows[i, 1])
        out[i, 1] = o.cue_pocketed
        out[i, 2:4] = r.balls_after.xy[0]
    return out


def pot_examples(search: SearchAgent, positions, rows, cands) -> tuple[np.ndarray, np.ndarray]:
    """(`pot_inputs` (M, POT_INPUTS), labels (M, 4)) of planned pots (rows and candidates as
    `planned_pots` gives them, rows grouped by position): each simulated alone with its ball
    (`simulate_pots`), the cue ball's rest mirrored into the pot's frame (x, y in [-1, 1])."""
    q = rows[:, 0].astype(int)
    table = search.table
    x = pot_inputs(positions[q, 0], positions[q, 1], rows[:, 1].astype(int), [c.direction for c in cands],
                   rows[:, 3], rows[:, 4], rows[:, 2], table, search.physics, search.radius)
    y = simulate_pots(search, positions, rows, cands)
    flip = pocket_frames(positions[q, 1], rows[:, 1].astype(int), table)[2]
    y[:, 2:4] = mirrored(y[:, 2:4], flip, table) * np.array([2.0 / table.length, 2.0 / table.width]) - 1.0
    return x, y


def make_pot_data(positions: int = 1000, seed: int = 0, log=print, first_chunk: int = 0) -> dict:
    """`positions` random positions (`random_positions`) in chunks of CHUNK, chunk c drawn from
    a generator seeded (seed, c) (chunks `first_chunk` on), every planned pot of each simulated:
    arrays inputs (M, POT_INPUTS) and labels (M, 4) (`simulate_pots`; the rests mirrored into
    the pot's frame, x, y in [-1, 1])."""
    search = SearchAgent("nine_ball", noise=None, seed=seed)
    start, inputs, labels = time.perf_counter(), [], []
    for first in range(0, positions, CHUNK):
        rng = np.random.default_rng([seed, first_chunk + first // CHUNK])
        pos = random_positions(rng, min(CHUNK, positions - first), search.table, search.radius)
        rows, cands = planned_pots(search, pos)
        if not len(rows):
            continue
        x, y = pot_examples(search, pos, rows, cands)
        inputs.append(x)
        labels.append(y)
        if log is not None:
            log(f"pots: {first + len(pos)}/{positions} positions, {sum(map(len, labels))} shots, "
                f"{time.perf_counter() - start:.0f} s")
    return {"inputs": np.concatenate(inputs), "labels": np.concatenate(labels)}


def _chunks_part(job) -> dict:
    make, positions, seed, first_chunk = job
    return make(positions, seed, log=None, first_chunk=first_chunk)


def parallel_chunks(make, positions: int, seed: int, workers: int, chunk: int = CHUNK) -> dict:
    """`make(positions, seed, log=None, first_chunk=...)` (a data maker that draws its positions
    in seeded chunks of `chunk`, as `make_pot_data` does of CHUNK) split over `workers` processes
    by whole chunks, joined in order: the same data as one process makes, whatever the number of
    workers."""
    chunks = -(-positions // chunk)
    share = -(-chunks // workers) * chunk
    jobs = [(make, min(share, positions - k * share), seed, k * share // chunk) for k in range(workers)
            if positions - k * share > 0]
    with ProcessPoolExecutor(len(jobs), mp_context=get_context("spawn")) as pool:
        parts = list(pool.map(_chunks_part, jobs))
    return {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}


def parallel_pot_data(positions: int, seed: int = 0, workers: int = 2) -> dict:
    """`make_pot_data` on `workers` processes (`parallel_chunks`)."""
    return parallel_chunks(make_pot_data, positions, seed, workers)


def fit_pots(data: dict, hidden=(128, 128), epochs: int = 30, seed: int = 0, lr: float = 2e-3, log=print) -> PotNet:
    """The pot net fitted with torch on one thread: cross-entropies of the pot and the scratch,
    and the squared error of the cue ball's rest where it did not drop; Adam, minibatches of 512."""
    import torch

    bce = torch.nn.functional.binary_cross_entropy_with_logits

    def loss(out, t):
        kept = 1.0 - t[:, 1]
        rest = (((out[:, 2:4] - t[:, 2:4]) ** 2).sum(axis=1) * kept).sum() / kept.sum().clamp(min=1.0)
        return bce(out[:, 0], t[:, 0]) + bce(out[:, 1], t[:, 1]) + rest

    return PotNet(fit_outputs(data["inputs"], data["labels"], POT_OUTPUTS, loss, hidden, epochs, seed, lr, log,
                              "pot fit"))


def fit_rest_errors(pots: PotNet, data: dict, table: Table, hidden=(64, 64), epochs: int = 8, seed: int = 0,
                    log=print) -> PotNet:
    """`pots` with a rest-error net: an MLP of the same inputs fitted (squared error, Adam, on one
    torch thread) to log(e + ERROR_FLOOR), e (m) how far the pot net's predicted rest lies from
    the simulated one, over the pots whose cue ball stayed on the table; its exp is a typical
    error of that prediction (`PotNet.rest_errors`)."""
    kept = np.asarray(data["labels"])[:, 1] < 0.5
    x, y = np.asarray(data["inputs"])[kept], np.asarray(data["labels"])[kept]
    miss = (pots.predict(x)[2] - y[:, 2:4]) * np.array([table.length, table.width]) / 2.0
    target = np.log(np.hypot(miss[:, 0], miss[:, 1]) + ERROR_FLOOR)[:, None]
    arrays = fit_outputs(x, target, 1, lambda out, t: ((out - t) ** 2).mean(), hidden, epochs, seed, 2e-3, log,
                         "rest-error fit")
    return PotNet({**pots.arrays, **{ERROR_PREFIX + k: v for k, v in arrays.items()}})


class PotNet(NumpyMLP):
    """The pot model in NumPy (`NumpyMLP`): `__call__` of `pot_inputs` rows gives
    (N, POT_OUTPUTS); `columns` the value net's features; with a rest-error net (the arrays
    named "err_...", `fit_rest_errors`) `rest_errors` how far off each predicted rest may be."""

    def __init__(self, arrays: dict):
        super().__init__(arrays)
        errors = {k[len(ERROR_PREFIX):]: v for k, v in arrays.items() if k.startswith(ERROR_PREFIX)}
        self.errors = NumpyMLP(errors) if errors else None

    def predict(self, x) -> tuple:
        """(the probability of the pot, of a scratch, the cue ball's rest in the pot's frame (N, 2))."""
        out = self(x)
        return 1.0 / (1.0 + np.exp(-out[:, 0])), 1.0 / (1.0 + np.exp(-out[:, 1])), out[:, 2:4]

    def rest_errors(self, x) -> np.ndarray | None:
        """(N,) m: a typical distance of each predicted rest from the true one, plus ERROR_FLOOR
        (None without a rest-error net)."""
        return None if self.errors is None else np.exp(self.errors(x)[:, 0].astype(np.float64))

    def read(self, features, table: Table, physics: Physics, radius: float) -> tuple:
        """(`columns`, the `rest_errors` of the rows' pots in order (None without a rest-error net))."""
        if self.inputs != POT_INPUTS:
            raise ValueError(f"this pot net was fitted to {self.inputs} inputs a pot, where `pot_inputs` now "
                             f"makes {POT_INPUTS}: fit it again (python train.py --algo value)")
        f = np.asarray(features, dtype=np.float32)
        out = np.zeros((len(f), POT_COLUMNS), dtype=np.float32)
        pots = np.flatnonzero((f[:, 0] == 1.0) & (f[:, 19] == 1.0))
        if not len(pots):
            return out, None if self.errors is None else np.zeros(0)
        g = f[pots].astype(np.float64)
        size = np.array([table.length, table.width])
        cue, obj = (g[:, 10:12] + 1.0) * size / 2.0, (g[:, 26:28] + 1.0) * size / 2.0
        pocket = np.argmax(g[:, 20:26], axis=1)
        x = pot_inputs(cue, obj, pocket, g[:, 7:9], g[:, 4] * MAX_SPEED, g[:, 6], g[:, 18], table, physics, radius)
        p_pot, p_scratch, rest = self.predict(x)
        flip = pocket_frames(obj, pocket, table)[2]
        rest = mirrored((rest.astype(np.float64) + 1.0) * size / 2.0, flip, table) * 2.0 / size - 1.0
        keep = p_pot * (1.0 - p_scratch)
        out[pots] = np.column_stack([p_pot, p_scratch, rest, keep, keep * g[:, 31]])
        return out, self.rest_errors(x)

    def columns(self, features, table: Table, physics: Physics, radius: float) -> np.ndarray:
        """(K, POT_COLUMNS) float32 of a menu's rows (`learned.candidate_features` leading):
        for a pot, its predicted probability of dropping and of a scratch, the cue ball's
        predicted rest (x, y in [-1, 1]), the chance it keeps the table (dropped and no
        scratch) and that times the ghost-ball next-shot quality; zeros for other shots."""
        return self.read(features, table, physics, radius)[0]

    def save_arrays(self) -> dict:
        return {POT_PREFIX + k: v for k, v in self.arrays.items()}
