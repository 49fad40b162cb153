"""`Window`: the pygame window of `render_mode="human"` (pygame imported lazily; clear errors)."""

from __future__ import annotations

import os
import sys

import numpy as np

INSTALL_HINT = "render_mode='human' needs pygame: pip install 'pool-env[play]' (or pip install pygame)"
DISPLAY_HINT = ("no display: set SDL_VIDEODRIVER=dummy for a headless run, or use render_mode='rgb_array' "
                "(frames as arrays) or pool_env.record_video")


def import_pygame():
    """pygame, imported quietly; ImportError naming the extra that installs it."""
    os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
    try:
        import pygame
    except ImportError:
        raise ImportError(INSTALL_HINT) from None
    return pygame


def check_display():
    """RuntimeError naming the fix when there is no display to open a window on (Linux and BSD:
    neither DISPLAY nor WAYLAND_DISPLAY, and no SDL_VIDEODRIVER chosen), before SDL tries any."""
    if sys.platform.startswith(("linux", "freebsd", "openbsd", "netbsd")):
        if not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY") or os.environ.get("SDL_VIDEODRIVER")):
            raise RuntimeError(DISPLAY_HINT)


def open_display(size, title):
    """(pygame, the display surface) of a new window of `size` (width, height) titled `title`."""
    check_display()
    pygame = import_pygame()
    try:
        pygame.display.init()
        pygame.display.set_caption(title)
        surface = pygame.display.set_mode((int(size[0]), int(size[1])))
    except pygame.error as exc:
        pygame.display.quit()
        raise RuntimeError(f"cannot open a window ({exc}); {DISPLAY_HINT}") from None
    return pygame, surface


class Window:
    """A pygame window showing uint8 (H, W, 3) frames: `show(frame)` one, `play(frames, fps)` an
    animation (returns early once the window is closed). The window opens at the first frame
    and is resized to it; closing it (the window's close button) or `close()` quits the display."""

    def __init__(self, title="pool_env"):
        self.title = title
        self.pygame = None
        self.surface = None
        self.closed = False  # the user closed the window
        self._clock = None

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
                self.pygame, self.surface = open_display((w, h), self.title)
                self._clock = self.pygame.time.Clock()
            else:
                self.surface = self.pygame.display.set_mode((w, h))
        self.pygame.surfarray.blit_array(self.surface, np.ascontiguousarray(frame.transpose(1, 0, 2)))
        self.pygame.display.flip()
        return self.pump()

    def play(self, frames, fps) -> bool:
        """Show `frames` one after another at `fps` frames a second; False if the window was closed."""
        for frame in frames:
            if not self.show(frame):
                return False
            self._clock.tick(float(fps))
        return True

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
    closed by `close()` (PoolBreakEnv and PoolGameEnv mix this in; `_window_title` names it)."""

    _window = None
    _window_title = "pool_env"

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
