"""`python -m pool_env.records.replay game.json [--video out.mp4] [--shot K]`: a saved game replayed, checked, shown."""

from __future__ import annotations

import argparse
import os
import sys

import gymnasium as gym

from ..render.window import Window, display_problem
from .saved import ReplayMismatch, load_game, make_env, replay
from .video import _Writer

PROG = "python -m pool_env.records.replay"


def main(argv=None) -> int:
    """0: every step replayed as recorded; 1: a step replayed differently; 2: a bad argument or file
    (one line on stderr; --debug or POOL_ENV_DEBUG=1: the traceback)."""
    parser = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n")[0])
    parser.add_argument("path", help="a saved game (pool_env.save_game)")
    parser.add_argument("--video", help="write the replayed shots to this .mp4 (without it, they are shown in a "
                        "window when there is a display)")
    parser.add_argument("--no-window", action="store_true", help="only check the replay, show nothing")
    parser.add_argument("--shot", type=int, help="stop after this many of the agent's shots")
    parser.add_argument("--debug", action="store_true", help="on an error, the full traceback instead of one line "
                        "(also POOL_ENV_DEBUG=1)")
    args = parser.parse_args(argv)
    if args.shot is not None and args.shot < 0:
        parser.exit(2, f"{PROG}: --shot must be >= 0, got {args.shot}\n")
    try:
        return replay_file(args)
    except (ValueError, OSError, gym.error.Error) as exc:  # a bad file, an env id or kwargs it cannot make
        if args.debug or os.environ.get("POOL_ENV_DEBUG", "") not in ("", "0"):
            raise
        print(f"{PROG}: {describe(exc, args.path)}", file=sys.stderr)
        return 2


def describe(exc: Exception, path: str) -> str:
    """The error in one line, naming the file: OSError's own text ("[Errno 2] No such file or
    directory: 'x'") puts the name last, and gymnasium's (an unknown env id) does not name it."""
    if isinstance(exc, OSError) and exc.filename:
        return f"cannot open {exc.filename}: {exc.strerror}"
    if isinstance(exc, gym.error.Error):
        return f"{path}: {exc}"
    return str(exc)


def count(n: int, noun: str) -> str:
    """ "1 step", "2 steps", "0 steps"."""
    return f"{n} {noun}{'' if n == 1 else 's'}"


def open_window(args, title):
    """The window the replay is shown in (None with --video or --no-window, or, saying why on
    stderr, when no one would see it)."""
    if args.video or args.no_window:
        return None
    problem = display_problem()
    if problem is not None:
        print(f"{PROG}: not shown: {problem}; checking the replay only (--video out.mp4 films it)", file=sys.stderr)
        return None
    return Window(title)


def replay_file(args) -> int:
    """Load, replay and film (--video) or show (a window, when there is a display) the saved game;
    a replay that differs is a result (1), not an error."""
    record = load_game(args.path)
    env = make_env(record)
    fps = env.unwrapped.metadata["render_fps"]
    writer = _Writer(args.video, fps) if args.video else None
    window = open_window(args, f"pool_env replay: {os.path.basename(args.path)}")
    on_step = None
    if writer is not None:
        on_step = lambda k, e: writer.append(e.unwrapped.shot_frames(fps))  # noqa: E731
    elif window is not None:
        on_step = lambda k, e: window.closed or window.play(e.unwrapped.shot_frames(fps), fps)  # noqa: E731
    try:
        replay(record, env, on_step=on_step, until=args.shot)
    except ReplayMismatch as exc:
        print(f"replay failed: {exc}", file=sys.stderr)
        return 1
    finally:
        if writer is not None:
            writer.close()
    steps = len(record["actions"]) if args.shot is None else min(args.shot, len(record["actions"]))
    print(f"replayed {count(steps, 'step')} of {record['env_id']} (seed {record['seed']}): every outcome as recorded"
          + (f"; video: {args.video}" if args.video else "") + ("; Esc or close the window to quit" if window else ""),
          flush=True)
    if window is not None:
        window.hold()
        window.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
