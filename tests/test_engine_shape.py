"""The engine's ids, module graph and size rules: what the compiled code dispatches on matches the names."""

import ast
import math
import pathlib
import pickle

import numpy as np
import pytest

from pool_env.physics import BALL_RADIUS, Balls, Physics, Table, ball_ball, cushion, kinds, simulate
from pool_env.physics.bundles import bounds_of
from pool_env.physics.config import BALL_BALL_MODELS, CUSHION_MODELS
from pool_env.physics.packed import bounds_packed

PHYSICS = pathlib.Path(__file__).resolve().parents[1] / "pool_env" / "physics"
PACKAGE = PHYSICS.parent
R, M = BALL_RADIUS, 0.170097


def _cut_contact():
    """Ball i sliding at 1 m/s (no spin) meets ball j at rest, line of centres 30 degrees off
    its path: rows at contact and the unit normal n from i to j."""
    n = np.array([math.cos(math.radians(30.0)), math.sin(math.radians(30.0))])
    bi = np.array([0.5, 0.5, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    bj = np.array([0.5 + 2 * R * n[0], 0.5 + 2 * R * n[1], 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    return bi, bj, n


@pytest.mark.parametrize("name", BALL_BALL_MODELS)
def test_ball_ball_id_dispatches_the_named_model(name):
    """The id Physics gives each name selects that model in the compiled dispatch."""
    physics = Physics(ball_ball=name)
    model_id = physics.model_ids()[0]
    assert model_id == BALL_BALL_MODELS.index(name)
    bi, bj, n = _cut_contact()
    ball_ball.resolve(model_id, bi, bj, R, R, M, M, physics.as_array())
    e, vn = physics.e_b, 1.0 * n[0]  # approach speed along n
    if name == "elastic":
        # Equal masses: j takes (1 + e)/2 of the normal velocity; spins untouched.
        assert np.allclose(bj[2:4], (1 + e) / 2 * vn * n, rtol=0, atol=1e-15)
        assert not np.any(bi[4:7]) and not np.any(bj[4:7])
    elif name == "seed":
        # The report's model: j leaves along n at e * vn, both balls rolling, no z-spin.
        assert np.allclose(bj[2:4], e * vn * n, rtol=0, atol=1e-15)
        for b in (bi, bj):
            assert b[4] == -b[3] / R and b[5] == b[2] / R and b[6] == 0.0
    else:
        # Friction at the contact throws j off the line of centres and spins it about z.
        assert bj[6] != 0.0 and abs(bj[2] * n[1] - bj[3] * n[0]) > 1e-6


@pytest.mark.parametrize("name", CUSHION_MODELS)
def test_cushion_id_dispatches_the_named_model(name):
    physics = Physics(cushion=name)
    model_id = physics.model_ids()[1]
    assert model_id == CUSHION_MODELS.index(name)
    # A ball sliding into the rail y = 0 (inward normal +y) at 45 degrees, with side spin.
    row = np.array([1.0, R, 1.0, -1.0, 0.0, 0.0, 10.0, 0.0])
    cushion.resolve(model_id, row, 0.0, 1.0, R, physics.as_array(), 0.0363)
    e = physics.e_c
    if name == "restitution":
        assert row[2] == 1.0 and row[3] == pytest.approx(e) and row[6] == 10.0
    elif name == "seed":
        # Mirrored, the whole velocity scaled by e, rolling.
        assert row[2] == pytest.approx(e) and row[3] == pytest.approx(e) and row[6] == 0.0
        assert row[4] == -row[3] / R and row[5] == row[2] / R
    else:
        # Han 2005 and Mathavan 2010: friction on the slip changes the velocity along the rail
        # and the spins; the two differ (Mathavan's cloth friction acts during the impact).
        assert row[2] != 1.0 and row[3] > 0.0 and row[6] != 10.0
        other = np.array([1.0, R, 1.0, -1.0, 0.0, 0.0, 10.0, 0.0])
        other_id = CUSHION_MODELS.index("mathavan2010" if name == "han2005" else "han2005")
        cushion.resolve(other_id, other, 0.0, 1.0, R, physics.as_array(), 0.0363)
        assert not np.allclose(row, other)


def test_event_kind_ids_name_their_kinds():
    named = {"ball_ball": kinds.BALL_BALL, "ball_cushion": kinds.BALL_CUSHION, "ball_pocket": kinds.BALL_POCKET,
             "sliding_rolling": kinds.SLIDING_ROLLING, "rolling_spinning": kinds.ROLLING_SPINNING,
             "rolling_stationary": kinds.ROLLING_STATIONARY, "spinning_stationary": kinds.SPINNING_STATIONARY,
             "sliding_stationary": kinds.SLIDING_STATIONARY, "sliding_spinning": kinds.SLIDING_SPINNING,
             "ball_ball_settle": kinds.BALL_BALL_SETTLE}
    assert {kinds.EVENT_KINDS[i]: i for i in named.values()} == named
    states = {"stationary": kinds.STATIONARY, "spinning": kinds.SPINNING, "sliding": kinds.SLIDING,
              "rolling": kinds.ROLLING, "pocketed": kinds.POCKETED}
    assert {kinds.STATE_NAMES[i]: i for i in states.values()} == states


def _imports(path):
    """The package modules a module imports (relative imports, anywhere in it: a lazy import
    inside a function closes a cycle as surely as one at the top)."""
    tree = ast.parse(path.read_text())
    here = path.relative_to(PACKAGE.parent).with_suffix("").parts[:-1]
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.level:
            base = here[: len(here) - node.level + 1]
            if node.module:
                out.add(".".join(base + tuple(node.module.split("."))))
            else:
                out.update(".".join(base + (alias.name,)) for alias in node.names)
    return out


def test_package_has_no_import_cycle():
    modules = {".".join(p.relative_to(PACKAGE.parent).with_suffix("").parts): p for p in PACKAGE.rglob("*.py")}
    graph = {name: {m for m in _imports(p) if m in modules} for name, p in modules.items()}
    state = {}

    def visit(name, trail):
        if state.get(name) == "done":
            return
        assert state.get(name) != "open", f"import cycle: {' -> '.join(trail + [name])}"
        state[name] = "open"
        for dep in sorted(graph[name]):
            visit(dep, trail + [name])
        state[name] = "done"

    for name in sorted(graph):
        visit(name, [])


def test_physics_functions_stay_short():
    """No function in pool_env/physics over 80 lines; no compiled one over 10 parameters."""
    compiled = {"kernel", "helper", "allocating", "allocating_helper", "entry", "inlined"}
    for path in PHYSICS.glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.FunctionDef):
                lines = node.end_lineno - node.lineno + 1
                assert lines <= 80, f"{path.name}:{node.lineno} {node.name} is {lines} lines"
                if any(isinstance(d, ast.Name) and d.id in compiled for d in node.decorator_list):
                    n_args = len(node.args.args)
                    assert n_args <= 10, f"{path.name}:{node.lineno} {node.name} takes {n_args} parameters"


def test_ball_under_the_cushion_nose_is_refused():
    """han2005 touches a ball at the nose height h: a ball with 2R <= h would pass under it."""
    balls = Balls([[0.5, 0.5]], v=[[1.0, 0.0]], radius=0.018)
    with pytest.raises(ValueError, match="no taller than the cushion nose at 0.0363 m"):
        simulate(balls, Table(2.0, 1.0), Physics.standard())
    # Another cushion model does not use the nose height: the shot runs (and ends).
    result = simulate(balls, Table(2.0, 1.0), Physics(cushion="restitution"))
    assert result.final.v.tolist() == [[0.0, 0.0]]


def test_an_unpickled_table_gives_the_engine_read_only_arrays_and_the_same_shot():
    """A Table pickled after a simulation (its engine views cached) comes back with read-only
    arrays throughout, views included: a writable array would be a new numba type, and the
    whole engine would compile a second time for it."""
    table = Table.eight_foot()
    balls = Balls([[0.5, 0.5], [1.0, 0.55]], v=[[1.0, 0.0], [0.0, 0.0]])
    before = simulate(balls, table, Physics.standard())
    copy = pickle.loads(pickle.dumps(table))
    assert all(not a.flags.writeable for a in (*bounds_of(copy), *bounds_packed(copy)) if isinstance(a, np.ndarray))
    after = simulate(balls, copy, Physics.standard())
    assert np.array_equal(after.final.xy, before.final.xy) and after.events == before.events
