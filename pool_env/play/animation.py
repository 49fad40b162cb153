"""A play window's step computed on a worker thread (`PendingStep`) while its shots are animated (`StepAnimation`)."""

from __future__ import annotations

import math
import threading

import numpy as np

from ..envs.game_env import shot_caption
from ..render.playback import sample_shot


class PendingStep:
    """`env.step(action)` run on a daemon thread (the engine releases the GIL: the window keeps
    drawing), the shots it has played so far readable while it runs. A daemon, so that closing
    the window does not wait for an opponent still thinking."""

    def __init__(self, env, action, shooter):
        self.env, self.base, self.shooter = env, env.unwrapped, shooter
        # The last step's records, to tell them from this step's until it has begun (the env
        # replaces its list when it does).
        self._before = self.base.step_records if self.base.game.has_rules else ()
        self._outcome = self._error = None
        self._over = threading.Event()
        self._thread = threading.Thread(target=self._run, args=(action,), name="pool_env.play step", daemon=True)
        self._thread.start()

    def _run(self, action):
        try:
            self._outcome = self.env.step(action)
        except Exception as exc:  # handed to the main thread: outcome() raises it there, as a step on it would
            self._error = exc
        finally:
            self._over.set()

    @property
    def done(self) -> bool:
        return self._over.is_set()

    def join(self, timeout=None) -> bool:
        """Wait for the step to end (at most `timeout` s); whether it has."""
        return self._over.wait(timeout)

    def outcome(self):
        """The step's (observation, reward, terminated, truncated, info); what it raised, raised here."""
        self.join()
        if self._error is not None:
            raise self._error
        return self._outcome

    def shots(self) -> list:
        """(Result, caption, messages) of each shot the step has played so far, as the env's own
        frames caption them (`PoolGameEnv.shot_frames`): the caption on every frame, the rules'
        messages on the last. A break env's one shot shows once the step is over."""
        base = self.base
        if not base.game.has_rules:
            result = base.playback.last_result if self.done else None
            return [] if result is None else [(result, None, [])]
        records = base.step_records  # a snapshot: the worker appends each shot as it is played
        if self._before and records[:1] and records[0] is self._before[0]:
            return []  # the step has not begun yet
        out = []
        for record in records:
            if record.error is not None:
                continue
            if not base.overlay:
                out.append((record.result, None, []))
                continue
            who = f"player {record.shooter + 1}" if base.hotseat else ("agent" if record.shooter == 0 else "opponent")
            out.append((record.result, shot_caption(base.game, record, who), list(record.ruling.messages)))
        return out


class StepAnimation:
    """A step's shots as frames, each drawn only when it is shown, from each shot's first frame
    in order: sampled from the exact trajectory at `fps` (render_fps, or more in slow motion)
    and shown at render_fps. The frames of a shot are there as soon as the shot is added; the
    animation waits on the last one until the next shot (or the step's end, `complete`) comes.

    `pos` is the frame shown, a float advanced by wall time (`advance`), but never beyond the
    frame after the last one drawn (`frame()`): a loop that blocked for seconds shows the next
    frame, not one seconds later, so no frame is ever skipped (unless `skip`ped)."""

    def __init__(self, renderer, orientation, fps):
        self.renderer, self.fps = renderer, float(fps)
        self.shots = []  # (caption, messages, (times, xy, pocketed, orientation)) per shot, in order
        self.complete = False  # every shot of the step is in
        self.skipped = False
        self.pos, self.shown = 0.0, -1  # the frame to show (a float), the last frame drawn
        self._orientation = np.asarray(orientation)  # the balls' orientations where the next shot starts
        self._drawn = (None, None)  # (frame index, image) of the last frame drawn

    @property
    def available(self) -> int:
        """The frames in so far."""
        return sum(len(track[0]) for _, _, track in self.shots)

    @property
    def finished(self) -> bool:
        return self.complete and self.pos >= self.available

    def add(self, shots, complete=False):
        """The step's shots so far ((Result, caption, messages), as `PendingStep.shots`): the new ones added."""
        for result, caption, messages in shots[len(self.shots):]:
            track = sample_shot(result, self._orientation, self.fps)
            self._orientation = track[3][-1]
            self.shots.append((caption, messages, track))
        self.complete = self.complete or complete

    def advance(self, frames):
        """Move on by `frames` (wall time in frames), but not past the frame after the last one
        drawn; while shots may still come, at most to the last frame in."""
        n = self.available
        end = n if self.complete else n - 1
        if self.skipped:
            self.pos = float(max(end, 0))
            return
        next_one = math.nextafter(self.shown + 2.0, 0.0)  # the last position still showing frame shown + 1
        self.pos = max(self.pos, min(self.pos + max(float(frames), 0.0), next_one, float(end)))

    def skip(self):
        """Skip to the end of what is in, and of every shot still to come."""
        self.skipped = True
        self.advance(0.0)

    def index(self):
        """(shot, frame of that shot, frame of the step) shown now, or None before the first frame is in."""
        k = min(int(self.pos), self.available - 1)
        if k < 0:
            return None
        j = k
        for s, (_, _, track) in enumerate(self.shots):
            if j < len(track[0]):
                return s, j, k
            j -= len(track[0])
        raise AssertionError("unreachable: k < available")

    def frame(self):
        """The frame shown now (uint8 (H, W, 3), the table only: `caption` says what it shows), or None
        before the first is in."""
        where = self.index()
        if where is None:
            return None
        s, j, k = where
        if self._drawn[0] != k:
            _, _, (_, xy, pocketed, orientation, heights) = self.shots[s]
            self._drawn = (k, self.renderer.draw(xy[j], pocketed[j], orientation[j],
                                                 None if heights is None else heights[j]))
        self.shown = max(self.shown, k)
        return self._drawn[1]

    def caption(self) -> list[str]:
        """The lines the env's own frames carry on the frame shown now: the shot's caption, and on
        its last frame the rules' messages too; [] before the first frame or without captions."""
        where = self.index()
        if where is None:
            return []
        s, j, _ = where
        caption, messages, track = self.shots[s]
        if caption is None:
            return []
        return [caption, *messages] if j == len(track[0]) - 1 else [caption]
