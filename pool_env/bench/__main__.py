"""Dispatch `python -m pool_env.bench NAME [options]` to pool_env.bench.NAME.main(argv)."""

import importlib
import os
import sys

PROG = "python -m pool_env.bench"
BENCHES = {
    "speed": "simulator speed against the targets (and pooltool when importable)",
    "env": "environment steps/s and rendering frames/s",
    "pixels": "frames/s of the pixel observations: batched in the native vector env, single, the renderer's",
    "accuracy": "fixed-step methods against the exact engine: error vs wall time",
    "stability": "random-scene sweep checking the invariants after every event",
    "vector": "shots/s of the native vector env beside SB3's and Gymnasium's, and of simulate_batch",
    "pockets": "our pocket model beside pooltool 0.6: pot/no-pot on a grid of straight and cut shots",
    "game": "Game.evaluate against restore + play, the run vector env's shots/s, 9-ball steps/s",
    "pooltool3d": "jump shots (flights, bounces, landings, a blocker) beside pooltool main's 3D and closed forms",
    "calibrate": "our physics fitted to pooltool's one-ball tracks (pool_env.calibrate), per cushion model",
}

# A bench whose module is named otherwise than the bench.
MODULES = {"pooltool3d": "pooltool_3d"}


def main(argv=None):
    """The bench's exit status; a missing or unknown NAME, or a bench's ValueError or OSError (a bad
    option or file), ends in one line on stderr and status 2 (--debug or POOL_ENV_DEBUG=1: the traceback)."""
    argv = sys.argv[1:] if argv is None else list(argv)
    debug = "--debug" in argv or os.environ.get("POOL_ENV_DEBUG", "") not in ("", "0")
    argv = [a for a in argv if a != "--debug"]  # the dispatcher's option, not the bench's
    if not argv or argv[0] in ("-h", "--help") or argv[0] not in BENCHES:
        print(f"usage: {PROG} NAME [options]\n")
        for name, what in BENCHES.items():
            print(f"  {name:<10} {what}")
        if argv and argv[0] in ("-h", "--help"):
            return 0
        problem = f"unknown bench {argv[0]!r}" if argv else "no bench given"
        problem += f"; choose one of {', '.join(BENCHES)}"
        if debug:
            raise ValueError(problem)
        print(f"{PROG}: {problem}", file=sys.stderr)
        return 2
    module = importlib.import_module(f"pool_env.bench.{MODULES.get(argv[0], argv[0])}")
    try:
        return module.main(argv[1:])
    except (ValueError, OSError) as exc:
        if debug:
            raise
        print(f"{PROG} {argv[0]}: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
