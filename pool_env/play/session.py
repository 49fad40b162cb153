"""`PlaySession`: `python -m pool_env.play`'s logic (events to shots, undo, save), testable without a display."""

from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np

from ..game import MAX_SPEED, Shot, place_cue_ball, placement_area
from ..physics import BALL_RADIUS
from ..records.saved import record_game, save_game
from ..render.window import import_pygame
from ..rules import cue_ball
from . import layout
from .aim import first_hit, shot_action
from .animation import PendingStep, StepAnimation
from .games import TABLE_SIZE, TWO_SIDED, make_env
from .layout import PANEL, STATUS_BAR
from .status import player_name, shot_lines, status_lines

SLOW = 4  # slow motion: this many times slower
KEYS = "R restart  U undo  S slow motion  W save  Esc quit"


class PlaySession:
    """A game played with the mouse: feed it pygame events (`handle`), let it play pending shots
    and follow them (`update`, then `tick` the animation), draw it (`play_draw.draw_session`).
    A shot's step (the shot, the opponent's replies) runs on a worker thread: its shots are
    animated from their first frame while the next ones are computed, the status saying the
    opponent is thinking; `wait` waits for it (scripts, tests). Mouse: press on the table and
    drag back from the cue ball, release to shoot (`shot_action`'s mapping; a drag shorter than
    a ball radius cancels); with ball in hand drag the cue ball itself to place it; click or
    drag on the tip diagram (right panel) to set the tip offset (clamped to the 0.5 R miscue
    limit); when shooting at the 8, click a pocket to call it first. Keys: R restart (a new rack), U undo the last
    shot (the game replayed without it), S slow motion, W write the game to a JSON file
    (`pool_env.save_game`; `python -m pool_env.records.replay` plays it again), Esc quit."""

    def __init__(self, game="nine_ball", opponent="ghost_ball", two_players=False, seed=0, size=TABLE_SIZE,
                 save_dir=".", animate=True):
        self.pygame = import_pygame()
        self.game, self.opponent, self.two_players = game, opponent, bool(two_players)
        self.seed, self.size, self.save_dir, self.animate = int(seed), tuple(size), Path(save_dir), animate
        self.env = make_env(game, opponent, two_players, size)
        self.base = self.env.unwrapped
        self.running, self.slow, self.saved_path = True, False, None
        self.tip = (0.0, 0.0)
        self.step = self.animation = None  # the step under way (a PendingStep), the shots shown (a StepAnimation)
        self._queued = None  # a key (R, U, W) pressed while the step is under way: done once it is over
        self.restart(self.seed)

    # --- state ------------------------------------------------------------------------------
    @property
    def window_size(self):
        return self.size[0] + PANEL, self.size[1] + STATUS_BAR

    @property
    def state(self):
        """The game's `rules.GameState` (None in the break envs)."""
        return getattr(self.base, "state", None)

    @property
    def busy(self) -> bool:
        """A step is under way (or over but not yet applied by `update`): the env is the worker's."""
        return self.step is not None

    @property
    def thinking(self) -> str:
        """What the window says while a step is under way."""
        has_opponent = self.game in TWO_SIDED and not self.two_players
        return "opponent thinking..." if has_opponent else "simulating the shot..."

    @property
    def cue_index(self) -> int:
        """The ball the shooter strikes: 0, or in three-cushion his own (white or yellow)."""
        return 0 if self.state is None else cue_ball(self.state)

    @property
    def in_hand(self):
        return None if self.state is None or self.done else self.state.ball_in_hand

    @property
    def needs_call(self) -> bool:
        """The shooter must call a pocket (the game's `calls_pocket`: every shot but the break in
        10-ball and 8-ball)."""
        return not self.done and not self.busy and self.base.game.calls_pocket

    @property
    def called_ball(self):
        """The ball a clicked pocket calls: in 10-ball the lowest on the table (the ball a shot
        calls when it names none, `Game.called_targets`); in 8-ball the legal target the aim
        line hits first (the 8 when it is the only one), None while the aim hits none."""
        targets = self.base.game.called_targets
        if self.game == "ten_ball" or len(targets) <= 1:
            return targets[0] if targets else 8
        if self.drag is None:
            return None
        back = np.asarray(self.drag) - np.asarray(self.cue_xy)
        if not back.any():
            return None
        _, hit = first_hit(self.base.balls, self.cue_xy, -back / math.hypot(*back), self.base.table, self.cue_index)
        return hit if hit in targets else None

    def restart(self, seed=None):
        """A new game (seed `seed`, default the next one)."""
        self.wait()
        self.seed = self.seed + 1 if seed is None else int(seed)
        self.actions, self.done, self.lines, self.note, self.animation = [], False, [], "", None
        self.env.reset(seed=self.seed)
        self._begin_turn()

    def _begin_turn(self):
        self.drag = self.pending = None
        self.placing = self.tipping = False
        self.called = None
        self._still = None
        balls = self.base.balls
        self.cue_xy = balls.xy[self.cue_index].copy()
        if self.in_hand is not None:
            x_lo, x_hi, y_lo, y_hi = placement_area(self.base.table, self.in_hand, float(balls.radii[0]))
            wanted = self.cue_xy if not balls.pocketed[0] else ((x_lo + x_hi) / 2, (y_lo + y_hi) / 2)
            self.cue_xy = self._placed(wanted)

    def _placed(self, wanted):
        """The free spot nearest `wanted` where the cue ball may go (ball in hand)."""
        placed = place_cue_ball(self.base.balls, self.base.table, self.base.physics, self.in_hand, wanted)
        return placed.xy[0].copy()

    # --- events -------------------------------------------------------------------------------
    def handle(self, event):
        """Apply one pygame event (mouse, keys, window close)."""
        pg = self.pygame
        if event.type == pg.QUIT:
            self.running = False
        elif event.type == pg.KEYDOWN:
            self._key(event.key)
        elif event.type == pg.MOUSEBUTTONDOWN and event.button == 1:
            self._press(event.pos)
        elif event.type == pg.MOUSEMOTION:
            self._move(event.pos)
        elif event.type == pg.MOUSEBUTTONUP and event.button == 1:
            self._release(event.pos)

    def _key(self, key):
        pg = self.pygame
        if key == pg.K_ESCAPE:
            self.running = False
        elif self.busy and key in (pg.K_r, pg.K_u, pg.K_w):  # they need the env, which is the worker's now
            self._queued = key
            self.note = "after the opponent's turn" if self.thinking.startswith("opponent") else "after the shot"
        elif key == pg.K_r:
            self.restart()
            self.note = f"new game (seed {self.seed})"
        elif key == pg.K_u:
            self.undo()
        elif key == pg.K_s:
            self.slow = not self.slow
            self.note = f"slow motion {'on' if self.slow else 'off'}"
        elif key == pg.K_w:
            self.write()

    def _press(self, pos):
        if self.animation is not None and not self.animation.skipped:  # a click skips the animation
            self.animation.skip()
            return
        if self.done or self.busy:
            return
        if self._tip_at(pos) is not None:
            self.tipping = True
            self.tip = self._tip_at(pos)
            return
        if pos[0] >= self.size[0] or pos[1] < STATUS_BAR:  # the panel or the status bar
            return
        xy = self.to_world(pos)
        pocket = layout.pocket_at(self.base.table, xy)
        if self.needs_call and pocket is not None:
            ball = self.called_ball
            ball = "the ball you aim at" if ball is None else f"the {ball}"
            self.called, self.note = pocket, f"{ball} called in pocket {pocket}"
        elif self.in_hand is not None and math.dist(xy, self.cue_xy) <= 2 * BALL_RADIUS:
            self.placing = True
        else:
            self.drag = xy

    def _move(self, pos):
        if self.tipping:
            self.tip = self._tip_at(pos, clamp=True)
        elif self.placing:
            x_lo, x_hi, y_lo, y_hi = placement_area(self.base.table, self.in_hand, BALL_RADIUS)
            x, y = self.to_world(pos)
            self.cue_xy, self._still = np.array([min(max(x, x_lo), x_hi), min(max(y, y_lo), y_hi)]), None
        elif self.drag is not None:
            self.drag = self.to_world(pos)

    def _release(self, pos):
        if self.tipping:
            self.tip, self.tipping = self._tip_at(pos, clamp=True), False
        elif self.placing:
            self._move(pos)
            self.cue_xy, self.placing, self._still = self._placed(self.cue_xy), False, None
        elif self.drag is not None:
            self.drag = self.to_world(pos)
            action = self.action()
            self.drag = None
            if action is None:
                return
            if self.needs_call and self.called is None:
                self.note = "shooting at the 8: click a pocket to call it first"
                return
            self.pending = action

    # --- actions ------------------------------------------------------------------------------
    def action(self):
        """The env action of the drag under way (None without one, or for a drag shorter than
        MIN_DRAG): the shot `shot_action` reads from the drag, from where the cue ball is to be
        placed (ball in hand), calling the clicked pocket, encoded by the game's layout."""
        if self.drag is None:
            return None
        head = shot_action(self.cue_xy, self.drag, self.tip)
        if head is None:
            return None
        power = float(np.hypot(head[0], head[1]))
        place = tuple(self.cue_xy) if self.in_hand is not None else None
        mass = float(self.base.balls.masses[self.cue_index])
        ball = self.called_ball if self.needs_call else None
        shot = Shot.aimed(head[0:2], power * MAX_SPEED, tuple(self.tip), place, self.called, mass=mass, ball=ball)
        return self.base.game.encode(shot)

    def update(self):
        """Follow the step under way (its shots to the animation as they are played; applied
        once over), then do a key pressed meanwhile, then start the pending shot, if any."""
        if self.step is not None:
            self._follow()
        if self.step is None and self._queued is not None:
            key, self._queued = self._queued, None
            self._key(key)
        if self.step is None and self.pending is not None:
            action, self.pending = self.pending, None
            self.shoot(action)

    def shoot(self, action):
        """Start the step of `action` (the shot, then the opponent's replies) on a worker thread
        and return: `update` follows it (the frames, the rules' messages), `wait` waits for it."""
        self.wait()
        action = np.asarray(action, dtype=np.float32)
        shooter = 0 if self.state is None else self.state.shooter
        self._still_frame()  # the table before the shot: shown until its first frame is in
        if self.animate:
            playback, fps = self.base.playback, self.base.metadata["render_fps"] * (SLOW if self.slow else 1)
            self.animation = StepAnimation(playback.renderer, playback.orientation, fps)
        self.actions.append([float(a) for a in action])
        self.note = ""
        self.step = PendingStep(self.env, action, shooter)

    def wait(self, timeout=None) -> bool:
        """Wait for the step under way (at most `timeout` s) and apply it; whether none is left under way."""
        if self.step is not None and self.step.join(timeout):
            self._follow()
        return self.step is None

    def _follow(self):
        """The step's new shots to the animation; the step applied if it is over (what it raised, raised here)."""
        step = self.step
        over = step.done  # read before the shots: then, when over, they are all of them
        if self.animation is not None:
            self.animation.add(step.shots(), complete=over)
        if not over:
            return
        self.step = None
        obs, reward, terminated, truncated, info = step.outcome()
        self.done = bool(terminated or truncated)
        self.lines = shot_lines(self, info, step.shooter)
        self._begin_turn()

    def undo(self):
        """Take back the last shot: the game replayed from its seed with every action but the last."""
        self.wait()
        if not self.actions:
            self.note = "nothing to undo"
            return
        actions = self.actions[:-1]
        self.env.reset(seed=self.seed)
        self.actions, self.done, self.lines, self.animation = [], False, [], None
        for action in actions:
            obs, reward, terminated, truncated, info = self.env.step(np.asarray(action, dtype=np.float32))
            self.actions.append(action)
            self.done = bool(terminated or truncated)
        self._begin_turn()
        self.note = f"undone: back to shot {len(self.actions) + 1}"

    def write(self, path=None):
        """Save the game so far (`pool_env.save_game`) and return the path (None if it cannot be saved)."""
        self.wait()
        if path is None:
            path = self.save_dir / f"pool_game_{self.game}_{time.strftime('%Y%m%d_%H%M%S')}.json"
        actions = iter(self.actions)
        env = make_env(self.game, self.opponent, self.two_players, self.size, render_mode=None)
        try:
            record = record_game(env, lambda obs: next(actions), seed=self.seed, max_steps=len(self.actions))
        except ValueError as exc:
            self.note = f"cannot save: {exc}"
            return None
        finally:
            env.close()
        self.saved_path = save_game(path, record)
        self.note = f"saved {self.saved_path}"
        print(f"pool_env.play: {self.note}", flush=True)
        return self.saved_path

    # --- geometry -----------------------------------------------------------------------------
    def to_world(self, pos):
        """Window pixel (col, row) to table metres (x, y) (`layout.to_world`)."""
        return layout.to_world(self.base.playback.renderer, pos)

    def to_pixel(self, xy):
        """Table metres (x, y) to the window's pixel (col, row) (`layout.to_pixel`)."""
        return layout.to_pixel(self.base.playback.renderer, xy)

    def tip_centre(self):
        return layout.tip_centre(self.size)

    def _tip_at(self, pos, clamp=False):
        return layout.tip_at(self.size, pos, clamp)

    def player(self, shooter=None):
        """A player's name (default: the shooter now): "you" and "opponent", or "player 1" and "player 2"."""
        return player_name(self.state, self.two_players, shooter)

    # --- drawing ------------------------------------------------------------------------------
    def status(self):
        """The lines of text on the table: the game, whose turn, ball in hand, the last shot's messages."""
        return status_lines(self)

    def table_frame(self):
        """The table now (uint8 (H, W, 3)), the cue ball where it is to be placed (`status` says the
        rest, in the bar above it); while a step is under way, the table before it."""
        return self._still_frame()

    def _still_frame(self):
        """The table now without text (drawn once a turn; kept while the worker has the env)."""
        if self._still is None:
            balls, playback = self.base.balls, self.base.playback
            xy, pocketed = balls.xy.copy(), balls.pocketed.copy()
            xy[self.cue_index], pocketed[self.cue_index] = self.cue_xy, False
            playback.frame()  # brings the rotation markers to the end of the last shot
            self._still = playback.renderer.draw(xy, pocketed, playback.orientation)
        return self._still

    def shot_frame(self):
        """The animation's frame shown now (a shot of the last step; `shot_caption` says what it is),
        or None: no animation, or its first frame is not in yet."""
        return None if self.animation is None else self.animation.frame()

    def shot_caption(self) -> list[str]:
        """The lines the env's own frames carry on the animation's frame shown now ([] without one)."""
        return [] if self.animation is None else self.animation.caption()

    def tick(self, seconds):
        """Advance the animation by `seconds` of wall time (at metadata["render_fps"] frames a
        second), but never past a frame not yet drawn (`StepAnimation.advance`): a loop that
        blocked shows the next frame, none is skipped."""
        if self.animation is not None:
            self.animation.advance(seconds * self.base.metadata["render_fps"])
            if self.animation.finished and self.step is None:
                self.animation = None

    def power(self):
        """(|a[0:2]|, cue-ball speed in m/s) of the drag under way, or None."""
        action = self.action()
        if action is None:
            return None
        power = float(np.hypot(action[0], action[1]))
        return power, power * MAX_SPEED
