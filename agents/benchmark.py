"""`python -m agents.benchmark --agent NAME|PATH`: one player scored on the fixed tasks, a leaderboard row."""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

import pool_env
from pool_env.envs.game_env import PoolGameEnv
from pool_env.players import is_model_path, player_names
from pool_env.players import make_player as registry_player

from .benchmark_tasks import BENCHMARK_VERSION, GAME_MAX_SHOTS, TASK_NAMES, TINY_GAMES, TINY_TASKS, Task, select_tasks
from .learned import LearnedPlayer, ValueNet
from .match import alternate, player_seed, points, run_episode
from .ratings import player_stats
from .stats import wilson
from .tournament import Timed, display_name, percent, play_game, step_shots, strip_timings

AGENT, OPPONENT = "agent", "opponent"  # the names the records use (a player may meet itself)
METRICS = ("games", "wins", "draws", "win_rate", "ci95", "balls_per_turn", "break_and_runs", "breaks",
           "break_and_run_rate", "fouls_per_game", "decisions", "seconds_per_decision")


# --- players ------------------------------------------------------------------------------------
def make_agent(spec: str, env):
    """The player `spec` names for `env`: a registered name (`pool_env.make_player`), an SB3 model's
    .zip, or a saved learned net (.npz, `agents.learned.ValueNet`). ValueError for an unknown name."""
    if spec.endswith(".npz"):
        if not Path(spec).is_file():
            raise ValueError(f"unknown agent {spec!r}: no such learned net file")
        game = env.game
        return LearnedPlayer(game.mode, net=ValueNet.load(spec), table=game.table, physics=game.physics)
    try:
        return registry_player(spec, env, seed=0)
    except ValueError as exc:
        raise ValueError(str(exc).replace("unknown player", "unknown agent", 1)) from None


def check_agent(spec: str) -> None:
    """ValueError before any game if `spec` names no player: not a registered name, and no model or net
    file there (a player that is named but cannot play a task is skipped there, saying why)."""
    if spec.endswith(".npz") or is_model_path(spec):
        if not any(Path(p).is_file() for p in (spec, Path(spec).with_suffix(".zip"))):
            kind = "learned net" if spec.endswith(".npz") else "model"
            raise ValueError(f"unknown agent {spec!r}: no such {kind} file")
    elif spec not in player_names():
        raise ValueError(f"unknown agent {spec!r}; choose one of {', '.join(player_names())}, a saved model's "
                         "path (.zip) or a learned net's (.npz)")


def task_players(spec: str, task: Task) -> dict:
    """{AGENT: player, OPPONENT: player (game tasks)} for `task`, each warmed up (untimed: compiles,
    caches) on a position outside the task's seeds; raises what building or warming one raised."""
    env = PoolGameEnv(task.game, opponent=None, noise=task.noise_option)
    players = {AGENT: make_agent(spec, env)}
    if task.opponent is not None:
        players[OPPONENT] = registry_player(task.opponent, env, seed=0)
    for player in players.values():
        player.act(env.reset(seed=0)[0])
    env.close()
    return players


# --- playing ------------------------------------------------------------------------------------
def play_practice(task: Task, players: dict, timers: dict, seed: int) -> dict:
    """One practice rack on `seed` (the break task: its one shot; the run-out: until the turn
    passes), as a tournament game record with the agent alone at the table."""
    env = PoolGameEnv(task.game, opponent=None, noise=task.noise_option,
                      max_shots=1 if task.kind == "break" else GAME_MAX_SHOTS)
    if hasattr(players[AGENT], "reset"):
        players[AGENT].reset(seed=player_seed(seed, 0))
    shots = []

    def stepped(step):
        shots.extend(step_shots(env.step_records, AGENT, OPPONENT))

    info = run_episode(env, timers[AGENT], seed, stepped).info
    env.close()
    won = info["winner"] == 0  # the 9 pocketed legally: on the break, or the rack cleared
    kept = task.kind == "break" and not info["turn_passed"] and not info["error"] and info["foul"] == 0
    return {"seed": int(seed), "players": [AGENT], "breaker": AGENT, "winner": AGENT if won else None,
            "shots": shots, "score": 1.0 if won or kept else 0.0}


def play_task(task: Task, players: dict, games: int) -> tuple[list[dict], Timed]:
    """The task's first `games` games (the agent breaks the even ones of a game task); the records
    and the agent's timer."""
    timers = {name: Timed(player, name) for name, player in players.items()}
    records = []
    for seed, breaker, other in alternate(task.seeds(games), AGENT, OPPONENT):
        if task.kind == "game":
            record = play_game(task.game, breaker, other, players, timers, seed, task.noise_option,
                               max_shots=GAME_MAX_SHOTS)
            record["score"] = points(record["winner"], AGENT)
        else:
            record = play_practice(task, players, timers, seed)
        records.append(record)
    return records, timers[AGENT]


def task_metrics(records: list[dict], timer: Timed) -> dict:
    """The task's row entry: win rate (each record's score: a draw counts half) with its 95 % Wilson
    interval, balls per turn, break-and-runs, fouls per game, seconds per decision (METRICS), the seeds."""
    s = player_stats(records, AGENT, timer)
    score = sum(r["score"] for r in records)
    return {"games": s["games"], "wins": sum(1 for r in records if r["score"] == 1.0),
            "draws": sum(1 for r in records if r["score"] == 0.5),
            "win_rate": score / max(s["games"], 1), "ci95": list(wilson(score, s["games"])),
            "balls_per_turn": s["balls_per_turn"], "break_and_runs": s["break_and_runs"], "breaks": s["breaks"],
            "break_and_run_rate": s["break_and_run_rate"], "fouls_per_game": s["fouls_per_game"],
            "decisions": s["decisions"], "seconds_per_decision": s["seconds_per_decision"],
            "seeds": [records[0]["seed"], records[-1]["seed"]], "forfeits": s["forfeits"]}


def run_task(spec: str, task: Task, games: int) -> dict:
    """One task's entry of the row, or {"skipped": why} for a player that cannot play it."""
    try:
        players = task_players(spec, task)
    except Exception as exc:  # noqa: BLE001 (e.g. a 9-ball-only player on 8-ball: the row says why)
        return {"skipped": f"{type(exc).__name__}: {exc}"}
    records, timer = play_task(task, players, games)
    return task_metrics(records, timer)


def benchmark(spec: str, games=None, tasks=None, log=None) -> dict:
    """The leaderboard row of the player `spec` (`make_agent`): every task of `tasks` (names, None:
    all) played for games[task name] games (an int: every task's count)."""
    check_agent(spec)
    chosen = select_tasks(tasks)
    counts = {t.name: games if isinstance(games, int) else games[t.name] for t in chosen}
    start, results = time.perf_counter(), {}
    for task in chosen:
        t0 = time.perf_counter()
        results[task.name] = run_task(spec, task, counts[task.name])
        if log is not None:
            r = results[task.name]
            what = r["skipped"] if "skipped" in r else f"won {r['wins']}/{r['games']}"
            log(f"{task.name}: {what} in {time.perf_counter() - t0:.1f} s")
    return {"benchmark_version": BENCHMARK_VERSION, "pool_env_version": pool_env.__version__,
            "agent": display_name(spec), "spec": spec, "games": counts, "tasks": results,
            "wall_seconds": time.perf_counter() - start}


# --- output ---------------------------------------------------------------------------------
def leaderboard_markdown(rows: list[dict]) -> str:
    """The leaderboard: each task's win rate [95 % CI] per row (a column a row), then each row's details."""
    names = [name for name in TASK_NAMES if any(name in row["tasks"] for row in rows)]
    lines = ["| task | " + " | ".join(f"{row['agent']} (v{row['benchmark_version']})" for row in rows) + " |",
             "| --- |" + " --- |" * len(rows)]
    lines += [f"| {name} | " + " | ".join(_cell(row["tasks"].get(name)) for row in rows) + " |" for name in names]
    for row in rows:
        lines += ["", f"{row['agent']} (`{command_of(row)}`):", "",
                  "| task | games | win rate [95 % CI] | balls / turn | break-and-run | fouls / game | ms / decision |",
                  "| --- | ---: | --- | ---: | ---: | ---: | ---: |"]
        for name, r in row["tasks"].items():
            if "skipped" in r:
                lines.append(f"| {name} | - | skipped: {r['skipped']} | | | | |")
                continue
            lines.append(f"| {name} | {r['games']} | {percent(r['win_rate'], r['ci95'])} | {r['balls_per_turn']:.2f} "
                         f"| {r['break_and_runs']}/{r['breaks']} | {r['fouls_per_game']:.2f} "
                         f"| {1000 * r['seconds_per_decision']:.3g} |")
    return "\n".join(lines) + "\n"


def _cell(result) -> str:
    if result is None:
        return ""
    return "skipped" if "skipped" in result else f"{percent(result['win_rate'], result['ci95'])} (n={result['games']})"


def command_of(row: dict) -> str:
    """The command that reproduces a row."""
    counts = row["games"]
    if len(set(counts.values())) == 1:
        games = f"--games {next(iter(counts.values()))}"
    else:
        games = " ".join(f"--games {name}={n}" for name, n in counts.items())
    tasks = "" if list(counts) == list(TASK_NAMES) else f" --tasks {','.join(counts)}"
    return f"python -m agents.benchmark --agent {row['spec']} {games}{tasks}"


def append_row(row: dict, leaderboard) -> list[dict]:
    """Append `row` to the leaderboard file (a JSON list, created if missing); returns every row."""
    path = Path(leaderboard)
    rows = json.loads(path.read_text()) if path.exists() else []
    rows.append(row)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(rows, indent=1) + "\n")
    return rows


# --- the command ------------------------------------------------------------------------------
PROG = "python -m agents.benchmark"


def game_counts(values: list[str] | None, tiny: bool) -> tuple[int, dict]:
    """(--games's default count, {task: count} overrides) from `--games N` and `--games TASK=N`."""
    default, overrides = (TINY_GAMES if tiny else 100), {}
    for value in values or []:
        name, _, n = value.rpartition("=")
        if not n.isdigit() or int(n) < 1:
            raise ValueError(f"--games takes N or TASK=N with N >= 1, got {value!r}")
        if name:
            overrides.update({t.name: int(n) for t in select_tasks([name])})
        else:
            default = int(n)
    return default, overrides


def main(argv=None) -> dict:
    """The command: a bad option or agent name ends in one line on stderr and exit status 2
    (--debug or POOL_ENV_DEBUG=1: the traceback); returns the row."""
    parser = argparse.ArgumentParser(prog=PROG, description=__doc__)
    parser.add_argument("--agent", required=True, help="a registered player (random, ghost_ball, search, learned, "
                        "search+value), an SB3 model's .zip or a learned net's .npz")
    parser.add_argument("--games", action="append", metavar="N|TASK=N",
                        help=f"games per task (default 100; --tiny: {TINY_GAMES}); TASK=N for one task (repeatable)")
    parser.add_argument("--tasks", help=f"comma list of tasks or base names (default: all; --tiny: "
                        f"{','.join(TINY_TASKS)})")
    parser.add_argument("--tiny", action="store_true", help="the CI configuration: few games, cheap tasks")
    parser.add_argument("--leaderboard", default="runs/benchmark/leaderboard.json",
                        help="the JSON list the row is appended to; the markdown table is written beside it (.md)")
    parser.add_argument("--debug", action="store_true", help="on an error, the full traceback")
    args = parser.parse_args(argv)
    log = lambda message: print(message, file=sys.stderr, flush=True)
    try:
        tasks = args.tasks.split(",") if args.tasks else (list(TINY_TASKS) if args.tiny else None)
        default, overrides = game_counts(args.games, args.tiny)
        counts = {t.name: overrides.get(t.name, default) for t in select_tasks(tasks)}
        row = benchmark(args.agent, counts, list(counts), log)
        rows = append_row(row, args.leaderboard)
        Path(args.leaderboard).with_suffix(".md").write_text(leaderboard_markdown(rows))
    except (ValueError, OSError) as exc:
        if args.debug or os.environ.get("POOL_ENV_DEBUG", "") not in ("", "0"):
            raise
        parser.exit(2, f"{PROG}: {exc}\n")
    print(leaderboard_markdown([row]))
    log(f"appended to {args.leaderboard} in {row['wall_seconds']:.1f} s")
    return row


__all__ = ["benchmark", "make_agent", "leaderboard_markdown", "append_row", "command_of", "strip_timings", "METRICS"]

if __name__ == "__main__":
    main()
