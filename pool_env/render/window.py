"""`Window`: the pygame window of `render_mode="human"`, offscreen when there is no display (clear errors)."""

from __future__ import annotations

import os
import sys

import numpy as np
from gymnasium import logger

INSTALL_HINT = "render_mode='human' needs pygame: pip install 'pool-env[play]' (or pip install pygame)"
DISPLAY_HINT = ("no display: set SDL_VIDEODRIVER=dummy for a headless run, or use render_mode='rgb_array' "
                "(frames as arrays) or pool_env.record_video")
# SDL's video drivers that draw to memory: no one sees their window, so nothing waits for a viewer.
HEADLESS_DRIVERS = ("offscreen", "dummy")
NO_DISPLAY_WARNING = ("render_mode='human': no display (DISPLAY, WAYLAND_DISPLAY and SDL_VIDEODRIVER are unset), "
                      "so the window is drawn offscreen (SDL's {driver!r} video driver), to nothing, without "
                      "real-time waits; to see it, run with a display, or use render_mode='rgb_array' (frames as "
                      "arrays) or pool_env.record_video")
_warned_no_display = False  # NO_DISPLAY_WARNING is given once a process, not at every env's window


def import_pygame():
    """pygame, imported quietly; ImportError naming the extra that installs it."""
    os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
    try:
        import pygame
    except ImportError:
        raise ImportError(INSTALL_HINT) from None
    return pygame


def check_display() -> bool:
    """Whether SDL has a display to open a window on: False on Linux and BSD with neither DISPLAY nor
    WAYLAND_DISPLAY set and no SDL_VIDEODRIVER chosen (elsewhere, or with a driver chosen, True).
    Told before SDL tries any driver, so that SDL prints no errors of its own."""
    if sys.platform.startswith(("linux", "freebsd", "openbsd", "netbsd")):
        return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")
                    or os.environ.get("SDL_VIDEODRIVER"))
    return True


def display_problem() -> str | None:
    """Why no one would see a window opened now, or None when someone would: pygame missing,
    SDL's video driver chosen as one that draws to memory (SDL_VIDEODRIVER=dummy or offscreen),
    or on Linux and BSD neither DISPLAY nor WAYLAND_DISPLAY set."""
    driver = os.environ.get("SDL_VIDEODRIVER", "")
    if driver.lower() in HEADLESS_DRIVERS:
        return f"SDL_VIDEODRIVER={driver} draws windows to memory, not to a screen"
    if sys.platform.startswith(("linux", "freebsd", "openbsd", "netbsd")) and not (
            os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")):
        return "no display (DISPLAY and WAYLAND_DISPLAY are unset)"
    try:
        import_pygame()
    except ImportError as exc:
        return str(exc)
    return None


def _init_headless(pygame) -> str:
    """pygame.display.init() on SDL's offscreen video driver ("dummy" if this SDL has none); the driver's
    name. SDL_VIDEODRIVER is set only for the init (SDL reads it then), so the process's environment,
    its subprocesses' and the next window's `check_display()` stay as the user left them."""
    error, previous = None, os.environ.get("SDL_VIDEODRIVER")  # unset, or "" (which SDL ignores)
    for driver in HEADLESS_DRIVERS:
        os.environ["SDL_VIDEODRIVER"] = driver
        try:
            pygame.display.init()
            return pygame.display.get_driver()
        except pygame.error as exc:  # "offscreen not available" in an SDL built without it
            pygame.display.quit()
            error = exc
        finally:
            if previous is None:
                del os.environ["SDL_VIDEODRIVER"]
            else:
                os.environ["SDL_VIDEODRIVER"] = previous
    raise RuntimeError(f"cannot open an offscreen window ({error}); use render_mode='rgb_array'")


def _warn_no_display(driver):
    """NO_DISPLAY_WARNING through Gymnasium's logger, the first time only."""
    global _warned_no_display
    if not _warned_no_display:
        _warned_no_display = True
        logger.warn(NO_DISPLAY_WARNING.format(driver=driver))


def open_display(size, title, headless=False):
    """(pygame, the display surface) of a new window of `size` (width, height) titled `title`. With no
    display (`check_display()`): RuntimeError(DISPLAY_HINT), or, when `headless`, a window on SDL's
    offscreen driver after a warning (once a process), as Gymnasium's classic-control envs do."""
    display = check_display()
    if not (display or headless):  # `python -m pool_env.play`: an unseen interactive game would never end
        raise RuntimeError(DISPLAY_HINT)
    pygame = import_pygame()
    try:
        if display:
            pygame.display.init()
        else:
            _warn_no_display(_init_headless(pygame))
        pygame.display.set_caption(title)
        surface = pygame.display.set_mode((int(size[0]), int(size[1])))
    except pygame.error as exc:
        pygame.display.quit()
        raise RuntimeError(f"cannot open a window ({exc}); {DISPLAY_HINT}") from None
    return pygame, surface


class Window:
    """A pygame window showing uint8 (H, W, 3) frames: `show(frame)` one, `play(frames, fps)` an
    animation (returns early once the window is closed). The window opens at the first frame
    and is resized to it; closing it (the window's close button) or `close()` quits the display.
    With no display (a headless server) it opens on SDL's offscreen driver after one warning a
    process, as Gymnasium's classic-control envs do; on that driver or SDL's dummy one (`realtime`
    False) `play` draws every frame without waiting, since no one watches it in real time."""

    def __init__(self, title="pool_env"):
        self.title = title
        self.pygame = None
        self.surface = None
        self.closed = False  # the user closed the window
        self.clock = None

    @property
    def is_open(self) -> bool:
        return self.surface is not None

    def show(self, frame) -> bool:
        """Draw `frame` and handle the window's events; False once the window was closed."""
        frame = np.asarray(frame)
        if frame.ndim != 3 or frame.shape[2] != 3:
            raise ValueError(f"a frame must be (H, W, 3), got shape {frame.shape}")
        if self.closed:
            return False
        h, w = frame.shape[:2]
        if self.surface is None or self.surface.get_size() != (w, h):
            if self.surface is None:
                self.pygame, self.surface = open_display((w, h), self.title, headless=True)
                self.clock = self.pygame.time.Clock()
            else:
                self.surface = self.pygame.display.set_mode((w, h))
        self.pygame.surfarray.blit_array(self.surface, np.ascontiguousarray(frame.transpose(1, 0, 2)))
        self.pygame.display.flip()
        return self.pump()

    @property
    def realtime(self) -> bool:
        """Whether `play` paces frames at `fps`: the window is open on a video driver that shows it."""
        return self.surface is not None and self.pygame.display.get_driver() not in HEADLESS_DRIVERS

    def play(self, frames, fps) -> bool:
        """Show `frames` one after another at `fps` frames a second (as fast as they are drawn when not
        `realtime`: a headless training run would otherwise wait seconds a shot); False if closed."""
        wait = None
        for frame in frames:
            if not self.show(frame):
                return False
            if wait is None:  # asked once the window is open: the first frame opens it
                wait = self.realtime
            if wait:
                self.clock.tick(float(fps))
        return True

    def hold(self) -> None:
        """Keep showing the last frame until the window is closed or Esc is pressed; at once when not
        `realtime` (no one could close it)."""
        if not self.realtime:
            return
        while not self.closed:
            for event in self.pygame.event.get():
                if event.type == self.pygame.QUIT or (event.type == self.pygame.KEYDOWN
                                                      and event.key == self.pygame.K_ESCAPE):
                    self.close()
                    self.closed = True
            self.clock.tick(30)

    def pump(self) -> bool:
        """Handle pending window events (a close request closes the window); False once closed."""
        if self.surface is None:
            return not self.closed
        for event in self.pygame.event.get():
            if event.type == self.pygame.QUIT:
                self.close()
                self.closed = True
                return False
        return True

    def frame(self) -> np.ndarray | None:
        """What the window shows now, (H, W, 3) uint8; None when it is not open."""
        if self.surface is None:
            return None
        return np.ascontiguousarray(self.pygame.surfarray.array3d(self.surface).transpose(1, 0, 2))

    def close(self):
        """Close the window (pygame.display.quit); safe to call again."""
        if self.surface is not None:
            self.pygame.display.quit()
        self.surface = None


class HumanWindow:
    """The envs' side of `render_mode="human"`: a `Window` opened at the first frame shown,
    closed by `close()` (PoolBreakEnv and PoolGameEnv mix this in; `_window_title` names it).
    Headless, the window is drawn offscreen without real-time waits (see `Window`), so that
    `gymnasium.utils.env_checker.check_env` and training scripts run with render_mode="human"."""

    _window = None
    _window_title = "pool_env"

    @property
    def window(self):
        """The `Window` of render_mode="human" (None until the first frame is shown)."""
        return self._window

    def close(self):
        self.playback.close()
        if self._window is not None:
            self._window.close()
            self._window = None

    def _show(self, frames):
        """render_mode="human": show `frames` in the window at `metadata["render_fps"]` (None)."""
        if self._window is None:
            self._window = Window(self._window_title)
        self._window.play(frames, self.metadata["render_fps"])
