"""`python -m pool_env.bench game`: the game core's figures: `Game.evaluate` against restore + play, and env throughput.

Measured as ratios taken in one run (the machine is shared: an absolute time varies by half):

- `Game.evaluate` of 256 candidate shots from a mid-game 9-ball position (after a break),
  against a loop of `restore` + `play` of the same shots (target: evaluate 3x as fast);
- the `PoolBreakRun-v0` native vector env (256 sub-envs, every core) in shots/s (target 8,000
  on 2 cores);
- `PoolNineBall-v0` against the random player, agent steps/s on one core (target 2,500);
- `PoolNineBall-v0` and `PoolEightBall-v0` against the ghost-ball player, agent steps/s on one
  core (target 1,000: the built-in opponent's planning is most of it).

`--against PATH` also measures the env figures of another checkout (its own fresh processes,
taking turns with ours) and prints ours / theirs.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

EVALUATE_TARGET, VECTOR_TARGET, GAME_TARGET, GHOST_BALL_TARGET = 3.0, 8000.0, 2500.0, 1000.0
CANDIDATES = 256
ENV_SCRIPT = r"""
import json, sys, time
import numpy as np, gymnasium as gym
import pool_env
seconds = float(sys.argv[1])
def game(env_id, opponent):
    env = gym.make(env_id, opponent=opponent)
    size = env.action_space.shape[0]
    env.reset(seed=0); rng = np.random.default_rng(1); env.step(rng.uniform(-1, 1, size).astype(np.float32))
    n, start = 0, time.process_time()
    while time.process_time() - start < seconds:
        _, _, te, tr, _ = env.step(rng.uniform(-1, 1, size).astype(np.float32)); n += 1
        if te or tr: env.reset()
    return n / (time.process_time() - start)
def run():
    envs = gym.make_vec("PoolBreakRun-v0", num_envs=256, vectorization_mode="vector_entry_point")
    envs.reset(seed=0); rng = np.random.default_rng(0); envs.step(rng.uniform(-1, 1, (256, 2)).astype(np.float32))
    n, start = 0, time.perf_counter()
    while time.perf_counter() - start < seconds:
        envs.step(rng.uniform(-1, 1, (256, 2)).astype(np.float32)); n += 256
    return n / (time.perf_counter() - start)
print(json.dumps({"nine_ball_vs_random": game("PoolNineBall-v0", "random"), "run_vector": run(),
                  "nine_ball_vs_ghost_ball": game("PoolNineBall-v0", "ghost_ball"),
                  "eight_ball_vs_ghost_ball": game("PoolEightBall-v0", "ghost_ball")}))
"""


def mid_game_position(seed: int = 3):
    """A 9-ball game after a full break at the 1 from the head spot, and 256 candidate shots."""
    import numpy as np

    from pool_env import rules
    from pool_env.game import Game, Shot

    game = Game("nine_ball", seed=seed)
    head = rules.head_spot(game.table)
    game.play(Shot.aimed(game.balls.xy[1] - np.array(head), 9.0, place=head))
    rng = np.random.default_rng(seed)
    angles, speeds, tops = rng.uniform(-np.pi, np.pi, CANDIDATES), rng.uniform(0.5, 4.0, CANDIDATES), \
        rng.uniform(-0.3, 0.3, CANDIDATES)
    return game, [Shot.aimed((np.cos(a), np.sin(a)), s, (0.0, t)) for a, s, t in zip(angles, speeds, tops)]


def evaluate_ratio(repeats: int, threads: int | None) -> dict:
    """Best-of-`repeats` seconds of evaluate and of the restore + play loop, taken in turns."""
    game, shots = mid_game_position()
    snapshot = game.snapshot()

    def loop():
        for shot in shots:
            game.restore(snapshot)
            game.play(shot)
        game.restore(snapshot)

    times = {"evaluate": [], "loop": []}
    loop()
    game.evaluate(shots, threads=threads)
    for _ in range(repeats):
        for name, run in (("loop", loop), ("evaluate", lambda: game.evaluate(shots, threads=threads))):
            start = time.perf_counter()
            run()
            times[name].append(time.perf_counter() - start)
    best = {name: min(values) for name, values in times.items()}
    return {"evaluate_s": best["evaluate"], "loop_s": best["loop"], "ratio": best["loop"] / best["evaluate"]}


def env_figures(path: str | None, seconds: float) -> dict:
    """The env figures measured in a fresh process of the checkout at `path` (None: this one)."""
    env = dict(os.environ)
    if path is not None:
        env["PYTHONPATH"] = path + os.pathsep + env.get("PYTHONPATH", "")
    # From a neutral folder: `python -c` puts the working folder first on sys.path, where a
    # checkout would shadow the one asked for.
    with tempfile.TemporaryDirectory() as folder:
        out = subprocess.run([sys.executable, "-c", ENV_SCRIPT, str(seconds)], capture_output=True, text=True,
                             env=env, check=True, cwd=folder)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m pool_env.bench game", description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=5, help="timed runs of each (best taken)")
    parser.add_argument("--seconds", type=float, default=3.0, help="seconds per env figure")
    parser.add_argument("--threads", type=int, default=None, help="evaluate's threads (default: every core)")
    parser.add_argument("--against", metavar="PATH", help="another checkout: its env figures beside ours")
    args = parser.parse_args(argv)
    if args.against is not None and not (Path(args.against) / "pool_env" / "__init__.py").is_file():
        parser.error(f"--against {args.against}: no pool_env package there")
    e = evaluate_ratio(args.repeats, args.threads)
    ours, theirs = env_figures(None, args.seconds), None
    if args.against:
        theirs = env_figures(str(Path(args.against).resolve()), args.seconds)
        ours = {k: (v + env_figures(None, args.seconds)[k]) / 2 for k, v in ours.items()}  # ours before and after
    print(f"| figure | ours | target | met |{' theirs | ours / theirs |' if theirs else ''}")
    print(f"| --- | --- | --- | --- |{' --- | --- |' if theirs else ''}")
    print(f"| Game.evaluate of {CANDIDATES} shots / a restore + play loop | {e['ratio']:.2f}x "
          f"({e['evaluate_s'] * 1e3:.1f} ms / {e['loop_s'] * 1e3:.1f} ms) | >= {EVALUATE_TARGET:.0f}x | "
          f"{'yes' if e['ratio'] >= EVALUATE_TARGET else 'NO'} |{' | |' if theirs else ''}")
    rows = (("run_vector", f"PoolBreakRun-v0 native vector env, 256 sub-envs, {os.cpu_count()} cores", VECTOR_TARGET,
             "shots/s"), ("nine_ball_vs_random", "PoolNineBall-v0 against the random player, one core", GAME_TARGET,
                          "steps/s"),
            ("nine_ball_vs_ghost_ball", "PoolNineBall-v0 against the ghost-ball player, one core", GHOST_BALL_TARGET,
             "steps/s"),
            ("eight_ball_vs_ghost_ball", "PoolEightBall-v0 against the ghost-ball player, one core", GHOST_BALL_TARGET,
             "steps/s"))
    for key, label, target, unit in rows:
        extra = f" {theirs[key]:,.0f} | {ours[key] / theirs[key]:.2f} |" if theirs else ""
        print(f"| {label} | {ours[key]:,.0f} {unit} | >= {target:,.0f} | {'yes' if ours[key] >= target else 'NO'} |"
              + extra)
    return 0
