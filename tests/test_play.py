"""render_mode="human" and `python -m pool_env.play`, headless (SDL's dummy video driver; conftest sets it)."""

import math
import sys
import threading
import time

import gymnasium as gym
import numpy as np
import pytest
from scenes import require_pygame

import pool_env
from pool_env.game import MAX_TIP_OFFSET, placement_area

pygame = require_pygame()

from pool_env.play.aim import DRAG_FULL, MIN_DRAG, shot_action  # noqa: E402
from pool_env.play.draw import CALL_RGB, draw_session  # noqa: E402
from pool_env.play.session import PlaySession  # noqa: E402
from pool_env.records.saved import replay  # noqa: E402
from pool_env.render.overlay import overlay  # noqa: E402

SIZE = (640, 360)
SMALL = (320, 180)  # the animation tests draw every frame of a step


def mouse(kind, pos):
    pos = tuple(float(v) for v in pos)
    if kind == "motion":
        return pygame.event.Event(pygame.MOUSEMOTION, pos=pos, rel=(0, 0), buttons=(1, 0, 0))
    return pygame.event.Event(pygame.MOUSEBUTTONDOWN if kind == "down" else pygame.MOUSEBUTTONUP, pos=pos, button=1)


def key(k):
    return pygame.event.Event(pygame.KEYDOWN, key=k, mod=0, unicode="")


def drag(session, start, end):
    for event in (mouse("down", start), mouse("motion", end), mouse("up", end)):
        session.handle(event)


@pytest.mark.parametrize("env_id", ["PoolBreak-v0", "PoolNineBall-v0"])
def test_human_mode_opens_draws_and_closes(env_id):
    env = gym.make(env_id, render_mode="human", render_size=SIZE)
    env.reset(seed=0)
    window = env.unwrapped.window
    assert window.is_open and pygame.display.get_init()
    env.step(np.array([1.0, 0.0] + [0.0] * (env.action_space.shape[0] - 2), dtype=np.float32))
    assert env.render() is None
    frame = window.frame()
    assert frame.shape == (SIZE[1], SIZE[0], 3) and frame.max() > 0  # the table, not a black window
    if env_id == "PoolBreak-v0":
        assert np.array_equal(frame, env.unwrapped.playback.frame())  # render() shows the table now
    env.close()
    assert not window.is_open and not pygame.display.get_init()
    env.close()  # twice is fine


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="the early display check is for Linux")
def test_the_drag_mapping():
    a = shot_action((1.0, 0.5), (0.7, 0.5), tip=(0.1, -0.2))  # dragged 0.3 m back along -x
    assert np.allclose(a, [0.3 / DRAG_FULL, 0.0, 0.1 / MAX_TIP_OFFSET, -0.2 / MAX_TIP_OFFSET])
    assert np.allclose(shot_action((1.0, 0.5), (1.0, -1.0))[:2], [0.0, 1.0])  # a long drag is full power
    assert shot_action((1.0, 0.5), (1.0 + 0.5 * MIN_DRAG, 0.5)) is None  # a click is no shot


def test_a_scripted_session_places_aims_shoots_undoes_and_saves(tmp_path):
    session = PlaySession("nine_ball", "ghost_ball", seed=3, size=SIZE, save_dir=tmp_path, animate=False)
    base = session.base
    assert session.in_hand == "behind_head_string"
    # Ball in hand: drag the cue ball to a free spot in the kitchen.
    spot = np.array([0.4, 0.45])
    drag(session, session.to_pixel(session.cue_xy), session.to_pixel(spot))
    assert np.allclose(session.cue_xy, spot, atol=2.0 / base.playback.renderer.scale)
    placed = session.cue_xy.copy()
    # The tip: a click on the diagram's lower half is draw (clamped to the miscue limit).
    cx, cy = session.tip_centre()
    session.handle(mouse("down", (cx, cy + 60)))
    session.handle(mouse("up", (cx, cy + 60)))
    assert session.tip == pytest.approx((0.0, -MAX_TIP_OFFSET))
    # Aim: press on the table, drag back about 0.3 m along -x from the cue ball, release.
    back = placed + np.array([-0.3, 0.02])
    session.handle(mouse("down", session.to_pixel(placed + (-0.15, 0.0))))  # off the cue ball: aiming
    session.handle(mouse("motion", session.to_pixel(back)))
    action = session.action()
    session.handle(mouse("up", session.to_pixel(back)))
    assert session.pending is not None and np.array_equal(session.pending, action)
    pulled = session.to_world(session.to_pixel(back)) - placed  # the drag, as the mouse reported it
    assert np.allclose(action[:2], -pulled / DRAG_FULL, atol=1e-6)  # opposite the drag, |a| = drag / 0.6 m
    assert math.hypot(*action[:2]) == pytest.approx(math.hypot(-0.3, 0.02) / DRAG_FULL, abs=0.01)
    assert np.allclose(action[2:4], [0.0, -1.0], atol=1e-6)
    x_lo, x_hi, y_lo, y_hi = placement_area(base.table, "behind_head_string", float(base.balls.radii[0]))
    wanted = (x_lo + 0.5 * (action[4] + 1) * (x_hi - x_lo), y_lo + 0.5 * (action[5] + 1) * (y_hi - y_lo))
    assert np.allclose(wanted, placed, atol=1e-6)
    session.update()  # the shot, then the opponent's replies, on the session's worker thread
    assert session.wait(60) and not session.busy
    assert len(session.actions) == 1 and session.pending is None
    assert session.status()[0].startswith("9-ball") and session.lines
    balls_1, state_1 = base.balls, base.state
    # A second shot, then undo: the game is back exactly where it was.
    cue = session.cue_xy
    drag(session, session.to_pixel(cue), session.to_pixel(cue + (0.1, 0.15)))
    session.update()
    session.wait()
    assert len(session.actions) == 2
    session.handle(key(pygame.K_u))
    assert len(session.actions) == 1
    assert np.array_equal(base.balls.xy, balls_1.xy) and np.array_equal(base.balls.pocketed, balls_1.pocketed)
    assert base.state == state_1
    # W writes a file that load_game and replay accept.
    session.handle(key(pygame.K_w))
    assert session.saved_path is not None and session.saved_path.exists()
    record = pool_env.load_game(session.saved_path)
    assert record["actions"] == session.actions
    env = replay(record)
    assert np.array_equal(env.unwrapped.balls.xy, balls_1.xy)
    # Drawing works on an off-screen surface, and R racks a new game.
    surface = pygame.Surface(session.window_size)
    draw_session(session, surface)
    assert pygame.surfarray.array3d(surface).max() > 0
    session.handle(key(pygame.K_r))
    assert session.actions == [] and session.seed == 4


def test_two_players_take_turns():
    session = PlaySession("nine_ball", two_players=True, seed=0, size=SIZE, animate=False)
    assert session.status()[0].startswith("9-ball  shot 1: player 1")
    cue = session.cue_xy
    drag(session, session.to_pixel(cue + (0.0, 0.1)), session.to_pixel(cue + (0.0, 0.12)))  # a miss: a foul
    session.update()
    session.wait()
    assert not session.done and session.state.shooter == 1
    assert "player 2" in session.status()[0]


def test_snooker_is_played_from_the_d_with_the_score_shown():
    session = PlaySession("snooker", two_players=True, seed=0, size=SIZE, animate=False)
    head, score = session.status()[:2]
    assert head.startswith("snooker  shot 1: player 1") and "in d" in head  # Section 3 Rule 4: from the D
    assert score == "score: player 1 0, player 2 0"
    cue = session.cue_xy
    drag(session, session.to_pixel(cue + (0.0, 0.1)), session.to_pixel(cue + (0.0, 0.12)))  # hits nothing: a foul
    session.update()
    session.wait()
    assert session.state.shooter == 1 and session.state.scores == (0, 4)  # the 4-point minimum (Rule 12)
    assert session.status()[1] == "score: player 1 0, player 2 4"


def test_three_cushion_passes_the_inning_and_the_other_player_strikes_the_yellow():
    session = PlaySession("three_cushion", two_players=True, seed=0, size=SIZE, animate=False)
    head, score, ball = session.status()[:3]
    assert head.startswith("three-cushion  shot 1: player 1") and score == "score: player 1 0, player 2 0"
    assert ball.startswith("white cue ball") and np.array_equal(session.cue_xy, session.base.balls.xy[0])
    cue = session.cue_xy
    drag(session, session.to_pixel(cue + (0.0, 0.1)), session.to_pixel(cue + (0.0, 0.12)))  # soft, away: no point
    session.update()
    session.wait()
    # UMB Art. 3.1: a miss ends the inning; each player has his own cue ball (the second the yellow).
    assert not session.done and session.state.shooter == 1 and session.cue_index == 1
    assert np.array_equal(session.cue_xy, session.base.balls.xy[1]) and session.status()[2].startswith("yellow")


def test_three_cushion_in_a_human_window_shows_the_last_frame_of_the_step():
    env = gym.make("ThreeCushion-v0", render_mode="human", render_size=SIZE, opponent=None)
    env.reset(seed=0)
    window = env.unwrapped.window
    assert window.is_open
    env.step(np.array([0.3, 0.0, 0.0, 0.0], np.float32))
    assert np.array_equal(window.frame(), env.unwrapped.shot_frames()[-1])
    env.close()
    assert not window.is_open


def test_ten_ball_calls_the_lowest_ball_in_the_clicked_pocket():
    session = PlaySession("ten_ball", two_players=True, seed=0, size=SIZE, animate=False)
    assert not session.needs_call  # nothing is called on the break (WPA Ten Ball 5)
    cue = session.cue_xy
    drag(session, session.to_pixel(cue + (-0.1, 0.0)), session.to_pixel(cue + (-0.4, 0.0)))  # a hard break
    session.update()
    session.wait()
    game = session.base.game
    if game.over or not session.needs_call:  # the break ended it (the 10 is spotted, so it never does)
        pytest.skip("no called shot follows this break")
    lowest = min(game.state.on_table)
    assert f"click a pocket to call the {lowest}" in session.status()  # Ten Ball 5: ball and pocket called
    pocket = session.base.table.pockets[3, :2]
    session.handle(mouse("down", session.to_pixel(pocket)))
    session.handle(mouse("up", session.to_pixel(pocket)))
    assert session.called == 3 and f"the {lowest} called in pocket 3" in session.status()


def play_out(session, seconds, limit=60.0):
    """Drive the session's loop with a fake clock until its step is over and shown: each turn
    update, draw the frame shown, tick `seconds(turn, frames drawn so far)`. The (step frame
    index, frame) drawn, the frame with its caption as the env's own frames carry it."""
    shown, turn, start = [], 0, time.monotonic()
    while session.busy or session.animation is not None:
        assert time.monotonic() - start < limit, "the step never ended"
        session.update()
        frame = session.shot_frame()
        if frame is not None:
            shown.append((session.animation.index()[2], overlay(frame, session.shot_caption())))
        session.tick(seconds(turn, len(shown)))
        turn += 1
    return shown


@pytest.mark.parametrize("game", ["nine_ball", "break"])
def test_every_frame_of_a_step_is_shown_from_the_first_in_order_even_after_a_blocked_tick(game):
    session = PlaySession(game, "ghost_ball", seed=0, size=SMALL)
    base = session.base
    cue = session.cue_xy
    drag(session, session.to_pixel(cue + (-0.15, 0.0)), session.to_pixel(cue + (-0.5, 0.01)))  # the break
    session.update()
    assert session.busy or session.step is None  # shoot() returned: the step is the worker's
    # 10 s "blocked" ticks right after the release, after the first frame and midway: each may
    # move on by one frame only.
    shown = play_out(session, lambda turn, drawn: 10.0 if turn in (0, 1) or drawn in (1, 2, 60) else 1 / 60)
    frames = base.shot_frames(base.metadata["render_fps"])  # the env's own frames of the step
    if game == "nine_ball":
        shooters = [record.shooter for record in base.step_records]
        assert shooters[0] == 0 and 1 in shooters  # the break, then the opponent's shots: all animated
    indices = [k for k, _ in shown]
    assert indices == sorted(indices) and sorted(set(indices)) == list(range(len(frames)))  # none skipped
    assert np.array_equal(shown[0][1], frames[0])  # the first new picture: the break's first frame
    first = {}
    for k, frame in shown:
        first.setdefault(k, frame)
    assert all(np.array_equal(first[k], frames[k]) for k in range(len(frames)))  # the env's frames, captions too
    assert session.shot_frame() is None and not session.busy  # over: the table again


def test_the_window_stays_responsive_while_the_opponent_thinks():
    thinking, go_on = threading.Event(), threading.Event()
    player = []

    def slow_opponent(observation):  # the ghost-ball player, after a wait the test ends
        thinking.set()
        go_on.wait(20)
        return player[0].act(observation)

    session = PlaySession("nine_ball", slow_opponent, seed=0, size=SMALL)
    player.append(pool_env.make_player("ghost_ball", session.base))
    action = np.zeros(session.base.action_space.shape, dtype=np.float32)
    action[0] = -0.5  # into the head cushion, no ball hit: a foul, the opponent's turn
    try:
        session.shoot(action)
        assert thinking.wait(20), "the opponent was never asked"
        assert session.busy and "opponent thinking..." in session.status()[0]
        # The break is animated while the opponent thinks: every frame, then it waits on the last.
        shown, n = [], None
        for turn in range(400):
            session.update()
            frame = session.shot_frame()
            if frame is not None:
                shown.append(session.animation.index()[2])
                n = session.animation.available
            session.tick(10.0 if turn == 3 else 1 / 30)
        assert n is not None and len(session.animation.shots) == 1  # only the break is in
        assert sorted(set(shown)) == list(range(n)) and shown[-1] == n - 1
        surface = pygame.Surface(session.window_size)
        draw_session(session, surface)  # the break's last frame, "opponent thinking..." over it
        pixels = pygame.surfarray.array3d(surface)
        assert (pixels[: SMALL[0], : SMALL[1]] == CALL_RGB).all(axis=-1).any()
        session.handle(key(pygame.K_u))  # undo needs the env: done once the opponent's turn is over
        assert session.note == "after the opponent's turn" and len(session.actions) == 1
        session.handle(pygame.event.Event(pygame.QUIT))
        assert not session.running and session.busy  # closing the window does not wait for the opponent
    finally:
        go_on.set()
    assert session.wait(30) and not session.busy
    assert not session.status()[0].endswith("thinking...")
    records = session.base.step_records
    session.update()  # the undo
    assert session.actions == [] and session.note.startswith("undone")
    assert [record.shooter for record in records][:2] == [0, 1]


def test_the_status_bar_is_off_the_table_and_the_panel_text_fits_the_panel():
    from pool_env.play.draw import MARGIN, PANEL_RGB, TEXT_RGB, panel_lines, status_rect
    from pool_env.play.session import PANEL, STATUS_BAR
    from pool_env.render.overlay import font

    session = PlaySession("nine_ball", "ghost_ball", seed=0, size=SIZE, animate=False)
    left, top, right, bottom = session.base.playback.renderer.table_box()
    x, y, w, h = status_rect(session)
    assert y + h <= top + STATUS_BAR  # the bar ends where the table's rails begin in the window
    assert session.window_size == (SIZE[0] + PANEL, SIZE[1] + STATUS_BAR)
    session.note = "saved /a/rather/long/folder/of/saved/games/pool_game_nine_ball_20260101_120000.json"
    surface = pygame.Surface(session.window_size)
    draw_session(session, surface)
    pixels = pygame.surfarray.array3d(surface).transpose(1, 0, 2)
    # The table is drawn below the bar exactly as rendered: no text on its rails or pockets.
    assert np.array_equal(pixels[STATUS_BAR:, : SIZE[0]], session.table_frame())
    assert (pixels[:STATUS_BAR, : SIZE[0]] == TEXT_RGB).all(axis=-1).any()  # the status is in the bar
    # The saved game's path is all there, on lines that end before the panel's right margin.
    lines = panel_lines(session, 20)
    assert "".join(lines).replace(" ", "").endswith(session.note.split()[1])
    assert all(font(15).getlength(line) <= PANEL - 2 * MARGIN for line in lines)
    assert (pixels[:, -(MARGIN - 1):] == PANEL_RGB).all()  # nothing runs off the edge
    # A click on the bar is not a shot.
    session.handle(mouse("down", (SIZE[0] / 2, STATUS_BAR / 2)))
    assert session.drag is None


def test_the_window_draws_with_no_display_variable_at_all():
    """pool_env.play's drawing on a plain surface in a process with neither DISPLAY, WAYLAND_DISPLAY
    nor SDL_VIDEODRIVER (conftest's dummy driver is not inherited): text, table, panel."""
    import json
    import os
    import subprocess
    from pathlib import Path

    code = (
        "import json, numpy as np, pygame\n"
        "from pool_env.play.session import PlaySession, STATUS_BAR\n"
        "from pool_env.play.draw import draw_session\n"
        "s = PlaySession('eight_ball', 'ghost_ball', seed=1, size=(320, 180), animate=False)\n"
        "surface = pygame.Surface(s.window_size)\n"
        "draw_session(s, surface)\n"
        "p = pygame.surfarray.array3d(surface).transpose(1, 0, 2)\n"
        "print(json.dumps({'same': bool(np.array_equal(p[STATUS_BAR:, :320], s.table_frame())),\n"
        "                  'display': pygame.display.get_init()}))\n")
    root = Path(__file__).resolve().parents[1]
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER")}
    env["PYTHONPATH"] = str(root)
    proc = subprocess.run([sys.executable, "-c", code], env=env, cwd=root, capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert json.loads(proc.stdout.strip().splitlines()[-1]) == {"same": True, "display": False}


def test_eight_ball_calls_the_aimed_ball_in_the_clicked_pocket_on_every_shot():
    # WPA 1.6: every shot but the break calls a ball and a pocket; the window calls the legal
    # ball the aim line hits first, in the pocket clicked.
    session = PlaySession("eight_ball", two_players=True, seed=0, size=SIZE, animate=False)
    assert not session.needs_call  # the break calls nothing (3.3)
    cue = session.cue_xy
    drag(session, session.to_pixel(cue + (-0.1, 0.0)), session.to_pixel(cue + (-0.4, 0.0)))  # a hard break
    session.update()
    session.wait()
    game = session.base.game
    if game.over or game.state.is_break:
        pytest.skip("no called shot follows this break")
    assert session.needs_call and session.called_ball is None  # no aim yet: nothing to call
    session.handle(mouse("down", session.to_pixel(session.base.table.pockets[3, :2])))
    assert session.called == 3
    balls = session.base.balls
    target = min(game.legal_targets, key=lambda b: math.dist(balls.xy[b], session.cue_xy))
    aim = session.cue_xy - 0.2 * (balls.xy[target] - session.cue_xy)  # drag back from the cue ball
    session.handle(mouse("down", session.to_pixel(aim)))
    session.handle(mouse("motion", session.to_pixel(aim)))
    ball = session.called_ball
    assert ball in game.legal_targets
    assert game.decode(session.action()).ball == ball and game.decode(session.action()).pocket == 3
