"""Helpers the tests share: layouts of numbered balls, and the gate on the play extra (pygame)."""

import importlib
import os

import numpy as np
import pytest

from pool_env.physics import Balls


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
