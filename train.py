"""Train an agent on the pool env, compare it with the baselines, and save everything in one run folder.

    python train.py                      # PPO on PoolBreak-v0, 6-9 minutes on 2 CPU cores (333 s idle, 516 s busy)
    python train.py --timesteps 2000     # a smoke run: every artefact in well under a minute
    python train.py --help               # every option

Single file, read top to bottom (in the spirit of CleanRL): options, run folder and logging,
vectorised envs, the model, training with a progress bar and TensorBoard, then the final
evaluation of the trained model, RandomAgent and the geometric heuristic on the same fixed
seeds (table printed, eval.json written), the saved model, the learning-curve PNG and an
.mp4 of the trained agent playing whole shots. The run folder's path is printed first.
"""

from __future__ import annotations

import argparse
import dataclasses
import functools
import json
import logging
import sys
import time
from dataclasses import dataclass, field
from datetime import datetime
from pathlib import Path


def option(default, help: str, **kwargs):
    return field(default=default, metadata={"help": help, **kwargs})


@dataclass
class Args:
    # --- what to train ---
    env_id: str = option("PoolBreak-v0", "PoolBreak-v0 (the break: one shot) or PoolBreakRun-v0 (play on)")
    algo: str = option("ppo", "learning algorithm", choices=("ppo", "sac"))
    timesteps: int = option(250_000, "total environment steps (shots) to train for")
    n_envs: int = option(2, "parallel environments")
    vec_env: str = option("auto", "auto: subprocesses when n_envs > 1", choices=("auto", "subproc", "dummy"))
    seed: int = option(0, "seed of the model and the training envs")
    spin: bool = option(False, "add the cue-tip offset (side, top) to the action")
    randomize_cue: bool = option(False, "start the cue ball anywhere in the kitchen")
    # --- hyperparameters (PPO unless marked) ---
    learning_rate: float = option(1e-3, "optimizer step size (PPO and SAC)")
    lr_schedule: str = option("linear", "learning rate over training: constant, or linear decay to 0",
                              choices=("constant", "linear"))
    n_steps: int = option(512, "PPO: steps per env between updates")
    batch_size: int = option(256, "minibatch size (PPO and SAC)")
    n_epochs: int = option(10, "PPO: passes over each rollout")
    gamma: float = option(0.99, "discount (matters only when an episode has more than one shot)")
    log_std_init: float = option(-1.0, "PPO: initial log standard deviation of the Gaussian policy")
    anneal_std: bool = option(True, "PPO: anneal the log std linearly to --log-std-final instead of learning it")
    log_std_final: float = option(-6.0, "PPO: log std at the end of training when annealing")
    net_arch: str = option("64,64", "hidden layer sizes of policy and value networks")
    # --- evaluation and outputs ---
    eval_episodes: int | None = option(None, "final evaluation episodes per agent (default 1000, 100 multi-shot)")
    eval_seed: int = option(1_000_000, "first seed of the fixed evaluation seeds (disjoint from training)")
    curve_points: int = option(50, "deterministic evaluations during training, for the learning curve")
    curve_episodes: int = option(200, "episodes per learning-curve evaluation")
    keep_best: bool = option(True, "final model: the best learning-curve checkpoint (else the last)")
    video_episodes: int = option(3, "episodes of the trained agent in the video (0: no video)")
    out: str = option("runs", "parent folder of the run folder")
    run_name: str | None = option(None, "run folder name (default: timestamp, env, algo, seed)")
    progress_bar: bool = option(True, "show a progress bar while training")


def parse_args(argv=None) -> Args:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    for f in dataclasses.fields(Args):
        flag = "--" + f.name.replace("_", "-")
        meta = dict(f.metadata)
        if f.type in ("bool", bool):
            parser.add_argument(flag, default=f.default, action=argparse.BooleanOptionalAction, **meta)
        else:
            kind = {"int": int, "float": float, "str": str}.get(str(f.type).split(" ")[0], str)
            parser.add_argument(flag, default=f.default, type=kind, **meta)
    return Args(**vars(parser.parse_args(argv)))


def main(args: Args) -> Path:
    started = time.perf_counter()
    # Heavy imports here, not at the top: subprocess envs re-import this file, and --help stays instant.
    import gymnasium as gym
    import torch
    from stable_baselines3 import PPO, SAC
    from stable_baselines3.common.callbacks import BaseCallback, CallbackList
    from stable_baselines3.common.env_util import make_vec_env
    from stable_baselines3.common.utils import LinearSchedule
    from stable_baselines3.common.vec_env import DummyVecEnv, SubprocVecEnv

    import pool_env
    from agents import BreakAgent, SB3Agent, baselines, evaluate, format_table, paired_difference
    from pool_env.physics import warm_up

    # --- the run folder and logging: everything this run makes goes in `run_dir` ---
    name = args.run_name or f"{datetime.now():%Y%m%d-%H%M%S}-{args.env_id}-{args.algo}-s{args.seed}"
    run_dir = Path(args.out) / name
    run_dir.mkdir(parents=True, exist_ok=True)
    log = logging.getLogger("train")
    log.setLevel(logging.INFO)
    log.handlers.clear()
    log.propagate = False
    for handler in (logging.StreamHandler(sys.stdout), logging.FileHandler(run_dir / "train.log")):
        handler.setFormatter(logging.Formatter("%(asctime)s %(message)s", "%H:%M:%S"))
        log.addHandler(handler)
    log.info("run folder: %s", run_dir.resolve())
    (run_dir / "args.json").write_text(json.dumps(dataclasses.asdict(args), indent=2))

    torch.set_num_threads(1)  # small networks: one thread is fastest, and leaves the cores to the envs
    env_kwargs = {"spin": args.spin, "randomize_cue": args.randomize_cue}
    probe = quiet_env(args.env_id, **env_kwargs)
    multi_shot = probe.unwrapped.max_shots > 1
    eval_episodes = args.eval_episodes or (100 if multi_shot else 1000)
    eval_seeds = list(range(args.eval_seed, args.eval_seed + eval_episodes))
    curve_seeds = list(range(args.eval_seed + 10_000_000, args.eval_seed + 10_000_000 + args.curve_episodes))
    log.info("env %s %s, pool_env %s, algo %s, %d timesteps on %d envs", args.env_id, env_kwargs,
             pool_env.__version__, args.algo.upper(), args.timesteps, args.n_envs)
    # Compile the physics (or load it from numba's cache) once, here, with a word on a first
    # run, rather than in each worker process behind a frozen progress bar.
    log.info("physics ready in %.1f s", warm_up())

    # --- training envs: Monitor logs every episode to monitor/*.csv (the learning curve) ---
    vec_cls = {"subproc": SubprocVecEnv, "dummy": DummyVecEnv}.get(args.vec_env)
    vec_cls = vec_cls or (SubprocVecEnv if args.n_envs > 1 else DummyVecEnv)
    (run_dir / "monitor").mkdir(exist_ok=True)
    envs = make_vec_env(functools.partial(quiet_env, args.env_id, **env_kwargs), n_envs=args.n_envs, seed=args.seed,
                        vec_env_cls=vec_cls, monitor_dir=str(run_dir / "monitor"))

    # --- the model ---
    net_arch = [int(n) for n in args.net_arch.split(",") if n]
    learning_rate = args.learning_rate
    if args.lr_schedule == "linear":
        learning_rate = LinearSchedule(args.learning_rate, 0.0, 1.0)  # SB3's own class: pickles cleanly
    common = dict(learning_rate=learning_rate, batch_size=args.batch_size, gamma=args.gamma, seed=args.seed,
                  device="cpu", tensorboard_log=str(run_dir / "tb"), verbose=0)
    if args.algo == "ppo":
        model = PPO("MlpPolicy", envs, n_steps=args.n_steps, n_epochs=args.n_epochs,
                    policy_kwargs=dict(net_arch=net_arch, log_std_init=args.log_std_init), **common)
    else:
        model = SAC("MlpPolicy", envs, learning_starts=1000, policy_kwargs=dict(net_arch=net_arch), **common)

    # --- training, with deterministic evaluations on fixed seeds for the learning curve ---
    class CurveCallback(BaseCallback):
        def __init__(self, every: int):
            super().__init__()
            self.every, self.next_at, self.points, self.failed_shots = every, 0, [], 0
            self.best = None

        def _on_step(self) -> bool:
            self.failed_shots += sum("error" in info for info in self.locals["infos"])
            if self.every and self.num_timesteps >= self.next_at:
                self.next_at += self.every
                self.measure()
            return True

        def measure(self):
            result = evaluate(SB3Agent(self.model), args.env_id, curve_seeds, env_kwargs)
            point = {"timesteps": int(self.num_timesteps), "reward": result["reward"],
                     "pocketed_per_shot": result["pocketed_per_shot"]["mean"],
                     "scratch_rate": result["scratch_rate"]["mean"]}
            self.points.append(point)
            if self.best is None or point["reward"]["mean"] > self.best["reward"]["mean"]:
                self.best = point
                self.model.save(run_dir / "best_model.zip")
            self.logger.record("eval/mean_reward", point["reward"]["mean"])
            self.logger.record("eval/scratch_rate", point["scratch_rate"])
            self.logger.dump(self.num_timesteps)

    class AnnealStd(BaseCallback):
        """Exploration from coarse to fine: the reward is a rugged function of the aim (a fifth of a
        ball radius can halve it), so the Gaussian policy's spread follows a fixed schedule,
        wide at first and narrow at the end, instead of being learned."""

        def _on_training_start(self) -> None:
            self.model.policy.log_std.requires_grad_(False)

        def _on_rollout_start(self) -> None:
            progress = min(self.num_timesteps / args.timesteps, 1.0)
            value = args.log_std_init + progress * (args.log_std_final - args.log_std_init)
            self.model.policy.log_std.data.fill_(value)
            self.logger.record("train/log_std", value)

        def _on_step(self) -> bool:
            return True

    # No more often than the policy changes (PPO updates once per rollout of n_steps * n_envs).
    every = max(args.timesteps // max(args.curve_points, 1), args.n_steps * args.n_envs if args.algo == "ppo" else 1)
    curve = CurveCallback(every if args.curve_points else 0)
    callbacks = [curve] + ([AnnealStd()] if args.algo == "ppo" and args.anneal_std else [])
    train_start = time.perf_counter()
    model.learn(total_timesteps=args.timesteps, callback=CallbackList(callbacks), progress_bar=args.progress_bar,
                tb_log_name="tb")
    if args.curve_points:
        curve.measure()
    train_time = time.perf_counter() - train_start
    envs.close()
    model.save(run_dir / "last_model.zip")
    log.info("trained %d steps in %.0f s (%.0f steps/s)", model.num_timesteps, train_time,
             model.num_timesteps / train_time)
    if args.keep_best and curve.best is not None:
        model = type(model).load(run_dir / "best_model.zip", device="cpu")
        log.info("keeping the best checkpoint: %d steps, reward %+.3f on the %d learning-curve seeds",
                 curve.best["timesteps"], curve.best["reward"]["mean"], len(curve_seeds))
    model.save(run_dir / "model.zip")
    log.info("model saved to %s", run_dir / "model.zip")
    if curve.failed_shots:
        log.info("%d training shots hit the simulator's event cap (episode truncated, reward 0)", curve.failed_shots)

    # --- final evaluation: every agent on the same fixed seeds ---
    eval_start = time.perf_counter()
    agents = {"trained": SB3Agent(model), **baselines(probe, seed=args.seed)}
    if not multi_shot:  # the naive break too: full power straight at the head ball
        agents["head-on break"] = BreakAgent.from_env(probe, row=1, offset=0.0)
    results = {name: evaluate(agent, args.env_id, eval_seeds, env_kwargs) for name, agent in agents.items()}
    eval_time = time.perf_counter() - eval_start
    log.info("evaluation on %d fixed seeds (%d..%d); mean ± 95%% CI, sd in brackets:\n%s", eval_episodes,
             eval_seeds[0], eval_seeds[-1], format_table(results))
    differences = {f"trained - {name}": paired_difference(results["trained"], results[name])
                   for name in results if name != "trained"}
    for key, diff in differences.items():
        log.info("reward %s: %+.3f ± %.3f (paired, same seeds)", key, diff["mean"], diff["ci95"])
    summary = {
        "env_id": args.env_id, "env_kwargs": env_kwargs, "algo": args.algo, "timesteps": int(model.num_timesteps),
        "eval_seeds": {"first": eval_seeds[0], "count": eval_episodes},
        "agents": {name: {k: v for k, v in r.items() if k != "per_episode"} for name, r in results.items()},
        "reward_differences": differences,
        "learning_curve": curve.points,
        "wall_time_s": {"training": train_time, "evaluation": eval_time},
        "args": dataclasses.asdict(args),
    }
    (run_dir / "eval_episodes.json").write_text(json.dumps({n: r["per_episode"] for n, r in results.items()}))

    # --- learning curve ---
    plot_learning_curve(run_dir, curve.points, {n: r["reward"]["mean"] for n, r in results.items() if n != "trained"},
                        f"{args.algo.upper()} on {args.env_id}", curve.best if args.keep_best else None)
    log.info("learning curve: %s", run_dir / "learning_curve.png")

    # --- a video of the trained agent: every shot, whole ---
    if args.video_episodes:
        video_start = time.perf_counter()
        video_env = gym.make(args.env_id, render_mode="rgb_array_list", **env_kwargs)
        frames = pool_env.record_video(video_env, SB3Agent(model), str(run_dir / "trained.mp4"),
                                       episodes=args.video_episodes, seed=args.eval_seed)
        video_env.close()
        summary["wall_time_s"]["video"] = time.perf_counter() - video_start
        log.info("video: %s (%d frames)", run_dir / "trained.mp4", frames)

    summary["wall_time_s"]["total"] = time.perf_counter() - started
    (run_dir / "eval.json").write_text(json.dumps(summary, indent=2))
    log.info("eval.json: %s; total wall time %.0f s", run_dir / "eval.json", summary["wall_time_s"]["total"])
    log.info("TensorBoard: tensorboard --logdir %s", run_dir / "tb")
    log.info("run folder: %s", run_dir.resolve())
    return run_dir


def read_monitor(folder: Path):
    """(timesteps at the end of each episode, episode rewards) from SB3 Monitor csv files, in time order."""
    import csv

    import numpy as np

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
    import numpy as np

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


def quiet_env(env_id: str, **kwargs):
    """gym.make without gymnasium's warnings: a shot the simulator cannot finish (rare) ends its
    episode with info["error"], which this script counts and logs instead."""
    import gymnasium as gym

    import pool_env  # noqa: F401  (registers the ids, also in subprocesses)

    gym.logger.min_level = gym.logger.ERROR
    return gym.make(env_id, **kwargs)


if __name__ == "__main__":
    main(parse_args())
