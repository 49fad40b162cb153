"""The commands' errors: a bad argument or file ends in one line on stderr naming the problem and exit
status 2, before any work (no run folder, no output file); --debug or POOL_ENV_DEBUG=1 shows the traceback.

Each case runs the command in a subprocess, in an empty folder, as a user would; none trains or plays
(every check comes before the work), so each takes about as long as the command's imports."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SAVED = ROOT / "tests" / "data" / "saved_games" / "nine_ball_ghost_vs_ghost.json"
N_SAVED = len(json.loads(SAVED.read_text())["actions"])  # its steps (tests/data/make_saved_games.py re-records it)
REPLAY = ("-m", "pool_env.records.replay")
TOURNAMENT = ("-m", "agents.tournament", "--games", "1", "--noise", "none", "--out", "tournament")
TRAIN = (str(ROOT / "train.py"), "--out", "runs")
PLAY = ("-m", "pool_env.play")
BENCH = ("-m", "pool_env.bench")


def write_files(folder: Path) -> None:
    """The bad files of the replay cases: empty, not JSON, outcomes short of the actions, keys missing."""
    (folder / "empty.json").write_text("")
    (folder / "junk.json").write_text("not a saved game\n")
    record = json.loads(SAVED.read_text())
    (folder / "short.json").write_text(json.dumps({**record, "outcomes": record["outcomes"][:-1]}))
    (folder / "keys.json").write_text(json.dumps({k: v for k, v in record.items() if k not in ("seed", "table")}))


# (id, the command's arguments, what its one line must say, what it must not say)
CASES = [
    ("replay-missing", (*REPLAY, "nope.json"), ["nope.json", "No such file"], []),
    ("replay-empty", (*REPLAY, "empty.json"), ["empty.json", "empty"], []),
    ("replay-not-json", (*REPLAY, "junk.json"), ["junk.json", "not JSON"], []),
    ("replay-short", (*REPLAY, "short.json"), ["short.json", f"{N_SAVED} actions but {N_SAVED - 1} outcomes"],
     ["missing"]),
    ("replay-missing-keys", (*REPLAY, "keys.json"), ["keys.json", "missing seed, table"], ["outcomes"]),
    ("train-timesteps-0", (*TRAIN, "--timesteps", "0"), ["--timesteps must be >= 1, got 0"], []),
    ("train-timesteps-negative", (*TRAIN, "--timesteps", "-5"), ["--timesteps must be >= 1, got -5"], []),
    ("train-env-id", (*TRAIN, "--env-id", "PoolBrake-v0"), ["--env-id PoolBrake-v0", "PoolBreak-v0"], []),
    ("tournament-typo", (*TOURNAMENT, "--players", "random,ghost_ball,serch"),
     ["unknown player 'serch'", "ghost_ball, learned, random, search"], []),
    ("tournament-one-left", (*TOURNAMENT, "--players", "random,serch"), ["unknown player 'serch'"], []),
    ("tournament-one-player", (*TOURNAMENT, "--players", "random"), ["at least two players, got random"], []),
    ("tournament-games-0", (*TOURNAMENT, "--games", "0"), ["--games must be >= 1, got 0"], []),
    ("play-size", (*PLAY, "--size", "-5", "300"), ["--size", "-5 300"], []),
    ("bench-unknown", (*BENCH, "nope"), ["unknown bench 'nope'", "speed"], []),
]
IDS = [case[0] for case in CASES]


def run(folder: Path, args, debug_env: bool = False) -> subprocess.CompletedProcess:
    """`python ARGS` in `folder`, importing this checkout, headless (the play window on SDL's dummy driver)."""
    env = {**os.environ, "PYTHONPATH": str(ROOT), "SDL_VIDEODRIVER": "dummy", "SDL_AUDIODRIVER": "dummy"}
    env.pop("POOL_ENV_DEBUG", None)
    if debug_env:
        env["POOL_ENV_DEBUG"] = "1"
    return subprocess.run([sys.executable, *args], cwd=folder, env=env, capture_output=True, text=True, timeout=120)


@pytest.fixture
def folder(tmp_path):
    write_files(tmp_path)
    return tmp_path


def made_nothing(folder: Path) -> None:
    """Nothing but the case's own input files: no run folder, no tournament output, no saved game."""
    assert sorted(p.name for p in folder.iterdir()) == ["empty.json", "junk.json", "keys.json", "short.json"]


@pytest.mark.parametrize(("name", "args", "says", "not_says"), CASES, ids=IDS)
def test_a_bad_input_ends_in_one_line_and_status_2(folder, name, args, says, not_says):
    proc = run(folder, args)
    lines = [line for line in proc.stderr.splitlines() if line.strip()]
    assert proc.returncode == 2, proc.stderr
    assert "Traceback" not in proc.stderr
    assert len(lines) == 1, proc.stderr
    prog = "train.py" if name.startswith("train") else "python -m " + args[1]
    assert lines[0].startswith(prog + ": "), lines[0]
    for words in says:
        assert words in lines[0], lines[0]
    for words in not_says:
        assert words not in lines[0], lines[0]
    made_nothing(folder)


@pytest.mark.parametrize(("name", "args", "says", "not_says"), CASES, ids=IDS)
def test_debug_shows_the_traceback(folder, name, args, says, not_says):
    proc = run(folder, (*args, "--debug"))
    assert proc.returncode != 0 and "Traceback (most recent call last)" in proc.stderr, proc.stderr
    assert says[-1] in proc.stderr.splitlines()[-1]  # the traceback ends in the same message
    made_nothing(folder)


def test_the_debug_environment_variable_shows_the_traceback(folder):
    proc = run(folder, (*TRAIN, "--timesteps", "0"), debug_env=True)
    assert proc.returncode != 0 and "Traceback (most recent call last)" in proc.stderr, proc.stderr
    made_nothing(folder)


def test_an_argparse_error_ends_in_the_line_naming_it(folder):
    """argparse's own errors (a bad type or choice) keep its usage lines; the last line names the problem."""
    proc = run(folder, (*TRAIN, "--opponent", "ghost"))
    assert proc.returncode == 2 and "Traceback" not in proc.stderr
    last = [line for line in proc.stderr.splitlines() if line.strip()][-1]
    assert last.startswith("train.py: error: argument --opponent: invalid choice: 'ghost'"), last
    made_nothing(folder)


def test_a_good_replay_still_succeeds(folder):
    proc = run(folder, (*REPLAY, str(SAVED), "--no-window"))
    assert proc.returncode == 0 and proc.stderr == "", proc.stderr
    assert proc.stdout.startswith(f"replayed {N_SAVED} steps of PoolNineBall-v0")
