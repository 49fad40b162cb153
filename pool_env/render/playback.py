"""`ShotPlayback`: a PoolBreakEnv's frames (the table now, the last shot) and the balls' orientations."""

from __future__ import annotations

import math

import numpy as np

from ..physics import BALL_RADIUS
from ..physics.kinds import POCKETED, Z
from .table import TableRenderer, integrate_orientation

ORIENTATION_SUBSTEPS = 4  # orientation integration steps per rendered frame


def quaternion_rotations(q) -> np.ndarray:
    """Rotation matrices (n, 3, 3) of quaternions (n, 4) (w, x, y, z), normalised first; random
    normal quaternions give uniformly random rotations."""
    q = np.asarray(q, dtype=np.float64)
    q = q / np.linalg.norm(q, axis=1, keepdims=True)
    w, x, y, z = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], axis=1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], axis=1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], axis=1),
    ], axis=1)


def frame_times(duration, fps) -> np.ndarray:
    """The times a shot of `duration` s is drawn at, at `fps`: 0, 1/fps, ... and its end."""
    times = np.arange(int(math.floor(duration * fps)) + 1) / fps
    return np.append(times, duration) if times[-1] < duration else times


def sample_shot(result, start, fps):
    """(times (F,), xy (F, n, 2), pocketed (F, n), orientation (F, n, 3, 3), heights (F, n) or
    None) of a shot (a `Result`) sampled at `fps` from its exact trajectory, the balls starting
    in orientations `start` (n, 3, 3): frames at t = 0, 1/fps, ... and at the shot's end.
    `heights` (m above where each ball rests on the cloth) is None if no ball left the cloth."""
    times = frame_times(result.duration, fps)
    # Angular velocity at the midpoints of ORIENTATION_SUBSTEPS substeps per frame interval:
    # the midpoint rule is exact while w changes linearly about a fixed axis (sliding, rolling).
    k = ORIENTATION_SUBSTEPS
    edges = times[:-1, None] + np.diff(times)[:, None] * (np.arange(k) + 0.5)[None, :] / k
    mids = edges.reshape(-1)
    rows, states = result.sample(np.concatenate([times, mids]))
    frames, n = len(times), rows.shape[1]
    xy = rows[:frames, :, 0:2]
    pocketed = states[:frames] == POCKETED
    w = np.nan_to_num(rows[frames:, :, 4:7])
    dt = np.repeat(np.diff(times) / k, k)
    steps = integrate_orientation(np.broadcast_to(np.eye(3), (w.shape[0] * n, 3, 3)),
                                  (w * dt[:, None, None]).reshape(-1, 3), 1.0).reshape(-1, n, 3, 3)
    orientation = np.empty((frames, n, 3, 3))
    current = start
    orientation[0] = current
    for f in range(1, frames):
        for s in range((f - 1) * k, f * k):
            current = steps[s] @ current
        orientation[f] = current
    orientation[-1] = integrate_orientation(orientation[-1], np.zeros((n, 3)), 0.0)  # re-orthonormalise
    heights = rows[:frames, :, Z]
    return times, xy, pocketed, orientation, (heights if heights.any() else None)


class ShotPlayback:
    """The frames of a `PoolBreakEnv`: the table now, and the last shot sampled from its exact
    trajectory at any frame rate, with every ball's orientation (which only the rotation
    markers show) carried from the random one drawn at `reset` through the shots.

    Integrating a shot's rotation costs about as much as sampling its frames, so it is done
    only when a frame is drawn. With `deferred=True` (the env has a render mode) the rotations
    of shots played without drawing are queued and applied in order when a frame is next
    drawn, so the markers never jump; with `deferred=False` they are dropped, and the markers
    may jump between shots.
    """

    def __init__(self, table, size, fps, deferred, palette="pool"):
        self.table, self.size, self.fps, self.deferred = table, size, float(fps), bool(deferred)
        self.palette = palette  # the balls' look (`TableRenderer`'s palette)
        self._renderer = None
        self._balls = None  # the balls now
        self._quaternions = None
        self._orientation = None  # (16, 3, 3), made from the quaternions when first drawn
        self._shot = None  # (Result, orientation at its start, or None: where the queued shots leave it)
        self._rotated = True  # whether self._orientation is at the end of the last shot
        self._pending = []  # Results of shots whose rotation is not yet in self._orientation
        self._tracks = {}  # fps -> sample_shot(...) of the last shot

    @property
    def renderer(self) -> TableRenderer:
        """The frame renderer (made on first use); `renderer.world_to_pixel` maps metres to pixels."""
        radius = BALL_RADIUS if self._balls is None else float(np.max(self._balls.radii))
        if self._renderer is None or self._renderer.ball_radius != radius:
            self._renderer = TableRenderer(self.table.length, self.table.width, self.table.pockets, radius, self.size,
                                           self.palette)
        return self._renderer

    @property
    def orientation(self) -> np.ndarray:
        """The balls' orientations (16, 3, 3), body to world, now: after every shot whose
        rotation was applied (see the class docstring)."""
        return self._orientation_now()

    def reset(self, balls, quaternions):
        """Start an episode: `balls` at rest, in the orientations of `quaternions` (16, 4)."""
        self._balls, self._quaternions = balls, quaternions
        self._orientation, self._rotated, self._pending = None, True, []
        self._shot, self._tracks = None, {}

    def shot(self, result):
        """A shot was played: `result` is its `Result`, or None if it failed (the balls stay put)."""
        if self.deferred:
            self._defer_rotation()
            start = None  # it starts where the queued shots leave the balls
        else:
            start = self._orientation
        self._tracks = {}
        if result is None:
            self._shot = None
            return
        self._balls, self._shot, self._rotated = result.final, (result, start), False

    @property
    def last_result(self):
        """The last shot's `Result` (None before any shot, or after a failed one)."""
        return None if self._shot is None else self._shot[0]

    def place(self, balls):
        """The balls were moved between shots (a ball spotted, the cue ball placed with ball in
        hand): the table now shows them."""
        self._balls = balls

    def frame(self) -> np.ndarray:
        """The table now: (H, W, 3) uint8."""
        if self._shot is not None and not self._rotated:
            self._track(self.fps)  # brings the orientation to the shot's end
        return self._draw(self._balls.xy, self._balls.pocketed, self._orientation_now())

    def shot_frames(self, fps=None) -> list[np.ndarray]:
        """The last shot's frames at `fps` (default `self.fps`), from its start to every ball at
        rest; before any shot (or after a failed one) the single frame of the table now."""
        fps = float(self.fps if fps is None else fps)
        if not (math.isfinite(fps) and fps > 0):
            raise ValueError(f"fps must be finite and > 0, got {fps!r}")
        if self._shot is None:
            return [self._draw(self._balls.xy, self._balls.pocketed, self._orientation_now())]
        _, xy, pocketed, orientation, heights = self._track(fps)
        return [self._draw(xy[k], pocketed[k], orientation[k], None if heights is None else heights[k])
                for k in range(len(xy))]

    def close(self):
        self._renderer = None
        self._tracks = {}

    def _track(self, fps):
        """sample_shot(...) of the last shot at `fps`, cached; the first one also advances the orientation."""
        cached = self._tracks.get(fps)
        if cached is not None:
            return cached
        result, start = self._shot
        if start is None:  # kept: a track at another fps must start here too, not at the shot's end
            start = self._orientation_now()
            self._shot = (result, start)
        track = sample_shot(result, start, fps)
        self._tracks[fps] = track
        if not self._rotated:
            self._orientation, self._rotated = track[3][-1], True
        return track

    def _defer_rotation(self):
        """Queue the last shot's rotation if it was never applied (no frame was drawn after it)."""
        if self._shot is not None and not self._rotated:
            self._pending.append(self._shot[0])
            self._rotated = True

    def _orientation_now(self):
        """The balls' orientations (16, 3, 3) now (or at the last shot's start, if it was not
        tracked), after applying the queued shots' rotations in order."""
        if self._orientation is None:
            self._orientation = quaternion_rotations(self._quaternions)
        while self._pending:
            result = self._pending.pop(0)
            self._orientation = sample_shot(result, self._orientation, self.fps)[3][-1]
        return self._orientation

    def _draw(self, xy, pocketed, orientation, heights=None):
        return self.renderer.draw(xy, pocketed, orientation, heights)


def step_shot_frames(playback: ShotPlayback, start, quaternions, results, fps=None) -> list[list[np.ndarray]]:
    """The frames of each shot of a step (`results`, the shots' Results in order), one list a
    shot: one shot is the playback's own last shot; several are replayed on a playback of their
    own from the step's `start` balls, the markers turning through them from `quaternions`."""
    if len(results) == 1:
        return [playback.shot_frames(fps)]
    replay = ShotPlayback(playback.table, playback.size, playback.fps, deferred=False, palette=playback.palette)
    replay.reset(start, quaternions)
    shots = []
    for result in results:
        replay.shot(result)
        shots.append(replay.shot_frames(fps))
    return shots
