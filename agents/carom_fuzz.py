"""Random three-cushion games, checked after every shot: every game ends, the scores add up, every state is valid.

python -m agents.carom_fuzz --games 2000 --noise both   (progress and a JSON summary on stdout)
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import time

import numpy as np

from pool_env.game import Game
from pool_env.physics.simulate import check_on_table
from pool_env.rules import ThreeCushionState


def options(rng) -> dict:
    """A random rule set: a short distance (1-3, sometimes none), an innings limit (always, so random play ends)."""
    points = [None, 1, 2, 3][int(rng.integers(4))]
    return {"points": points, "innings_limit": int(rng.integers(1, 16)), "equalizing": bool(rng.integers(2))}


def check_shot(game, record, tally) -> None:
    """AssertionError unless the shot left a valid game: the state rebuilt through its checks,
    the balls on the table, a point only for a valid carom without a foul."""
    state = record.state_after
    assert ThreeCushionState(**{f.name: getattr(state, f.name) for f in dataclasses.fields(state)}) == state
    balls = record.balls_after
    assert len(balls) == 3 and not balls.pocketed.any() and not balls.v.any()
    check_on_table(balls, game.table, game.physics)
    ruling, outcome = record.ruling, record.outcome
    assert ruling.point == (outcome.point and ruling.foul is None)
    tally["points"] += bool(ruling.point)
    assert sum(state.scores) == tally["points"], (state.scores, tally)


def play_game(seed: int, noise, max_shots: int = 2000) -> dict:
    """One random game; its summary. AssertionError for anything the rules forbid."""
    rng = np.random.default_rng(seed)
    opts = options(rng)
    game = Game("three_cushion", noise=noise, seed=seed, **opts)
    tally, errors = {"points": 0}, 0
    while not game.over:
        assert game.shots < max_shots, f"game {seed} did not end in {max_shots} shots"
        record = game.play(rng.uniform(-1.0, 1.0, game.layout.size))
        if record.error is not None:
            errors += 1
            assert errors < 50, f"game {seed}: {record.error}"
            continue
        check_shot(game, record, tally)
    state, rules = game.state, game.state.rules
    if state.winner is not None:
        assert state.scores[state.winner] >= state.scores[1 - state.winner]
    if rules.innings_limit is not None:
        assert max(state.innings) <= rules.innings_limit
    assert state.innings[state.starter] - state.innings[1 - state.starter] in (0, 1)
    return {"seed": seed, "shots": game.shots, "scores": state.scores, "winner": state.winner, "errors": errors,
            "equalizing": state.equalizing}


def fuzz(games: int, noise, first_seed: int = 0, progress=None) -> dict:
    start, shots, points, draws, eq, errors = time.perf_counter(), 0, 0, 0, 0, 0
    for k in range(games):
        out = play_game(first_seed + k, noise)
        shots += out["shots"]
        points += sum(out["scores"])
        draws += out["winner"] is None
        eq += out["equalizing"]
        errors += out["errors"]
        if progress and (k + 1) % 100 == 0:
            progress(f"{k + 1}/{games} games, {shots} shots, {time.perf_counter() - start:.0f} s")
    return {"games": games, "noise": noise, "all_ended": True, "shots": shots, "points": points, "draws": draws,
            "ended_in_equalising_inning": eq, "shot_errors": errors, "seconds": time.perf_counter() - start}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--games", type=int, default=2000)
    parser.add_argument("--noise", default="both", help="none, olympiad or both")
    args = parser.parse_args(argv)
    for noise in ([None, "olympiad"] if args.noise == "both" else [None if args.noise == "none" else args.noise]):
        print(json.dumps(fuzz(args.games, noise, progress=lambda m: print(m, flush=True))), flush=True)


if __name__ == "__main__":
    main()
