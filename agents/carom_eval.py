"""Points per inning of a three-cushion player: innings from random positions, with a 95 % interval.

python -m agents.carom_eval --innings 300 --noise olympiad
"""

from __future__ import annotations

import argparse
import json
import math
import time

import numpy as np

from pool_env.game import Game
from pool_env.physics import CAROM_MASS, CAROM_RADIUS, Balls
from pool_env.players import make_player

MAX_RUN = 25  # points: an inning this long is stopped (counted as MAX_RUN), so a perfect player ends


def random_balls(table, rng) -> Balls:
    """Three carom balls at uniform spots on the table, 2 cm or more off the cushions and each other."""
    margin, gap = CAROM_RADIUS + 0.02, 2 * CAROM_RADIUS + 0.02
    while True:
        xy = np.column_stack([rng.uniform(margin, table.length - margin, 3),
                              rng.uniform(margin, table.width - margin, 3)])
        d = np.hypot(*(xy[:, None, :] - xy[None, :, :]).transpose(2, 0, 1))
        if d[np.triu_indices(3, 1)].min() > gap:
            return Balls(xy, radius=CAROM_RADIUS, mass=CAROM_MASS)


def points_per_inning(player: str, innings: int, noise, seed: int = 0) -> dict:
    """`innings` innings of `player`, each from a random position (not a starting stroke)."""
    game = Game("three_cushion", noise=noise, seed=seed, points=MAX_RUN + 1)
    agent = make_player(player, game, seed=seed)
    rng = np.random.default_rng(seed)
    runs, shots, start = [], 0, time.perf_counter()
    for _ in range(innings):
        game.reset(balls=random_balls(game.table, rng))
        run = 0
        while run < MAX_RUN:
            record = game.play(agent.decide(game))
            shots += 1
            if not (record.ruling is not None and record.ruling.point):
                break
            run += 1
        runs.append(run)
    runs = np.array(runs, dtype=float)
    half = 1.96 * runs.std(ddof=1) / math.sqrt(len(runs))
    return {"player": player, "noise": noise, "innings": innings, "points_per_inning": float(runs.mean()),
            "ci95": [float(runs.mean() - half), float(runs.mean() + half)], "capped": int((runs >= MAX_RUN).sum()),
            "shots": shots, "seconds_per_shot": (time.perf_counter() - start) / max(shots, 1)}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--player", default="carom_search")
    parser.add_argument("--innings", type=int, default=200)
    parser.add_argument("--noise", default="none", help="none or a noise preset (olympiad)")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    noise = None if args.noise == "none" else args.noise
    print(json.dumps(points_per_inning(args.player, args.innings, noise, args.seed)))


if __name__ == "__main__":
    main()
