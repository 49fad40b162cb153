"""Snooker frames between two players, the built-in player's figures (mean break, frames won) and the random-frame fuzz.

    python -m agents.snooker_match --frames 20 --noise olympiad      # the snooker player against random
    python -m agents.snooker_match --fuzz 2000 --noise olympiad      # random frames, every state checked

A frame ends with the last black (WPBSA Section 3 Rule 3) or at `max_shots` shots, when the
higher score takes it (level: no winner): the shot limit is this harness's, as a concession
ends a real frame that cannot finish.
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

from agents.stats import wilson
from pool_env.game import Game
from pool_env.physics.simulate import check_on_table
from pool_env.players import RandomAgent
from pool_env.players.snooker import SnookerPlayer
from pool_env.rules.snooker import SnookerState, check_state

MAX_SHOTS = 400


def play_frame(game: Game, players, breaker: int, seed: int, max_shots: int = MAX_SHOTS, check=False) -> dict:
    """One frame from a new rack, `players[k]` a callable (the game) -> Shot or action for player
    k. Returns the winner (None: level at the shot limit), the scores, the visits' points by
    player, the shots and how it ended; `check` verifies every state and ball on the way (`check_frame`)."""
    game.reset(seed, breaker=breaker)
    visits = ([], [])
    shooter, run = game.shooter, 0
    while not game.over and game.shots < max_shots:
        before = game.state
        record = game.play(players[game.shooter](game))
        if record.error is not None:
            raise RuntimeError(f"shot {game.shots}: {record.error}")
        if check:
            check_shot(before, record, game)
        run += record.ruling.points
        if game.over or game.shooter != shooter:
            visits[shooter].append(run)
            shooter, run = game.shooter, 0
    scores = game.state.scores
    winner = game.winner
    if winner is None and scores[0] != scores[1]:
        winner = 0 if scores[0] > scores[1] else 1
    return {"winner": winner, "scores": scores, "visits": visits, "shots": game.shots,
            "ended": "black" if game.over else "shot_limit"}


def check_shot(before: SnookerState, record, game: Game) -> None:
    """AssertionError unless the shot kept the frame sound: a valid state, every ball accounted
    for (on the table in the state and the balls alike, or potted), the scores grown by exactly
    the points and the penalty."""
    state, balls = record.state_after, record.balls_after
    check_state(state)
    on_table = frozenset(int(k) for k in np.flatnonzero(~balls.pocketed[1:]) + 1)
    expected = on_table if state.winner is None else on_table - {21}
    assert state.on_table == expected, (sorted(state.on_table), sorted(on_table))
    ruling = record.ruling
    gained = [state.scores[k] - before.scores[k] for k in (0, 1)]
    me = before.shooter
    assert gained[me] == ruling.points and gained[1 - me] == ruling.penalty, (gained, ruling)
    assert not (ruling.points and ruling.penalty)
    assert ruling.penalty == 0 or 4 <= ruling.penalty <= 7
    if state.winner is None:
        check_on_table(balls, game.table, game.physics)  # on the cloth (or hanging in a mouth), no overlaps


def random_player(seed):
    agent = RandomAgent(6, seed=seed)
    return lambda game: agent.act(None)


def match(frames: int, noise, seed: int = 0) -> dict:
    """The snooker player (player 0) against the random player, alternating the break."""
    results = []
    for k in range(frames):
        game = Game("snooker", noise=noise, seed=seed + k)
        player = SnookerPlayer(game, seed=seed + k)
        results.append(play_frame(game, (lambda g, p=player: p.decide(), random_player(seed + k)), k % 2, seed + k))
    won = sum(r["winner"] == 0 for r in results)
    visits = [v for r in results for v in r["visits"][0]]
    lo, hi = wilson(won, frames)
    return {"frames": frames, "won": won, "wilson95": [round(lo, 3), round(hi, 3)],
            "mean_break": round(float(np.mean(visits)), 3), "visits": len(visits),
            "highest_break": max(visits, default=0), "scores": [r["scores"] for r in results],
            "ended": [r["ended"] for r in results]}


def fuzz(frames: int, noise, seed: int = 0, max_shots: int = MAX_SHOTS) -> dict:
    """Random frames (both players random), every shot checked (`check_shot`)."""
    ended = {"black": 0, "shot_limit": 0}
    shots = 0
    for k in range(frames):
        game = Game("snooker", noise=noise, seed=seed + k)
        r = play_frame(game, (random_player(2 * (seed + k)), random_player(2 * (seed + k) + 1)), k % 2, seed + k,
                       max_shots, check=True)
        ended[r["ended"]] += 1
        shots += r["shots"]
    return {"frames": frames, "ended": ended, "shots": shots, "noise": noise}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=0)
    parser.add_argument("--fuzz", type=int, default=0)
    parser.add_argument("--noise", default="none", choices=("none", "olympiad"))
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    args.noise = None if args.noise == "none" else args.noise
    start = time.perf_counter()
    out = {}
    if args.frames:
        out["match"] = match(args.frames, args.noise, args.seed)
    if args.fuzz:
        out["fuzz"] = fuzz(args.fuzz, args.noise, args.seed)
    out["seconds"] = round(time.perf_counter() - start, 1)
    print(json.dumps(out))


if __name__ == "__main__":
    main()
