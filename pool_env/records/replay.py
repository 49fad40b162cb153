"""`python -m pool_env.records.replay game.json [--video out.mp4] [--shot K]`: replay a saved game, checked."""

from __future__ import annotations

import argparse
import sys

from .saved import ReplayMismatch, load_game, make_env, replay
from .video import _Writer


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m pool_env.records.replay", description=__doc__.split("\n")[0])
    parser.add_argument("path", help="a saved game (pool_env.save_game)")
    parser.add_argument("--video", help="write the replayed shots to this .mp4")
    parser.add_argument("--shot", type=int, help="stop after this many of the agent's shots")
    args = parser.parse_args(argv)
    record = load_game(args.path)
    env = make_env(record)
    writer = None
    if args.video:
        fps = env.unwrapped.metadata["render_fps"]
        writer = _Writer(args.video, fps)
    on_step = (lambda k, e: writer.append(e.unwrapped.shot_frames(fps))) if writer else None
    try:
        replay(record, env, on_step=on_step, until=args.shot)
    except ReplayMismatch as exc:
        print(f"replay failed: {exc}", file=sys.stderr)
        return 1
    finally:
        if writer is not None:
            writer.close()
    steps = len(record["actions"]) if args.shot is None else min(args.shot, len(record["actions"]))
    print(f"replayed {steps} steps of {record['env_id']} (seed {record['seed']}): every outcome as recorded"
          + (f"; video: {args.video}" if args.video else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
