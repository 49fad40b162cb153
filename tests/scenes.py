"""Helpers the tests share: layouts of numbered balls, and the gate on the play extra (pygame)."""

import importlib
import os

import numpy as np
import pytest

from pool_env.physics import Balls
from pool_env.rules import codes


def layout(n, on):
    """n balls by number: those in `on` (number -> (x, y)) on the table, the rest pocketed."""
    xy = np.zeros((n, 2))
    pocketed = np.ones(n, dtype=bool)
    for k, p in on.items():
        xy[k], pocketed[k] = p, False
    return Balls(xy, pocketed=pocketed)


def require_pygame():
    """pygame, or a skip of the calling test module (a failure with POOL_ENV_REQUIRE_PYGAME=1, as CI sets)."""
    try:
        return importlib.import_module("pygame")
    except ImportError:
        if os.environ.get("POOL_ENV_REQUIRE_PYGAME") == "1":
            raise
        pytest.skip("pygame is not installed (pip install -e '.[play]'); POOL_ENV_REQUIRE_PYGAME=1 makes this fail",
                    allow_module_level=True)


def named(info: dict) -> dict:
    """An env's numeric info with its codes as names (`pool_env.rules.codes.decode_info`) and the
    pocketed mask as the list of ball numbers (0 the cue ball), for asserting on."""
    out = codes.decode_info(info)
    if "pocketed" in out:
        out["pocketed"] = list(out["pocketed"])
    return out
