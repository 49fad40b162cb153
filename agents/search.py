"""`SearchAgent`: a PickPocket-style player that simulates candidate shots in one batch and plays the best."""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass

import gymnasium as gym
import numpy as np

import pool_env  # noqa: F401  (registers the envs)
from pool_env import rules
from pool_env.game import (
    GAME_BALLS,
    MAX_SPEED,
    Game,
    GameView,
    Shot,
    decode_action,
    decode_game_observation,
    decode_observation,
    encode_action,
    env_layout,
    placement_area,
)
from pool_env.physics import BALL_RADIUS, Balls, Physics, Table
from pool_env.players import Agent, GhostBallAgent, game_of
from pool_env.players import geometry as geo
from pool_env.players.planner import DX, DY, OK, SCORE, SPEED

from .search_plan import SearchPlanner
from .stats import wilson

ARRIVALS = (0.25, 0.7, 1.6)  # m/s: the object ball's speed at the pocket, every pot planned at each
TIPS = ((0.0, 0.0), (0.0, 0.3), (0.0, -0.3))  # (side, top) in R: stun, follow, draw
JITTER = (0.0, math.radians(0.15), -math.radians(0.15))  # aim corrections tried around the ghost-ball line
SAFETY_SPEEDS = (1.2, 2.2, 3.5)  # m/s
SAFETY_EDGES = (0.0, 0.9, -0.9, 1.6, -1.6)  # aim this many R beside the legal ball's centre
KICK_SPEEDS = (2.5, 4.5)  # m/s: off one rail at the mirror image of a legal ball
KICK_TURNS = tuple(math.radians(t) for t in (0.0, 0.5, -0.5, 1.0, -1.0, 2.0, -2.0))  # around the image line
BREAK_SPEEDS = (10.0, 12.0)  # m/s
BREAK_SIDES = (0.0, 0.15, -0.15, 0.35, -0.35)  # m from the head spot, along the head string (game break)
BREAK_OFFSETS = (0.0, 0.1, -0.1, 0.3, -0.3)  # R beside the head ball's centre
RUN_BREAKS = ((3, 1.3), (3, -1.3), (1, 0.1), (1, -0.1), (2, 1.0), (2, -1.0), (3, 1.1), (3, 1.5))  # (row, offset)
SPOT_BACKS = (0.12, 0.3)  # m: ball-in-hand spots this far behind the object ball
SPOT_TURNS = (0.0, math.radians(25.0), -math.radians(25.0))  # ... on the pot line and turned off it
SPOTS = 6  # ball-in-hand spots searched in full
SPOT_TRIES = 14  # spots (best by the cheap ranking) whose shots are planned to rank them
# Values of an outcome (the shooter's view): a win, a pot with the position it leaves (from
# CONTINUE up to 1 with the best next shot's quality), a miss leaving the opponent a shot,
# a foul (ball in hand for the opponent), a loss.
WIN, CONTINUE, MISS, FOUL, LOSS = 1.0, 0.35, -0.55, -0.75, -1.0
PUSH_OUT_SPEEDS = (0.6, 1.3)  # m/s: the push outs tried, soft rolls of the cue ball ...
PUSH_OUT_TURNS = tuple(math.radians(a) for a in range(0, 360, 45))  # ... in eight directions
IN_HAND_QUALITY = 1.0  # the next shooter's quality with ball in hand
SEPARATION, SEPARATION_PASSES = 1e-9, 5  # m: overlaps the observation's rounding leaves, undone
LOOKAHEAD_WORK = 150  # outcomes x legal balls the lookahead scores per decision (best plain value first)
SIMULATION_CHUNK, LOOKAHEAD_CHUNK = 64, 4  # with `seconds`: candidates simulated, looked ahead, between time checks


@dataclass
class Candidate:
    """One shot to try: the cue ball sent along `direction` at `speed` m/s with tip `tip`,
    from `spot` (ball in hand; None: where it lies), `ball` called in `pocket` (a pot's ball
    and pocket; 8-ball and 10-ball read the call)."""

    direction: np.ndarray
    speed: float
    tip: tuple = (0.0, 0.0)
    spot: np.ndarray | None = None
    pocket: int | None = None
    kind: str = "pot"
    prior: float = 0.0
    ball: int | None = None


def legal_mask(legal, n_balls: int) -> np.ndarray:
    """(n_balls,) bool of a set of legal ball numbers (the cue ball's entry False)."""
    mask = np.zeros(n_balls, dtype=bool)
    mask[[int(b) for b in legal]] = True
    return mask


def decode(observation, n_balls: int, table: Table, game: bool = True) -> GameView:
    """Read a game observation (`pool_env.game.decode_game_observation`, n_balls 10, 11 or 16) or,
    with `game=False`, a `PoolBreakEnv` observation (16 balls, every object ball legal)."""
    if game:
        game_of_size = {n: name for name, n in GAME_BALLS.items()}  # 10 nine_ball, 11 ten_ball, 16 eight_ball
        return decode_game_observation(observation, game_of_size[n_balls], table)
    xy, on_table = decode_observation(observation, table)
    xy = np.where(on_table[:, None], xy, 0.5 * np.array([table.length, table.width]))
    return GameView(xy, on_table, frozenset(int(b) for b in np.flatnonzero(on_table[1:]) + 1))


def racked(xy, on_table, radius: float = BALL_RADIUS) -> bool:
    """Every object ball on the table, each touching (within 10 %) another: the break is next."""
    p = xy[1:][on_table[1:]]
    if len(p) < len(xy) - 1 or len(p) < 2:
        return False
    d = np.hypot(p[:, None, 0] - p[None, :, 0], p[:, None, 1] - p[None, :, 1])
    np.fill_diagonal(d, np.inf)
    return bool(np.all(d.min(axis=1) < 2.2 * radius))


def game_state(decoded: GameView, game: str, rule_options: dict | None = None) -> rules.GameState:
    """The `rules.GameState` of a decoded game observation, the shooter as player 0."""
    state = rules.new_game(game, breaker=0, **(rule_options or {}))
    groups = (None, None)
    if decoded.group is not None:
        groups = (decoded.group, "stripes" if decoded.group == "solids" else "solids")
    on = frozenset(int(b) for b in np.flatnonzero(decoded.on_table[1:]) + 1)
    is_break = decoded.ball_in_hand == "behind_head_string" and racked(decoded.xy, decoded.on_table)
    return dataclasses.replace(state, on_table=on, shooter=0, ball_in_hand=decoded.ball_in_hand,
                               fouls=decoded.fouls, groups=groups, is_break=is_break, shot=0 if is_break else 1,
                               push_out=bool(decoded.push_out and not is_break))


def balls_of(decoded: GameView, radius: float = BALL_RADIUS) -> Balls:
    """The balls of a decoded observation (pocketed balls parked at the origin). Touching balls
    that the observation's float32 rounding made overlap are pushed apart to touch."""
    xy = np.where(decoded.on_table[:, None], decoded.xy, 0.0)
    on = np.flatnonzero(decoded.on_table)
    p = xy[on]
    d = np.hypot(p[:, None, 0] - p[None, :, 0], p[:, None, 1] - p[None, :, 1]) + 3.0 * radius * np.eye(len(on))
    for _ in range(SEPARATION_PASSES if np.any(d < 2.0 * radius + SEPARATION) else 0):
        moved = False
        for a in range(len(on)):
            for b in range(a + 1, len(on)):
                gap = xy[on[b]] - xy[on[a]]
                dist = float(np.hypot(*gap))
                if dist < 2.0 * radius + SEPARATION and dist > 0.0:
                    push = gap / dist * (2.0 * radius + SEPARATION - dist) * 0.5
                    xy[on[a]] -= push
                    xy[on[b]] += push
                    moved = True
        if not moved:
            break
    return Balls(xy, radius=radius, pocketed=~decoded.on_table)


class SearchAgent(Agent):
    """Plays by simulation (PickPocket-style): candidate shots (ghost-ball pots of every legal
    ball into every pocket at three speeds with stun, follow and draw and small aim
    corrections; kicks off each rail when no pot is on; safeties; with ball in hand, the
    best-ranked spots times their shots; on the break, spots x aims x speeds) are all
    simulated in one `simulate_batch` call (`noise_samples` draws each when the env has
    noise), judged by the rules and scored: a win, a pot plus the quality of the position it
    leaves (depth-1 lookahead: the best ghost-ball score of the next legal ball), a miss minus
    the opponent's best shot, a foul, a loss. The best mean value is played.

    The pots, the ball-in-hand spots' ranking and the lookahead's qualities are planned in
    batches on the compiled ghost-ball planner (`SearchPlanner`).

    `budget` caps the simulated shots per decision (candidates x noise samples); the lookahead
    covers the best candidates by their plain value (`LOOKAHEAD_WORK`). `seconds` (optional)
    caps the decision's wall time: the candidates (best prior first) are simulated
    `SIMULATION_CHUNK` at a time and the lookahead takes `LOOKAHEAD_CHUNK` candidates at a
    time, each batch only while the decision has used less than `seconds` (the first batch of
    simulations always runs; a candidate left unsimulated is not chosen). Decisions then depend
    on the machine's speed; without it they depend only on the seed and the observation.
    `last_stats` holds the last decision's candidates, simulations, seconds and value."""

    name = "search"

    def __init__(self, game: str | None = "nine_ball", table: Table | None = None, physics: Physics | None = None,
                 noise: dict | None = None, spin: bool = True, budget: int = 600, noise_samples: int = 6,
                 seed: int | None = 0, lookahead: bool = True, threads: int = 1, seconds: float | None = None,
                 rule_options: dict | None = None, radius: float = BALL_RADIUS, decisions: bool = False):
        if game is not None and game not in GAME_BALLS:
            raise ValueError(f"unknown game {game!r}; choose one of {', '.join(GAME_BALLS)} or None (PoolBreakRun-v0)")
        if int(budget) < 1 or int(noise_samples) < 1:
            raise ValueError(f"budget and noise_samples must be >= 1, got {budget!r}, {noise_samples!r}")
        self.game, self.n_balls = game, GAME_BALLS.get(game, 16)
        self.table = Table.eight_foot() if table is None else table
        self.physics = Physics.standard() if physics is None else physics
        self.noise, self.spin, self.radius = noise, bool(spin or game is not None), radius
        self.budget, self.noise_samples = int(budget), int(noise_samples) if noise else 1
        self.lookahead, self.threads, self.seconds = bool(lookahead), int(threads), seconds
        self.rule_options = dict(rule_options or {})
        self.plans = SearchPlanner(self.table, self.physics, radius)  # the pots, qualities and spots, at once
        self.scorer = GhostBallAgent(self.table, self.physics, radius=radius)  # its break shots (PoolBreakRun-v0)
        self.pockets = self.scorer.pockets
        self.seed = seed
        self.rng = np.random.default_rng(seed)
        self.last_stats: dict = {}
        # The game it plans on: the env's own rules and strike, at the position it decodes.
        layout = ("cue_spin" if self.spin else "cue") if game is None else \
            env_layout(game, decisions=decisions, calling=self.rule_options.get("calling"))
        self.sim = Game(game or "run", self.table, self.physics, noise, layout=layout, **self.rule_options)

    @classmethod
    def from_env(cls, env, **options) -> SearchAgent:
        """For a game env (PoolNineBall-v0, PoolEightBall-v0, the PettingZoo AEC envs), PoolBreakRun-v0 or a Game."""
        game = game_of(env)
        if game.has_rules:
            return cls(game=game.mode, table=game.base_table, physics=game.base_physics, noise=game.noise,
                       rule_options=game.rule_options, decisions=game.layout.decision, **options)
        return cls(game=None, table=game.base_table, physics=game.base_physics, spin=game.layout.spin, **options)

    def reset(self, seed: int | None = None) -> None:
        if seed is not None:
            self.seed = seed
        self.rng = np.random.default_rng(self.seed)

    # --- a decision ----------------------------------------------------------------------------
    def act(self, observation) -> np.ndarray:
        start = time.perf_counter()
        d = decode(observation, self.n_balls, self.table, game=self.game is not None)
        state = game_state(d, self.game, self.rule_options) if self.game is not None else None
        candidates = self.candidates(d, state)[: max(1, self.budget // self.noise_samples)]
        values, simulated = self.evaluate(d, state, candidates, start)
        best = int(np.argmax(values))
        self.last_stats = {"candidates": len(candidates), "simulations": simulated * self.noise_samples,
                           "seconds": time.perf_counter() - start, "value": float(values[best]),
                           "kind": candidates[best].kind}
        if d.push_out:  # WPA 2.4: a push out, if one scores better than the best shot
            value, shot = self.push_out(d, state)
            if value > values[best]:
                self.last_stats.update(value=value, kind="push_out")
                return self.sim.encode(shot)
        return self.action(candidates[best], d.ball_in_hand)

    def push_out(self, d: GameView, state) -> tuple[float, Shot]:
        """(the mean value, the Shot) of the best push out from the decoded position: soft rolls
        of the cue ball (`PUSH_OUT_SPEEDS` x `PUSH_OUT_TURNS`) simulated with the noise draws;
        each legal one scored for both replies the opponent has (WPA 2.4): he shoots, worth
        MISS x q to us (q the shooter's best ghost-ball quality from there), or passes it back,
        worth CONTINUE + (1 - CONTINUE) q; he takes the one worse for us. A foul scores FOUL."""
        self.sim.reset(balls=balls_of(d, self.radius), state=state)
        shots = [Shot.aimed((math.cos(t), math.sin(t)), v, push_out=True)
                 for v in PUSH_OUT_SPEEDS for t in PUSH_OUT_TURNS]
        records = self.sim.evaluate(shots, draws=self.noise_samples, seed=self.rng, threads=self.threads)
        values = []
        for record in records:
            if record.error is not None or record.ruling.foul is not None:
                values.append(FOUL)
                continue
            balls = record.balls_after
            q = self.quality(balls.xy, ~balls.pocketed, rules.legal_targets(record.state_after))
            values.append(min(MISS * q, CONTINUE + (1.0 - CONTINUE) * q))
        means = np.array(values).reshape(len(shots), self.noise_samples).mean(axis=1)
        best = int(np.argmax(means))
        return float(means[best]), shots[best]

    def candidates(self, d: GameView, state) -> list[Candidate]:
        """Every candidate of this decision, best prior first (pots, then kicks and safeties)."""
        if racked(d.xy, d.on_table, self.radius):
            return self.break_candidates(d, state)
        if d.ball_in_hand is not None:
            spots = self.spots(d)
            xys = np.repeat(d.xy[None], len(spots), axis=0)
            xys[:, 0] = spots
            return self.ranked([c for cands in self.candidates_from(xys, d.on_table, d.legal, spots) for c in cands])
        return self.ranked(self.shot_candidates(d.xy, d.on_table, d.legal))

    def ranked(self, cands: list[Candidate]) -> list[Candidate]:
        """Pots by prior first, but the budget keeps a quarter of its room for kicks and safeties."""
        room = max(1, self.budget // self.noise_samples)
        pots = sorted((c for c in cands if c.kind == "pot"), key=lambda c: -c.prior)
        rest = sorted((c for c in cands if c.kind != "pot"), key=lambda c: -c.prior)
        keep = max(room - len(rest), (3 * room) // 4)
        return pots[:keep] + rest[: room - min(keep, len(pots))]

    # --- candidate generation --------------------------------------------------------------------
    def shot_candidates(self, xy, on_table, legal) -> list[Candidate]:
        """Ghost-ball pots of the legal balls; kicks if no pot is on; safeties."""
        return self.candidates_from(np.asarray(xy, dtype=np.float64)[None], on_table, legal, [None])[0]

    def candidates_from(self, xys, on_table, legal, spots) -> list[list[Candidate]]:
        """`shot_candidates` of one layout from several cue-ball spots (xys (S, n, 2), the cue
        ball of each at its spot; `spots` the candidates' `spot`s), every pot planned at once."""
        n = len(xys)
        mask = legal_mask(legal, len(on_table))
        index, rows = self.plans.pots(xys, np.repeat(np.asarray(on_table)[None], n, axis=0),
                                      np.repeat(mask[None], n, axis=0), ARRIVALS)
        out: list[list[Candidate]] = [[] for _ in range(n)]
        tips = self.tips()
        for i in np.flatnonzero(rows[:, OK]):
            q, k, score, speed = int(index[i, 0]), i % len(ARRIVALS), float(rows[i, SCORE]), float(rows[i, SPEED])
            shot = np.array([rows[i, DX], rows[i, DY]])
            for j, turn in enumerate(JITTER):
                direction = geo.rotate(shot, turn)
                for t, tip in enumerate(tips):
                    out[q].append(Candidate(direction, speed, tip, spots[q], int(index[i, 2]),
                                            prior=score * (1.0 - 0.1 * j - 0.05 * t - 0.02 * k),
                                            ball=int(index[i, 1])))
        for q in range(n):
            rest = self.safeties(xys[q], on_table, legal)
            if not out[q]:
                rest += self.kicks(xys[q], legal)
            out[q] += rest if spots[q] is None else [dataclasses.replace(c, spot=spots[q]) for c in rest]
        return out

    def tips(self):
        return TIPS if self.spin else TIPS[:1]

    def safeties(self, xy, on_table, legal) -> list[Candidate]:
        out = []
        for ball in sorted(legal):
            to = xy[ball] - xy[0]
            dist = float(np.hypot(*to))
            if dist < 1e-9:
                continue
            side = np.array([-to[1], to[0]]) / dist
            for edge in SAFETY_EDGES:
                direction = geo.unit(xy[ball] + edge * self.radius * side - xy[0])
                for speed in SAFETY_SPEEDS:
                    out.append(Candidate(direction, speed, kind="safety", prior=-dist - abs(edge)))
        return out

    def kicks(self, xy, legal) -> list[Candidate]:
        """One-rail kicks: the cue ball aimed at a legal ball's image in each rail's line."""
        R, L, W = self.radius, self.table.length, self.table.width
        out = []
        for ball in sorted(legal):
            x, y = xy[ball]
            for image in ((2 * R - x, y), (2 * (L - R) - x, y), (x, 2 * R - y), (x, 2 * (W - R) - y)):
                line = geo.unit(np.array(image) - xy[0])
                for turn in KICK_TURNS:
                    for speed in KICK_SPEEDS:
                        out.append(Candidate(geo.rotate(line, turn), speed, kind="kick", prior=-1.0 - abs(turn)))
        return out

    def spots(self, d: GameView) -> list[np.ndarray]:
        """Ball in hand: straight-in (and turned) spots behind each legal ball for each open
        pocket, ranked cheaply (open mouth, distances), the best `SPOT_TRIES` then ranked by the
        best ghost-ball score from there (a coarse grid when none is free); the best `SPOTS`."""
        area = placement_area(self.table, d.ball_in_hand, self.radius)
        x_lo, x_hi, y_lo, y_hi = area
        objects = np.flatnonzero(d.on_table[1:]) + 1
        cheap, rank = self.plans.spot_ranks(d.xy, d.on_table, legal_mask(d.legal, len(d.on_table)), SPOT_BACKS,
                                            SPOT_TURNS)
        cheap = cheap[np.lexsort((cheap[:, 1], cheap[:, 0], rank))[::-1]]  # best first (a sort of the tuples)
        spots = [np.array(p) for p in cheap[self.free_all(cheap, d, objects, area)]][:SPOT_TRIES]
        if len(spots) < SPOTS:
            spots += [np.array((x, y)) for x in np.linspace(x_lo, x_hi, 6) for y in np.linspace(y_lo, y_hi, 3)
                      if self.free((x, y), d, objects, area)]
        if not spots:
            return [np.array((0.5 * (x_lo + x_hi), 0.5 * (y_lo + y_hi)))]
        on = d.on_table.copy()
        on[0] = True
        xys = np.repeat(d.xy[None], len(spots), axis=0)
        xys[:, 0] = spots
        quality = self.qualities(xys, np.repeat(on[None], len(spots), axis=0), [d.legal] * len(spots))
        points = np.array(spots)
        order = np.lexsort((points[:, 1], points[:, 0], quality))[::-1]  # (quality, spot) best first
        return [np.array(tuple(points[k])) for k in order[:SPOTS]]

    def free_all(self, spots, d: GameView, objects, area) -> np.ndarray:
        """`free` of each spot (K, 2)."""
        x_lo, x_hi, y_lo, y_hi = area
        on = d.xy[objects]
        gap = np.hypot(on[None, :, 0] - spots[:, None, 0], on[None, :, 1] - spots[:, None, 1]).min(axis=1,
                                                                                               initial=np.inf)
        return ((x_lo <= spots[:, 0]) & (spots[:, 0] <= x_hi) & (y_lo <= spots[:, 1]) & (spots[:, 1] <= y_hi)
                & (gap >= 2.2 * self.radius))

    def free(self, spot, d: GameView, objects, area) -> bool:
        """The spot is inside the placement area and clear of every object ball."""
        x_lo, x_hi, y_lo, y_hi = area
        gap = np.min(np.hypot(*(d.xy[objects] - np.asarray(spot)).T), initial=np.inf)
        return x_lo <= spot[0] <= x_hi and y_lo <= spot[1] <= y_hi and gap >= 2.2 * self.radius

    def break_candidates(self, d: GameView, state) -> list[Candidate]:
        """The break: spots along the head string (game envs) x aims beside the head ball x speeds;
        PoolBreakRun-v0 (no ball in hand): `BreakAgent` aims at several rack rows."""
        objects = np.flatnonzero(d.on_table[1:]) + 1
        out = []
        if d.ball_in_hand is None:
            for row, offset in RUN_BREAKS:
                self.scorer.breaker.row, self.scorer.breaker.offset = row, offset
                a = self.scorer.breaker.break_shot(d.xy, d.on_table)
                for tip in self.tips()[:1] + (((0.3, 0.0),) if self.spin else ()):
                    out.append(Candidate(geo.unit(a[:2]), MAX_SPEED, tip, kind="break"))
            return out
        x_lo, x_hi, y_lo, y_hi = placement_area(self.table, d.ball_in_hand, self.radius)
        head = rules.head_spot(self.table)
        for side in BREAK_SIDES:
            spot = np.array((min(head[0], x_hi) - 0.02, min(max(head[1] + side, y_lo), y_hi)))
            target = objects[np.argmin(np.hypot(*(d.xy[objects] - spot).T))]
            to = geo.unit(d.xy[target] - spot)
            for offset in BREAK_OFFSETS:
                aim = d.xy[target] + offset * self.radius * np.array([-to[1], to[0]])
                for speed in BREAK_SPEEDS:
                    out.append(Candidate(geo.unit(aim - spot), speed, spot=spot, kind="break"))
        return out

    # --- evaluation ------------------------------------------------------------------------------
    def evaluate(self, d: GameView, state, candidates, start) -> tuple[np.ndarray, int]:
        """(the mean value of each candidate over its noise samples, the candidates simulated):
        `Game.evaluate` of the candidates' actions (as the env reads them) from the decoded
        position, in one batch (with `seconds`, in chunks until the time is up; a candidate
        left unsimulated gets -inf)."""
        records, judged, plain = self.judged(d, state, candidates, start)
        done = len(records) // self.noise_samples
        if not self.lookahead:
            return plain, done
        values = plain - 10.0  # only the candidates that get the lookahead can be chosen
        self.look_ahead(values, self.looked_at(plain, done, d.legal), judged, start)
        return values, done

    def judged(self, d: GameView, state, candidates, start) -> tuple[list, list, np.ndarray]:
        """(the `simulate` records, each judged (`judge`), each candidate's mean plain value
        over its draws: -inf if left unsimulated)."""
        s = self.noise_samples
        records = self.simulate(d, state, candidates, start)
        judged = [self.judge(state, records[k], candidates[k // s]) for k in range(len(records))]
        plain = np.full(len(candidates), -np.inf)
        plain[: len(records) // s] = np.array([v for v, _ in judged]).reshape(-1, s).mean(axis=1)
        return records, judged, plain

    def looked_at(self, plain, done: int, legal) -> np.ndarray:
        """The candidates the lookahead scores: the best by their plain value, as many as
        LOOKAHEAD_WORK outcomes x legal balls allow (at least 4), among the `done` simulated."""
        return np.argsort(-plain)[: max(4, LOOKAHEAD_WORK // (self.noise_samples * max(1, len(legal))))][:done]

    def simulate(self, d: GameView, state, candidates, start) -> list:
        """The `ShotRecord`s of the candidates' actions (as the env reads them) from the decoded
        position, `noise_samples` draws each, candidate major: `Game.evaluate` in one batch (with
        `seconds`, `SIMULATION_CHUNK` candidates at a time while the time lasts)."""
        self.sim.reset(balls=balls_of(d, self.radius), state=state)
        area, pockets = self.sim.placement_area(), self.table.pockets.shape[0]  # as sim.decode reads them
        targets = self.sim.called_targets  # 10-ball: a pot calls the first, the lowest ball (its target)
        shots = [decode_action(self.sim.layout, self.action(cand, d.ball_in_hand, area), area, pockets, targets)
                 for cand in candidates]
        chunk = len(shots) if self.seconds is None else SIMULATION_CHUNK
        records = []
        for at in range(0, len(shots), chunk):
            if records and time.perf_counter() - start > self.seconds:
                break
            records += self.sim.evaluate(shots[at:at + chunk], draws=self.noise_samples, seed=self.rng,
                                         threads=self.threads)
        return records

    def look_ahead(self, values, chosen, judged, start) -> None:
        """values[c] for each chosen candidate: its mean `deep_value`, the qualities of all their
        outcomes planned at once (with `seconds`, a few candidates at a time until the time is up)."""
        s = self.noise_samples
        chunk = len(chosen) if self.seconds is None else LOOKAHEAD_CHUNK
        for at in range(0, len(chosen), chunk):
            if self.seconds is not None and time.perf_counter() - start > self.seconds:
                break
            part = chosen[at:at + chunk]
            infos = [judged[c * s + k][1] for c in part for k in range(s)]
            asked = [i for i in infos if i is not None and (i[0] == "miss" or i[3] is None)]
            qualities = iter(self.qualities([i[1].xy for i in asked], [~i[1].pocketed for i in asked],
                                            [i[2] for i in asked]) if asked else ())
            for c in part:
                values[c] = np.mean([self.deep_value(*judged[c * s + k], qualities) for k in range(s)])

    def judge(self, state, record, cand):
        """(plain value, what the lookahead needs) of one simulated shot (a `ShotRecord`)."""
        if record.error is not None:
            return FOUL, None
        if state is None:  # PoolBreakRun-v0: no rules, a scratch ends the episode
            if record.outcome.cue_pocketed:
                return LOSS, None
            final = record.balls_after
            left = np.count_nonzero(~final.pocketed[1:])
            if left == 0:
                return WIN, None
            on = frozenset(int(b) for b in np.flatnonzero(~final.pocketed[1:]) + 1)
            kept = len(record.pocketed) > 0
            return (CONTINUE + 0.5 * (1 - CONTINUE)) if kept else MISS, ("self" if kept else "miss", final, on, None)
        after, ruling = record.state_after, record.ruling
        if ruling.winner is not None:
            return (WIN if ruling.winner == 0 else LOSS), None
        balls = record.balls_after
        legal = rules.legal_targets(after)
        if not ruling.turn_passed:
            return CONTINUE + 0.5 * (1 - CONTINUE), ("self", balls, legal, after.ball_in_hand)
        if ruling.foul is not None:
            return FOUL - (0.15 if after.fouls[0] >= 2 else 0.0), None
        return MISS * 0.5, ("opponent", balls, legal, None)

    def deep_value(self, value, info, qualities=None) -> float:
        """The value with the depth-1 lookahead: the next shooter's best ghost-ball quality
        (`qualities`: an iterator of the qualities of the outcomes that need one, in order;
        None: planned here)."""
        if info is None:
            return value
        who, balls, legal, in_hand = info
        if who != "miss" and in_hand is not None:
            q = IN_HAND_QUALITY
        else:
            q = self.quality(balls.xy, ~balls.pocketed, legal) if qualities is None else next(qualities)
        if who == "miss":  # PoolBreakRun-v0: our turn again after a miss
            return MISS + 0.5 * q
        return CONTINUE + (1.0 - CONTINUE) * q if who == "self" else MISS * q

    def quality(self, xy, on_table, legal) -> float:
        """The best ghost-ball score (capped at 1) of a legal ball into any pocket from this layout."""
        return float(self.qualities([xy], [on_table], [legal])[0])

    def qualities(self, xys, on_tables, legals) -> np.ndarray:
        """`quality` of many layouts (each an xy, on-table flags and legal balls), planned at once."""
        on = np.array(on_tables, dtype=bool)
        masks = np.array([legal_mask(legal, on.shape[1]) for legal in legals]).reshape(on.shape)
        return self.plans.qualities(np.array(xys, dtype=np.float64), on, masks, IN_HAND_QUALITY)

    def choose(self, game) -> str:
        """Its option of `game`'s pending decision (a `pool_env.game.Game` with decisions).
        After a push out it scores both replies from the position: shooting is worth its own
        best ghost-ball quality q there, passing leaves the opponent that shot (1 - q for it):
        it shoots when q >= 1/2. After an illegal 8-ball break it takes ball in hand; after the
        8 on the break it spots it."""
        pending = game.pending
        if pending is None:
            raise ValueError("no decision is pending")
        if pending.name == "push_out_reply":
            balls = game.balls
            q = self.quality(balls.xy, ~balls.pocketed, game.legal_targets)
            return "shoot" if q >= 1.0 - q else "pass"
        return {"illegal_break": "ball_in_hand", "eight_on_break": "spot_eight"}[pending.name]

    # --- the action ------------------------------------------------------------------------------
    def action(self, cand: Candidate, in_hand, area=False) -> np.ndarray:
        """The env's action for a candidate (`pool_env.game.encode_action` of its shot); `area`
        the placement area of `in_hand` if already known."""
        shot = Shot.aimed(cand.direction, min(cand.speed, MAX_SPEED), cand.tip, place=cand.spot, pocket=cand.pocket,
                          ball=cand.ball)
        if area is False:
            area = None if in_hand is None else placement_area(self.table, in_hand, self.radius)
        targets = self.sim.called_targets if self.sim.has_rules else ()  # the position's (simulate reset it)
        return encode_action(self.sim.layout, shot, area, max(self.table.pockets.shape[0], 1), targets)


# --- measuring ---------------------------------------------------------------------------------
def head_to_head(games: int = 20, seed: int = 0, env_id: str = "PoolNineBall-v0", noise=None, **options) -> dict:
    """`SearchAgent` against the env's ghost-ball opponent, alternating breaks, game k seeded
    `seed + k`: wins, the win rate and its 95 % interval, break-and-run rate (games the agent
    broke and won in its first turn), seconds per decision (median, p95)."""
    wins = breaks = runs = 0
    seconds = []
    for k in range(games):
        env = gym.make(env_id, opponent="ghost_ball", noise=noise, agent_breaks=k % 2 == 0)
        agent = SearchAgent.from_env(env, seed=seed + k, **options)
        obs, info = env.reset(seed=seed + k)
        first_turn, done = True, info["winner"] >= 0  # the opponent broke and ran out in reset
        while not done:
            obs, _, terminated, truncated, info = env.step(agent.act(obs))
            seconds.append(agent.last_stats["seconds"])
            done = terminated or truncated
            if not done and info["opponent_shots"]:
                first_turn = False
        won = info.get("winner") == 0  # the agent is player 0 (-1: no winner)
        wins += won
        breaks += k % 2 == 0
        runs += won and first_turn and k % 2 == 0
        env.close()
    lo, hi = wilson(wins, games)
    return {"games": games, "wins": wins, "win_rate": wins / max(games, 1), "ci95": (lo, hi),
            "breaks": breaks, "break_and_runs": runs, "break_and_run_rate": runs / max(breaks, 1),
            "decisions": len(seconds), "median_seconds": float(np.median(seconds)) if seconds else 0.0,
            "p95_seconds": float(np.percentile(seconds, 95)) if seconds else 0.0}


def clear_rate(episodes: int = 20, seed: int = 0, **options) -> dict:
    """`SearchAgent` in PoolBreakRun-v0: racks cleared (every object ball down, no scratch) and
    balls pocketed per episode, episode k seeded `seed + k`."""
    cleared, balls = 0, []
    for k in range(episodes):
        env = gym.make("PoolBreakRun-v0")
        agent = SearchAgent.from_env(env, seed=seed + k, **options)
        obs, _ = env.reset(seed=seed + k)
        done, info = False, {}
        while not done:
            obs, _, terminated, truncated, info = env.step(agent.act(obs))
            done = terminated or truncated
        cleared += info["balls_left"] == 0 and not info["scratch"]
        balls.append(15 - info["balls_left"])
        env.close()
    lo, hi = wilson(cleared, episodes)
    return {"episodes": episodes, "cleared": cleared, "clear_rate": cleared / max(episodes, 1), "ci95": (lo, hi),
            "balls_per_episode": float(np.mean(balls)) if balls else 0.0}


def search_player(env, seed=None, **options) -> SearchAgent:
    """The player registry's "search" (`pool_env.make_player("search", env)`)."""
    return SearchAgent.from_env(env, seed=0 if seed is None else seed, **options)


if __name__ == "__main__":
    import argparse
    import json

    parser = argparse.ArgumentParser(description="SearchAgent against the ghost-ball player")
    parser.add_argument("--games", type=int, default=20)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--env-id", default="PoolNineBall-v0")
    parser.add_argument("--noise", default=None)
    args = parser.parse_args()
    if args.env_id == "PoolBreakRun-v0":
        print(json.dumps(clear_rate(args.games, args.seed), indent=1))
    else:
        print(json.dumps(head_to_head(args.games, args.seed, args.env_id, args.noise), indent=1))
