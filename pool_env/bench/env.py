"""`python -m pool_env.bench env`: environment steps/s without rendering, and rendering frames/s."""

from __future__ import annotations

import argparse
import time
import warnings

import gymnasium as gym
import numpy as np

import pool_env  # noqa: F401  (registers the ids)

STEP_TARGET = 1000.0  # steps/s, PoolBreak-v0 on one core
FRAME_TARGET = 500.0  # frames/s at the default size
RANDOMIZE_TARGET = 0.95  # steps/s with randomize="default" over without: at most 5 % slower
SLICES = 10  # the on and off runs alternate in this many slices each, so a change of load hits both alike


class _Clock:
    """Wall time and this process's CPU time since creation (CPU time is what one core gives,
    even when other processes share the machine)."""

    def __init__(self):
        self._wall, self._cpu = time.perf_counter(), time.process_time()

    def wall(self):
        return time.perf_counter() - self._wall

    def cpu(self):
        return time.process_time() - self._cpu


def _steps_per_second(env_id, seconds, seed, **kwargs):
    """Random actions, resetting whenever an episode ends (resets are counted in the time)."""
    env = gym.make(env_id, **kwargs)
    env.action_space.seed(seed)
    env.reset(seed=seed)
    env.step(env.action_space.sample())  # load the compiled engine before timing
    env.reset(seed=seed)
    steps = episodes = failures = 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a failed shot is counted below, not printed
        clock = _Clock()
        while clock.wall() < seconds:
            _, _, terminated, truncated, info = env.step(env.action_space.sample())
            steps += 1
            failures += bool(info["error"])
            if terminated or truncated:
                episodes += 1
                env.reset()
        wall, cpu = clock.wall(), clock.cpu()
    env.close()
    return steps / cpu, steps / wall, steps, episodes, failures


def _randomized_ratio(env_id, seconds, seed):
    """CPU steps/s of `env_id` with randomize="default" and without, measured in alternating
    slices of one run (random actions, every episode's reset counted): a dict of the on and
    off figures per CPU s, on per wall s, their ratio, and its two causes: the CPU time a
    reset costs with and without (µs) and the steps' own time on and off (the drawn tables'
    physics: slower cloth, livelier cushions), resets left out."""
    envs = {}
    for on in (False, True):
        env = gym.make(env_id, **({"randomize": "default"} if on else {}))
        env.action_space.seed(seed)
        env.reset(seed=seed)
        env.step(env.action_space.sample())  # load the compiled engine before timing
        env.reset(seed=seed)
        envs[on] = {"env": env, "steps": 0, "resets": 0, "cpu": 0.0, "wall": 0.0, "reset_cpu": 0.0}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for _ in range(SLICES):
            for entry in envs.values():
                _randomized_slice(entry, seconds / (2 * SLICES))
    for entry in envs.values():
        entry["env"].close()
    on, off = envs[True], envs[False]
    step_on, step_off = ((e["cpu"] - e["reset_cpu"]) / e["steps"] for e in (on, off))
    return {"on": on["steps"] / on["cpu"], "on_wall": on["steps"] / on["wall"], "off": off["steps"] / off["cpu"],
            "ratio": (on["steps"] / on["cpu"]) / (off["steps"] / off["cpu"]),
            "reset_us": tuple(1e6 * e["reset_cpu"] / max(e["resets"], 1) for e in (on, off)),
            "step_ratio": step_off / step_on}


def _randomized_slice(entry, seconds):
    """Steps of entry's env for `seconds` of wall time, its counts and CPU times added to `entry`."""
    env, clock = entry["env"], _Clock()
    while clock.wall() < seconds:
        _, _, terminated, truncated, _ = env.step(env.action_space.sample())
        entry["steps"] += 1
        if terminated or truncated:
            before = time.process_time()
            env.reset()
            entry["reset_cpu"] += time.process_time() - before
            entry["resets"] += 1
    entry["cpu"] += clock.cpu()
    entry["wall"] += clock.wall()


def _frames_per_second(mode, seconds, seed, size):
    """rgb_array: render() of a table after a break. rgb_array_list: whole shots, from the exact
    trajectory (sampling, orientation integration and drawing), counted per frame."""
    env = gym.make("PoolBreakRun-v0", render_mode=mode, render_size=size)
    env.action_space.seed(seed)
    env.reset(seed=seed)
    env.step(np.array([1.0, 0.0], dtype=np.float32))
    env.render()
    frames = 0
    if mode == "rgb_array":
        clock = _Clock()
        while clock.wall() < seconds:
            for _ in range(50):
                frames += env.render().shape[0] > 0
        wall, cpu = clock.wall(), clock.cpu()
    else:
        env.reset(seed=seed)
        action = np.array([1.0, 0.0], dtype=np.float32)  # a break, then random shots
        wall = cpu = 0.0
        while wall < seconds:
            # The physics is not timed. The step hands the playback a new shot, whose frames are
            # not sampled yet: the render below samples the trajectory and carries the balls'
            # orientation through it, then draws, and all three are timed.
            _, _, terminated, truncated, _ = env.step(action)
            clock = _Clock()
            frames += len(env.render())
            wall, cpu = wall + clock.wall(), cpu + clock.cpu()
            if terminated or truncated:
                env.reset()
            action = env.action_space.sample()
    env.close()
    return frames / cpu, frames / wall, frames


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m pool_env.bench env", description=__doc__)
    parser.add_argument("--seconds", type=float, default=3.0, help="time per measurement (default 3)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--size", default="640x360", help="frame size WxH (default 640x360)")
    args = parser.parse_args(argv)
    size = tuple(int(v) for v in args.size.lower().split("x"))

    rows = []
    for env_id in ("PoolBreak-v0", "PoolBreakRun-v0"):
        cpu, wall, steps, episodes, failures = _steps_per_second(env_id, args.seconds, args.seed)
        target = STEP_TARGET if env_id == "PoolBreak-v0" else None
        note = f"{steps} steps, {episodes} episodes" + (f", {failures} failed shots" if failures else "")
        rows.append((f"{env_id} steps/s, no rendering", cpu, wall, target, note))
    for env_id in ("PoolNineBall-v0", "PoolEightBall-v0"):
        for opponent in ("random", "ghost_ball"):
            cpu, wall, steps, episodes, failures = _steps_per_second(env_id, args.seconds, args.seed, opponent=opponent)
            note = f"{steps} agent shots (and the opponent's), {episodes} games" + (
                f", {failures} failed shots" if failures else "")
            rows.append((f"{env_id} vs {opponent} steps/s", cpu, wall, None, note))
    for env_id in ("PoolBreak-v0", "PoolBreakRun-v0", "PoolNineBall-v0"):  # a reset every 1, ~3, ~20+ steps
        r = _randomized_ratio(env_id, 2 * args.seconds, args.seed)
        verdict = "ok" if r["ratio"] >= RANDOMIZE_TARGET else "MISS"
        rows.append((f"{env_id} randomized steps/s", r["on"], r["on_wall"], None,
                     f"{r['ratio']:.3f} of the {r['off']:.0f} without, in the same run (target >= {RANDOMIZE_TARGET}: "
                     f"{verdict}); a reset {r['reset_us'][0]:.0f} us against {r['reset_us'][1]:.0f}, the steps "
                     f"alone {r['step_ratio']:.3f}"))
    for mode, what in (("rgb_array", "render() of the table"), ("rgb_array_list", "whole shots, per frame")):
        cpu, wall, frames = _frames_per_second(mode, args.seconds, args.seed, size)
        rows.append((f"{mode} frames/s at {size[0]}x{size[1]}", cpu, wall, FRAME_TARGET, f"{what}, {frames} frames"))

    print("pool_env environment benchmark: one process on one core, random actions")
    print("(per CPU second of this process, and per wall second, which other load on the machine lowers)\n")
    print(f"| {'measure':<40} | {'per CPU s':>9} | {'per wall s':>10} | {'target':>8} | {'':<4} | notes")
    print(f"| {'-' * 40} | {'-' * 9} | {'-' * 10} | {'-' * 8} | {'-' * 4} | -----")
    for name, cpu, wall, target, note in rows:
        verdict = "" if target is None else ("ok" if cpu >= target else "MISS")
        shown = "" if target is None else f">= {target:.0f}"
        print(f"| {name:<40} | {cpu:>9.0f} | {wall:>10.0f} | {shown:>8} | {verdict:<4} | {note}")
    return 0
