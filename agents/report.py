"""A training run's report: verdicts against the baselines, the win-rate table, progress lines, the learning curve."""

from __future__ import annotations

import csv
import math
from datetime import timedelta
from pathlib import Path

import numpy as np

from .stats import Z95, wilson


def progress_line(done: int, total: int, elapsed: float, rewards: list[float]) -> str:
    """Shots done / total, shots/s, the recent episodes' mean reward, elapsed and estimated remaining
    time (at the average rate so far, learning-curve evaluations included); `done` and `elapsed` > 0."""
    reward = f"{sum(rewards) / len(rewards):+.3f} (last {len(rewards)} episodes)" if rewards else "-"
    left = max(total - done, 0) * elapsed / done
    clock = lambda seconds: str(timedelta(seconds=round(seconds)))
    return (f"progress: {done:,}/{total:,} shots ({100 * done / total:.0f} %), {done / elapsed:,.0f} shots/s, "
            f"mean reward {reward}, {clock(elapsed)} elapsed, {clock(left)} left")


def verdict(differences: dict[str, dict], trained_steps: int, min_timesteps: int, untrained: dict | None,
            episodes: int) -> str:
    """The comparison in words: "beats X" only when the paired 95 % interval of the reward
    difference excludes zero in the trained agent's favour, and no claim at all from a run too
    short to mean anything, or whose kept checkpoint (`untrained`) is the untrained policy."""
    reasons = no_claim_reasons(trained_steps, min_timesteps, untrained, episodes)
    if reasons:
        return "no claim against the baselines: " + "; ".join(reasons)
    claims = []
    for key, d in differences.items():
        low, high = d["mean"] - d["ci95"], d["mean"] + d["ci95"]
        word = "beats" if low > 0 else "loses to" if high < 0 else "is not distinguishable from"
        claims.append(f"{word} {key.removeprefix('trained - ')} ({d['mean']:+.3f} ± {d['ci95']:.3f})")
    return ("the trained agent " + ", ".join(claims)
            + " in reward per episode (paired on the same seeds; 95 % intervals)")


def no_claim_reasons(trained_steps: int, min_timesteps: int, untrained: dict | None, episodes: int) -> list[str]:
    """Why a run may claim nothing: too short, the untrained policy kept, a single evaluation episode."""
    reasons = []
    if trained_steps < min_timesteps:
        reasons.append(f"too short to mean anything ({trained_steps:,} timesteps, under --min-timesteps "
                       f"{min_timesteps:,})")
    if untrained is not None:
        reasons.append(f"the kept checkpoint is the untrained policy (the first evaluation, at "
                       f"{untrained['timesteps']:,} timesteps, before any policy update)")
    if episodes < 2:
        reasons.append("one evaluation episode gives no confidence interval")
    return reasons


def game_summary(games: list[dict]) -> dict:
    """Wins, losses, unfinished games (max_shots or a simulator error: half a win each), the win
    rate with its 95 % Wilson interval (also among the games the agent broke and did not), the
    reward per game (+1 a win, -1 a loss, 0 unfinished: mean, sd, 95 % half-width), shots per game."""
    def rate(subset):
        wins = sum(g["winner"] == "agent" for g in subset) + 0.5 * sum(g["winner"] is None for g in subset)
        low, high = wilson(wins, len(subset))
        return {"mean": wins / max(len(subset), 1), "low": low, "high": high, "games": len(subset)}

    reward = np.array([{"agent": 1.0, "opponent": -1.0}.get(g["winner"], 0.0) for g in games])
    sd = float(reward.std(ddof=1)) if reward.size > 1 else 0.0
    return {"episodes": len(games), "wins": sum(g["winner"] == "agent" for g in games),
            "losses": sum(g["winner"] == "opponent" for g in games),
            "unfinished": sum(g["winner"] is None for g in games), "win_rate": rate(games),
            "win_rate_breaking": rate([g for g in games if g["agent_breaks"]]),
            "win_rate_not_breaking": rate([g for g in games if not g["agent_breaks"]]),
            "reward": {"mean": float(reward.mean()), "sd": sd, "ci95": Z95 * sd / math.sqrt(reward.size)},
            "shots_per_game": float(np.mean([g["shots"] for g in games]))}  # both players' shots


def game_table(results: dict[str, dict]) -> str:
    """A markdown table of game_summary results, a row per agent."""
    def cell(w):
        return f"{100 * w['mean']:.1f} % [{100 * w['low']:.1f}, {100 * w['high']:.1f}]"

    rows = ["| agent | win rate [95 % CI] | breaking | not breaking | wins | losses | unfinished | shots / game |",
            "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for name, r in results.items():
        rows.append(f"| {name} | {cell(r['win_rate'])} | {cell(r['win_rate_breaking'])} | "
                    f"{cell(r['win_rate_not_breaking'])} | {r['wins']} | {r['losses']} | {r['unfinished']} | "
                    f"{r['shots_per_game']:.1f} |")
    return "\n".join(rows)


def game_verdict(win_rate: dict, opponent: str, reasons: list[str]) -> str:
    """"beats" the opponent only when the win rate's 95 % interval lies above 50 %, and no claim
    at all for the reasons no_claim_reasons gives."""
    if reasons:
        return f"no claim against {opponent}: " + "; ".join(reasons)
    figure = f"{100 * win_rate['mean']:.1f} % [{100 * win_rate['low']:.1f}, {100 * win_rate['high']:.1f}]"
    word = ("beats" if win_rate["low"] > 0.5 else "loses to" if win_rate["high"] < 0.5
            else "is not distinguishable from")
    return f"the trained agent {word} {opponent} (win rate {figure}, 95 % Wilson interval, {win_rate['games']} games)"


def read_monitor(folder: Path):
    """(timesteps at the end of each episode, episode rewards) from SB3 Monitor csv files, in time order."""
    rows = []
    for path in sorted(folder.glob("*.monitor.csv")):
        with open(path) as f:
            next(f)  # the JSON header line
            rows += [(float(r["t"]), float(r["r"]), int(r["l"])) for r in csv.DictReader(f)]
    rows.sort()
    lengths = np.array([r[2] for r in rows], dtype=np.int64)
    return np.cumsum(lengths), np.array([r[1] for r in rows])


def plot_learning_curve(run_dir: Path, points: list[dict], baselines: dict[str, float], title: str,
                        kept: dict | None = None) -> None:
    """Training episodes' reward (rolling mean, from the Monitor files) and the deterministic
    evaluations against timesteps, with the baselines' final evaluation as horizontal lines."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 5.2), dpi=120)
    steps, rewards = read_monitor(run_dir / "monitor")
    if len(rewards):
        window = max(1, len(rewards) // 50)
        smooth = np.convolve(rewards, np.ones(window) / window, mode="valid")
        ax.plot(steps[window - 1:], smooth, color="tab:blue", alpha=0.6,
                label=f"training episodes (stochastic policy, rolling mean of {window} episodes)")
    if points:
        t = [p["timesteps"] for p in points]
        mean = np.array([p["reward"]["mean"] for p in points])
        ci = np.array([p["reward"]["ci95"] for p in points])
        ax.plot(t, mean, "o-", color="tab:red", label="trained agent, deterministic (fixed seeds)")
        ax.fill_between(t, mean - ci, mean + ci, color="tab:red", alpha=0.15)
    if kept is not None:
        ax.plot([kept["timesteps"]], [kept["reward"]["mean"]], "*", color="black", markersize=14,
                label="kept checkpoint (model.zip)")
    colours = iter(["tab:gray", "tab:green", "tab:purple", "tab:orange"])
    for name, value in baselines.items():
        ax.axhline(value, linestyle="--", color=next(colours), label=f"{name} ({value:+.2f})")
    ax.set_xlabel("timesteps (shots)")
    ax.set_ylabel("episode reward")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, frameon=False)
    fig.tight_layout()
    fig.savefig(run_dir / "learning_curve.png")
    plt.close(fig)

