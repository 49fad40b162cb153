"""Train an agent on the pool env, compare it with the baselines, and save everything in one run folder.

    python train.py                      # PPO on PoolBreak-v0, about 5.5 minutes on 2 CPU cores (321 s)
    python train.py --timesteps 2000     # a smoke run: every artefact in well under a minute
    python train.py --help               # every option
    python train.py --env-id PoolNineBall-v0 --opponent ghost_ball --ghost-ball-action --practice
                                         # 9-ball: practice run-outs through the ghost-ball action
                                         # wrapper, judged by the win rate against the ghost-ball player

Read top to bottom (in the spirit of CleanRL): the options, then `main`, whose phases follow
it in the order they run; the callbacks during training are in agents/train_callbacks.py, the
evaluations and the video at the end in agents/run_eval.py, the words and tables of the report
in agents/report.py. The phases: the run folder and logging, the vectorised envs and the
model, training (learning-curve evaluations, a progress bar on a terminal and a progress
line every few seconds in train.log and on a redirected stdout, TensorBoard), the final
evaluation of the trained model, RandomAgent and the geometric heuristic on the same fixed
seeds (table printed and written to results.md with a verdict, eval.json written), the
learning-curve PNG and an .mp4 of the trained agent playing whole shots. The run folder's
path is printed first. The game envs (PoolNineBall-v0, PoolEightBall-v0) are judged by the win
rate against --opponent (95 % Wilson interval, fixed seeds, breaks alternating) instead, and
the video is of whole games.
"""

from __future__ import annotations

import argparse
import dataclasses
import functools
import json
import logging
import os
import sys
import time
from dataclasses import dataclass, field
from datetime import datetime
from pathlib import Path

log = logging.getLogger("train")  # to the console and the run folder's train.log (set up in open_run)
PROG = "train.py"  # how errors name the command


def option(default, help: str, **kwargs):
    return field(default=default, metadata={"help": help, **kwargs})


@dataclass
class Args:
    # --- what to train ---
    env_id: str = option("PoolBreak-v0", "PoolBreak-v0 (the break: one shot), PoolBreakRun-v0 (play on), "
                         "PoolNineBall-v0 or PoolEightBall-v0 (a game against --opponent)")
    algo: str = option("ppo", "learning algorithm; value: the learned player's recipe (game envs: a value net over "
                       "the search player's candidate shots, fitted to its simulated values; agents/learned_train.py)",
                       choices=("ppo", "sac", "value"))
    timesteps: int = option(250_000, "total environment steps (shots) to train for")
    n_envs: int = option(2, "parallel environments")
    vec_env: str = option("native", "native: one process, every step's shots in one simulate_batch call on all "
                          "cores (pool_env.envs.sb3.SB3VecEnv); auto: SB3 subprocesses when n_envs > 1",
                          choices=("native", "auto", "subproc", "dummy"))
    seed: int = option(0, "seed of the model and the training envs")
    spin: bool = option(False, "add the cue-tip offset (side, top) to the action")
    randomize_cue: bool = option(False, "start the cue ball anywhere in the kitchen")
    # --- game envs only ---
    opponent: str = option("ghost_ball", "game envs: the opponent of the evaluations (and of training unless "
                           "--practice)", choices=("ghost_ball", "random"))
    practice: bool = option(False, "game envs: train without an opponent (run-outs: +1 per ball pocketed legally, "
                            "+1 for the rack; the episode ends when the turn passes), evaluate against --opponent")
    ghost_ball_action: bool = option(False, "game envs: act through pool_env.envs.wrappers.GhostBallAction (choose "
                                     "ball and pocket, correct the ghost-ball aim, speed, tip, placement)")
    shaping: bool = option(False, "game envs against an opponent: +0.1 per ball pocketed legally, -0.1 per foul")
    noise: str = option("none", "game envs: the cue's noise in every game (none, or olympiad: "
                        "pool_env.game.NOISE_PRESETS)", choices=("none", "olympiad"))
    # --- the learned player (--algo value) ---
    data_games: int = option(800, "--algo value: games per labelling round (each decision's candidate shots simulated)")
    rounds: int = option(2, "--algo value: labelling rounds (the first on ghost-ball self-play, each later one on "
                         "the last net's games against the ghost-ball player)")
    fit_epochs: int = option(30, "--algo value: passes over the labelled data in each fit of the nets")
    pot_positions: int = option(40000, "--algo value: random two-ball positions whose ghost-ball pots are simulated "
                                "to fit the pot net the value nets read (0: no pot net)")
    pot_games: int = option(7500, "--algo value: ghost-ball games whose positions' menu pots are simulated too, each "
                            "alone with its ball, for the pot net (0: only the random positions)")
    safe_positions: int = option(30000, "--algo value: random two-ball positions whose safeties and kicks are "
                                 "simulated to fit the safety net the value nets read (0: none; needs the pot net)")
    combos: bool = option(False, "--algo value: the value nets also read where each shot sends its object ball and "
                          "the cue ball into a third ball, and that ball's line to a pocket (needs the safety net)")
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
    progress_every: float = option(10.0, "seconds between progress lines in train.log, also on stdout unless the "
                                   "progress bar draws on a terminal (0: none)")
    min_timesteps: int = option(25_000, "a run shorter than this makes no claim against the baselines")


def parse_args(argv=None) -> tuple[Args, bool]:
    """The options, checked before anything is made (a bad one ends in one line on stderr and exit
    status 2), and whether an error shows its traceback (--debug, or POOL_ENV_DEBUG=1)."""
    parser = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n")[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    for f in dataclasses.fields(Args):
        flag = "--" + f.name.replace("_", "-")
        meta = dict(f.metadata)
        if f.type in ("bool", bool):
            parser.add_argument(flag, default=f.default, action=argparse.BooleanOptionalAction, **meta)
        else:
            kind = {"int": int, "float": float, "str": str}.get(str(f.type).split(" ")[0], str)
            parser.add_argument(flag, default=f.default, type=kind, **meta)
    # Not an Args field: how errors are shown is no part of the run (args.json).
    parser.add_argument("--debug", action="store_true",
                        help="on an error, the full traceback instead of one line (also POOL_ENV_DEBUG=1)")
    options = vars(parser.parse_args(argv))
    debug = options.pop("debug") or os.environ.get("POOL_ENV_DEBUG", "") not in ("", "0")
    args = Args(**options)
    try:
        check_args(args)
    except ValueError as exc:
        if debug:
            raise
        parser.exit(2, f"{parser.prog}: {exc}\n")
    return args, debug


AT_LEAST = {"data_games": 1, "rounds": 1, "fit_epochs": 1, "timesteps": 1, "n_envs": 1, "seed": 0, "n_steps": 1,
            "batch_size": 2, "n_epochs": 1, "eval_episodes": 1, "eval_seed": 0, "curve_points": 0, "curve_episodes": 1,
            "video_episodes": 0, "progress_every": 0, "min_timesteps": 0,
            "pot_positions": 0, "pot_games": 0, "safe_positions": 0}  # least values (SB3: batch_size 2)


def check_args(args: Args) -> None:
    """ValueError naming the first bad option. Every check is made here, before the run folder:
    a mistake found later would leave a half-made run folder behind, or fail after minutes of work."""
    import gymnasium as gym

    import pool_env  # noqa: F401  (registers the ids)

    env_ids = [env_id for env_id, spec in gym.registry.items() if str(spec.entry_point).startswith("pool_env.")]
    if args.env_id not in env_ids:
        raise ValueError(f"--env-id {args.env_id} is not a pool_env env; choose one of {', '.join(env_ids)}")
    for name, least in AT_LEAST.items():
        value = getattr(args, name)
        if value is not None and not value >= least:
            raise ValueError(f"--{name.replace('_', '-')} must be >= {least}, got {value}")
    from agents.learned_train import ROUND_SEEDS

    if args.algo == "value" and args.seed + args.rounds * ROUND_SEEDS > args.eval_seed:
        raise ValueError(f"--algo value: the labelled games' seeds (--seed {args.seed} + {ROUND_SEEDS:,} a round) "
                         f"would reach the evaluation's (--eval-seed {args.eval_seed})")
    if args.algo == "value" and not is_game(args.env_id):
        raise ValueError(f"--algo value trains a game player: --env-id PoolNineBall-v0 or PoolEightBall-v0, "
                         f"not {args.env_id}")
    if not args.learning_rate > 0:
        raise ValueError(f"--learning-rate must be > 0, got {args.learning_rate}")
    if not 0 <= args.gamma <= 1:
        raise ValueError(f"--gamma must be between 0 and 1, got {args.gamma}")
    if not all(n.strip().isdigit() and int(n) > 0 for n in args.net_arch.split(",") if n):
        raise ValueError(f"--net-arch must be positive layer sizes separated by commas (e.g. 64,64), "
                         f"got {args.net_arch!r}")


def cli(argv=None) -> int:
    """The command: the checked options, then `main`. An OSError on the way (--out not writable, a
    full disk) ends in one line on stderr and exit status 2, unless --debug."""
    args, debug = parse_args(argv)
    try:
        main(args)
    except OSError as exc:
        if debug:
            raise
        print(f"{PROG}: {exc}", file=sys.stderr)
        return 2
    return 0


def main(args: Args) -> Path:
    """The whole job. Each phase is a function below, in the order it runs. Each imports what it
    needs (not the top of the file): subprocess envs re-import this file, and --help stays instant."""
    from agents.report import plot_learning_curve
    from agents.run_eval import film, final_evaluation

    started = time.perf_counter()
    run = open_run(args)                                 # run folder, logging, the env's facts, compiled physics
    if args.algo == "value":                             # the learned player: labelled data and a value net
        return learned_player(args, run)
    model = make_model(args, run)                        # vectorised training envs and the PPO or SAC model
    model, curve, train_time = train(args, run, model)   # learn, keep the best checkpoint
    summary = final_evaluation(args, run, model, curve)  # every agent on the same seeds: table, verdict, results.md
    summary["wall_time_s"]["training"] = train_time
    baseline_rewards = {name: a["reward"]["mean"] for name, a in summary["agents"].items() if name != "trained"}
    plot_learning_curve(run.dir, curve.points, baseline_rewards, f"{args.algo.upper()} on {args.env_id}",
                        curve.best if args.keep_best else None)
    log.info("learning curve: %s", run.dir / "learning_curve.png")
    if args.video_episodes:
        summary["wall_time_s"]["video"] = film(args, run, model)
    summary["wall_time_s"]["total"] = time.perf_counter() - started
    (run.dir / "eval.json").write_text(json.dumps(summary, indent=2))
    log.info("eval.json: %s; total wall time %.0f s", run.dir / "eval.json", summary["wall_time_s"]["total"])
    log.info("TensorBoard: tensorboard --logdir %s", run.dir / "tb")
    log.info("run folder: %s", run.dir.resolve())
    return run.dir


def learned_player(args: Args, run) -> Path:
    """`--algo value`: `agents.learned_train.recipe` in the run folder (learned.npz, learned.json)."""
    from agents.learned_train import recipe

    game = "nine_ball" if args.env_id == "PoolNineBall-v0" else "eight_ball"
    noise = None if args.noise == "none" else args.noise
    recipe(game, noise, args.data_games, args.rounds, run.eval_seeds, args.seed, args.n_envs, run.dir,
           log=log.info, epochs=args.fit_epochs, pot_positions=args.pot_positions,
           safe_positions=args.safe_positions, combos=args.combos, pot_games=args.pot_games)
    log.info("run folder: %s", run.dir.resolve())
    return run.dir


@dataclass
class Run:
    """What the phases share: the run folder and the env's fixed facts."""
    dir: Path
    env_kwargs: dict
    probe: object            # one env: its spaces and table, for the baselines
    multi_shot: bool
    eval_seeds: list[int]    # the final evaluation's, the same for every agent
    curve_seeds: list[int]   # the learning curve's (and the best checkpoint's), disjoint from eval_seeds
    game: bool = False       # a game env: judged by the win rate against args.opponent
    train_kwargs: dict | None = None  # the training envs' kwargs, when not env_kwargs (game practice)


def open_run(args: Args) -> Run:
    """The run folder and logging (everything this run makes goes in the folder), args.json, the env."""
    import pool_env
    from agents.run_eval import quiet_env
    from pool_env.physics import warm_up

    name = args.run_name or f"{datetime.now():%Y%m%d-%H%M%S}-{args.env_id}-{args.algo}-s{args.seed}"
    run_dir = Path(args.out) / name
    run_dir.mkdir(parents=True, exist_ok=True)
    log.setLevel(logging.INFO)
    log.handlers.clear()
    log.propagate = False
    console = logging.StreamHandler(sys.stdout)
    if args.progress_bar and sys.stdout.isatty():  # the bar shows progress there; train.log still gets the lines
        console.addFilter(lambda record: not getattr(record, "progress", False))
    for handler in (console, logging.FileHandler(run_dir / "train.log")):
        handler.setFormatter(logging.Formatter("%(asctime)s %(message)s", "%H:%M:%S"))
        log.addHandler(handler)
    log.info("run folder: %s", run_dir.resolve())
    (run_dir / "args.json").write_text(json.dumps(dataclasses.asdict(args), indent=2))

    game = is_game(args.env_id)
    env_kwargs = {"opponent": args.opponent} if game else {"spin": args.spin, "randomize_cue": args.randomize_cue}
    if game and args.noise != "none":
        env_kwargs["noise"] = args.noise
    train_kwargs = ({"opponent": None} if args.practice else {**env_kwargs, "shaping": args.shaping}) if game else None
    probe = quiet_env(args.env_id, **env_kwargs)
    multi_shot = probe.unwrapped.max_shots > 1
    default_episodes = 400 if args.algo == "value" else 200 if game else 100 if multi_shot else 1000
    eval_episodes = args.eval_episodes or default_episodes
    eval_seeds = list(range(args.eval_seed, args.eval_seed + eval_episodes))
    curve_seeds = list(range(args.eval_seed + 10_000_000, args.eval_seed + 10_000_000 + args.curve_episodes))
    if args.algo == "value":
        log.info("env %s %s, pool_env %s, the learned player: %d rounds of %d labelled games on %d processes",
                 args.env_id, env_kwargs, pool_env.__version__, args.rounds, args.data_games, args.n_envs)
    else:
        log.info("env %s %s, pool_env %s, algo %s, %d timesteps on %d envs", args.env_id, env_kwargs,
                 pool_env.__version__, args.algo.upper(), args.timesteps, args.n_envs)
    if game and args.algo != "value":
        log.info("training envs %s%s", train_kwargs, ", through GhostBallAction" if args.ghost_ball_action else "")
    # Compile the physics (or load it from numba's cache) once, here, with a word on a first
    # run, rather than in each worker process behind a frozen progress bar.
    log.info("physics ready in %.1f s", warm_up())
    return Run(run_dir, env_kwargs, probe, multi_shot, eval_seeds, curve_seeds, game, train_kwargs)


def is_game(env_id: str) -> bool:
    """True for the game envs (PoolNineBall-v0, PoolEightBall-v0): `pool_env.envs.game_env.PoolGameEnv`."""
    import gymnasium as gym

    import pool_env  # noqa: F401  (registers the ids)

    return str(gym.spec(env_id).entry_point).startswith("pool_env.envs.game_env:")


def make_model(args: Args, run: Run):
    """Vectorised training envs (Monitor logs every episode to monitor/*.csv: the learning curve) and the model."""
    import torch
    from stable_baselines3 import PPO, SAC
    from stable_baselines3.common.env_util import make_vec_env
    from stable_baselines3.common.utils import LinearSchedule
    from stable_baselines3.common.vec_env import DummyVecEnv, SubprocVecEnv

    from agents.run_eval import quiet_env

    torch.set_num_threads(1)  # small networks: one thread is fastest, and leaves the cores to the envs
    (run.dir / "monitor").mkdir(exist_ok=True)
    train_kwargs = run.env_kwargs if run.train_kwargs is None else run.train_kwargs
    wrapper = None
    if run.game and args.ghost_ball_action:
        from pool_env.envs.wrappers import GhostBallAction

        wrapper = GhostBallAction  # a Python wrapper: SB3's subprocess envs rather than the native vector env
    if args.vec_env == "native" and wrapper is None:
        # The same shots as DummyVecEnv over gym.make envs (tests/test_sb3_vec.py), simulated together.
        from stable_baselines3.common.vec_env import VecMonitor

        from pool_env.envs.sb3 import SB3VecEnv

        quiet_env(args.env_id)  # silences gymnasium's per-shot warnings in this process, as in the workers
        envs = SB3VecEnv(args.env_id, num_envs=args.n_envs, **train_kwargs)
        envs.seed(args.seed)
        envs = VecMonitor(envs, filename=str(run.dir / "monitor" / "native"))
    else:
        vec_cls = {"subproc": SubprocVecEnv, "dummy": DummyVecEnv}.get(args.vec_env)
        vec_cls = vec_cls or (SubprocVecEnv if args.n_envs > 1 else DummyVecEnv)
        envs = make_vec_env(functools.partial(quiet_env, args.env_id, **train_kwargs), n_envs=args.n_envs,
                            seed=args.seed, vec_env_cls=vec_cls, monitor_dir=str(run.dir / "monitor"),
                            wrapper_class=wrapper)

    net_arch = [int(n) for n in args.net_arch.split(",") if n]
    learning_rate = args.learning_rate
    if args.lr_schedule == "linear":
        learning_rate = LinearSchedule(args.learning_rate, 0.0, 1.0)  # SB3's own class: pickles cleanly
    common = dict(learning_rate=learning_rate, batch_size=args.batch_size, gamma=args.gamma, seed=args.seed,
                  device="cpu", tensorboard_log=str(run.dir / "tb"), verbose=0)
    if args.algo == "ppo":
        return PPO("MlpPolicy", envs, n_steps=args.n_steps, n_epochs=args.n_epochs,
                   policy_kwargs=dict(net_arch=net_arch, log_std_init=args.log_std_init), **common)
    return SAC("MlpPolicy", envs, learning_starts=1000, policy_kwargs=dict(net_arch=net_arch), **common)


def train(args: Args, run: Run, model):
    """Learn (callbacks: agents/train_callbacks.py), save the last model, then keep the best
    learning-curve checkpoint as model.zip."""
    from agents.train_callbacks import make_callbacks

    curve, callbacks = make_callbacks(args, run)
    train_start = time.perf_counter()
    model.learn(total_timesteps=args.timesteps, callback=callbacks, progress_bar=args.progress_bar, tb_log_name="tb")
    if args.curve_points and curve.points[-1]["timesteps"] != model.num_timesteps:
        curve.measure()  # the final policy, unless the last evaluation already saw it
    train_time = time.perf_counter() - train_start
    model.get_env().close()
    model.save(run.dir / "last_model.zip")
    log.info("trained %d steps in %.0f s (%.0f steps/s)", model.num_timesteps, train_time,
             model.num_timesteps / train_time)
    if args.keep_best and curve.best is not None:
        model = type(model).load(run.dir / "best_model.zip", device="cpu")
        untrained = " (the first evaluation, before any policy update: the untrained policy)"
        log.info("keeping the best checkpoint: %d steps, reward %+.3f on the %d learning-curve seeds%s",
                 curve.best["timesteps"], curve.best["reward"]["mean"], len(run.curve_seeds),
                 untrained if curve.kept_untrained else "")
    model.save(run.dir / "model.zip")
    log.info("model saved to %s", run.dir / "model.zip")
    if curve.failed_shots:
        log.info("%d training shots hit the simulator's event cap (episode truncated, reward 0)", curve.failed_shots)
    return model, curve, train_time


if __name__ == "__main__":
    sys.exit(cli())
