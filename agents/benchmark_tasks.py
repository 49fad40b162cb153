"""The benchmark's fixed tasks, their seeds and `BENCHMARK_VERSION`: the one home of the protocol's constants."""

from __future__ import annotations

from dataclasses import dataclass

# Bump when a change to the physics, the rules, a task, its seeds or a reference opponent moves
# any score of a player that did not change (tests/test_benchmark.py pins a reference row of
# ghost_ball on a tiny configuration, and fails to remind one to bump it): rows of different
# versions do not compare.
BENCHMARK_VERSION = 2  # 2: 8-ball calls a ball and a pocket on every shot (WPA 1.6)

MAX_GAMES = 10_000  # each task owns seeds first_seed .. first_seed + MAX_GAMES - 1
GAME_MAX_SHOTS = 100  # the agent's shots before a game (or a practice rack) stops unfinished
NOISES = ("none", "olympiad")  # every task is played without noise and with the Computational Pool Olympiad's


@dataclass(frozen=True)
class Task:
    """One benchmark task: what is played (`kind`: "break", "runout" or "game"), which game,
    against whom, with which noise, and the first of its seeds (game k plays on first_seed + k)."""

    name: str
    kind: str
    game: str
    opponent: str | None
    noise: str
    first_seed: int
    what: str

    @property
    def noise_option(self):
        """The envs' `noise=` argument for this task."""
        return None if self.noise == "none" else self.noise

    def seeds(self, games: int) -> range:
        """The seeds of the first `games` games (ValueError past MAX_GAMES or under 1)."""
        if int(games) != games or not 1 <= games <= MAX_GAMES:
            raise ValueError(f"games must be an integer in 1 .. {MAX_GAMES}, got {games!r}")
        return range(self.first_seed, self.first_seed + int(games))


_BASES = (  # (name, kind, game, opponent, what is scored)
    ("break", "break", "nine_ball", None, "9-ball break, one shot: won if the breaker keeps the table "
     "(a ball pocketed without a foul) or pockets the 9"),
    ("runout", "runout", "nine_ball", None, "9-ball practice from the break: won if the breaker clears the "
     "rack before the turn passes"),
    ("nine_ghost_ball", "game", "nine_ball", "ghost_ball", "9-ball game against ghost_ball, breaks alternating"),
    ("nine_search", "game", "nine_ball", "search", "9-ball game against search, breaks alternating"),
    ("eight_ghost_ball", "game", "eight_ball", "ghost_ball", "8-ball game against ghost_ball, breaks alternating"),
)

TASKS = tuple(Task(f"{name}-{noise}", kind, game, opponent, noise, 1_000_000 * (1 + 2 * k + n), what)
              for k, (name, kind, game, opponent, what) in enumerate(_BASES) for n, noise in enumerate(NOISES))
TASK_NAMES = tuple(task.name for task in TASKS)
TINY_GAMES = 2  # games per task in the --tiny configuration (CI)
TINY_TASKS = ("break-none", "runout-olympiad", "nine_ghost_ball-none", "eight_ghost_ball-olympiad")


def select_tasks(names=None) -> list[Task]:
    """The tasks named (a task's full name, or its base name for both noise settings; None: all),
    in TASKS order; ValueError naming the choices for an unknown name."""
    if names is None:
        return list(TASKS)
    wanted = set()
    for name in names:
        matches = {t.name for t in TASKS if name in (t.name, t.name.rsplit("-", 1)[0])}
        if not matches:
            raise ValueError(f"unknown task {name!r}; choose from {', '.join(TASK_NAMES)} "
                             f"(or a base name: {', '.join(b[0] for b in _BASES)})")
        wanted |= matches
    return [t for t in TASKS if t.name in wanted]
