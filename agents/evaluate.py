"""Play agents on fixed seeds and summarise: reward, balls pocketed per shot, scratch rate, with spread."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np

from pool_env.players import Agent, BreakAgent, GhostBallAgent, RandomAgent

from .match import run_episode

Z95 = 1.959964  # two-sided 95 % normal quantile


def heuristic_for(env) -> Agent:
    """The geometric baseline for an env: the break rule for one-shot episodes, the ghost-ball
    player (which breaks with the same rule) when an episode has more shots."""
    unwrapped = env.unwrapped
    return BreakAgent.from_env(env) if unwrapped.max_shots == 1 else GhostBallAgent.from_env(env)


def baselines(env, seed: int = 0) -> dict[str, Agent]:
    """{"random": RandomAgent, "heuristic": the geometric baseline} for this env."""
    return {"random": RandomAgent(env.action_space, seed=seed), "heuristic": heuristic_for(env)}


def play_episode(env, agent, seed: int) -> dict:
    """One episode from `env.reset(seed=seed)`; returns its reward, balls pocketed, shots and scratches."""
    if hasattr(agent, "reset"):
        agent.reset(seed=seed)
    act = agent.act if hasattr(agent, "act") else agent
    tally = {"reward": 0.0, "pocketed": 0, "shots": 0, "scratches": 0, "errors": 0}

    def count(step):
        tally["reward"] += step.reward
        tally["pocketed"] += int(step.info["pocketed"][1:].sum())  # the object balls of the mask
        tally["shots"] += 1
        tally["scratches"] += int(step.info["scratch"])
        tally["errors"] += int(step.info["error"])

    end = run_episode(env, act, seed, count)
    return {"seed": int(seed), "reward": tally["reward"], "pocketed": tally["pocketed"], "shots": tally["shots"],
            "scratches": tally["scratches"], "cleared": bool(end.info["balls_left"] == 0), "errors": tally["errors"]}


def _spread(values) -> dict:
    x = np.asarray(values, dtype=np.float64)
    sd = float(x.std(ddof=1)) if x.size > 1 else 0.0
    return {"mean": float(x.mean()), "sd": sd, "ci95": Z95 * sd / math.sqrt(x.size)}


def summarize(episodes: list[dict]) -> dict:
    """Means with spread over episodes (sd, and the 95 % confidence half-width of the mean).

    `pocketed_per_shot` is each episode's balls / shots; `scratch_rate` is scratches per shot
    over all shots, its ci95 the binomial normal approximation."""
    shots = sum(e["shots"] for e in episodes)
    scratches = sum(e["scratches"] for e in episodes)
    p = scratches / shots
    return {
        "episodes": len(episodes),
        "reward": _spread([e["reward"] for e in episodes]),
        "pocketed_per_shot": _spread([e["pocketed"] / e["shots"] for e in episodes]),
        "pocketed_per_episode": _spread([e["pocketed"] for e in episodes]),
        "shots_per_episode": _spread([e["shots"] for e in episodes]),
        "scratch_rate": {"mean": p, "ci95": Z95 * math.sqrt(p * (1 - p) / shots), "shots": shots},
        "cleared_rate": float(np.mean([e["cleared"] for e in episodes])),
        "simulator_errors": sum(e["errors"] for e in episodes),
    }


def evaluate(agent, env_id: str, seeds, env_kwargs: dict | None = None) -> dict:
    """Play `agent` (anything with `.act(obs)`, or a callable) once from every seed; return
    the summary with the per-episode records under "per_episode"."""
    env = gym.make(env_id, **(env_kwargs or {}))
    try:
        episodes = [play_episode(env, agent, int(seed)) for seed in seeds]
    finally:
        env.close()
    return {**summarize(episodes), "per_episode": episodes}


def paired_difference(a: dict, b: dict) -> dict:
    """Mean reward difference a - b over the same seeds, with sd and 95 % half-width."""
    ra = {e["seed"]: e["reward"] for e in a["per_episode"]}
    rb = {e["seed"]: e["reward"] for e in b["per_episode"]}
    common = sorted(set(ra) & set(rb))
    if not common:
        raise ValueError("the two evaluations share no seeds")
    return _spread([ra[s] - rb[s] for s in common])


def format_table(results: dict[str, dict]) -> str:
    """A plain-text table of summaries (mean +- 95 % half-width, sd in brackets)."""
    header = ("agent", "reward", "balls / shot", "scratch rate", "balls / episode", "shots / episode")
    rows = []
    for name, r in results.items():
        rows.append((
            name,
            f"{r['reward']['mean']:+.3f} ± {r['reward']['ci95']:.3f} (sd {r['reward']['sd']:.2f})",
            f"{r['pocketed_per_shot']['mean']:.3f} ± {r['pocketed_per_shot']['ci95']:.3f}",
            f"{r['scratch_rate']['mean']:.3f} ± {r['scratch_rate']['ci95']:.3f}",
            f"{r['pocketed_per_episode']['mean']:.2f}",
            f"{r['shots_per_episode']['mean']:.2f}",
        ))
    widths = [max(len(str(row[k])) for row in (header, *rows)) for k in range(len(header))]
    line = lambda row: "| " + " | ".join(str(c).ljust(w) for c, w in zip(row, widths)) + " |"
    rule = "|" + "|".join("-" * (w + 2) for w in widths) + "|"
    return "\n".join([line(header), rule, *(line(row) for row in rows)])
