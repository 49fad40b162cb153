"""What a first shot compiles: a level scene with the core collision models compiles neither the airborne
code nor the other models; a ball in the air, or another model, compiles the full engine."""

import json
import os
import subprocess
import sys
import textwrap

import pytest

# In a fresh process with an empty numba cache, every dispatcher a shot's compile reaches has
# a signature afterwards (numba types the whole call graph it reaches, so this is the set of
# functions compiled). Prints the compiled function names after each shot, one JSON line.
PROGRAM = textwrap.dedent("""
    import json, sys
    from numba.core.registry import CPUDispatcher
    from pool_env.physics import Balls, Physics, Table, simulate

    def compiled():
        names = []
        for name, module in list(sys.modules.items()):
            if name.startswith("pool_env.physics"):
                for attr, obj in vars(module).items():
                    if isinstance(obj, CPUDispatcher) and obj.py_func.__module__ == name and obj.signatures:
                        names.append(f"{name}.{attr}")
        return sorted(names)

    table = Table.eight_foot()
    level = simulate(Balls([[0.5, 0.5], [1.0, 0.55]], v=[[1.0, 0.0], [0.0, 0.0]]), table, Physics.standard())
    after_level = compiled()
    # The cue ball 1 cm above the cloth, moving at 1 m/s: it lands and bounces.
    flying = simulate(Balls([[0.5, 0.5], [1.0, 0.55]], v=[[1.0, 0.0], [0.0, 0.0]], z=[0.01, 0.0]), table,
                      Physics.standard())
    after_air = compiled()
    # A level shot into a rail under another cushion model runs on the full engine, compiled already.
    other = simulate(Balls([[0.5, 0.5], [1.0, 0.55]], v=[[-1.0, 0.0], [0.0, 0.0]]), table,
                     Physics(cushion="mathavan2010"))
    print(json.dumps({"level": after_level, "air": after_air, "other": compiled(),
                      "level_events": level.stats["events"], "air_kinds": sorted({e.kind for e in flying.events}),
                      "other_kinds": sorted({e.kind for e in other.events})}))
""")


@pytest.mark.slow
def test_a_level_shot_compiles_no_airborne_function(tmp_path):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path), POOL_ENV_JIT="1")  # numba compiles (no extension)
    out = subprocess.run([sys.executable, "-c", PROGRAM], env=env, capture_output=True, text=True, timeout=900)
    assert out.returncode == 0, out.stderr[-3000:]
    data = json.loads(out.stdout.strip().splitlines()[-1])
    level, air = set(data["level"]), set(data["air"])
    assert {"pool_env.physics.engine.simulate_scene", "pool_env.physics.predict.predict"} <= level
    assert data["level_events"] > 0
    # A level scene: nothing of airborne.py, nor the fixed-step and seed-report loops, nor the
    # collision models other than the core's (frictional, han2005).
    for module in ("airborne", "fixed", "fixed_frame", "fixed_priori", "fixed_posteriori", "seed_loop", "mathavan"):
        assert not [f for f in level if f.startswith(f"pool_env.physics.{module}.")], module
    others = {"pool_env.physics.ball_ball.seed", "pool_env.physics.ball_ball.elastic",
              "pool_env.physics.ball_ball._seed_group", "pool_env.physics.cushion.seed",
              "pool_env.physics.cushion.restitution"}
    assert {"pool_env.physics.ball_ball.frictional", "pool_env.physics.cushion.han2005"} <= level
    assert not level & others
    # A ball in the air reaches the 3D engine: the landing (a ball_table event) is airborne.py's.
    assert "ball_table" in data["air_kinds"]
    assert {"pool_env.physics.airborne.land", "pool_env.physics.airborne.boundary_times",
            "pool_env.physics.airborne.pair_time"} <= air
    # The full engine holds every collision model: another one compiles nothing more.
    assert others | {"pool_env.physics.mathavan.mathavan2010"} <= air
    assert set(data["other"]) == air and "ball_cushion" in data["other_kinds"]
