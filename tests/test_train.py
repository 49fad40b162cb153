"""train.py: a smoke run with tiny settings produces every artefact, and --help lists the options."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]


def run_train(*args, timeout=240):
    return subprocess.run([sys.executable, str(ROOT / "train.py"), *args], cwd=ROOT, capture_output=True, text=True,
                          timeout=timeout)


def test_help_lists_every_option():
    out = run_train("--help", timeout=60)
    assert out.returncode == 0, out.stderr
    for flag in ("--env-id", "--algo", "--timesteps", "--n-envs", "--seed", "--spin", "--eval-episodes", "--out"):
        assert flag in out.stdout


@pytest.fixture(scope="module")
def smoke_run(tmp_path_factory):
    out_dir = tmp_path_factory.mktemp("runs")
    proc = run_train("--timesteps", "2000", "--eval-episodes", "30", "--curve-points", "2", "--curve-episodes", "10",
                     "--video-episodes", "1", "--out", str(out_dir), "--run-name", "smoke", "--no-progress-bar")
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return out_dir / "smoke", proc.stdout


@pytest.mark.slow
def test_smoke_run_writes_every_artefact(smoke_run):
    run_dir, stdout = smoke_run
    assert str(run_dir.resolve()) in stdout  # the run folder is printed
    for name in ("model.zip", "eval.json", "learning_curve.png", "trained.mp4", "train.log", "args.json"):
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
