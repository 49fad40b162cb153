"""What a video's overlay says and draws: captions per shot, cue lines, the scratch pocket, episode cards."""

from __future__ import annotations

import math

import numpy as np

from ..envs.infos import NO_WINNER
from ..physics.kinds import BALL_POCKET
from ..render.overlay import card, cue_line, fit_band, font_size, overlay, pocket_mark
from ..render.playback import frame_times
from ..rules import codes, cue_ball

CUE_SECONDS = 0.5  # the cue line is shown this long before each shot
CARD_SECONDS = 1.5  # each episode ends on a card with its result, this long


def shot_facts(record) -> dict:
    """What the captions tell of one shot, from its `ShotRecord`: the object balls pocketed, a
    scratch, the foul's name, the rules' lines, a failure."""
    facts = {"pocketed": [int(b) for b in record.pocketed], "scratch": record.scratch, "foul": record.foul,
             "messages": list(record.ruling.messages) if record.ruling is not None else [],
             "error": record.error is not None, "cue_ball": cue_ball(record.state_before)}
    if record.ruling is not None and hasattr(record.ruling, "point"):  # carom: a point or none, no pockets
        facts["point"] = bool(record.ruling.point)
    return facts


def shot_summary(facts: dict) -> str:
    """One shot in words (its `shot_facts`): the balls pocketed, a scratch, a foul."""
    balls = facts.get("pocketed", [])
    if "point" in facts:
        parts = ["point" if facts["point"] else "no point"]
    else:
        parts = [("pocketed " + ", ".join(str(b) for b in balls)) if balls else "nothing pocketed"]
    if facts.get("scratch"):
        parts.append("cue ball pocketed (scratch)")
    if facts.get("foul"):
        parts.append(f"foul: {facts['foul'].replace('_', ' ')}")
    if facts.get("error"):
        parts.append("could not be simulated")
    return "; ".join(parts)


def episode_result(base, episode: int, info: dict, reward: float, shots: int, balls: int, scratches: int) -> list:
    """The lines of an episode's closing card."""
    lines = [f"episode {episode}"]
    if base.game.has_rules:
        name = base.game.label
        winner = info.get("winner", NO_WINNER)
        if winner != NO_WINNER:
            reason = codes.decode("end_reason", info["end_reason"]) if "end_reason" in info else None
            who = "agent" if winner == 0 else "opponent"
            lines.append(f"{who} wins {name}" + (f" ({reason.replace('_', ' ')})" if reason else ""))
        elif info.get("draw"):
            lines.append(f"{name}: a draw")
        else:
            lines.append(f"{name}: no winner ({'error' if info.get('error') else 'shot limit'})")
        if "scores" in info:
            lines.append(f"score {int(info['scores'][0])}-{int(info['scores'][1])}")
        lines.append(f"{shots} shots, reward {reward:+.2f}")
        return lines
    lines.append(f"{balls} ball{'s' if balls != 1 else ''} in {shots} shot{'s' if shots != 1 else ''}"
                 + (f", {scratches} scratch{'es' if scratches != 1 else ''}" if scratches else ""))
    lines.append(f"reward {reward:+.2f}")
    return lines


class Story:
    """An episode told on its frames: `step(frames, info, reward, first)` decorates one step's
    frames (every shot of it), `card(info)` is the closing card. `episode` is the episode's
    number as the saved games' and the recorder's file names have it (from 0)."""

    def __init__(self, base, episode: int, fps: float):
        self.base, self.episode, self.fps = base, episode, float(fps)
        self.reward, self.shots, self.balls, self.scratches = 0.0, 0, 0, 0
        self.last = []  # lines about the last shot

    def step(self, frames, info, reward, first):
        """The step's frames with the overlay: per shot the cue frames, then its moving frames."""
        results, infos = self._shots(info)
        counts = [len(frame_times(r.duration, self.fps)) for r in results]
        if not results or sum(counts) != len(frames):  # a failed shot: the table as it is
            self.reward += reward
            self.last = [f"last shot: {shot_summary({'error': bool(info.get('error'))})}"]
            return [self._caption(frame) for frame in (frames if first else frames[-1:])]
        out, start = [], 0
        for k, (result, shot_info, count) in enumerate(zip(results, infos, counts, strict=True)):
            shot = frames[start : start + count]
            start += count
            self.shots += 1
            who = shot_info.pop("_who", None)
            label = f"shot {self.shots}" + (f" ({who})" if who else "")
            rows, _ = result.sample(np.zeros(1))
            c = shot_info.pop("cue_ball", 0)
            cue = cue_line(shot[0], self.base.playback.renderer, rows[0, c, 0:2], rows[0, c, 2:4])
            out += [self._caption(cue, label)] * round(CUE_SECONDS * self.fps)
            pocket_at = self._cue_pocket(result)
            for j in range(1, count):
                frame = shot[j]
                if pocket_at is not None and min(j / self.fps, result.duration) >= pocket_at[0]:
                    frame = pocket_mark(frame, self.base.playback.renderer, pocket_at[1])
                if j == count - 1:  # the shot is over: what it did
                    self._note(shot_info, reward if k == len(results) - 1 else 0.0, who)
                out.append(self._caption(frame, label))
        return out

    def card(self, info):
        """The episode's closing card (on the last frame, dimmed)."""
        frame = self.base.shot_frames(self.fps)[-1]
        lines = episode_result(self.base, self.episode, info, self.reward, self.shots, self.balls, self.scratches)
        return card(frame, lines)

    def _shots(self, info):
        """(the step's Results, the `shot_facts` of each) in the order they were played."""
        records = [record for record in self.base.step_records if record.error is None]
        if not self.base.game.has_rules:
            return ([r.result for r in records], [shot_facts(r) for r in records])
        facts = [{**shot_facts(r), "_who": "agent" if r.shooter == 0 else "opponent"} for r in records]
        return [r.result for r in records], facts

    @staticmethod
    def _cue_pocket(result):
        """(time, pocket) of the cue ball falling in during `result`, or None."""
        times, kind, i, j = result.event_arrays
        hits = np.flatnonzero((kind == BALL_POCKET) & (i == 0))
        return (float(times[hits[0]]), int(j[hits[0]])) if hits.size else None

    def _note(self, info, reward, who):
        self.reward += reward
        if who in (None, "agent"):
            self.balls += len(info["pocketed"])
            self.scratches += bool(info["scratch"])
        self.last = [f"last shot{f' ({who})' if who else ''}: {shot_summary(info)}"]
        self.last += [m for m in info.get("messages", []) if m]

    def caption_rows(self, frame) -> int:
        """The rows at the bottom of `frame` below the cloth (the rail and the letterbox): the caption's room."""
        bottom = self.base.playback.renderer.cloth_box()[3]
        return max(0, frame.shape[0] - math.ceil(bottom))

    def _caption(self, frame, label=None):
        """The frame with the caption in the band under the cloth: the episode, the shot, the reward
        so far, what the last shot did, as large as fits there (elided at the smallest size)."""
        head = f"episode {self.episode}" + (f"   {label}" if label else "") + f"   reward so far {self.reward:+.2f}"
        lines, size = fit_band([head, *self.last], frame.shape[1], self.caption_rows(frame), font_size(frame.shape[0]))
        return overlay(frame, lines, where="bottom", size=size)
