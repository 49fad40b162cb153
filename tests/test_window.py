"""render_mode="human" without a display: an offscreen window, one warning, no real-time waits (render/window.py)."""

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
from scenes import require_pygame

pygame = require_pygame()

from pool_env.render import window as window_module  # noqa: E402
from pool_env.render.window import DISPLAY_HINT, Window, open_display  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]  # this checkout, so the subprocess imports its pool_env
linux_only = pytest.mark.skipif(not sys.platform.startswith("linux"),
                                reason="'no display' is told by DISPLAY/WAYLAND_DISPLAY on Linux only")


def run_python(code, **env_vars):
    """The JSON that `code` prints last, run in a new Python with no display variable at all (conftest's
    SDL_VIDEODRIVER=dummy included) plus `env_vars`: the headless server that a test process is not."""
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER")}
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT)] + [p for p in [env.get("PYTHONPATH")] if p])
    env.update(env_vars)
    proc = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], env=env, cwd=ROOT,
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-3000:]
    return json.loads(proc.stdout.strip().splitlines()[-1])


@linux_only
def test_check_env_passes_without_a_display_and_warns_once():
    out = run_python("""
        import json, os, warnings
        import gymnasium as gym
        from gymnasium.utils.env_checker import check_env
        import pool_env

        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")  # count every warning, not Python's first-per-line
            for env_id in ("PoolBreak-v0", "PoolNineBall-v0", "ThreeCushion-v0"):
                check_env(gym.make(env_id).unwrapped)  # every render mode, "human" included
            env = gym.make("PoolBreak-v0", render_mode="human")
            env.reset(seed=0)
            import pygame
            driver = pygame.display.get_driver()
            env.close()
        print(json.dumps({"no_display": [str(w.message) for w in caught if "no display" in str(w.message)],
                          "driver": driver, "sdl_videodriver": os.environ.get("SDL_VIDEODRIVER")}))
    """)
    assert len(out["no_display"]) == 1, out  # four human-mode windows, one warning
    assert "offscreen" in out["no_display"][0] and "rgb_array" in out["no_display"][0]
    assert out["driver"] in ("offscreen", "dummy")
    assert out["sdl_videodriver"] is None  # set for pygame's init only, not left in the environment


def test_a_headless_human_break_does_not_wait_in_real_time():
    out = run_python("""
        import json, warnings
        import numpy as np
        import gymnasium as gym
        import pool_env

        class CountingClock:  # stands in for the window's pygame clock: each tick would be a wait
            ticks = 0
            def tick(self, fps):
                CountingClock.ticks += 1

        env = gym.make("PoolBreak-v0", render_mode="human")
        action = np.zeros(env.action_space.shape, np.float32)
        action[0] = 1.0  # a full-power break: a long shot, hundreds of frames
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            env.reset(seed=0)
            env.step(action)  # opens the window
            window = env.unwrapped.window
            window.clock = CountingClock()
            env.reset(seed=0)
            env.step(action)
        import pygame
        print(json.dumps({"frames": len(env.unwrapped.shot_frames()), "ticks": CountingClock.ticks,
                          "realtime": window.realtime, "driver": pygame.display.get_driver(),
                          "warnings": [str(w.message) for w in caught if "no display" in str(w.message)]}))
        env.close()
    """, SDL_VIDEODRIVER="dummy")
    assert out["driver"] == "dummy" and out["frames"] > 60, out  # a long shot, hundreds of frames shown
    assert out["ticks"] == 0 and out["realtime"] is False, out  # no frame waited for the clock
    assert out["warnings"] == []  # the user chose the dummy driver: nothing to warn about


class FakeClock:
    def __init__(self):
        self.ticks = []

    def tick(self, fps):
        self.ticks.append(fps)


def frames(n, size=(24, 16)):
    return [np.full((size[1], size[0], 3), 10 * i, np.uint8) for i in range(n)]


@pytest.mark.parametrize("driver, ticks", [("x11", 5), ("wayland", 5), ("dummy", 0), ("offscreen", 0)])
def test_play_waits_a_frame_only_on_a_driver_that_shows_it(monkeypatch, driver, ticks):
    window = Window("test")
    assert window.show(frames(1)[0])  # opened on conftest's dummy driver
    monkeypatch.setattr(window.pygame.display, "get_driver", lambda: driver)
    window.clock = FakeClock()
    assert window.realtime is (ticks > 0)
    shown = frames(5)
    assert window.play(shown, 30)
    assert window.clock.ticks == [30.0] * ticks  # one tick a frame, at the fps asked for, or none
    assert np.array_equal(window.frame(), shown[-1])  # every frame still drawn, the last one showing
    window.close()


@linux_only
def test_no_offscreen_driver_falls_back_to_dummy(monkeypatch):
    for name in ("SDL_VIDEODRIVER", "DISPLAY", "WAYLAND_DISPLAY"):
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setattr(window_module, "_warned_no_display", False)
    real_init = pygame.display.init

    def init_without_offscreen():  # an SDL built without the offscreen driver
        if os.environ.get("SDL_VIDEODRIVER") == "offscreen":
            raise pygame.error("offscreen not available")
        real_init()

    monkeypatch.setattr(pygame.display, "init", init_without_offscreen)
    with pytest.warns(UserWarning, match="no display.*'dummy' video driver"):
        pg, surface = open_display((32, 20), "test", headless=True)
    assert pg.display.get_driver() == "dummy" and surface.get_size() == (32, 20)
    assert "SDL_VIDEODRIVER" not in os.environ
    pg.display.quit()


@linux_only
def test_an_interactive_window_without_a_display_still_names_the_fix(monkeypatch):
    """`python -m pool_env.play` (open_display without `headless`) keeps refusing: no one could play."""
    for name in ("SDL_VIDEODRIVER", "DISPLAY", "WAYLAND_DISPLAY"):
        monkeypatch.delenv(name, raising=False)
    assert window_module.check_display() is False
    with pytest.raises(RuntimeError, match="SDL_VIDEODRIVER=dummy") as info:
        open_display((32, 20), "test")
    assert str(info.value) == DISPLAY_HINT and not pygame.display.get_init()
    monkeypatch.setenv("DISPLAY", ":0")
    assert window_module.check_display() is True


@linux_only
def test_display_problem_names_why_no_one_would_see_a_window(monkeypatch):
    for name in ("SDL_VIDEODRIVER", "DISPLAY", "WAYLAND_DISPLAY"):
        monkeypatch.delenv(name, raising=False)
    assert "DISPLAY and WAYLAND_DISPLAY are unset" in window_module.display_problem()
    monkeypatch.setenv("WAYLAND_DISPLAY", "wayland-0")
    assert window_module.display_problem() is None
    for driver in ("dummy", "offscreen"):  # a display, but a driver that draws to memory
        monkeypatch.setenv("SDL_VIDEODRIVER", driver)
        assert f"SDL_VIDEODRIVER={driver}" in window_module.display_problem()
    monkeypatch.setenv("SDL_VIDEODRIVER", "x11")
    assert window_module.display_problem() is None
