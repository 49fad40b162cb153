"""Shared test fixtures: keep global logging state from leaking between tests."""

import gymnasium as gym
import pytest


@pytest.fixture(autouse=True)
def restore_gymnasium_log_level():
    """Some tests (and train.py) silence Gymnasium's warnings; the env tests count them."""
    level = gym.logger.min_level
    yield
    gym.logger.min_level = level


@pytest.fixture(autouse=True)
def headless_windows(monkeypatch):
    """No test opens a real window: render_mode="human" and pool_env.play draw on SDL's dummy driver."""
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    monkeypatch.setenv("SDL_AUDIODRIVER", "dummy")
