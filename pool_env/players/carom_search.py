"""`CaromSearchAgent`: the three-cushion player that finds points by batched search on `Game.evaluate`."""

from __future__ import annotations

import math

import numpy as np

from ..game import CONTACT_TIME, Game, Shot, decode_carom_observation
from ..physics import Balls
from ..rules import ThreeCushionState
from .base import Agent, game_of
from .geometry import separated

DIRECTIONS = 90  # cue directions, evenly spaced around the cue ball (4 degrees apart)
SPEEDS = (2.5, 3.5, 5.0)  # m/s off the tip: a carom ball's three-cushion speeds (a table's length and more)
TIPS = ((0.0, 0.0), (0.3, 0.1), (-0.3, 0.1))  # (side, top) in ball radii: centre, running English either way
SHORTLIST = 24  # the best candidates of the first pass, simulated again under the noise
DRAWS = 8  # noise draws per shortlisted candidate


def near_miss(record) -> float:
    """How close a shot that scored nothing came to a point, in [0, 1): the second ball
    reached, and the cushions before it (or in the shot), as fractions of what a point needs."""
    o = record.outcome
    if o is None or record.ruling is None:
        return 0.0
    balls = (o.first_ball is not None) + (o.second_ball is not None)
    return 0.3 * balls + 0.1 * min(o.cushions_before_second, 3) / 3.0


class CaromSearchAgent(Agent):
    """Plays three-cushion by search: DIRECTIONS x SPEEDS x TIPS candidate shots of the
    shooter's cue ball, each simulated once (`Game.evaluate`, under the game's noise), ranked by
    the point (else how near a point came: `near_miss`); the SHORTLIST best are simulated
    DRAWS more times each under the noise, and the highest share of points wins (ties: the
    first pass's rank). Without noise the first pass is exact and decides. `decide(game)` plans
    from a `Game`'s position; `act(observation)` from an observation of an env of the game it
    was made for (same table, physics, noise and rules): it sets up that position in a planning
    game of its own (the balls as the observation has them, to float32)."""

    name = "carom_search"

    def __init__(self, game: Game, seed: int | None = None, directions: int = DIRECTIONS, speeds=SPEEDS,
                 tips=TIPS, shortlist: int = SHORTLIST, draws: int = DRAWS):
        if game.mode != "three_cushion":
            raise ValueError(f"carom_search plays three-cushion, not {game.mode!r}")
        if directions < 1 or shortlist < 1 or draws < 1:
            raise ValueError("directions, shortlist and draws must be >= 1")
        self.planner = Game("three_cushion", table=game.base_table, physics=game.base_physics, noise=game.noise,
                            layout=game.layout.name, **game.rule_options)
        self.radius, self.mass = self.planner.balls.radius, self.planner.balls.mass  # nominal, not a draw
        self.directions, self.speeds, self.tips = int(directions), tuple(speeds), tuple(tips)
        self.shortlist, self.draws = int(shortlist), int(draws)
        self.rng = np.random.default_rng(seed)

    @classmethod
    def from_env(cls, env, seed=None, **options) -> CaromSearchAgent:
        return cls(game_of(env), seed=seed, **options)

    def reset(self, seed: int | None = None) -> None:
        if seed is not None:
            self.rng = np.random.default_rng(seed)

    def candidates(self, game: Game) -> list[Shot]:
        """The first pass's shots from `game`'s position now."""
        mass = float(game.balls.masses[game.state.cue_ball])
        shots = []
        for k in range(self.directions):
            angle = 2.0 * math.pi * k / self.directions
            for speed in self.speeds:
                force = speed * mass / CONTACT_TIME
                for tip in self.tips:
                    shots.append(Shot((force * math.cos(angle), force * math.sin(angle)), tip))
        return shots

    def decide(self, game: Game) -> Shot:
        """The shot to play from `game`'s position now (the game does not change)."""
        shots = self.candidates(game)
        first = game.evaluate(shots, seed=int(self.rng.integers(2**63 - 1)))
        rank = [1.0 if r.ruling is not None and r.ruling.point else near_miss(r) for r in first]
        order = sorted(range(len(shots)), key=lambda k: -rank[k])
        if game.noise is None:
            return shots[order[0]]
        short = order[: self.shortlist]
        again = game.evaluate([shots[k] for k in short], draws=self.draws, seed=int(self.rng.integers(2**63 - 1)))
        share = [sum(bool(r.ruling is not None and r.ruling.point) for r in again[i * self.draws:(i + 1) * self.draws])
                 for i in range(len(short))]
        best = max(range(len(short)), key=lambda i: (share[i], rank[short[i]]))
        return shots[short[best]]

    def act(self, observation) -> np.ndarray:
        view = decode_carom_observation(observation, self.planner.table, self.planner.state.rules)
        radius = float(np.max(self.planner.balls.radii))
        balls = Balls(separated(view.xy, (False,) * 3, radius), radius=self.radius, mass=self.mass)
        # The viewer is player 0 of the planning game; the score does not change what a point is.
        starter = 0 if view.own_ball == 0 else 1
        state = ThreeCushionState(self.planner.state.rules, shooter=0, starter=starter,
                                  innings=(1, 0) if starter == 0 else (1, 1), is_break=view.is_break,
                                  equalizing=view.equalizing)
        self.planner.reset(balls=balls, state=state)
        return self.planner.encode(self.decide(self.planner))
