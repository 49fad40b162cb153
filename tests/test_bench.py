"""The benchmarks' helpers: the shared kinetic energy, the speed bench's A/B machinery, the accuracy bench's output."""

import json
import math
import os
import pathlib

import numpy as np
import pytest

from pool_env.bench import accuracy, pooltool_3d, speed
from pool_env.physics import Balls, Physics, simulate
from pool_env.physics.kinds import VX, VY, WX, WZ
from pool_env.physics.objects import kinetic_energy


def _balls(rng, pocketed):
    n = len(pocketed)
    xy = np.column_stack([0.1 + 0.2 * np.arange(n), np.full(n, 0.5)])
    return Balls(xy, v=rng.normal(size=(n, 2)), w=30 * rng.normal(size=(n, 3)),
                 radius=rng.uniform(0.02, 0.03, n), mass=rng.uniform(0.1, 0.2, n), pocketed=pocketed)


def _solid_ball_energy(v, w, radius, mass):
    """1/2 m |v|^2 + 1/2 I |w|^2 with I = 2/5 m R^2 (a solid sphere), one ball in plain floats."""
    inertia = 0.4 * mass * radius * radius
    return 0.5 * mass * (v[0] ** 2 + v[1] ** 2) + 0.5 * inertia * (w[0] ** 2 + w[1] ** 2 + w[2] ** 2)


def test_kinetic_energy_is_the_solid_ball_formula_per_ball_and_balls_energy_skips_pocketed():
    balls = _balls(np.random.default_rng(0), [False, True, False, False])
    per_ball = kinetic_energy(balls.v, balls.w, balls.radii, balls.masses)
    formula = [_solid_ball_energy(balls.v[i], balls.w[i], balls.radii[i], balls.masses[i]) for i in range(4)]
    np.testing.assert_allclose(per_ball, formula, rtol=1e-15)
    assert balls.energy() == pytest.approx(per_ball[[0, 2, 3]].sum(), rel=1e-15)


def test_kinetic_energy_broadcasts_over_samples():
    balls = _balls(np.random.default_rng(1), [False] * 3)
    result = simulate(balls, speed.two_ball_shot()[1], Physics.standard())
    rows, _ = result.sample(np.linspace(0.0, result.duration, 7))
    stacked = kinetic_energy(rows[..., VX:VY + 1], rows[..., WX:WZ + 1], balls.radii, balls.masses)
    assert stacked.shape == (7, 3)
    for k in range(7):
        at = result.at(float(np.linspace(0.0, result.duration, 7)[k]))
        assert stacked[k][~at.pocketed].sum() == pytest.approx(at.energy(), rel=1e-12)


def test_interleaved_takes_turns_abba():
    versions = [speed.Version("ours", "a"), speed.Version("theirs", "b")]
    order = []
    out = speed.interleaved(versions, 4, lambda v: order.append(v.name) or len(order))
    assert order == ["ours", "theirs", "theirs", "ours"] * 2
    assert out == {"ours": [1, 4, 5, 8], "theirs": [2, 3, 6, 7]}


def test_shot_figures_pool_the_rounds_per_rack():
    runs = [{"break": [[1.0, 2.0], [10.0, 10.0]], "events": [5, 6], "two_ball": [1.0, 3.0], "two_ball_events": 2},
            {"break": [[3.0, 4.0], [30.0, 30.0]], "events": [5, 6], "two_ball": [5.0], "two_ball_events": 2}]
    fig = speed.shot_figures(runs)
    # rack medians over both rounds: 2.5 and 20; the break figure is their median
    assert fig["break"] == pytest.approx(11.25)
    assert fig["two_ball"] == 3.0
    assert fig["by_round"] == [(5.75, 2.0), (16.75, 5.0)]


def test_run_python_refuses_a_folder_whose_pool_env_it_did_not_import(tmp_path):
    with pytest.raises(RuntimeError, match="not from"):
        speed.run_python(speed.IMPORT, speed.Version("theirs", str(tmp_path)))


def test_quick_skips_the_cold_compile_and_rejects_a_folder_without_pool_env(tmp_path):
    args = speed.parse_args(["--quick"])
    assert args.no_cold and (args.seeds, args.rounds) == (5, 2)
    assert speed.parse_args(["--quick", "--seeds", "3"]).seeds == 3
    with pytest.raises(SystemExit):
        speed.parse_args(["--against", str(tmp_path)])


@pytest.mark.slow
def test_speed_against_itself_prints_every_figure_and_a_ratio(capsys):
    argv = ["--quick", "--seeds", "1", "--repeats", "1", "--rounds", "1", "--runs", "1", "--against", speed.OURS]
    assert speed.main(argv) == 0
    out = capsys.readouterr().out
    for _, what, _ in speed.FIGURES:
        assert what in out
    assert "| ours / theirs |" in out and "skipped (--quick)" in out


@pytest.mark.slow
def test_vector_bench_prints_every_figure_beside_its_target(capsys):
    from pool_env.bench import vector

    assert vector.main(["--quick"]) == 0
    out = capsys.readouterr().out
    for what in ("PoolBreak-v0 native vector env, num_envs 64", "SB3 SubprocVecEnv, 2 workers",
                 "Gymnasium AsyncVectorEnv, 2 workers", "PoolBreakRun-v0 native vector env",
                 "simulate_batch, 2 threads", "256 native envs, resident memory"):
        assert what in out, what
    assert ">= 4,000" in out and ">= 8,000" in out and "<= 200 MB" in out


def test_accuracy_writes_to_an_untracked_folder_unless_told_to_update_the_docs():
    docs = pathlib.Path(__file__).resolve().parents[1] / "docs"
    args = accuracy.parse_args([])
    assert args.out == os.path.join("runs", "accuracy") and not args.update_docs  # runs/ is git-ignored
    assert pathlib.Path(accuracy.parse_args(["--update-docs"]).out) == docs
    assert accuracy.parse_args(["--out", "elsewhere"]).out == "elsewhere"
    with pytest.raises(SystemExit):
        accuracy.parse_args(["--update-docs", "--out", "elsewhere"])


@pytest.mark.slow
def test_accuracy_quick_run_writes_its_page_and_plot_and_leaves_the_docs_alone(tmp_path, capsys):
    docs = pathlib.Path(__file__).resolve().parents[1] / "docs"
    before = {name: (docs / name).stat().st_mtime_ns for name in ("accuracy.md", "accuracy.png")}
    assert accuracy.main(["--quick", "--out", str(tmp_path)]) == 0
    page = (tmp_path / "accuracy.md").read_text()
    assert (tmp_path / "accuracy.png").stat().st_size > 0
    assert "## The report's own loop" in page and "| report's loop | 1/60 |" in page
    assert "The report's own loop" in capsys.readouterr().out
    assert {name: (docs / name).stat().st_mtime_ns for name in before} == before


@pytest.mark.slow
def test_game_bench_prints_every_figure_beside_its_target(capsys):
    from pool_env.bench import game

    assert game.main(["--seconds", "0.2", "--repeats", "1", "--decisions", "2"]) == 0
    out = capsys.readouterr().out
    for label in ("Game.evaluate of 256 shots", "PoolBreakRun-v0 native vector env", "against the random player",
                  "PoolNineBall-v0 against the ghost-ball player", "PoolEightBall-v0 against the ghost-ball player",
                  "native vector env of 64", "search player, 9-ball mid-game, no noise",
                  "search player, 9-ball mid-game, olympiad noise"):
        assert label in out
    assert out.count(">= ") == 5  # the search's target is a ratio to another checkout (--against)


def test_speed_says_fastfiz_is_not_installed_without_a_python_that_imports_it(tmp_path, capsys, monkeypatch):
    monkeypatch.delenv("POOL_ENV_FASTFIZ_PYTHON", raising=False)
    args = speed.parse_args(["--quick", "--fastfiz", str(tmp_path / "no-python")])
    assert speed.fastfiz_python(args) is None
    speed.print_fastfiz({"ours": {"two_ball": 20e-6}})
    assert "FastFiz not installed" in capsys.readouterr().out


def test_fastfiz_ratio_is_theirs_over_ours_against_its_target(capsys):
    peer = {"two_ball": 30e-6, "events": 10, "theta": 2, "python": "py"}
    speed.print_fastfiz({"ours": {"two_ball": 20e-6}, "fastfiz": peer})
    out = capsys.readouterr().out
    assert "FastFiz / ours = 1.50" in out and "target >= 1.2: met" in out


def test_pooltool3d_bench_runs_without_pooltool_and_names_what_it_skipped(tmp_path, capsys):
    assert pooltool_3d.main(["--no-pooltool", "--strikes", "2", "--out", str(tmp_path)]) == 0
    out = json.loads((tmp_path / "pooltool_3d.json").read_text())
    assert out["notes"]["pooltool"] == "skipped (--no-pooltool)"
    assert len(out["rows"]) == 2 and all(r["pooltool"] is None for r in out["rows"])
    ran = out["notes"]["ours"].startswith("ran")
    assert ran or out["notes"]["ours"].startswith("skipped: ")
    assert all((r["ours"] is not None) == ran for r in out["rows"])
    assert "skipped" in capsys.readouterr().out


def test_pooltool3d_closed_forms_follow_the_bounce_laws():
    """A centre hit at speed v, elevation t: the slate returns v_z = e v sin t; the stop-slip
    impulse (2/7) v cos t is below the sliding one mu (1 + e) v sin t at 45 degrees, so the ball
    leaves rolling at 5/7 v cos t; each flight lasts 2 v_z / g, and the bottom rises
    h_k = e^(2k) (e v sin t)^2 / (2g) until h_k < 5 mm."""
    p = pooltool_3d
    v, t, e, g = 4.0, math.radians(45.0), p.E_T, p.G
    path, settle = p.flights(*p.struck(v, t, 0.0, 0.0))
    vz, vh = e * v * math.sin(t), 5.0 / 7.0 * v * math.cos(t)
    heights = [e ** (2 * k) * vz * vz / (2 * g) for k in range(10)]
    n = next(k for k, h in enumerate(heights) if h < p.BOUNCE_STOP)
    assert len(path) == n
    assert path[0]["duration"] == pytest.approx(2 * vz / g, rel=1e-12)
    assert [f["peak"] for f in path] == pytest.approx(heights[:n], rel=1e-12)
    assert path[0]["landing"] == pytest.approx([vh * 2 * vz / g, 0.0], abs=1e-12)
    assert settle["t"] == pytest.approx(sum(2 * vz * e ** k / g for k in range(n)), rel=1e-12)


def test_pooltool3d_blocker_is_cleared_exactly_when_the_apex_over_it_is_two_radii_up():
    """A flight whose apex is over the blocker, centre H above the blocker's, passes it at the
    distance D(s)^2 = vx^2 s^2 + (H - g s^2 / 2)^2 (s the time from the apex), whose least value
    is H^2 at the apex when vx^2 >= g H: the ball clears iff H >= 2R."""
    p, r, g = pooltool_3d, pooltool_3d.BALL_RADIUS, pooltool_3d.G
    vx, d = 3.0, 0.5
    for scale, verdict in ((1.0 + 1e-6, "jumped"), (1.0 - 1e-6, "hit")):
        vz = math.sqrt(2.0 * g * 2.0 * r * scale)
        apex = vz / g
        flight = {"t0": 0.0, "start": [d - vx * apex, 0.0], "vh": [vx, 0.0], "vz": vz, "duration": 2.0 * apex,
                  "landing": [d + vx * apex, 0.0]}
        assert vx * vx >= g * 2.0 * r * scale
        assert p.clearance([flight], {"t": 2.0 * apex, "xy": flight["landing"]}, d)["verdict"] == verdict


def test_pixels_bench_prints_batched_and_single_beside_the_target(capsys):
    from pool_env.bench import pixels

    assert pixels.main(["--quick"]) == 0
    out = capsys.readouterr().out
    for what in ("84x84 RGB: batched, native vector env of 16", "84x84 RGB: single env", "TableRenderer.draw"):
        assert what in out, what
    assert ">= 10,000" in out
    with pytest.raises(ValueError, match="num-envs"):
        pixels.main(["--num-envs", "0"])


def test_pooltool_table_shape_gives_the_eight_foot_tables_documented_mouths():
    """The table pooltool is given has Table.eight_foot's mouths between the jaw points: 4.5625 in
    at the corners and 5.0625 in at the sides (the WPA ranges' middles, 0.1159 and 0.1286 m)."""
    from pool_env.bench.speed_pooltool import table_shape
    from pool_env.physics import Table

    shape = table_shape(Table.eight_foot())
    assert shape["corner"] == pytest.approx(4.5625 * 0.0254, abs=1e-4)
    assert shape["side"] == pytest.approx(5.0625 * 0.0254, abs=1e-4)
    assert (shape["l"], shape["w"]) == (2.24, 1.12)
    with pytest.raises(ValueError, match="six-pocket"):
        table_shape(Table(2.24, 1.12))
