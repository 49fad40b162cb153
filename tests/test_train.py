"""train.py: a smoke run with tiny settings produces every artefact, reports progress, makes no claim
from a run too short to mean anything; --help lists the options; the verdict's wording."""

import json
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
PROGRESS = re.compile(r"progress: [\d,]+/2,000 shots \(\d+ %\), [\d,]+ shots/s, mean reward [+-]\d+\.\d{3} "
                      r"\(last \d+ episodes\), \d+:\d\d:\d\d elapsed, \d+:\d\d:\d\d left")


def run_train(*args, timeout=240):
    return subprocess.run([sys.executable, str(ROOT / "train.py"), *args], cwd=ROOT, capture_output=True, text=True,
                          timeout=timeout)


def test_help_lists_every_option():
    out = run_train("--help", timeout=60)
    assert out.returncode == 0, out.stderr
    for flag in ("--env-id", "--algo", "--timesteps", "--n-envs", "--seed", "--spin", "--eval-episodes", "--out",
                 "--progress-every", "--min-timesteps"):
        assert flag in out.stdout


def test_verdict_claims_only_what_the_intervals_show():
    from agents.report import verdict

    differences = {"trained - random": {"mean": 0.31, "ci95": 0.05},      # interval above zero
                   "trained - heuristic": {"mean": -0.03, "ci95": 0.13},  # straddles zero
                   "trained - head-on break": {"mean": -0.8, "ci95": 0.1}}
    words = verdict(differences, trained_steps=250_000, min_timesteps=25_000, untrained=None, episodes=1000)
    assert words.startswith("the trained agent beats random (+0.310 ± 0.050), is not distinguishable from heuristic")
    assert "loses to head-on break" in words
    # A difference whose interval only touches zero is no win.
    assert "beats" not in verdict({"trained - random": {"mean": 0.1, "ci95": 0.1}}, 250_000, 25_000, None, 1000)
    # Too short, or the untrained policy kept: no claim, whatever the intervals say.
    short = verdict(differences, trained_steps=2_048, min_timesteps=25_000, untrained=None, episodes=1000)
    assert "beats" not in short and "too short to mean anything (2,048 timesteps" in short
    kept = verdict(differences, 250_000, 25_000, untrained={"timesteps": 2}, episodes=1000)
    assert "beats" not in kept and "untrained policy" in kept


def test_progress_line_fields():
    from agents.report import progress_line

    line = progress_line(10_000, 20_000, 4.0, [1.0, -1.0, 3.0])
    assert line == ("progress: 10,000/20,000 shots (50 %), 2,500 shots/s, mean reward +1.000 (last 3 episodes), "
                    "0:00:04 elapsed, 0:00:04 left")


@pytest.fixture(scope="module")
def smoke_run(tmp_path_factory):
    out_dir = tmp_path_factory.mktemp("runs")
    # The progress bar stays on: stdout is captured (not a terminal), as in CI or a run redirected to a file.
    proc = run_train("--timesteps", "2000", "--eval-episodes", "30", "--curve-points", "2", "--curve-episodes", "10",
                     "--video-episodes", "1", "--out", str(out_dir), "--run-name", "smoke", "--progress-every", "0.1")
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return out_dir / "smoke", proc.stdout


@pytest.mark.slow
def test_smoke_run_writes_every_artefact(smoke_run):
    run_dir, stdout = smoke_run
    assert str(run_dir.resolve()) in stdout  # the run folder is printed
    for name in ("model.zip", "eval.json", "results.md", "learning_curve.png", "trained.mp4", "train.log",
                 "args.json"):
        assert (run_dir / name).is_file() and (run_dir / name).stat().st_size > 0, name
    assert list((run_dir / "tb").rglob("events.out.tfevents.*")), "no TensorBoard log"
    assert list((run_dir / "monitor").glob("*.monitor.csv")), "no Monitor log"
    assert (run_dir / "learning_curve.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.slow
def test_smoke_run_evaluates_all_agents_on_the_same_seeds(smoke_run):
    run_dir, stdout = smoke_run
    result = json.loads((run_dir / "eval.json").read_text())
    assert result["env_id"] == "PoolBreak-v0" and result["eval_seeds"]["count"] == 30
    assert {"trained", "random", "heuristic"} <= set(result["agents"])
    for summary in result["agents"].values():
        assert summary["episodes"] == 30
        for key in ("reward", "pocketed_per_shot", "scratch_rate"):
            assert np.isfinite(summary[key]["mean"]) and np.isfinite(summary[key]["ci95"])
    assert "trained - random" in result["reward_differences"]
    episodes = json.loads((run_dir / "eval_episodes.json").read_text())
    assert [e["seed"] for e in episodes["trained"]] == [e["seed"] for e in episodes["random"]]
    # The table is logged (console and train.log), not only written to the json.
    log = (run_dir / "train.log").read_text()
    assert "| trained" in log and "| heuristic" in log and "| trained" in stdout
    # ... and written to results.md, a row per agent, with the paired differences and the verdict.
    results = (run_dir / "results.md").read_text()
    for name in result["agents"]:
        assert re.search(rf"^\| {re.escape(name)} +\| [+-]\d", results, re.M), name
    assert "| agent" in results and "balls / shot" in results and "scratch rate" in results
    assert "- trained - random: " in results and f"Verdict: {result['verdict']}." in results


@pytest.mark.slow
def test_smoke_run_reports_progress_when_stdout_is_not_a_terminal(smoke_run):
    run_dir, stdout = smoke_run
    assert PROGRESS.search(stdout), stdout
    assert PROGRESS.search((run_dir / "train.log").read_text())


@pytest.mark.slow
def test_smoke_run_makes_no_claim(smoke_run):
    """A 2,000-step run can keep the untrained policy, whose weakest tap never scratches and so
    out-scores random on reward: the run must say it is too short rather than that it beats random."""
    run_dir, stdout = smoke_run
    result = json.loads((run_dir / "eval.json").read_text())
    assert result["trained_timesteps"] >= 2000
    for text in (stdout, (run_dir / "train.log").read_text(), (run_dir / "results.md").read_text(),
                 result["verdict"]):
        assert "beats" not in text
        assert "too short to mean anything (2,048 timesteps, under --min-timesteps 25,000)" in text


@pytest.mark.slow
def test_smoke_run_model_and_video_are_usable(smoke_run):
    import imageio_ffmpeg

    from agents import SB3Agent

    run_dir, _ = smoke_run
    agent = SB3Agent.load(run_dir / "model.zip")
    assert agent.act(np.zeros(49, dtype=np.float32)).shape == (2,)
    frames, seconds = imageio_ffmpeg.count_frames_and_secs(str(run_dir / "trained.mp4"))
    assert frames > 30 and seconds > 1  # a whole shot, not a single frame


@pytest.mark.slow
def test_sac_option_runs(tmp_path):
    proc = run_train("--algo", "sac", "--timesteps", "1200", "--eval-episodes", "5", "--curve-points", "0",
                     "--video-episodes", "0", "--n-envs", "1", "--out", str(tmp_path), "--run-name", "sac",
                     "--no-progress-bar")
    assert proc.returncode == 0, proc.stdout + proc.stderr
    from agents import algorithm_of

    assert algorithm_of(tmp_path / "sac" / "model.zip") == "SAC"
    assert (tmp_path / "sac" / "eval.json").is_file() and (tmp_path / "sac" / "learning_curve.png").is_file()


def test_game_verdict_and_summary():
    from agents.report import game_summary, game_table, game_verdict

    games = ([{"winner": "agent", "agent_breaks": k % 2 == 0, "shots": 5} for k in range(150)]
             + [{"winner": "opponent", "agent_breaks": k % 2 == 0, "shots": 7} for k in range(48)]
             + [{"winner": None, "agent_breaks": False, "shots": 100}] * 2)
    summary = game_summary(games)
    win = summary["win_rate"]
    assert (summary["wins"], summary["losses"], summary["unfinished"]) == (150, 48, 2)
    assert win["mean"] == pytest.approx(151 / 200) and win["low"] < win["mean"] < win["high"]
    assert summary["reward"]["mean"] == pytest.approx((150 - 48) / 200)
    assert game_verdict(win, "ghost_ball", []).startswith("the trained agent beats ghost_ball (win rate 75.5 %")
    assert "is not distinguishable from x" in game_verdict({"mean": 0.52, "low": 0.45, "high": 0.59,
                                                                  "games": 200}, "x", [])
    assert "loses to x" in game_verdict({"mean": 0.3, "low": 0.24, "high": 0.37, "games": 200}, "x", [])
    assert game_verdict(win, "ghost_ball", ["too short"]) == "no claim against ghost_ball: too short"
    assert "| trained | 75.5 % [" in game_table({"trained": summary})


@pytest.mark.slow
def test_game_env_smoke_run(tmp_path):
    """The game path: 9-ball through GhostBallAction, practice training, win rates against ghost_ball."""
    proc = run_train("--env-id", "PoolNineBall-v0", "--opponent", "ghost_ball", "--ghost-ball-action", "--practice",
                     "--timesteps", "600", "--n-steps", "128", "--batch-size", "64", "--eval-episodes", "6",
                     "--curve-points", "1", "--curve-episodes", "4", "--video-episodes", "1", "--out", str(tmp_path),
                     "--run-name", "game", "--no-progress-bar", timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    run_dir = tmp_path / "game"
    for name in ("model.zip", "eval.json", "results.md", "learning_curve.png", "trained.mp4", "eval_episodes.json"):
        assert (run_dir / name).is_file() and (run_dir / name).stat().st_size > 0, name
    result = json.loads((run_dir / "eval.json").read_text())
    assert result["env_id"] == "PoolNineBall-v0" and result["train_kwargs"] == {"opponent": None}
    assert {"trained", "ghost_ball", "random"} == set(result["agents"])
    for summary in result["agents"].values():
        win = summary["win_rate"]
        assert summary["episodes"] == 6 and win["low"] - 1e-9 <= win["mean"] <= win["high"] + 1e-9
        assert summary["wins"] + summary["losses"] + summary["unfinished"] == 6
    episodes = json.loads((run_dir / "eval_episodes.json").read_text())
    assert [e["agent_breaks"] for e in episodes["trained"]] == [True, False] * 3  # breaks alternate
    results = (run_dir / "results.md").read_text()
    assert "| trained |" in results and "| ghost_ball |" in results and "no claim against ghost_ball" in results
    from agents import SB3Agent

    assert SB3Agent.load(run_dir / "model.zip").act(np.zeros(44, dtype=np.float32)).shape == (13,)
