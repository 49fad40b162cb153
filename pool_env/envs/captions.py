"""The game envs' captions: each shot's first overlay line, the score, and captioned frames of shots."""

from __future__ import annotations

from .. import rules
from ..render.overlay import overlay


def shot_caption(game, record, who: str) -> str:
    """The overlay's first line for a shot of `who`: the game, the shot's number, ball in hand,
    the 8's called pocket, the score after it (snooker)."""
    hand = record.ball_in_hand
    hand = f", ball in hand ({hand.replace('_', ' ')})" if hand else ""
    shoots_eight = game.mode == "eight_ball" and 8 in rules.legal_targets(record.state_before)
    called = record.called_pocket
    called = f", 8 called in pocket {called}" if called is not None and shoots_eight else ""
    return f"{game.label}  shot {record.state_after.shot}: {who} shoots{hand}{called}{score_text(record.state_after)}"


def score_text(state) -> str:
    """", score a-b" (player 0's first) for a game that keeps a score (snooker), else ""."""
    scores = getattr(state, "scores", None)
    return "" if scores is None else f", score {scores[0]}-{scores[1]}"


def captioned(shots, captions, on: bool = True) -> list:
    """The frames of several shots (a list of frame lists) with their (caption, messages):
    the caption on every frame, the rules' messages added on each shot's last."""
    frames = []
    for shot, (caption, messages) in zip(shots, captions):
        if not on:
            frames += shot
            continue
        frames += [overlay(frame, [caption]) for frame in shot[:-1]]
        frames.append(overlay(shot[-1], [caption, *messages]))
    return frames
