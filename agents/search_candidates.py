"""The search player's candidate shots: pots, safeties, kicks, ball-in-hand spots, breaks (`SearchAgent`'s mixin)."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from pool_env import rules
from pool_env.game import MAX_SPEED, GameView, placement_area
from pool_env.players import geometry as geo
from pool_env.players.planner import DX, DY, OK, SCORE, SPEED

from .search_position import legal_mask, racked

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


class CandidateShots:
    """The candidates of a decision, for `SearchAgent` (which holds what they read: the table,
    the planner `plans`, the break player `scorer`, `radius`, `spin`, `budget`, `noise_samples`,
    and `qualities` for ranking ball-in-hand spots)."""

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
