"""Dispatch `python -m pool_env.bench NAME [options]` to pool_env.bench.NAME.main(argv)."""

import importlib
import sys

BENCHES = {
    "speed": "simulator speed against the targets (and pooltool when importable)",
    "env": "environment steps/s and rendering frames/s",
    "accuracy": "fixed-step methods against the exact engine: error vs wall time",
    "stability": "random-scene sweep checking the invariants after every event",
    "vector": "shots/s of the native vector env beside SB3's and Gymnasium's, and of simulate_batch",
    "pockets": "our pocket model beside pooltool 0.6: pot/no-pot on a grid of straight and cut shots",
    "game": "Game.evaluate against restore + play, the run vector env's shots/s, 9-ball steps/s",
}


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if not argv or argv[0] in ("-h", "--help") or argv[0] not in BENCHES:
        print("usage: python -m pool_env.bench NAME [options]\n")
        for name, what in BENCHES.items():
            print(f"  {name:<10} {what}")
        return 0 if argv and argv[0] in ("-h", "--help") else 2
    module = importlib.import_module(f"pool_env.bench.{argv[0]}")
    return module.main(argv[1:])


if __name__ == "__main__":
    sys.exit(main())
