"""A player's 10-ball win rate against an opponent in PoolTenBall-v0 (breaks alternating), with a Wilson interval.

python -m agents.ten_ball_match --player ghost_ball --opponent random --games 400
"""

from __future__ import annotations

import argparse
import json
import time

import gymnasium as gym

import pool_env  # noqa: F401  (registers the ids)
from agents.match import alternate, run_episode
from agents.stats import wilson
from pool_env.players import make_player


def match(player: str = "ghost_ball", opponent: str = "random", games: int = 400, noise=None, seed: int = 0,
          progress=None) -> dict:
    """`games` games of `player` (the env's agent) against `opponent`, the agent breaking in
    the even games; wins, losses, games cut at the shot limit, the win rate and its 95 % Wilson interval."""
    envs = {breaks: gym.make("PoolTenBall-v0", opponent=opponent, noise=noise, agent_breaks=breaks)
            for breaks in (True, False)}
    agents = {breaks: make_player(player, env.unwrapped, seed=seed) for breaks, env in envs.items()}
    wins = losses = cut = 0
    start = time.perf_counter()
    for k, (game_seed, breaks, _) in enumerate(alternate(range(seed, seed + games), True, False)):
        end = run_episode(envs[breaks], agents[breaks].act, game_seed)  # breaks: the agent breaks
        wins += end.terminated and end.reward > 0
        losses += end.terminated and end.reward < 0
        cut += end.truncated
        if progress and (k + 1) % 50 == 0:
            progress(f"{k + 1}/{games} games, {wins} won, {time.perf_counter() - start:.0f} s")
    low, high = wilson(wins, games)
    return {"player": player, "opponent": opponent, "noise": noise, "games": games, "wins": wins, "losses": losses,
            "cut_at_shot_limit": cut, "win_rate": wins / games, "wilson95": [low, high],
            "seconds": time.perf_counter() - start}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--player", default="ghost_ball")
    parser.add_argument("--opponent", default="random")
    parser.add_argument("--games", type=int, default=400)
    parser.add_argument("--noise", default=None)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    print(json.dumps(match(args.player, args.opponent, args.games, args.noise, args.seed,
                           progress=lambda m: print(m, flush=True))), flush=True)


if __name__ == "__main__":
    main()
