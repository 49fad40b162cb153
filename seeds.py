"""`python seeds.py --seeds 5 [train.py's options]`: train.py's run on several seeds, and the table across them.

One run's figures depend on the machine (the CPU kernels torch picks change the training, the
physics replays bit for bit), so a result is stated across seeds: each seed k = seed, seed + 1,
... trains and evaluates exactly as `python train.py --seed k` (its own run folder, the same
evaluation seeds), then `seeds.md` and `seeds.json` (in the parent folder of the runs) give, for
each agent and for the trained agent's paired difference with each baseline, the mean across
the seeds and its 95 % interval (Student's t with seeds - 1 degrees of freedom), with every
seed's own figure beside it.
"""

from __future__ import annotations

import dataclasses
import json
import math
import statistics
import sys
from pathlib import Path

import train

# Two-sided 95 % quantiles of Student's t by degrees of freedom (any statistics table; e.g.
# NIST/SEMATECH e-Handbook of Statistical Methods, table 1.3.6.7.2).
T95 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306, 9: 2.262, 10: 2.228,
       15: 2.131, 20: 2.086, 30: 2.042}


def t95(dof: int) -> float:
    """The quantile for `dof` degrees of freedom (the table's nearest entry at or below it: wider)."""
    return T95[max(k for k in T95 if k <= dof)]


def across(values: list[float]) -> dict:
    """Mean, the 95 % interval's half-width across the seeds, and the values."""
    mean = statistics.fmean(values)
    half = t95(len(values) - 1) * statistics.stdev(values) / math.sqrt(len(values)) if len(values) > 1 else math.inf
    return {"mean": mean, "ci95": half, "values": values}


def summarize(evals: list[dict]) -> dict:
    """The across-seed figures of several runs' eval.json."""
    agents = {name: {key: across([e["agents"][name][key]["mean"] for e in evals])
                     for key in ("reward", "pocketed_per_episode", "scratch_rate")}
              for name in evals[0]["agents"]}
    differences = {name: across([e["reward_differences"][name]["mean"] for e in evals])
                   for name in evals[0]["reward_differences"]}
    return {"seeds": [e["args"]["seed"] for e in evals], "agents": agents, "reward_differences": differences}


def markdown(summary: dict, env_id: str, timesteps: int, claim: bool = True) -> str:
    """The table of `summary`; with `claim` False (runs shorter than train.py's --min-timesteps)
    the verdicts say that nothing is claimed."""
    seeds = summary["seeds"]
    lines = [f"# {env_id}: {timesteps:,} shots of training on {len(seeds)} seeds ({', '.join(map(str, seeds))})", "",
             "Mean across the seeds, with its 95 % interval (Student's t), then each seed's own figure.", "",
             "| agent | reward per episode | balls per episode | scratch rate | by seed (reward) |",
             "| --- | --- | --- | --- | --- |"]
    for name, a in summary["agents"].items():
        r, b, s = a["reward"], a["pocketed_per_episode"], a["scratch_rate"]
        by_seed = ", ".join(f"{v:+.3f}" for v in r["values"])
        lines.append(f"| {name} | {r['mean']:+.3f} ± {r['ci95']:.3f} | {b['mean']:.3f} ± {b['ci95']:.3f} | "
                     f"{100 * s['mean']:.1f} % ± {100 * s['ci95']:.1f} | {by_seed} |")
    lines += ["", "| paired difference (reward) | across seeds | by seed | verdict |", "| --- | --- | --- | --- |"]
    for name, d in summary["reward_differences"].items():
        low, high = d["mean"] - d["ci95"], d["mean"] + d["ci95"]
        verdict = "better" if low > 0 else "worse" if high < 0 else "no difference shown"
        verdict = verdict if claim else "no claim: runs shorter than --min-timesteps"
        lines.append(f"| {name} | {d['mean']:+.3f} ± {d['ci95']:.3f} | {', '.join(f'{v:+.3f}' for v in d['values'])} "
                     f"| {verdict} |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    count = 5
    if "--seeds" in argv:
        k = argv.index("--seeds")
        try:
            count = int(argv[k + 1])
        except (IndexError, ValueError):
            print("seeds.py: --seeds needs a number of seeds (>= 2)", file=sys.stderr)
            return 2
        del argv[k:k + 2]
    if count < 2:
        print(f"seeds.py: --seeds must be >= 2 (an interval across seeds needs two), got {count}", file=sys.stderr)
        return 2
    args, _ = train.parse_args(argv)
    stem = args.run_name or f"{args.env_id}-{args.algo}-{args.timesteps}"
    runs = []
    for k in range(count):
        seed_args = dataclasses.replace(args, seed=args.seed + k, run_name=f"{stem}-s{args.seed + k}")
        runs.append(train.main(seed_args))
    evals = [json.loads((run / "eval.json").read_text()) for run in runs]
    summary = summarize(evals)
    out = Path(args.out)
    (out / f"{stem}-seeds.json").write_text(json.dumps(summary, indent=2))
    table = markdown(summary, args.env_id, args.timesteps, claim=args.timesteps >= args.min_timesteps)
    (out / f"{stem}-seeds.md").write_text(table)
    print(table)
    print(f"seeds.py: wrote {out / f'{stem}-seeds.md'} and {out / f'{stem}-seeds.json'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
