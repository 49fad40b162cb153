"""The layers: modules import only from their layer and the ones before it, pool_env never agents, no lazy imports."""

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
# physics < rules < game < (players, render) < (envs, multiagent) < records < play < bench; agents on top.
LAYERS = {
    "pool_env.physics": 0, "pool_env.rules": 1, "pool_env.game": 2, "pool_env.players": 3, "pool_env.render": 3,
    "pool_env.envs": 4, "pool_env.multiagent": 4, "pool_env.records": 5, "pool_env.play": 6, "pool_env.bench": 7,
    "pool_env": 4, "agents": 9,  # the package's root holds the env ids' registry (and lazy names), nothing else
}
TOOLS = ("pool_env.bench",)  # the benchmarks time imports in fresh processes: they import where they measure
# What a function may import: the optional extras, and the standard library's `importlib` (the
# package root's lazy names); never a module of this project or a required dependency.
OPTIONAL = {"pygame", "stable_baselines3", "pettingzoo", "ray", "torch", "tensorboard", "matplotlib", "tqdm", "rich",
            "pooltool", "supersuit", "importlib"}
# The two lazy imports that are their module's point: numba in physics/compiled.py (the engine
# compiled ahead of time runs without it; the JIT imports it when a call needs it), gymnasium in
# the package root (the env ids are registered when gymnasium is imported, so the physics alone
# never imports it).
LAZY = {("pool_env.physics.compiled", "numba"), ("pool_env", "gymnasium")}


def modules():
    for package in ("pool_env", "agents"):
        for path in sorted((ROOT / package).rglob("*.py")):
            parts = list(path.relative_to(ROOT).with_suffix("").parts)
            is_package = parts[-1] == "__init__"
            name = ".".join(parts[:-1] if is_package else parts)
            yield name, path, is_package


def layer_of(module: str) -> int | None:
    best = None
    for prefix, layer in LAYERS.items():
        if module == prefix or module.startswith(prefix + "."):
            if best is None or len(prefix) > len(best[0]):
                best = (prefix, layer)
    return None if best is None else best[1]


def in_functions(tree) -> set:
    """The ids of the import nodes inside a function (or a class)."""
    nested = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef, ast.Lambda)):
            nested |= {id(inner) for inner in ast.walk(node) if isinstance(inner, (ast.Import, ast.ImportFrom))}
    return nested


def imports(tree, name, is_package):
    """(imported module, line, at function level) of every import in a module's tree."""
    package = name if is_package else name.rpartition(".")[0]
    nested = in_functions(tree)
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out += [(alias.name, node.lineno, id(node) in nested) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                module = ".".join(base + ([node.module] if node.module else []))
            else:
                module = node.module
            targets = [f"{module}.{alias.name}" for alias in node.names] if not node.module else [module]
            out += [(target, node.lineno, id(node) in nested) for target in targets]
    return out


MODULES = list(modules())


@pytest.mark.parametrize("name, path, is_package", MODULES, ids=[m[0] for m in MODULES])
def test_imports_go_only_down_the_layers(name, path, is_package):
    tree = ast.parse(path.read_text())
    own, tool = layer_of(name), name.startswith(TOOLS)
    for target, line, nested in imports(tree, name, is_package):
        root = target.split(".")[0]
        assert not (name.startswith("pool_env") and root == "agents"), f"{path.name}:{line}: pool_env imports agents"
        assert not nested or tool or root in OPTIONAL or (name, root) in LAZY, \
            f"{path.name}:{line}: function-level import of {target} (only optional extras may be)"
        if root not in ("pool_env", "agents"):
            continue
        theirs = layer_of(target)
        assert theirs <= own, f"{path.name}:{line}: {name} (layer {own}) imports {target} (layer {theirs})"
        if theirs == own == LAYERS["pool_env.players"]:  # players and render are peers: neither imports the other
            assert target.split(".")[:2] == name.split(".")[:2], f"{path.name}:{line}: {name} imports its peer {target}"


def test_the_layers_test_sees_a_violation():
    """The checker itself: a physics module importing the envs, a function-level import of the
    game, and pool_env importing agents are all caught."""
    bad = ast.parse("from ..envs import break_env\ndef f():\n    from ..game import Game\nimport agents\n")
    found = imports(bad, "pool_env.physics.engine", False)
    assert ("pool_env.envs", 1, False) in found and ("pool_env.game", 3, True) in found
    assert ("agents", 4, False) in found
    assert layer_of("pool_env.envs.break_env") > layer_of("pool_env.physics.engine")
    relative = imports(ast.parse("from . import rules\n"), "pool_env.game.core", False)
    assert relative == [("pool_env.game.rules", 1, False)]
