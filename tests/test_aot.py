"""The engine compiled ahead of time (pool_env/build_aot.py, physics/compiled.py) against numba's JIT.

Each engine runs in its own fresh process (the mode is chosen at import): the same scenes must
give bit-identical events and final states, the JIT must take over when the extension is
missing or stale, and the first shot under the extension imports neither numba nor gymnasium.
The comparisons skip where the extension is not built (POOL_ENV_NO_AOT, a failed build), and
fail instead with POOL_ENV_REQUIRE_AOT=1 (as CI sets: its install must have built it).
"""

import json
import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from pool_env.physics import compiled

ROOT = Path(__file__).resolve().parents[1]
BUILT = compiled.extension()[1] == "aot"


def test_the_extension_is_built_where_it_must_be():
    if os.environ.get("POOL_ENV_REQUIRE_AOT") == "1":
        assert BUILT, f"POOL_ENV_REQUIRE_AOT=1 but the ahead-of-time engine is {compiled.extension()[1]}"


needs_extension = pytest.mark.skipif(not BUILT, reason=f"ahead-of-time engine: {compiled.extension()[1]}")

# Digests of every engine run's raw output (final rows and states, the event log), in order,
# over breaks, the 2-ball shot, mid-game shots, jump shots and a ball in the air; then which
# engine ran and what was imported. argv[1]: Python run first (e.g. to block the extension).
DIGESTS = textwrap.dedent("""
    import sys
    exec(sys.argv[1])
    import hashlib, json, math
    import numpy as np
    from pool_env.physics import BALL_MASS, Balls, Physics, Table, compiled, rack, simulate, strike
    from pool_env.bench.shots import break_shot, two_ball_shot

    physics = Physics.standard()

    def digest(result):
        f = result.final
        h = hashlib.sha256(repr([tuple(e) for e in result.events]).encode())
        for a in (f.xy, f.v, f.w, f.pocketed):
            h.update(np.ascontiguousarray(a).tobytes())
        return h.hexdigest()

    out = []
    for seed in range(8):
        balls, table = break_shot(seed)
        result = simulate(balls, table, physics)
        out.append(digest(result))
        final = result.final
        if not final.pocketed[0] and not final.pocketed[1:].all():
            k = 1 + int(final.pocketed[1:].argmin())
            aim = final.xy[k] - final.xy[0]
            rest = Balls(final.xy, pocketed=final.pocketed)
            out.append(digest(simulate(strike(rest, force=aim / math.hypot(*aim) * 2 * BALL_MASS / 0.005), table,
                                       physics)))
    out.append(digest(simulate(*two_ball_shot(), physics)))
    table = Table.eight_foot()
    for seed in range(3):
        shot = strike(rack(table, seed=seed), force=(30.0, 0.5 * seed), elevation=0.3, offset=(0.0, 0.01))
        out.append(digest(simulate(shot, table, physics)))
    out.append(digest(simulate(Balls([[0.5, 0.5], [1.0, 0.55]], v=[[1.0, 0.0], [0.0, 0.0]], z=[0.01, 0.0]), table,
                               physics)))
    print(json.dumps({"digests": out, "engine": compiled.engine(), "why": compiled.WHY,
                      "numba": "numba" in sys.modules}))
""")


# Runs tests/test_hard_cases.py (not its slow tests) and prints the digest of every Result made.
HARD_CASES = textwrap.dedent("""
    import hashlib, json, sys
    import numpy as np
    import pytest
    from pool_env.physics import compiled, result

    digests = []
    made = result.Result.__init__

    def recording(self, *args, **kwargs):
        made(self, *args, **kwargs)
        h = hashlib.sha256(repr([tuple(e) for e in self.events]).encode())
        for a in (self.final.xy, self.final.v, self.final.w, self.final.pocketed):
            h.update(np.ascontiguousarray(a).tobytes())
        digests.append(h.hexdigest())

    result.Result.__init__ = recording
    code = pytest.main(["-q", "-p", "no:cacheprovider", "-m", "not slow", "tests/test_hard_cases.py"])
    print(json.dumps({"code": int(code), "digests": digests, "engine": compiled.engine()}))
""")


def run(code, *args, env=None, cwd=ROOT):
    env = dict(os.environ if env is None else env)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(cwd), env.get("PYTHONPATH")) if p)
    out = subprocess.run([sys.executable, "-c", code, *args], cwd=cwd, env=env, capture_output=True, text=True,
                         timeout=900)
    assert out.returncode == 0, out.stderr[-3000:]
    return json.loads(out.stdout.strip().splitlines()[-1]), out.stderr


def jit_env():
    return dict(os.environ, POOL_ENV_JIT="1")


def aot_env():
    return {k: v for k, v in os.environ.items() if k != "POOL_ENV_JIT"}


@needs_extension
def test_the_extension_and_the_jit_give_bit_identical_results():
    aot, _ = run(DIGESTS, "", env=aot_env())
    jit, _ = run(DIGESTS, "", env=jit_env())
    assert (aot["engine"], aot["numba"]) == ("aot", False)
    assert (jit["engine"], jit["why"]) == ("jit", "POOL_ENV_JIT is set")
    assert len(aot["digests"]) > 12 and aot["digests"] == jit["digests"]


@pytest.mark.slow
@needs_extension
def test_the_hard_cases_run_bit_identically_on_the_extension_and_the_jit():
    aot, _ = run(HARD_CASES, env=aot_env())
    jit, _ = run(HARD_CASES, env=jit_env())
    assert (aot["code"], aot["engine"], jit["code"], jit["engine"]) == (0, "aot", 0, "jit")
    assert len(aot["digests"]) > 100 and aot["digests"] == jit["digests"]


@needs_extension
def test_without_the_extension_the_jit_runs_the_same_shots():
    block = "sys.modules['pool_env.physics.engine_aot'] = None"  # its import then fails
    missing, _ = run(DIGESTS, block, env=aot_env())
    assert missing["engine"] == "jit" and missing["why"].startswith("not importable") and missing["numba"]
    assert missing["digests"] == run(DIGESTS, "", env=aot_env())[0]["digests"]


@needs_extension
def test_a_stale_extension_is_set_aside_silently(tmp_path):
    # A copy of the package whose physics sources differ from the ones the extension was built from.
    shutil.copytree(ROOT / "pool_env", tmp_path / "pool_env", ignore=shutil.ignore_patterns("__pycache__"))
    with open(tmp_path / "pool_env" / "physics" / "motion.py", "a") as f:
        f.write("# edited after the build\n")
    code = ("import json, warnings; warnings.simplefilter('always'); import pool_env.physics.compiled as c; "
            "print(json.dumps({'engine': c.engine(), 'why': c.WHY, 'file': c.__file__}))")
    out, err = run(code, env=aot_env(), cwd=tmp_path)
    assert Path(out["file"]).is_relative_to(tmp_path)
    assert (out["engine"], out["why"]) == ("jit", "stale")
    assert err == ""  # a command's error stays one line (tests/test_cli.py)


@needs_extension
def test_the_first_shot_imports_neither_numba_nor_gymnasium():
    code = textwrap.dedent("""
        import json, sys
        from pool_env.physics import Physics, Table, rack, simulate, strike
        t = Table.eight_foot()
        simulate(strike(rack(t, seed=0), force=(8 * 0.170097 / 0.005, 0.0)), t, Physics.standard())
        print(json.dumps(sorted(m for m in ("numba", "gymnasium", "scipy") if m in sys.modules)))
    """)
    assert run(code, env=aot_env())[0] == []


def test_the_env_ids_are_registered_whichever_of_pool_env_and_gymnasium_comes_first():
    for imports in ("import pool_env, gymnasium", "import gymnasium, pool_env",
                    "import pool_env; import gymnasium.spaces"):
        code = (f"{imports}; import json, sys; "
                "print(json.dumps(['PoolEightBall-v0' in sys.modules['gymnasium'].registry, "
                "'pool_env.physics' in sys.modules]))")
        assert run(code)[0] == [True, False], imports


def test_arguments_are_keyed_by_what_numba_compiles_for():
    a = np.zeros((3, 2))
    readonly = a.copy()
    readonly.flags.writeable = False
    keys = {compiled.arg_key(x) for x in (a, readonly, a[:, 0], np.asfortranarray(a), a.astype(np.int64))}
    assert len(keys) == 5  # writability, layout (a column is not contiguous) and dtype each count
    assert compiled.arg_key(a[0]) == compiled.arg_key(np.zeros(2))
    assert compiled.args_key((None, True, 1, 2.0, (a, a))) == ("NoneType", "bool", "int", "float", "tuple")
    assert compiled.arg_key(np.float64(1.0)) != compiled.arg_key(1.0)


@needs_extension
def test_a_call_the_extension_was_not_built_for_runs_under_the_jit():
    # placement.overlapping was built for writable arrays (Balls checks its own before it freezes
    # them); read-only ones (a Balls' arrays) take the JIT.
    code = textwrap.dedent("""
        import json, sys
        import numpy as np
        from pool_env.physics import Table, placement, rack
        balls = rack(Table.eight_foot(), seed=1)
        args = (balls.xy, balls.radii, balls.pocketed, np.zeros(len(balls.radii)), 0.3)
        built = placement.overlapping(*(np.array(a) if isinstance(a, np.ndarray) else a for a in args))
        before = "numba" in sys.modules
        args[3].flags.writeable = False
        other = placement.overlapping(*args)
        print(json.dumps([repr(built), repr(other), before, "numba" in sys.modules]))
    """)
    built, other, before, after = run(code, env=aot_env())[0]
    assert built == other and (before, after) == (False, True)
