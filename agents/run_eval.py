"""The end of a train.py run: the trained model and the baselines on fixed seeds, the game matches, the video."""

from __future__ import annotations

import dataclasses
import json
import logging
import time

import gymnasium as gym

import pool_env
from pool_env.envs.wrappers import GhostBallActionAgent
from pool_env.players import BreakAgent, GameGhostBallAgent, RandomAgent

from .evaluate import baselines, evaluate, format_table, paired_difference
from .match import alternate, env_winner, run_episode
from .report import game_summary, game_table, game_verdict, no_claim_reasons, verdict
from .sb3 import SB3Agent

log = logging.getLogger("train")  # train.py's logger: its console and the run folder's train.log

# `args` below is train.py's options (`Args`), `run` what its phases share (`Run`).


def final_evaluation(args, run, model, curve) -> dict:
    """The trained model and the baselines on the same fixed seeds: the table and the paired reward
    differences (logged and written to results.md), the verdict, eval_episodes.json; returns eval.json's content."""

    if run.game:
        return game_evaluation(args, run, model, curve)
    eval_start = time.perf_counter()
    agents = {"trained": SB3Agent(model), **baselines(run.probe, seed=args.seed)}
    if not run.multi_shot:  # the naive break too: full power straight at the head ball
        agents["head-on break"] = BreakAgent.from_env(run.probe, row=1, offset=0.0)
    results = {name: evaluate(agent, args.env_id, run.eval_seeds, run.env_kwargs) for name, agent in agents.items()}
    eval_time = time.perf_counter() - eval_start
    seeds = f"{len(run.eval_seeds)} fixed seeds ({run.eval_seeds[0]}..{run.eval_seeds[-1]})"
    table = format_table(results)
    log.info("evaluation on %s; mean ± 95%% CI, sd in brackets:\n%s", seeds, table)
    differences = {f"trained - {name}": paired_difference(results["trained"], results[name])
                   for name in results if name != "trained"}
    for key, diff in differences.items():
        log.info("reward %s: %+.3f ± %.3f (paired, same seeds)", key, diff["mean"], diff["ci95"])
    words = verdict(differences, curve.trained_steps, args.min_timesteps, curve.best if curve.kept_untrained else None,
                    len(run.eval_seeds))
    log.info("verdict: %s", words)

    kept = (f"the checkpoint at {curve.best['timesteps']:,} timesteps, the best of {len(curve.points)} evaluations "
            f"on {len(run.curve_seeds)} learning-curve seeds" if args.keep_best and curve.best else "the last model")
    (run.dir / "results.md").write_text("\n".join([
        f"# {args.algo.upper()} on {args.env_id}, seed {args.seed}", "",
        f"Trained {curve.trained_steps:,} timesteps; the model is {kept}.", "",
        f"Final evaluation on {seeds}, the same for every agent; mean ± 95 % confidence interval, sd in brackets:",
        "", table, "", "Reward difference, trained minus each baseline, paired on the same seeds (± 95 % CI):", "",
        *(f"- {key}: {d['mean']:+.3f} ± {d['ci95']:.3f}" for key, d in differences.items()), "",
        f"Verdict: {words}.", ""]))
    log.info("results table: %s", run.dir / "results.md")
    (run.dir / "eval_episodes.json").write_text(json.dumps({n: r["per_episode"] for n, r in results.items()}))
    return {
        "env_id": args.env_id, "env_kwargs": run.env_kwargs, "algo": args.algo,
        "timesteps": int(model.num_timesteps), "trained_timesteps": curve.trained_steps,
        "eval_seeds": {"first": run.eval_seeds[0], "count": len(run.eval_seeds)},
        "agents": {name: {k: v for k, v in r.items() if k != "per_episode"} for name, r in results.items()},
        "reward_differences": differences,
        "verdict": words,
        "learning_curve": curve.points,
        "wall_time_s": {"evaluation": eval_time},
        "args": dataclasses.asdict(args),
    }


def film(args, run, model) -> float:
    """A video of the trained agent, every shot whole; returns its wall time."""
    video_start = time.perf_counter()
    video_env = gym.make(args.env_id, render_mode="rgb_array_list", **run.env_kwargs)
    frames = pool_env.record_video(video_env, trained_agent(args, run, model), str(run.dir / "trained.mp4"),
                                   episodes=args.video_episodes, seed=args.eval_seed)
    video_env.close()
    log.info("video: %s (%d frames)", run.dir / "trained.mp4", frames)
    return time.perf_counter() - video_start


def trained_agent(args, run, model):
    """The trained model as a player of the bare env (through GhostBallAction's mapping when trained with it)."""
    agent = SB3Agent(model)
    if run.game and args.ghost_ball_action:
        return GhostBallActionAgent(agent, run.probe)
    return agent


def play_games(agent, args, run, seeds) -> dict:
    """`agent` against args.opponent, one game per seed, the agent breaking the even-numbered ones:
    game_summary of the records, which it keeps under "per_episode". As in agents.tournament, the
    breaker is the env's agent and the other player its opponent, so the breaker's turn is always a
    step of the env (never played inside its reset) and its break-and-runs count as they happen."""
    as_agent = quiet_env(args.env_id, **run.env_kwargs)  # the agent breaks; args.opponent replies
    as_opponent = quiet_env(args.env_id, **{**run.env_kwargs, "opponent": lambda obs: agent.act(obs)})
    other = (GameGhostBallAgent.from_env(as_opponent) if args.opponent == "ghost_ball"
             else RandomAgent(as_opponent.action_space, seed=0))
    games = []
    for seed, breaker, other_name in alternate(seeds, "agent", "opponent"):
        env, player = (as_agent, agent) if breaker == "agent" else (as_opponent, other)
        for each in (agent, other):
            if hasattr(each, "reset"):
                each.reset(seed=int(seed))
        steps = []
        end = run_episode(env, player.act, int(seed), steps.append)
        shots = sum(1 + step.info["opponent_shots"] for step in steps)  # both players' shots
        games.append({"seed": int(seed), "agent_breaks": breaker == "agent",
                      "winner": env_winner(end.info, breaker, other_name), "shots": shots})
    as_agent.close()
    as_opponent.close()
    return {**game_summary(games), "per_episode": games}


def game_evaluation(args, run, model, curve) -> dict:
    """Game envs: the trained model, the opponent's own player (ghost_ball) and random, each
    playing args.opponent on the same seeds, breaks alternating: win rates with 95 % Wilson
    intervals (logged and written to results.md), the verdict, eval_episodes.json; returns eval.json's content."""
    eval_start = time.perf_counter()
    agents = {"trained": trained_agent(args, run, model), "ghost_ball": GameGhostBallAgent.from_env(run.probe),
              "random": RandomAgent(run.probe.action_space, seed=args.seed)}
    results = {name: play_games(agent, args, run, run.eval_seeds) for name, agent in agents.items()}
    eval_time = time.perf_counter() - eval_start
    seeds = f"{len(run.eval_seeds)} fixed seeds ({run.eval_seeds[0]}..{run.eval_seeds[-1]})"
    table = game_table(results)
    log.info("win rates against %s on %s, breaks alternating (95 %% Wilson intervals):\n%s", args.opponent, seeds,
             table)
    reasons = no_claim_reasons(curve.trained_steps, args.min_timesteps, curve.best if curve.kept_untrained else None,
                               len(run.eval_seeds))
    words = game_verdict(results["trained"]["win_rate"], args.opponent, reasons)
    log.info("verdict: %s", words)
    kept = (f"the checkpoint at {curve.best['timesteps']:,} timesteps, the best of {len(curve.points)} evaluations "
            f"on {len(run.curve_seeds)} learning-curve games" if args.keep_best and curve.best else "the last model")
    how = ("practice run-outs (no opponent)" if args.practice else f"games against {args.opponent}"
           + (" with shaping" if args.shaping else ""))
    (run.dir / "results.md").write_text("\n".join([
        f"# {args.algo.upper()} on {args.env_id}{' through GhostBallAction' if args.ghost_ball_action else ''}, "
        f"seed {args.seed}", "",
        f"Trained {curve.trained_steps:,} timesteps (shots) on {how}; the model is {kept}.", "",
        f"Final evaluation: each agent plays {args.opponent} on {seeds}, the same for every agent, breaking the "
        "even-numbered games; win rate (an unfinished game counts half) with the 95 % Wilson interval:", "",
        table, "", f"Verdict: {words}.", ""]))
    log.info("results table: %s", run.dir / "results.md")
    (run.dir / "eval_episodes.json").write_text(json.dumps({n: r["per_episode"] for n, r in results.items()}))
    return {
        "env_id": args.env_id, "env_kwargs": run.env_kwargs, "train_kwargs": run.train_kwargs, "algo": args.algo,
        "ghost_ball_action": args.ghost_ball_action, "opponent": args.opponent,
        "timesteps": int(model.num_timesteps), "trained_timesteps": curve.trained_steps,
        "eval_seeds": {"first": run.eval_seeds[0], "count": len(run.eval_seeds)},
        "agents": {name: {k: v for k, v in r.items() if k != "per_episode"} for name, r in results.items()},
        "verdict": words, "learning_curve": curve.points, "wall_time_s": {"evaluation": eval_time},
        "args": dataclasses.asdict(args),
    }


def quiet_env(env_id: str, **kwargs):
    """gym.make without gymnasium's warnings: a shot the simulator cannot finish (rare) ends its
    episode with info["error"], which this script counts and logs instead."""
    gym.logger.min_level = gym.logger.ERROR
    return gym.make(env_id, **kwargs)
