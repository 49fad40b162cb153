"""`python -m pool_env.bench vector`: shots/s of the native vector env beside its peers, and of simulate_batch.

A "shot" is a step that simulates one (an autoreset step that only resets does not count:
under Gymnasium's NEXT_STEP mode the step after an episode ends is such a step for that
sub-env). Random actions, all in one run, so the ratios compare like with like on a noisy
machine. Targets for 2 cores.
"""

from __future__ import annotations

import argparse
import functools
import os
import subprocess
import sys
import time
import warnings

import numpy as np

TARGETS = {
    "break_shots": 4000.0,  # PoolBreak-v0 through the native vector env, shots/s
    "run_shots": 8000.0,  # PoolBreakRun-v0, shots/s
    "vs_subproc": 3.5,  # native / SB3 SubprocVecEnv with 2 workers (PoolBreak-v0)
    "vs_async": 2.0,  # native / Gymnasium AsyncVectorEnv with 2 workers (PoolBreak-v0)
    "batch_threads": 1.8,  # simulate_batch, 2 threads / 1 thread
    "memory_mb": 200.0,  # resident memory of 256 native envs beyond the interpreter
}


def _gym_vector(env_id, num_envs, mode):
    """A Gymnasium vector env: mode "native" (the vector entry point, SAME_STEP autoreset),
    "sync" or "async" (Gymnasium's own, default NEXT_STEP autoreset)."""
    import gymnasium as gym

    import pool_env  # noqa: F401  (registers the ids)

    if mode == "native":
        return gym.make_vec(env_id, num_envs=num_envs, vectorization_mode="vector_entry_point",
                            autoreset_mode=gym.vector.AutoresetMode.SAME_STEP), True
    return gym.make_vec(env_id, num_envs=num_envs, vectorization_mode=mode), False


def _gym_shots_per_second(env_id, num_envs, mode, seconds, seed):
    env, same_step = _gym_vector(env_id, num_envs, mode)
    env.action_space.seed(seed)
    env.reset(seed=seed)
    env.step(env.action_space.sample())  # compile or load the engine, start the workers
    shots, resetting = 0, np.zeros(num_envs, dtype=bool)
    start = time.perf_counter()
    while time.perf_counter() - start < seconds:
        _, _, terminated, truncated, _ = env.step(env.action_space.sample())
        shots += num_envs if same_step else int(np.count_nonzero(~resetting))
        resetting = terminated | truncated
    rate = shots / (time.perf_counter() - start)
    env.close()
    return rate


def make_env(env_id):
    """One env, made in whichever process calls this (SB3's worker processes import nothing
    of ours by themselves: the import registers the ids)."""
    import gymnasium as gym

    import pool_env  # noqa: F401

    return gym.make(env_id)


def _sb3_shots_per_second(env_id, num_envs, kind, seconds, seed):
    """SB3 vector envs reset an ended episode within the same step: every step is a shot."""
    from stable_baselines3.common.env_util import make_vec_env
    from stable_baselines3.common.vec_env import DummyVecEnv, SubprocVecEnv

    cls = SubprocVecEnv if kind == "subproc" else DummyVecEnv
    env = make_vec_env(functools.partial(make_env, env_id), n_envs=num_envs, seed=seed, vec_env_cls=cls)
    rng = np.random.default_rng(seed)
    low, high = env.action_space.low, env.action_space.high
    env.reset()
    env.step(rng.uniform(low, high, size=(num_envs,) + low.shape).astype(np.float32))
    shots, start = 0, time.perf_counter()
    while time.perf_counter() - start < seconds:
        env.step(rng.uniform(low, high, size=(num_envs,) + low.shape).astype(np.float32))
        shots += num_envs
    rate = shots / (time.perf_counter() - start)
    env.close()
    return rate


def _batch_rates(shots, repeats):
    """Breaks per second: a Python loop of simulate, and simulate_batch at 1 and 2 threads."""
    from pool_env.bench.speed import break_shot
    from pool_env.physics import Physics, simulate, simulate_batch

    physics, scenes = Physics.standard(), [break_shot(seed) for seed in range(shots)]
    table = scenes[0][1]
    balls = [b for b, _ in scenes]
    simulate_batch(balls[:4], table, physics)

    def best(fn):
        times = []
        for _ in range(repeats):
            start = time.perf_counter()
            fn()
            times.append(time.perf_counter() - start)
        return shots / min(times)

    loop = best(lambda: [simulate(b, table, physics) for b in balls])
    one = best(lambda: simulate_batch(balls, table, physics, threads=1))
    two = best(lambda: simulate_batch(balls, table, physics, threads=2))
    return loop, one, two


MEMORY_PROBE = (
    "import gymnasium as gym, pool_env, resource, sys\n"
    "def rss():\n"
    "    return int(open('/proc/self/statm').read().split()[1]) * 4096 / 2**20\n"
    "base = rss()\n"
    "env = gym.make_vec('PoolBreak-v0', num_envs=256, vectorization_mode='vector_entry_point')\n"
    "env.reset(seed=0)\n"
    "for _ in range(5):\n"
    "    env.step(env.action_space.sample())\n"
    "print(rss() - base)\n"
)


def _memory_mb():
    """Resident memory (MB) that 256 native envs (and five steps) add to an interpreter that has
    already imported gymnasium and pool_env (and loaded nothing compiled)."""
    out = subprocess.run([sys.executable, "-c", MEMORY_PROBE], capture_output=True, text=True, check=True)
    return float(out.stdout.strip().splitlines()[-1])


def _row(name, value, unit, target=None, ratio=None):
    met = "" if target is None else ("yes" if value >= target else "NO")
    tgt = "" if target is None else f">= {target:,.0f}" if unit == "shots/s" else f">= {target}"
    return f"| {name} | {value:,.0f} {unit} | {ratio or ''} | {tgt} | {met} |"


def _env_rows(env_id, sizes, seconds, seed):
    rows, native = [], {}
    for n in sizes:
        native[n] = _gym_shots_per_second(env_id, n, "native", seconds, seed)
    best = max(native.values())
    target = TARGETS["break_shots" if env_id == "PoolBreak-v0" else "run_shots"]
    for n, rate in native.items():
        rows.append(_row(f"{env_id} native vector env, num_envs {n}", rate, "shots/s",
                         target if rate == best else None))
    peers = {
        "SB3 SubprocVecEnv, 2 workers": _sb3_shots_per_second(env_id, 2, "subproc", seconds, seed),
        "SB3 DummyVecEnv, 8 envs": _sb3_shots_per_second(env_id, 8, "dummy", seconds, seed),
        "Gymnasium AsyncVectorEnv, 2 workers": _gym_shots_per_second(env_id, 2, "async", seconds, seed),
        "Gymnasium SyncVectorEnv, 8 envs": _gym_shots_per_second(env_id, 8, "sync", seconds, seed),
    }
    for name, rate in peers.items():
        ratio = best / rate
        target = None
        if env_id == "PoolBreak-v0" and name.startswith("SB3 Subproc"):
            target = TARGETS["vs_subproc"]
        if env_id == "PoolBreak-v0" and name.startswith("Gymnasium Async"):
            target = TARGETS["vs_async"]
        met = "" if target is None else f" (target >= {target:.1f}x: {'met' if ratio >= target else 'NOT met'})"
        rows.append(_row(f"{env_id} {name}", rate, "shots/s", None, f"native best / this = {ratio:.2f}{met}"))
    return rows


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m pool_env.bench vector", description=__doc__.split("\n")[0])
    parser.add_argument("--seconds", type=float, default=3.0, help="seconds per measurement")
    parser.add_argument("--sizes", default="1,8,64,256", help="num_envs of the native vector env")
    parser.add_argument("--batch-shots", type=int, default=256, help="breaks per simulate_batch call")
    parser.add_argument("--quick", action="store_true", help="1 s per measurement, num_envs 8 and 64")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    seconds, sizes = (1.0, [8, 64]) if args.quick else (args.seconds, [int(s) for s in args.sizes.split(",")])
    print(f"pool_env vector bench ({os.cpu_count()} cores; random actions; shots/s counts steps that simulate)\n")
    print("| what | figure | ratio | target | met |\n| --- | --- | --- | --- | --- |")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for env_id in ("PoolBreak-v0", "PoolBreakRun-v0"):
            for row in _env_rows(env_id, sizes, seconds, args.seed):
                print(row, flush=True)
        loop, one, two = _batch_rates(64 if args.quick else args.batch_shots, 2 if args.quick else 5)
    print(_row("breaks: Python loop of simulate", loop, "shots/s"))
    print(_row("breaks: simulate_batch, 1 thread", one, "shots/s", None, f"{one / loop:.2f} x the loop"))
    print(_row("breaks: simulate_batch, 2 threads", two, "shots/s", None,
               f"{two / one:.2f} x 1 thread (target >= {TARGETS['batch_threads']}: "
               f"{'met' if two / one >= TARGETS['batch_threads'] else 'NOT met'})"))
    memory = _memory_mb()
    print(f"| 256 native envs, resident memory beyond the interpreter | {memory:.0f} MB | | "
          f"<= {TARGETS['memory_mb']:.0f} MB | {'yes' if memory <= TARGETS['memory_mb'] else 'NO'} |")
    return 0

