"""`python -m pool_env.play`: play pool with the mouse in a pygame window (against a player, a model or a friend)."""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from ..render.window import open_display
from .draw import draw_session
from .games import GAMES, TABLE_SIZE, opponent_names
from .session import PlaySession

PROG = "python -m pool_env.play"

EPILOG = """mouse: press on the table and drag back from the cue ball, release to shoot (a drag of 0.6 m on
the table is full power, 12 m/s); with ball in hand drag the cue ball to place it; click the tip diagram to
set draw, follow and English; shooting at the 8 in 8-ball, click a pocket to call it.
keys: R restart, U undo the last shot, S slow motion, W save the game (python -m pool_env.records.replay
plays it), Esc quit."""


def parse(argv=None):
    """The options, checked: a bad one ends in one line on stderr and exit status 2, before a window opens."""
    parser = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n")[0], epilog=EPILOG,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--game", choices=list(GAMES), default="nine_ball")
    parser.add_argument("--opponent", default="ghost_ball",
                        help=f"a player ({', '.join(opponent_names())}) or a model (runs/<name>/model.zip)")
    parser.add_argument("--two-players", action="store_true", help="two humans take turns on one screen")
    parser.add_argument("--seed", type=int, default=0, help="the first rack's seed (R racks the next seed)")
    parser.add_argument("--size", type=int, nargs=2, default=list(TABLE_SIZE), metavar=("W", "H"),
                        help="the table's size in pixels")
    parser.add_argument("--save-dir", default=".", help="where W writes games")
    parser.add_argument("--screenshot", metavar="PNG", help="draw a scripted opening (headless: "
                        "SDL_VIDEODRIVER=dummy), save the window to PNG and quit")
    parser.add_argument("--debug", action="store_true", help="on an error, the full traceback instead of one line "
                        "(also POOL_ENV_DEBUG=1)")
    args = parser.parse_args(argv)
    args.debug = args.debug or os.environ.get("POOL_ENV_DEBUG", "") not in ("", "0")
    problem = check(args)
    if problem is not None:
        if args.debug:
            raise ValueError(problem)
        parser.exit(2, f"{PROG}: {problem}\n")
    return args


def check(args) -> str | None:
    """What is wrong with the options that argparse lets through, or None: found now rather than
    with the window open (the renderer refuses a bad size only at the first frame)."""
    if min(args.size) < 1:
        return f"--size must be two positive numbers of pixels, got {args.size[0]} {args.size[1]}"
    folder = Path(args.screenshot).resolve().parent if args.screenshot else None
    if folder is not None and not folder.is_dir():
        return f"--screenshot {args.screenshot}: no folder {folder}"
    return None


def run(session, surface, pygame):
    """The event loop: events to the session, pending shots played, the window drawn at 60 Hz."""
    clock = pygame.time.Clock()
    while session.running:
        for event in pygame.event.get():
            session.handle(event)
        session.update()
        session.tick(clock.get_time() / 1000.0)
        draw_session(session, surface)
        pygame.display.flip()
        clock.tick(60)


def screenshot(session, surface, pygame, path):
    """A break shot aimed (the ball in hand placed, a drag under way), drawn and saved to `path`."""
    pg = pygame
    cue = session.to_pixel(session.cue_xy)
    target = session.to_pixel(session.base.balls.xy[1])
    back = cue - 0.35 * (target - cue)
    for event in (pg.event.Event(pg.MOUSEBUTTONDOWN, pos=session.tip_centre(), button=1),
                  pg.event.Event(pg.MOUSEBUTTONUP, pos=(session.tip_centre()[0] + 8, session.tip_centre()[1] + 20),
                                 button=1),
                  pg.event.Event(pg.MOUSEBUTTONDOWN, pos=tuple(back), button=1),
                  pg.event.Event(pg.MOUSEMOTION, pos=tuple(back), rel=(0, 0), buttons=(1, 0, 0))):
        session.handle(event)
    draw_session(session, surface)
    pygame.image.save(surface, path)
    print(f"wrote {path}")


def main(argv=None) -> int:
    args = parse(argv)
    try:
        session = PlaySession(args.game, args.opponent, args.two_players, seed=args.seed, size=args.size,
                              save_dir=args.save_dir)
        pygame, surface = open_display(session.window_size, f"pool_env: {args.game}")
    except (ImportError, RuntimeError, ValueError, OSError) as exc:  # no pygame or display, a bad opponent or game
        if args.debug:
            raise
        print(f"{PROG}: {exc}", file=sys.stderr)
        return 2
    try:
        if args.screenshot:
            screenshot(session, surface, pygame, args.screenshot)
        else:
            run(session, surface, pygame)
    finally:
        pygame.display.quit()
    return 0


if __name__ == "__main__":
    sys.exit(main())
