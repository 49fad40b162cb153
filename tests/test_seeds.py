"""seeds.py: the default run across training seeds: Student's t intervals, the table, a smoke run over two seeds."""

import importlib.util
import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def load_seeds():
    sys.path.insert(0, str(ROOT))  # seeds.py imports train.py from beside it
    spec = importlib.util.spec_from_file_location("seeds_script", ROOT / "seeds.py")
    module = sys.modules[spec.name] = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_interval_across_seeds_is_students_t():
    seeds = load_seeds()
    # Values 1, 2, 3: mean 2, sample sd 1, t(0.975, 2 dof) = 4.303, half-width 4.303 / sqrt(3).
    out = seeds.across([1.0, 2.0, 3.0])
    assert out["mean"] == 2.0 and math.isclose(out["ci95"], 4.303 / math.sqrt(3.0))
    assert seeds.t95(4) == 2.776 and seeds.t95(12) == 2.228  # 12 dof: the table's 10 (a wider interval)


def test_the_table_states_each_verdict_from_the_interval():
    seeds = load_seeds()
    evals = []
    for k, (trained, diff) in enumerate([(1.2, 0.1), (1.0, -0.1), (1.1, 0.0)]):
        agent = {"reward": {"mean": trained}, "pocketed_per_episode": {"mean": 1.0}, "scratch_rate": {"mean": 0.1}}
        evals.append({"args": {"seed": k}, "agents": {"trained": agent},
                      "reward_differences": {"trained - heuristic": {"mean": diff},
                                             "trained - random": {"mean": 1.0 + diff}}})
    summary = seeds.summarize(evals)
    assert summary["seeds"] == [0, 1, 2] and math.isclose(summary["agents"]["trained"]["reward"]["mean"], 1.1)
    table = seeds.markdown(summary, "PoolBreak-v0", 250_000)
    assert "| trained - heuristic | +0.000 ± 0.248 | +0.100, -0.100, +0.000 | no difference shown |" in table
    assert "| trained - random | +1.000 ± 0.248 |" in table and "| better |" in table
    assert "no claim" in seeds.markdown(summary, "PoolBreak-v0", 512, claim=False)


def test_fewer_than_two_seeds_is_refused_in_one_line(tmp_path):
    out = subprocess.run([sys.executable, str(ROOT / "seeds.py"), "--seeds", "1"], cwd=tmp_path, capture_output=True,
                         text=True, timeout=60)
    assert out.returncode == 2 and out.stderr.strip().splitlines() == [
        "seeds.py: --seeds must be >= 2 (an interval across seeds needs two), got 1"]


@pytest.mark.slow
def test_a_smoke_run_over_two_seeds_writes_the_table(tmp_path):
    out = subprocess.run([sys.executable, str(ROOT / "seeds.py"), "--seeds", "2", "--timesteps", "512", "--n-steps",
                          "128", "--eval-episodes", "20", "--curve-points", "1", "--curve-episodes", "4",
                          "--video-episodes", "0", "--out", str(tmp_path)], cwd=tmp_path, capture_output=True,
                         text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    summary = json.loads((tmp_path / "PoolBreak-v0-ppo-512-seeds.json").read_text())
    assert summary["seeds"] == [0, 1] and len(summary["agents"]["trained"]["reward"]["values"]) == 2
    assert (tmp_path / "PoolBreak-v0-ppo-512-s0" / "eval.json").is_file()
    assert "no claim" in (tmp_path / "PoolBreak-v0-ppo-512-seeds.md").read_text()
