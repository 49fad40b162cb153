"""agents.benchmark: the tiny configuration end to end, every metric in the row, the pinned reference row,
determinism by seed, the tasks' seeds, and clear errors for bad agent and task names."""

import json
from pathlib import Path

import pytest

from agents import benchmark as bench
from agents.benchmark_tasks import BENCHMARK_VERSION, MAX_GAMES, NOISES, TASK_NAMES, TASKS, TINY_TASKS, select_tasks
from agents.learned import weights_path

# ghost_ball's tiny row: (wins, decisions, balls per turn, fouls per game, break-and-runs) per task.
# A change that moves it moved the benchmark: bump BENCHMARK_VERSION, then update PINNED_VERSION and this.
PINNED_VERSION = 2
PINNED = {"break-none": (2, 2, 1.0, 0.0, 0), "runout-olympiad": (0, 3, 0.5, 0.0, 0),
          "nine_ghost_ball-none": (2, 14, 13 / 3, 0.5, 0), "eight_ghost_ball-olympiad": (1, 16, 1.125, 0.5, 0)}


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    """ghost_ball on the --tiny configuration through the command line: the row and the leaderboard files."""
    leaderboard = tmp_path_factory.mktemp("benchmark") / "leaderboard.json"
    row = bench.main(["--agent", "ghost_ball", "--tiny", "--leaderboard", str(leaderboard)])
    return row, leaderboard


def test_tiny_row_has_every_metric(tiny):
    row, leaderboard = tiny
    assert row["benchmark_version"] == BENCHMARK_VERSION and row["agent"] == "ghost_ball"
    assert list(row["tasks"]) == list(TINY_TASKS)
    for name, result in row["tasks"].items():
        assert set(bench.METRICS) <= set(result), name
        assert result["games"] == 2 and result["seeds"][1] - result["seeds"][0] == 1
        lo, hi = result["ci95"]
        assert 0.0 <= lo <= result["win_rate"] <= hi <= 1.0
        assert result["decisions"] >= result["games"] and result["seconds_per_decision"] > 0.0
    assert json.loads(leaderboard.read_text()) == [row]
    md = leaderboard.with_suffix(".md").read_text()
    assert f"| task | ghost_ball (v{BENCHMARK_VERSION}) |" in md and bench.command_of(row) in md


def test_leaderboard_appends(tiny, tmp_path):
    row, _ = tiny
    path = tmp_path / "board.json"
    bench.append_row(row, path)
    rows = bench.append_row({**row, "agent": "again"}, path)
    assert [r["agent"] for r in rows] == ["ghost_ball", "again"]
    assert [r["agent"] for r in json.loads(path.read_text())] == ["ghost_ball", "again"]


def test_pinned_reference_row(tiny):
    """Fails when physics, rules, tasks or seeds move ghost_ball's tiny row: bump BENCHMARK_VERSION."""
    assert BENCHMARK_VERSION == PINNED_VERSION, "BENCHMARK_VERSION was bumped: re-pin PINNED"
    for name, (wins, decisions, balls, fouls, runs) in PINNED.items():
        r = tiny[0]["tasks"][name]
        assert (r["wins"], r["decisions"], r["break_and_runs"]) == (wins, decisions, runs), name
        assert r["balls_per_turn"] == pytest.approx(balls) and r["fouls_per_game"] == pytest.approx(fouls), name


def test_deterministic_by_seed():
    """The same tasks and counts give the same row (timings aside); random draws from the task's seeds."""
    tasks = ["nine_ghost_ball-olympiad", "runout-none"]
    for agent in ("random", "ghost_ball"):
        first, second = (bench.strip_timings(bench.benchmark(agent, 2, tasks)) for _ in range(2))
        assert first == second, agent


def test_command_reproduces_its_row(tiny, tmp_path):
    row, _ = tiny
    argv = bench.command_of(row).split()[3:]  # after "python -m agents.benchmark"
    again = bench.main([*argv, "--leaderboard", str(tmp_path / "board.json")])
    assert again["games"] == row["games"]
    assert bench.strip_timings(again["tasks"]) == bench.strip_timings(row["tasks"])


def test_tasks_cover_the_protocol():
    bases = {name.rsplit("-", 1)[0] for name in TASK_NAMES}
    assert bases == {"break", "runout", "nine_ghost_ball", "nine_search", "eight_ghost_ball"}
    assert {(t.name.rsplit("-", 1)[0], t.noise) for t in TASKS} == {(b, n) for b in bases for n in NOISES}
    seeds = [set(t.seeds(MAX_GAMES)) for t in TASKS]
    assert sum(len(s) for s in seeds) == len(set().union(*seeds))  # no two tasks share a seed
    assert [t.name for t in select_tasks(["nine_search"])] == ["nine_search-none", "nine_search-olympiad"]
    with pytest.raises(ValueError, match="games must be an integer"):
        TASKS[0].seeds(MAX_GAMES + 1)


def test_a_player_that_cannot_play_a_task_is_skipped_saying_why():
    row = bench.benchmark("search+value", 1, ["eight_ghost_ball-none"])
    assert "eight_ball" in row["tasks"]["eight_ghost_ball-none"]["skipped"]  # no 8-ball value net is shipped


def test_a_saved_learned_net_plays_as_the_learned_player():
    tasks = ["break-none"]
    by_path = bench.benchmark(str(weights_path("nine_ball")), 1, tasks)
    by_name = bench.benchmark("learned", 1, tasks)
    assert by_path["agent"] == "nine_ball"
    assert bench.strip_timings(by_path["tasks"]) == bench.strip_timings(by_name["tasks"])


@pytest.mark.parametrize("argv, message", [
    (["--agent", "nobody"], "unknown agent 'nobody'; choose one of"),
    (["--agent", "missing.npz"], "no such learned net file"),
    (["--agent", "missing.zip"], "no such model file"),
    (["--agent", "random", "--tasks", "snooker"], "unknown task 'snooker'"),
    (["--agent", "random", "--games", "0"], "--games takes N or TASK=N"),
    (["--agent", "random", "--games", "runout=x"], "--games takes N or TASK=N"),
])
def test_bad_input_ends_in_one_line(argv, message, tmp_path, capsys):
    with pytest.raises(SystemExit) as exit_info:
        bench.main([*argv, "--leaderboard", str(tmp_path / "board.json")])
    assert exit_info.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0]
    assert not (tmp_path / "board.json").exists()


def test_game_counts_per_task():
    default, overrides = bench.game_counts(["50", "nine_search=10", "break-none=3"], tiny=False)
    assert default == 50
    assert overrides == {"nine_search-none": 10, "nine_search-olympiad": 10, "break-none": 3}
    assert bench.game_counts(None, tiny=True) == (2, {})


def test_the_docs_leaderboard_is_the_reference_rows():
    """docs/benchmark.md shows docs/results/benchmark.json's rows, every one of this BENCHMARK_VERSION
    (a bump asks for the reference rows to be run again) with every metric of every task it played."""
    root = Path(__file__).resolve().parents[1]
    rows = json.loads((root / "docs/results/benchmark.json").read_text())
    assert [row["agent"] for row in rows][:4] == ["random", "ghost_ball", "search", "learned"]
    for row in rows:
        assert row["benchmark_version"] == BENCHMARK_VERSION, row["agent"]
        assert list(row["tasks"]) == list(TASK_NAMES)
        for result in row["tasks"].values():
            assert "skipped" in result or set(bench.METRICS) <= set(result)
    assert bench.leaderboard_markdown(rows) in (root / "docs/benchmark.md").read_text()
