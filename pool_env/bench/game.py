"""`python -m pool_env.bench game`: the game core's figures: `Game.evaluate` against restore + play, and env throughput.

Measured as ratios taken in one run (the machine is shared: an absolute time varies by half):

- `Game.evaluate` of 256 candidate shots from a mid-game 9-ball position (after a break),
  against a loop of `restore` + `play` of the same shots (target: evaluate 3x as fast);
- the `PoolBreakRun-v0` native vector env (256 sub-envs, every core) in shots/s (target 8,000
  on 2 cores);
- `PoolNineBall-v0` against the random player, agent steps/s on one core (target 2,500);
- `PoolNineBall-v0` and `PoolEightBall-v0` against the ghost-ball player, agent steps/s on one
  core (target 1,000: the built-in opponent's planning is most of it).

- `PoolNineBall-v0` and `PoolEightBall-v0` against the ghost-ball player in the native vector
  env (64 sub-envs, one thread: the opponents' shots of a round planned in one call), agent
  steps/s (no target: beside the single env's figure);
- the search player (`make_player("search", ...)`, PoolNineBall-v0, its default budget of
  600 simulations) on mid-game positions (the ghost-ball player's first decisions of seeded
  games), without noise and with `noise="olympiad"`: simulated shots per second of decision
  time (no target alone; with `--against`, ours / theirs: target 3x an older checkout's).

`--against PATH` also measures the env and search figures of another checkout (its own fresh
processes, taking turns with ours) and prints ours / theirs.
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
SEARCH_RATIO_TARGET = 3.0  # the search's simulations/s against an older checkout's (`--against`)
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
def vector(env_id):
    envs = gym.make_vec(env_id, num_envs=64, vectorization_mode="vector_entry_point", opponent="ghost_ball",
                        threads=1)
    size = envs.single_action_space.shape[0]
    envs.reset(seed=0); rng = np.random.default_rng(2); envs.step(rng.uniform(-1, 1, (64, size)).astype(np.float32))
    n, start = 0, time.process_time()
    while time.process_time() - start < seconds:
        envs.step(rng.uniform(-1, 1, (64, size)).astype(np.float32)); n += 64
    return n / (time.process_time() - start)
print(json.dumps({"nine_ball_vs_random": game("PoolNineBall-v0", "random"), "run_vector": run(),
                  "nine_ball_vs_ghost_ball": game("PoolNineBall-v0", "ghost_ball"),
                  "eight_ball_vs_ghost_ball": game("PoolEightBall-v0", "ghost_ball"),
                  "nine_ball_vector_vs_ghost_ball": vector("PoolNineBall-v0"),
                  "eight_ball_vector_vs_ghost_ball": vector("PoolEightBall-v0")}))
"""
SEARCH_SCRIPT = r"""
import json, sys, time
import gymnasium as gym
import pool_env
from pool_env.players import make_player
decisions = int(sys.argv[1])
out = {}
for noise in (None, "olympiad"):
    env = gym.make("PoolNineBall-v0", opponent="ghost_ball", noise=noise)
    ghost, agent = make_player("ghost_ball", env), make_player("search", env, seed=0)
    observations, seed = [], 0
    while len(observations) < decisions:  # the ghost-ball player's first decisions after the break
        obs, _ = env.reset(seed=seed); steps, done = 0, False
        while not done and steps < 8:
            if steps: observations.append(obs)
            obs, _, te, tr, _ = env.step(ghost.act(obs)); done, steps = te or tr, steps + 1
        seed += 1
    agent.act(observations[0])
    sims, spent = 0, 0.0
    for k, obs in enumerate(observations[:decisions]):
        agent.reset(seed=k); start = time.perf_counter(); agent.act(obs); spent += time.perf_counter() - start
        sims += agent.last_stats["simulations"]
    out["search_" + (noise or "no_noise")] = sims / spent
print(json.dumps(out))
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


def env_figures(path: str | None, seconds: float, script: str = ENV_SCRIPT) -> dict:
    """The env figures (or the search's, `script=SEARCH_SCRIPT` with `seconds` the decisions
    timed) measured in a fresh process of the checkout at `path` (None: the one this module is in)."""
    env = dict(os.environ)
    path = str(Path(__file__).resolve().parents[2]) if path is None else path  # this checkout, not an installed one
    env["PYTHONPATH"] = path + os.pathsep + env.get("PYTHONPATH", "")
    # From a neutral folder: `python -c` puts the working folder first on sys.path, where a
    # checkout would shadow the one asked for.
    with tempfile.TemporaryDirectory() as folder:
        out = subprocess.run([sys.executable, "-c", script, str(seconds)], capture_output=True, text=True,
                             env=env, check=True, cwd=folder)
    return json.loads(out.stdout.strip().splitlines()[-1])


def both(path, argument, script) -> tuple[dict, dict | None]:
    """(ours, theirs): ours alone, or with `path` ours before and after theirs (averaged)."""
    ours = env_figures(None, argument, script)
    if path is None:
        return ours, None
    theirs = env_figures(str(Path(path).resolve()), argument, script)
    after = env_figures(None, argument, script)
    return {k: (v + after[k]) / 2 for k, v in ours.items()}, theirs


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m pool_env.bench game", description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=5, help="timed runs of each (best taken)")
    parser.add_argument("--seconds", type=float, default=3.0, help="seconds per env figure")
    parser.add_argument("--threads", type=int, default=None, help="evaluate's threads (default: every core)")
    parser.add_argument("--against", metavar="PATH", help="another checkout: its env and search figures beside ours")
    parser.add_argument("--decisions", type=int, default=30, help="search decisions timed per noise setting (0: none)")
    args = parser.parse_args(argv)
    if args.against is not None and not (Path(args.against) / "pool_env" / "__init__.py").is_file():
        parser.error(f"--against {args.against}: no pool_env package there")
    e = evaluate_ratio(args.repeats, args.threads)
    ours, theirs = both(args.against, args.seconds, ENV_SCRIPT)
    if args.decisions > 0:
        search, search_theirs = both(args.against, args.decisions, SEARCH_SCRIPT)
        ours = {**ours, **search}
        theirs = None if theirs is None else {**theirs, **search_theirs}
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
    for key, label, unit in (("nine_ball_vector_vs_ghost_ball", "PoolNineBall-v0 against the ghost-ball player, "
                              "native vector env of 64, one thread", "steps/s"),
                             ("eight_ball_vector_vs_ghost_ball", "PoolEightBall-v0 against the ghost-ball player, "
                              "native vector env of 64, one thread", "steps/s"),
                             ("search_no_noise", "search player, 9-ball mid-game, no noise", "simulations/s"),
                             ("search_olympiad", "search player, 9-ball mid-game, olympiad noise", "simulations/s")):
        if key not in ours:
            continue
        if theirs is None or key not in theirs:
            print(f"| {label} | {ours[key]:,.0f} {unit} | | |{' | |' if theirs else ''}")
            continue
        ratio, target = ours[key] / theirs[key], SEARCH_RATIO_TARGET if key.startswith("search") else None
        met = "" if target is None else ("yes" if ratio >= target else "NO")
        print(f"| {label} | {ours[key]:,.0f} {unit} | {'' if target is None else f'>= {target:.0f}x theirs'} | "
              f"{met} | {theirs[key]:,.0f} | {ratio:.2f} |")
    return 0
