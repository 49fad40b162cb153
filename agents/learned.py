"""`LearnedPlayer`: scores the search's candidate shots with a small network, one evaluation per shot, no simulation."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from pool_env import rules
from pool_env.game import GAME_BALLS, MAX_SPEED
from pool_env.physics import BALL_RADIUS, Physics, Table
from pool_env.players import Agent, game_of
from pool_env.players import geometry as geo
from pool_env.players.planner import D1, D2, DN, DX, DY, OK, SCORE, SCRATCH, SPEED

from .learned_combos import combo_columns
from .learned_features import contact_frame, outcome_features, roll_at_contact
from .learned_pots import POT_COLUMNS, POT_PREFIX, PotNet
from .learned_safeties import SAFE_PREFIX, SafetyNet
from .search import SearchAgent
from .search_candidates import ARRIVALS, Candidate
from .search_position import decode, game_state, legal_mask, racked

WEIGHTS = Path(__file__).with_name("weights")  # the shipped networks, one file per game
KINDS = ("pot", "safety", "kick", "break")
CANDIDATE_FEATURES = 36  # see `candidate_features`
LAYOUT = 5  # the feature rows new nets are fitted on (`menu`)
LABEL_LAYOUT = 2  # the rows labelled data keeps: layouts 3-5 add only columns computed from them, at fit time
BREAK_PREFIX = "break_"  # a saved net's arrays of its break net (`ValueNet.breaks`)
EXPLORE = 0.25  # share of the data games' shots played by a random menu candidate (positions off the usual path)
REST_POINTS = 6  # the next shot's quality is averaged over the predicted rest and this many points around it ...
REST_SPREAD = 0.1  # m ... this far off, or with the pot net's rest-error net as far as it says, within REST_SPREADS
REST_SPREADS = (0.03, 0.5)  # m


@dataclass
class Menu:
    """A decision's candidate shots (`agents.search.Candidate`) and their feature rows (K, F)."""

    candidates: list
    features: np.ndarray


def cue_rest(search: SearchAgent, cue, obj, d, speed: float, top: float):
    """Where the ghost-ball model leaves the cue ball sent along `d` at `speed` m/s with the tip
    `top` at the ball `obj` (`geometry.cue_path`'s last point: the contact by `geometry.collision`)."""
    phys, R = search.physics, search.radius
    travel, ghost, n, t = contact_frame(cue, obj, d, R)  # the cue ball's run to the contact
    v = geo.speed_after(speed, travel, phys)
    roll = roll_at_contact(speed, top, travel, phys)
    _, _, cn, ct = geo.collision(v, roll, float(d @ n), float(d @ t), phys)
    path = geo.cue_path(ghost, cn * n + ct * t, roll * d, phys, search.table, R)
    return path[-1] if len(path) else ghost


def game_ball_of(game: str | None) -> int:
    """The ball that wins the game: the 9 in 9-ball, else the 8."""
    return 9 if game == "nine_ball" else 8


def next_qualities(search: SearchAgent, xy, on_table, state, balls, rests) -> np.ndarray:
    """(M,): the best ghost-ball score (capped at 1) of the shooter's next shot if ball `balls[m]`
    drops and the cue ball stops at `rests[m]` (1 if that ball wins the game), all at once."""
    if state is None or not len(balls):
        return np.zeros(len(balls))
    game_ball = game_ball_of(state.kind)
    n = len(on_table)
    xys = np.repeat(np.asarray(xy, dtype=np.float64)[None], len(balls), axis=0)
    xys[:, 0] = rests
    ons = np.repeat(np.asarray(on_table, dtype=bool)[None], len(balls), axis=0)
    ons[:, 0] = True  # the cue ball stops at the rest, on the table even if it was in hand (after a scratch)
    ons[np.arange(len(balls)), balls] = False
    legal = {}
    for ball in set(int(b) for b in balls):
        if ball != game_ball and len(state.on_table) > 1:
            after = dataclasses.replace(state, on_table=state.on_table - {ball}, is_break=False)
            legal[ball] = legal_mask(rules.legal_targets(after), n)
    masks = np.array([legal.get(int(b), np.zeros(n, dtype=bool)) for b in balls])
    q = search.plans.qualities(xys, ons, masks, 1.0)
    return np.where([int(b) in legal for b in balls], q, 1.0)


def first_contacts(xy, on_table, cue, directions, radius: float, table: Table) -> np.ndarray:
    """(K, 3): for the cue ball sent from `cue` along each direction, the first object ball it
    meets (0: none before the first rail), the distance to that contact, and the first ball it
    meets after one reflection off that rail (0: none)."""
    objects = np.flatnonzero(on_table[1:]) + 1
    d = np.asarray(directions, dtype=np.float64).reshape(-1, 2)
    out = np.zeros((len(d), 3))
    lo, hi = np.array([radius, radius]), np.array([table.length - radius, table.width - radius])
    with np.errstate(divide="ignore", invalid="ignore"):
        to_rail = np.where(d > 0, (hi - cue) / d, np.where(d < 0, (lo - cue) / d, np.inf)).min(axis=1)
    first, dist = _first_ball(xy[objects], cue[None], d, radius)
    out[:, 0] = np.where(dist < to_rail, objects[first] if len(objects) else 0, 0)
    out[:, 1] = np.minimum(dist, to_rail)
    bounce = cue + d * to_rail[:, None]
    hit_x = np.isclose(bounce[:, 0], lo[0]) | np.isclose(bounce[:, 0], hi[0])
    reflected = np.where(hit_x[:, None], d * [-1.0, 1.0], d * [1.0, -1.0])
    second, dist2 = _first_ball(xy[objects], bounce, reflected, radius)
    out[:, 2] = np.where((out[:, 0] == 0) & np.isfinite(dist2), objects[second] if len(objects) else 0, 0)
    return out


def _first_ball(balls, start, d, radius):
    """(index of the first ball met, distance to the contact) of rays start + s d (K rays)."""
    if not len(balls):
        return np.zeros(len(d), dtype=int), np.full(len(d), np.inf)
    rel = balls[None, :, :] - start[:, None, :]  # (K, B, 2)
    along = rel[..., 0] * d[:, None, 0] + rel[..., 1] * d[:, None, 1]
    perp2 = rel[..., 0] ** 2 + rel[..., 1] ** 2 - along**2
    reach = 4.0 * radius * radius - perp2
    contact = np.where((along > 0) & (reach > 0), along - np.sqrt(np.maximum(reach, 0.0)), np.inf)
    first = np.argmin(contact, axis=1)
    return first, contact[np.arange(len(d)), first]


def pot_candidates(search: SearchAgent, xy, on_table, legal, state=None) -> tuple[list, list]:
    """The ghost-ball pots of `SearchAgent` (every legal ball x pocket x arrival speed x tip, the
    aim not jittered) with what the planner knew of each: (candidates, their planner rows)."""
    xy = np.asarray(xy, dtype=np.float64)
    mask = legal_mask(legal, len(on_table))
    index, plan = search.plans.pots(xy[None], np.asarray(on_table)[None], mask[None], ARRIVALS)
    cands, rows, balls, rests = [], [], [], []
    for i in np.flatnonzero(plan[:, OK] > 0):
        ball, pocket, k = int(index[i, 1]), int(index[i, 2]), i % len(ARRIVALS)
        direction, speed = np.array([plan[i, DX], plan[i, DY]]), float(plan[i, SPEED])
        for t, tip in enumerate(search.tips()):
            rest = cue_rest(search, xy[0], xy[ball], direction, speed, tip[1])
            cands.append(Candidate(direction, speed, tip, pocket=pocket,
                                   prior=float(plan[i, SCORE]) * (1.0 - 0.05 * t - 0.02 * k), ball=ball))
            rows.append([ball, pocket, k, float(plan[i, SCORE]), float(plan[i, DN]), float(plan[i, D1]),
                         float(plan[i, D2]), float(plan[i, SCRATCH]), rest])
            balls.append(ball)
            rests.append(rest)
    quality = next_qualities(search, xy, on_table, state, np.array(balls, dtype=int), np.array(rests).reshape(-1, 2))
    for row, q in zip(rows, quality, strict=True):
        row.append(float(q))
    return cands, rows


def shot_menu(search: SearchAgent, d, state) -> tuple[list, list]:
    """Every candidate of a decision with its planner row (None for a shot that is not a pot)."""
    if racked(d.xy, d.on_table, search.radius):
        cands = search.break_candidates(d, state)
        return cands, [None] * len(cands)
    spots = [None] if d.ball_in_hand is None else search.spots(d)
    cands, rows = [], []
    for spot in spots:
        xy = d.xy
        if spot is not None:
            xy = d.xy.copy()
            xy[0] = spot
        pots, pot_rows = pot_candidates(search, xy, d.on_table, d.legal, state)
        rest = search.safeties(xy, d.on_table, d.legal)
        if not pots:
            rest += search.kicks(xy, d.legal)
        cands += [dataclasses.replace(c, spot=spot) for c in pots + rest]
        rows += pot_rows + [None] * len(rest)
    return cands, rows


def candidate_features(cands, rows, d, table: Table, game_ball: int, pockets, radius: float,
                       hits=None) -> np.ndarray:
    """(K, CANDIDATE_FEATURES) float32: kind (4), speed / MAX_SPEED, tip (side, top), direction
    (cos, sin), placed, the cue ball's spot (x, y in [-1, 1]), and for a pot: the planner's score,
    cos of the cut, cue-object and object-pocket distances (m), a slot kept at 0 (the shipped
    net's layout has it: the batched planner gives no open fraction), scratch risk,
    arrival-speed index, the pocket (one-hot, 6), the object ball (x, y), is it the
    game ball (the 9, the 8), the cue ball's predicted rest (x, y), the next shot's ghost-ball
    quality from there (`next_qualities`), the rest in a pocket; for a game's break, in the pot's
    slot kept at 0, the aim's offset from the nearest object ball's centre (in ball radii: the
    same for a break candidate in every rack, whose jitter turns the direction); for every shot:
    the first ball it meets is legal, the distance to it, the first ball met after one rail is legal."""
    out = np.zeros((len(cands), CANDIDATE_FEATURES), dtype=np.float32)
    scale = np.array([2.0 / table.length, 2.0 / table.width])
    for i, (c, row) in enumerate(zip(cands, rows, strict=True)):
        out[i, KINDS.index(c.kind)] = 1.0
        out[i, 4] = c.speed / MAX_SPEED
        out[i, 5:7] = c.tip
        out[i, 7:9] = c.direction
        cue = d.xy[0] if c.spot is None else np.asarray(c.spot)
        out[i, 9] = c.spot is not None
        out[i, 10:12] = cue * scale - 1.0
        if row is not None:
            ball, pocket, k, score, cos_cut, d1, d2, scratch, rest, quality = row
            out[i, 12:20] = (min(score, 2.0), cos_cut, d1, d2, 0.0, scratch, k, 1.0)
            out[i, 20 + pocket] = 1.0
            out[i, 26:28] = d.xy[ball] * scale - 1.0
            out[i, 28] = ball == game_ball
            out[i, 29:31] = np.asarray(rest) * scale - 1.0
            out[i, 31] = quality
            out[i, 32] = geo.enters_pocket(np.asarray(rest).reshape(1, 2), pockets)
        elif c.kind == "break" and c.spot is not None:
            out[i, 16] = aim_offset(d, cue, c.direction, radius)
    hits = contacts_of(cands, d, table, radius) if hits is None else hits
    out[:, 33] = [int(b) in d.legal for b in hits[:, 0]]
    out[:, 34] = np.minimum(hits[:, 1], 3.0)
    out[:, 35] = [int(b) in d.legal for b in hits[:, 2]]
    return out


def aim_offset(d, cue, direction, radius: float) -> float:
    """How far (in ball radii, signed) the line from `cue` along `direction` passes beside the
    centre of the object ball nearest `cue`."""
    objects = np.flatnonzero(d.on_table[1:]) + 1
    if not len(objects):
        return 0.0
    to = d.xy[objects] - cue
    near = to[np.argmin(np.hypot(to[:, 0], to[:, 1]))]
    return float(direction[0] * near[1] - direction[1] * near[0]) / radius


def contacts_of(cands, d, table: Table, radius: float) -> np.ndarray:
    """(K, 3): `first_contacts` of each candidate from its own cue-ball spot."""
    hits = np.zeros((len(cands), 3))
    for spot in {None if c.spot is None else tuple(c.spot) for c in cands}:
        rows_here = [i for i, c in enumerate(cands) if (None if c.spot is None else tuple(c.spot)) == spot]
        cue = d.xy[0] if spot is None else np.asarray(spot)
        hits[rows_here] = first_contacts(d.xy, d.on_table, cue, [cands[i].direction for i in rows_here], radius, table)
    return hits


def menu(search: SearchAgent, observation, game: str | None, layout: int = LAYOUT,
         pots: PotNet | None = None, safeties: SafetyNet | None = None) -> tuple[Menu, object]:
    """The decision's `Menu` for a game observation, and its decoded view. Feature rows of
    `layout` 2: `candidate_features`, `learned_features.outcome_features`, the observation;
    layout 3: and the pot net `pots`' columns (`pot_columns`); layout 4: and the safety net
    `safeties`' columns (`SafetyNet.columns`); layout 5: and the third balls the shots send
    their object ball or cue ball into (`learned_combos.combo_columns`); layout 1 (the first
    shipped nets): without the outcome features."""
    if layout >= 3 and pots is None:
        raise ValueError("layout 3 feature rows need the pot net (pots=)")
    if layout >= 4 and safeties is None:
        raise ValueError("layout 4 feature rows need the safety net (safeties=)")
    d = decode(observation, search.n_balls, search.table, game=game is not None)
    state = game_state(d, game, search.rule_options) if game is not None else None
    cands, rows = shot_menu(search, d, state)
    game_ball = game_ball_of(game)
    hits = contacts_of(cands, d, search.table, search.radius)
    parts = [candidate_features(cands, rows, d, search.table, game_ball, search.pockets, search.radius, hits)]
    if layout >= 2:
        parts.append(outcome_features(search, d, state, cands, rows, hits))
    parts.append(np.broadcast_to(np.asarray(observation, dtype=np.float32), (len(cands), len(observation))))
    if layout >= 3:
        parts.append(pot_columns(search, pots, d, state, parts[0]))
    if layout >= 4:
        parts.append(safeties.columns(search, parts[0], d, state))
    if layout >= 5:
        parts.append(combo_columns(search, parts[0], d, game_ball))
    return Menu(cands, np.concatenate(parts, axis=1)), d


def pot_columns(search: SearchAgent, pots: PotNet, d, state, rows) -> np.ndarray:
    """(K, POT_COLUMNS + 2) float32 of a menu's `candidate_features` rows: `PotNet.columns`, then
    for a pot the next shot's ghost-ball quality around the pot net's cue-ball rest
    (`spread_qualities`, as far around as its rest-error net expects the rest to be off, else
    REST_SPREAD) and that times the chance it keeps the table (zeros for other shots).
    The pot's ball is the one on the table at the row's object-ball place."""
    cols, errors = pots.read(rows, search.table, search.physics, search.radius)
    out = np.zeros((len(rows), POT_COLUMNS + 2), dtype=np.float32)
    out[:, :POT_COLUMNS] = cols
    pot = np.flatnonzero((rows[:, 0] == 1.0) & (rows[:, 19] == 1.0))
    if not len(pot):
        return out
    size = np.array([search.table.length, search.table.width])
    placed = (d.xy * (2.0 / size) - 1.0).astype(np.float32)  # as `candidate_features` wrote them
    gap = np.abs(placed[None, :, :] - rows[pot, None, 26:28]).sum(axis=2) + np.where(d.on_table[None], 0.0, np.inf)
    gap[:, 0] = np.inf
    balls = np.argmin(gap, axis=1)
    rests = (cols[pot, 2:4].astype(np.float64) + 1.0) * size / 2.0
    spread = np.full(len(pot), REST_SPREAD) if errors is None else np.clip(errors, *REST_SPREADS)
    q = spread_qualities(search, d, state, balls, rests, spread)
    out[pot, POT_COLUMNS] = q
    out[pot, POT_COLUMNS + 1] = q * cols[pot, 4]
    return out


def spread_qualities(search: SearchAgent, d, state, balls, rests, spread) -> np.ndarray:
    """(M,): `next_qualities` averaged over each rest and REST_POINTS points `spread[m]` m around
    it (kept on the cloth): a leave whose quality holds as far off as the rest may be predicted
    wrong is worth more than one that is good only at the predicted point."""
    turns = 2.0 * np.pi * np.arange(REST_POINTS) / REST_POINTS
    ring = np.column_stack([np.cos(turns), np.sin(turns)])
    offsets = np.concatenate([np.zeros((1, len(rests), 2)), ring[:, None, :] * np.asarray(spread)[None, :, None]])
    size = np.array([search.table.length, search.table.width])
    points = np.clip(rests[None] + offsets, search.radius, size - search.radius).reshape(-1, 2)
    q = next_qualities(search, d.xy, d.on_table, state, np.tile(balls, len(offsets)), points)
    return q.reshape(len(offsets), -1).mean(axis=0)


class ValueNet:
    """A small MLP in NumPy (tanh hidden layers, linear output) with the input standardised:
    the arrays of `save`/`load` (an .npz file). `breaks` (the arrays named "break_..."), if
    any, is a second net that scores the break's menus (`score`). "columns", if saved, is how
    many leading feature columns the net reads. `pots` (the arrays named "pot_...") is the
    pot net whose columns a layout-3 net's rows end with (`menu`); `safeties` ("safe_...")
    the safety net whose columns follow them in a layout-4 or 5 net's rows."""

    def __init__(self, arrays: dict, breaks: ValueNet | None = None, pots: PotNet | None = None,
                 safeties: SafetyNet | None = None):
        prefixes = (BREAK_PREFIX, POT_PREFIX, SAFE_PREFIX)
        own = {k: v for k, v in arrays.items() if not k.startswith(prefixes)}
        inner = {k[len(BREAK_PREFIX):]: v for k, v in arrays.items() if k.startswith(BREAK_PREFIX)}
        pot = {k[len(POT_PREFIX):]: v for k, v in arrays.items() if k.startswith(POT_PREFIX)}
        safe = {k[len(SAFE_PREFIX):]: v for k, v in arrays.items() if k.startswith(SAFE_PREFIX)}
        self.pots = pots if pots is not None else PotNet(pot) if pot else None
        self.safeties = safeties if safeties is not None else SafetyNet(safe) if safe else None
        self.arrays = {k: np.asarray(v, dtype=np.float32) for k, v in own.items()}
        self.layers = sorted({int(k[1:]) for k in self.arrays if k.startswith("w")})
        self.layout = int(self.arrays["layout"]) if "layout" in self.arrays else 1
        self.columns = int(self.arrays["columns"]) if "columns" in self.arrays else None  # reads only these
        self.breaks = breaks if breaks is not None else ValueNet(inner) if inner else None

    def score(self, features: np.ndarray) -> np.ndarray:
        """The values of a menu's rows: by `breaks` if it is the break's menu and there is one."""
        if self.breaks is not None and np.all(features[:, KINDS.index("break")] == 1.0):
            return self.breaks(features)
        return self(features)

    def __call__(self, x: np.ndarray) -> np.ndarray:
        x = np.asarray(x, dtype=np.float32)
        h = ((x if self.columns is None else x[:, :self.columns]) - self.arrays["mean"]) / self.arrays["std"]
        for n in self.layers:
            h = h @ self.arrays[f"w{n}"] + self.arrays[f"b{n}"]
            if n != self.layers[-1]:
                h = np.tanh(h)
        return h[:, 0]

    def all_arrays(self) -> dict:
        """Its arrays with those of its break net, pot net and safety net (prefixed): what `save` writes."""
        inner = {} if self.breaks is None else {BREAK_PREFIX + k: v for k, v in self.breaks.arrays.items()}
        return {**self.arrays, **inner, **({} if self.pots is None else self.pots.save_arrays()),
                **({} if self.safeties is None else self.safeties.save_arrays())}

    def save(self, path) -> None:
        np.savez_compressed(path, **self.all_arrays())

    @classmethod
    def load(cls, path) -> ValueNet:
        with np.load(path) as f:
            return cls(dict(f))


def weights_path(game: str) -> Path:
    """The shipped network of a game ("nine_ball", "eight_ball"), fitted to noiseless labels and
    played at any noise (docs/players.md gives its results at both settings)."""
    return WEIGHTS / f"{game}.npz"


class LearnedPlayer(Agent):
    """Plays a game by one network evaluation per shot: the `SearchAgent`'s candidate shots
    (ghost-ball pots of the legal balls at three speeds with stun, follow and draw, safeties,
    kicks, ball-in-hand spots, breaks), each described by what the ghost-ball planner knows of it
    and the observation, are scored by a value network trained to predict the search's simulated
    value of the shot; the best-scoring one is played. Nothing is simulated at decision time."""

    name = "learned"

    def __init__(self, game: str = "nine_ball", net: ValueNet | None = None, table: Table | None = None,
                 physics: Physics | None = None, radius: float = BALL_RADIUS):
        if game not in GAME_BALLS:
            raise ValueError(f"unknown game {game!r}; choose one of {', '.join(GAME_BALLS)}")
        self.game = game
        self.search = SearchAgent(game, table=table, physics=physics, noise=None, radius=radius)
        if net is None:
            path = weights_path(game)
            if not path.exists():
                raise FileNotFoundError(f"no learned {game} player is shipped ({path.name} is missing)")
            net = ValueNet.load(path)
        self.net = net
        self.last_stats: dict = {}

    @classmethod
    def from_env(cls, env, **options) -> LearnedPlayer:
        game = game_of(env)
        if not game.has_rules:
            raise TypeError("the learned player plays the games (PoolNineBall-v0, PoolEightBall-v0)")
        return cls(game.mode, table=game.base_table, physics=game.base_physics, **options)

    def act(self, observation) -> np.ndarray:
        m, d = menu(self.search, observation, self.game, self.net.layout, self.net.pots, self.net.safeties)
        values = self.net.score(m.features)
        best = int(np.argmax(values))
        self.last_stats = {"candidates": len(m.candidates), "value": float(values[best]),
                           "kind": m.candidates[best].kind}
        return self.search.action(m.candidates[best], d.ball_in_hand)


def learned_player(env, seed=None, **options) -> LearnedPlayer:
    """The player registry's "learned" (`pool_env.make_player("learned", env)`)."""
    return LearnedPlayer.from_env(env, **options)
