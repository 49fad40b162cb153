"""Random 10-ball games, checked after every shot and decision: every game ends, every ball accounted for, valid states.

python -m agents.ten_ball_fuzz --games 2000 --noise both   (progress and a JSON summary on stdout)
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import time

import numpy as np

from pool_env.game import Game, Shot
from pool_env.physics.simulate import check_on_table
from pool_env.rules import GameState

MAX_SHOTS = 3000  # random play ends by three fouls long before this (WPA Ten Ball 11)


def check_position(game) -> None:
    """AssertionError unless the game now is a valid start: the state rebuilt through its
    checks, every object ball either on the table in the state and the balls or off in both,
    the balls at rest on the table, and a fresh Game accepting the position."""
    state, balls = game.state, game.balls
    assert GameState(**{f.name: getattr(state, f.name) for f in dataclasses.fields(state)}) == state
    on = frozenset(int(b) for b in np.flatnonzero(~balls.pocketed[1:]) + 1)
    assert on == state.on_table, (sorted(on), sorted(state.on_table))
    assert not balls.v.any() and not balls.w.any()
    if state.ball_in_hand is None and not game.over:  # a game-ending scratch leaves the cue ball down
        assert not balls.pocketed[0]
        check_on_table(balls, game.table, game.physics)
    if not game.over:
        Game("ten_ball", decisions=True).reset(balls=balls, state=state)


def aimed_shot(game, rng) -> Shot:
    """A shot at the lowest ball (from where the cue ball lies, or placed at random with ball
    in hand), at a random speed (full power on the break), calling a random ball and pocket,
    a push out when one may be declared, one time in two."""
    balls, area = game.balls, game.placement_area()
    place = None if area is None else (rng.uniform(area[0], area[1]), rng.uniform(area[2], area[3]))
    cue = np.asarray(place if place is not None else balls.xy[0])
    target = balls.xy[min(game.legal_targets)] + rng.normal(0.0, 0.01, 2)
    speed = 11.0 if game.state.is_break else rng.uniform(0.5, 6.0)
    on = sorted(game.state.on_table)
    return Shot.aimed(target - cue, speed, place=place, pocket=int(rng.integers(6)), ball=int(rng.choice(on)),
                      push_out=bool(game.may_push_out and rng.random() < 0.5))


def play_game(seed: int, noise) -> dict:
    """One random game (half the shots random actions, half aimed at the lowest ball: `aimed_shot`;
    random decisions); its summary."""
    rng = np.random.default_rng(seed)
    game = Game("ten_ball", noise=noise, seed=seed, layout="ten_ball_decide")
    errors = decisions = push_outs = 0
    while not game.over:
        assert game.shots < MAX_SHOTS, f"game {seed} did not end in {MAX_SHOTS} shots"
        if game.pending is not None:
            game.decide(game.decode_decision(rng.uniform(-1.0, 1.0, game.layout.size)))
            decisions += 1
            check_position(game)
            continue
        action = rng.uniform(-1.0, 1.0, game.layout.size) if rng.random() < 0.5 else aimed_shot(game, rng)
        if isinstance(action, Shot):
            push_outs += action.push_out
        else:
            push_outs += bool(game.may_push_out and action[game.layout.decision_index] > 0)
        record = game.play(action)
        if record.error is not None:
            errors += 1
            assert errors < 50, f"game {seed}: {record.error}"
            continue
        check_position(game)
    return {"seed": seed, "shots": game.shots, "winner": game.winner, "errors": errors, "decisions": decisions,
            "push_outs": push_outs, "end_reason": record.ruling.end_reason}


def fuzz(games: int, noise, first_seed: int = 0, progress=None) -> dict:
    start, shots, errors, decisions, push_outs, ends = time.perf_counter(), 0, 0, 0, 0, {}
    for k in range(games):
        out = play_game(first_seed + k, noise)
        shots += out["shots"]
        errors += out["errors"]
        decisions += out["decisions"]
        push_outs += out["push_outs"]
        ends[out["end_reason"]] = ends.get(out["end_reason"], 0) + 1
        if progress and (k + 1) % 100 == 0:
            progress(f"{k + 1}/{games} games, {shots} shots, {time.perf_counter() - start:.0f} s")
    return {"games": games, "noise": noise, "all_ended": True, "shots": shots, "decisions": decisions,
            "push_outs": push_outs, "end_reasons": ends, "shot_errors": errors,
            "seconds": time.perf_counter() - start}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--games", type=int, default=2000)
    parser.add_argument("--noise", default="both", help="none, olympiad or both")
    args = parser.parse_args(argv)
    for noise in ([None, "olympiad"] if args.noise == "both" else [None if args.noise == "none" else args.noise]):
        print(json.dumps(fuzz(args.games, noise, progress=lambda m: print(m, flush=True))), flush=True)


if __name__ == "__main__":
    main()
