"""`python -m pool_env.bench pixels`: frames/s of the pixel observations, batched in the native vector env and single.

"Batched" is the native vector env's observation of all its sub-envs at once (what its `reset`
and `step` return: one compiled call draws every frame); "single" is one env's observation
(`env.unwrapped.observer.observe(env)`, what `reset` and `step` of a `gymnasium.make` env
return); "renderer" is `TableRenderer.draw` at the same size, the NumPy path the frames equal.
The balls are where a random shot after the break left them. The target is for 2 cores.
"""

from __future__ import annotations

import argparse
import os
import time
import warnings

TARGET_BATCHED = 10_000.0  # frames/s of the native vector env's pixel observations, 2 cores


def rate(fn, count: int, seconds: float) -> float:
    """count / (the best wall time of fn() over repeats filling about `seconds`)."""
    fn()  # warm: compiled code loaded, caches filled
    best, spent = float("inf"), 0.0
    while spent < seconds:
        t0 = time.perf_counter()
        fn()
        dt = time.perf_counter() - t0
        best, spent = min(best, dt), spent + dt
    return count / best


def vector_env(env_id: str, num_envs: int, size, gray: bool, seed: int):
    import gymnasium as gym

    import pool_env  # noqa: F401  (registers the ids)

    envs = gym.make_vec(env_id, num_envs=num_envs, vectorization_mode="vector_entry_point", obs_type="pixels",
                        obs_size=size, grayscale=gray, autoreset_mode="SameStep")
    envs.reset(seed=seed)
    envs.action_space.seed(seed)
    envs.step(envs.action_space.sample())
    return envs


def rows(env_id: str, num_envs: int, size, gray: bool, seconds: float, seed: int) -> list[str]:
    envs = vector_env(env_id, num_envs, size, gray, seed)
    observer, subs = envs.unwrapped.observer, envs.unwrapped.envs
    batched = rate(lambda: observer.batch([observer.capture(e) for e in subs]), num_envs, seconds)
    single = rate(lambda: [observer.observe(e) for e in subs[:64]], min(64, num_envs), seconds)
    renderer = observer.frames.renderer
    balls = [e.game.balls for e in subs[:16]]
    drawn = rate(lambda: [renderer.draw(b.xy, b.pocketed) for b in balls], len(balls), seconds)
    what = f"{env_id} {size[0]}x{size[1]} {'gray' if gray else 'RGB'}"
    met = "yes" if batched >= TARGET_BATCHED else "NO"
    return [f"| {what}: batched, native vector env of {num_envs} | {batched:,.0f} frames/s | "
            f">= {TARGET_BATCHED:,.0f} | {met} |",
            f"| {what}: single env | {single:,.0f} frames/s | | |",
            f"| {what}: TableRenderer.draw (NumPy) | {drawn:,.0f} frames/s | | |"]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m pool_env.bench pixels", description=__doc__.split("\n")[0])
    parser.add_argument("--seconds", type=float, default=2.0, help="seconds per measurement")
    parser.add_argument("--num-envs", type=int, default=256, help="sub-envs of the native vector env")
    parser.add_argument("--quick", action="store_true", help="0.3 s per measurement, 16 sub-envs, 84x84 only")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    if args.num_envs < 1 or args.seconds <= 0:
        raise ValueError("--num-envs must be >= 1 and --seconds > 0")
    seconds, num_envs = (0.3, 16) if args.quick else (args.seconds, args.num_envs)
    cases = [("PoolBreakRun-v0", (84, 84), False)] if args.quick else [
        ("PoolBreakRun-v0", (84, 84), False), ("PoolBreakRun-v0", (84, 84), True),
        ("PoolBreakRun-v0", (96, 96), False), ("Snooker-v0", (96, 96), False)]
    print(f"pool_env pixels bench ({os.cpu_count()} cores; frames of the balls after a random shot)\n")
    print("| what | figure | target | met |\n| --- | --- | --- | --- |")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for env_id, size, gray in cases:
            for row in rows(env_id, num_envs if env_id != "Snooker-v0" else min(num_envs, 64), size, gray,
                            seconds, args.seed):
                print(row, flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
