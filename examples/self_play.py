"""Self-play: PPO against frozen copies of itself at 9-ball or 8-ball, then against the ghost-ball player (PettingZoo).

Phase 1 trains Stable-Baselines3's PPO on the single-agent env (`PoolNineBall-v0`) with
`opponent=` a frozen copy of its own policy, refreshed every round (the classic self-play
loop). Phase 2 puts the trained policy and the built-in `GameGhostBallAgent` at one table
through the two-agent AEC env (`pool_env.multiagent.nine_ball_v0`), alternating the break,
and prints who won each game. Needs the `train` and `multiagent` extras.

    python examples/self_play.py                          # a demo: about 20 s
    python examples/self_play.py --rounds 20 --steps 20000 --games 50

The defaults are tiny: the policy stays close to random and the ghost-ball player wins.
"""

import argparse
import time

import gymnasium as gym
import numpy as np

import pool_env  # noqa: F401  (registers the env ids)
from pool_env.players.game_ghost_ball import GameGhostBallAgent
from pool_env.rules import codes

IDS = {"nine_ball": "PoolNineBall-v0", "eight_ball": "PoolEightBall-v0"}


def parse_args(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("--game", default="nine_ball", choices=sorted(IDS))
    p.add_argument("--rounds", type=int, default=3, help="self-play rounds (the opponent refreshed before each)")
    p.add_argument("--steps", type=int, default=2048, help="PPO steps (agent shots) per round")
    p.add_argument("--games", type=int, default=4, help="games of the trained policy against the ghost-ball player")
    p.add_argument("--seed", type=int, default=0)
    args = p.parse_args(argv)
    if min(args.rounds, args.steps, args.games) < 1:
        p.error("--rounds, --steps and --games must be >= 1")
    return args


class FrozenPolicy:
    """An opponent for the single-agent env: a copy of a PPO policy's weights, acting deterministically."""

    def __init__(self):
        self.policy = None

    def update(self, model):
        if self.policy is None:
            self.policy = model.policy_class(model.observation_space, model.action_space, model.lr_schedule,
                                             **model.policy_kwargs).to(model.device)
            self.policy.set_training_mode(False)
        self.policy.load_state_dict(model.policy.state_dict())

    def act(self, observation):
        if self.policy is None:
            raise RuntimeError("FrozenPolicy.update(model) first")
        return self.policy.predict(observation, deterministic=True)[0]


def self_play(args):
    """Phase 1: PPO against a frozen copy of itself, `args.rounds` rounds of `args.steps` shots."""
    from stable_baselines3 import PPO

    frozen = FrozenPolicy()  # the env's opponent: a frozen copy of the model, refreshed each round
    env = gym.make(IDS[args.game], opponent=frozen)
    model = PPO("MlpPolicy", env, n_steps=256, batch_size=64, n_epochs=4, seed=args.seed, device="cpu", verbose=0)
    for round_ in range(args.rounds):
        start = time.perf_counter()
        frozen.update(model)
        model.learn(args.steps, reset_num_timesteps=round_ == 0)
        returns = [ep["r"] for ep in model.ep_info_buffer] or [float("nan")]
        print(f"round {round_ + 1}/{args.rounds}: {args.steps} shots in {time.perf_counter() - start:.1f} s, "
              f"mean return against the frozen copy {np.mean(returns):+.2f} over the last {len(returns)} games")
    env.close()
    return model


def tournament(model, args):
    """Phase 2: the trained policy against the ghost-ball player through the AEC env; the wins."""
    module = __import__(f"pool_env.multiagent.{args.game}_v0", fromlist=["env"])
    aec = module.env()
    ghost = GameGhostBallAgent(args.game)
    wins = {"ppo": 0, "ghost_ball": 0, "none": 0}
    for game in range(args.games):
        ppo_seat = "player_0" if game % 2 == 0 else "player_1"  # player_0 breaks: alternate the break
        players = {ppo_seat: lambda obs: model.predict(obs, deterministic=True)[0],
                   ("player_1" if ppo_seat == "player_0" else "player_0"): ghost.act}
        aec.reset(seed=args.seed + game)
        for agent in aec.agent_iter():
            observation, _, termination, truncation, info = aec.last()
            aec.step(None if termination or truncation else players[agent](observation))
        winner = info["winner"]  # the winner's number k of player_k, -1 for none
        name = "none" if winner < 0 else ("ppo" if f"player_{winner}" == ppo_seat else "ghost_ball")
        wins[name] += 1
        reason = codes.decode("end_reason", info["end_reason"])
        print(f"game {game + 1}: PPO as {ppo_seat}, {info['shots']} shots, winner {name}"
              f"{' (' + reason + ')' if reason else ''}")
    aec.close()
    return wins


def main(argv=None):
    args = parse_args(argv)
    start = time.perf_counter()
    model = self_play(args)
    wins = tournament(model, args)
    print(f"PPO {wins['ppo']}, ghost-ball {wins['ghost_ball']}, unfinished {wins['none']} "
          f"({time.perf_counter() - start:.0f} s in all)")


if __name__ == "__main__":
    main()
