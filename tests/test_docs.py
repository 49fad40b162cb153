"""Every ```python block in README.md and docs/*.md runs as pasted: each in a fresh Python
process, in an empty temporary working directory (not the repository root), with a time limit.

An HTML comment on the line just before a block's opening fence (invisible when the page is
rendered) tells this test about the block:

- `<!-- slow -->`: the block takes seconds (training, videos); it runs under the `slow` marker.
- `<!-- not-run: <reason> -->`: the block cannot run here; it is reported as skipped with the
  reason. Keep these rare: `test_not_run_blocks_are_rare` counts them.
- `<!-- needs: module ... -->`: the block imports an optional library (docs/clients.md's, of
  the `clients` extra); it is skipped where one is missing, unless POOL_ENV_REQUIRE_CLIENTS=1
  (CI's clients venv), where it must run.
"""

from __future__ import annotations

import importlib.util
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
TIME_LIMIT = 300  # s per block; the slowest (training a stand-in model, a rack video) take about 20 s
MAX_NOT_RUN = 1

FENCE = re.compile(r"^```(\S*)\s*$")
MARK = re.compile(r"^<!--\s*(slow|not-run:\s*(?P<reason>.*?)|needs:\s*(?P<modules>.*?))\s*-->$")
REQUIRE_CLIENTS = os.environ.get("POOL_ENV_REQUIRE_CLIENTS") == "1"


def python_blocks(path: Path):
    """(line of the opening fence, code, marker, not-run reason) for each ```python block."""
    lines = path.read_text().splitlines()
    blocks, i = [], 0
    while i < len(lines):
        fence = FENCE.match(lines[i])
        if not fence:
            i += 1
            continue
        end = next((k for k in range(i + 1, len(lines)) if lines[k].strip() == "```"), None)
        assert end is not None, f"{path.name}:{i + 1}: code block never closed"
        if fence.group(1) == "python":
            before = next((lines[k].strip() for k in range(i - 1, -1, -1) if lines[k].strip()), "")
            mark = MARK.match(before)
            kind = None if mark is None else ("slow" if mark.group(1) == "slow" else
                                              "needs" if mark.group("modules") else "not-run")
            reason = mark.group("reason") or mark.group("modules") if mark is not None else None
            blocks.append((i + 1, "\n".join(lines[i + 1:end]) + "\n", kind, reason))
        i = end + 1
    return blocks


BLOCKS = [(path, *block) for path in PAGES for block in python_blocks(path)]


def params():
    for path, line, code, kind, reason in BLOCKS:
        marks = []
        if kind == "slow":
            marks.append(pytest.mark.slow)
        elif kind == "not-run":
            marks.append(pytest.mark.skip(reason=f"not run: {reason}"))
        elif kind == "needs" and not REQUIRE_CLIENTS:
            missing = [m for m in reason.split() if importlib.util.find_spec(m) is None]
            if missing:
                marks.append(pytest.mark.skip(reason=f"needs {', '.join(missing)} (pip install -e '.[clients]')"))
        yield pytest.param(code, marks=marks, id=f"{path.relative_to(ROOT)}:{line}")


def test_blocks_are_found():
    # Guards the parser: the pages hold these blocks (update the count when adding examples).
    names = {path.relative_to(ROOT).as_posix() for path, *_ in BLOCKS}
    assert {"README.md", "docs/env.md", "docs/clients.md"} <= names
    assert len(BLOCKS) >= 5
    needs = {reason for path, _, _, kind, reason in BLOCKS if kind == "needs"}
    assert {"torchrl", "tianshou", "skrl", "rl_zoo3", "supersuit", "moviepy"} <= needs  # clients.md's recipes


def test_not_run_blocks_are_rare():
    not_run = [f"{path.name}:{line} ({reason})" for path, line, _, kind, reason in BLOCKS if kind == "not-run"]
    assert all(reason for *_, kind, reason in BLOCKS if kind == "not-run"), "a not-run block must say why"
    assert len(not_run) <= MAX_NOT_RUN, f"too many doc examples are not run: {not_run}"


@pytest.mark.parametrize("code", list(params()))
def test_block_runs_as_pasted(code, tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg")
    try:
        proc = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env, capture_output=True, text=True,
                              timeout=TIME_LIMIT)
    except subprocess.TimeoutExpired:
        pytest.fail(f"the block did not finish within {TIME_LIMIT} s:\n{code}", pytrace=False)
    if proc.returncode != 0:
        pytest.fail(f"the block failed:\n{code}\n--- stderr ---\n{proc.stderr[-4000:]}", pytrace=False)
