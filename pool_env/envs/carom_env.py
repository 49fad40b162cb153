"""`ThreeCushionEnv`: three-cushion billiards (UMB rules) against an opponent, or practice (ThreeCushion-v0)."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from ..game import CAROM_OBSERVATION_SIZE, ELEVATED, Game, carom_observation, simulate_struck
from ..render.overlay import overlay
from ..render.playback import ShotPlayback, step_shot_frames
from ..render.window import HumanWindow
from .captions import captioned, shot_caption
from .common import can_render
from .infos import sampled_info
from .obs_types import Observer
from .opponents import resolve_opponent

AGENT, OPPONENT = 0, 1
WINNERS = {None: -1, AGENT: 0, OPPONENT: 1}  # info["winner"]: -1 none (or a draw: info["draw"])


class ThreeCushionEnv(HumanWindow, gym.Env):
    """Three-cushion (`pool_env.rules.ThreeCushion`, docs/games.md) on the carom table: one step
    is one shot of the agent (player 0, who plays the first inning with the white unless
    `agent_breaks=False`); the opponent's innings are played inside `step`.

    | argument | default | meaning |
    | --- | --- | --- |
    | `opponent` | `"carom_search"` | a player's name (`pool_env.make_player`; `"ghost_ball"` is the carom
      search player here too), an agent with `act(observation)`, a callable, or None: practice, the episode ends
      when the inning passes |
    | `noise` | None | None, `"olympiad"` or a dict (`pool_env.game.NOISE_PRESETS`), on both players' shots |
    | `points`, `innings_limit`, `equalizing` | 15, None, True | the rules' options (`ThreeCushion`) |
    | `agent_breaks` | True | False: the opponent plays the first inning, inside `reset` |
    | `max_shots` | 200 | truncate after this many agent shots |
    | `elevation` | False | add the cue's elevation as the action's last entry (as the pool envs': masse, jumps) |
    | `table`, `physics` | the carom presets | |
    | `hotseat` | False | with `opponent=None`: two people at one table, each step the shot of whoever is to
      shoot, the episode going on when the inning passes until the game ends (`python -m pool_env.play --game
      three_cushion --two-players`); observations from player 0's side, rewards +1 per point of either |
    | `render_mode`, `render_size` | None, (640, 360) | "rgb_array": `render()` is the table now, with the score;
      "rgb_array_list": every frame of the last step's shots (`shot_frames`); "human": a pygame window that
      plays every shot (no display: drawn offscreen, see `pool_env.render.window`); "ansi": the text observation |
    | `overlay` | True | frames carry a line of text: the game, whose shot, the score and innings |
    | `obs_type`, `obs_size`, `grayscale` | as `PoolBreakEnv` | `"state"` (below), `"pixels"`, `"dict"`, `"text"`
      (docs/observations.md) |

    Action `Box(-1, 1, (4,))` (5 with `elevation`): the "cue_spin" layout (force as a fraction of MAX_FORCE, tip
    side and top as fractions of the miscue limit), striking the agent's own cue ball.
    Observation `Box(-1, 1, (15,))`: `pool_env.game.carom_observation` from the agent's side
    (the balls, whose cue ball, score and innings). Reward: +1 per agent point, -1 per opponent
    point in the step. Info (numeric, the same keys every time): `points` and
    `opponent_points` (this step), `scores` and `innings` (agent, opponent), `opponent_shots`,
    `winner` (-1 none, 0 the agent, 1 the opponent), `draw`, `error` (a shot could not be
    simulated: the episode is truncated), `pocketed` (the pool envs' mask, always all False
    here: generic clients read it from every env). `env.unwrapped.step_records` holds the step's records.
    `pool_env.record_video` films it with the overlay; `python -m pool_env.play --game three_cushion`
    plays it with the mouse.
    """

    metadata = {"render_modes": ["human", "rgb_array", "rgb_array_list", "ansi"], "render_fps": 30}

    def __init__(self, opponent="carom_search", noise=None, points: int | None = 15, innings_limit: int | None = None,
                 equalizing: bool = True, agent_breaks: bool = True, max_shots: int = 200, table=None, physics=None,
                 render_mode=None, elevation: bool = False, render_size=(640, 360), overlay: bool = True,
                 hotseat: bool = False, obs_type="state", obs_size=(84, 84), grayscale=False, randomize=None):
        if render_mode not in (None, *self.metadata["render_modes"]):
            raise ValueError(f"ThreeCushion-v0's render modes are {self.metadata['render_modes']}, got {render_mode!r}")
        if isinstance(max_shots, bool) or not isinstance(max_shots, int) or max_shots < 1:
            raise ValueError(f"max_shots must be an integer >= 1, got {max_shots!r}")
        self.game = Game("three_cushion", table=table, physics=physics, noise=noise, points=points,
                         innings_limit=innings_limit, equalizing=equalizing,
                         layout="cue_spin" + (ELEVATED if elevation else ""), randomize=randomize)
        self.agent_breaks, self.max_shots, self.render_mode = bool(agent_breaks), max_shots, render_mode
        self.render_size, self.overlay, self.hotseat = (int(render_size[0]), int(render_size[1])), bool(overlay), \
            bool(hotseat)
        self.observation_space = spaces.Box(-1.0, 1.0, (CAROM_OBSERVATION_SIZE,), np.float32)
        self.action_space = spaces.Box(-1.0, 1.0, (self.game.layout.size,), np.float32)
        self.observer = Observer(self, obs_type, type(self).observe, obs_size, grayscale,
                                 carom_rules=self.game.state.rules)
        self.observation_space, self.obs_type = self.observer.space, obs_type
        self.text_observer = Observer(self, "text", None)  # render_mode="ansi"
        self.opponent, self.opponent_player, self.opponent_name = resolve_opponent(opponent, self)
        if self.hotseat and self.opponent is not None:
            raise ValueError("hotseat is two people at one table: it takes opponent=None")
        if self.hotseat and not self.agent_breaks:
            raise ValueError("hotseat: player 0 plays the first inning; keep agent_breaks=True")
        self.playback = ShotPlayback(self.game.table, self.render_size, self.metadata["render_fps"],
                                     deferred=render_mode is not None, palette="carom")
        self._window_title = "pool_env: three_cushion"
        self.agent_shots, self.step_records, self._started = 0, [], False
        self._quaternions = self._step_start = None

    @property
    def table(self):
        return self.game.table

    @property
    def physics(self):
        return self.game.physics

    @property
    def balls(self):
        """The balls now (the saved games and videos read them)."""
        return self.game.balls

    @property
    def state(self):
        """The rules' state (`pool_env.rules.ThreeCushionState`; the agent is player 0); None before the first reset."""
        return self.game.state if self._started else None

    def observe(self, viewer: int = AGENT) -> np.ndarray:
        g = self.game
        return carom_observation(g.balls, g.state, viewer, self.agent_shots, self.max_shots, g.table)

    @property
    def renderer(self):
        """The frame renderer (`pool_env.render.table.TableRenderer`, the carom palette)."""
        return self.playback.renderer

    def render(self):
        """The table now (uint8 (H, W, 3)) with the game's line on it ("rgb_array"); the last step's
        frames ("rgb_array_list"); shown in the window ("human"); None without a render mode."""
        if not can_render(self.render_mode, self._started):
            return None
        if self.render_mode == "ansi":
            return self.text_observer.observe(self)
        if self.render_mode == "rgb_array_list":
            return self.shot_frames()
        frame = self._annotate(self.playback.frame())
        if self.render_mode == "human":
            return self._show([frame])
        return frame

    def _annotate(self, frame):
        """`frame` with the game's line: who is to shoot (or the result), the score, the innings."""
        if not self.overlay:
            return frame
        state = self.game.state
        if state.ended:
            who = "draw" if state.winner is None else self._who(state.winner) + " wins"
        else:
            who = self._who(state.shooter) + " to shoot"
        score = f"score {state.scores[0]}-{state.scores[1]}, innings {state.innings[0]}-{state.innings[1]}"
        return overlay(frame, [f"three-cushion: {who}, {score}"])

    def _who(self, player: int) -> str:
        if self.hotseat:
            return f"player {player + 1}"
        return "agent" if player == AGENT else "opponent"

    def shot_frames(self, fps=None) -> list[np.ndarray]:
        """Every shot of the last step (the agent's, then the opponent's innings) sampled at `fps`,
        captioned (`overlay`); after `reset` the starting frame (and the opponent's first inning)."""
        if not self._started:
            raise RuntimeError("call reset() before shot_frames()")
        records = [record for record in self.step_records if record.error is None]
        if not records:
            return [self._annotate(frame) for frame in self.playback.shot_frames(fps)]
        shots = step_shot_frames(self.playback, self._step_start, self._quaternions, [r.result for r in records], fps)
        captions = [(shot_caption(self.game, r, self._who(r.shooter)), list(r.ruling.messages)) for r in records]
        return captioned(shots, captions, self.overlay)

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        if options:
            raise ValueError(f"ThreeCushion-v0's reset takes no options, got {sorted(options)}")
        self.game.reset(rng=np.random.default_rng(int(self.np_random.integers(2**63 - 1))),
                        breaker=AGENT if self.agent_breaks else OPPONENT)
        if self.opponent_player is not None:
            self.opponent_player.reset(int(self.np_random.integers(2**31)))
        # The balls' markers (only the frames show them): drawn from their own generator, so that
        # the game's and the opponent's draws stay the same whether or not the env renders.
        self._quaternions = np.random.default_rng(self.np_random_seed).normal(size=(len(self.game.balls), 4))
        self.playback.reset(self.game.balls, self._quaternions)
        self.agent_shots, self.step_records, self._started = 0, [], True
        self._step_start = self.game.balls
        against, error = self._opponent_turn()
        if self.render_mode == "human":
            self._show(self.shot_frames())
        return self.observer.observe(self), {**self._info(0, against, error), **sampled_info(self.game)}

    def step(self, action):
        struck = self.strike(action)
        out = self.finish(self.game.resolve(struck, simulate_struck(struck, self.game.table, self.game.physics)))
        if self.render_mode == "human":
            self._show(self.shot_frames())
        return out

    def strike(self, action):
        """`step`'s first half: the agent's shot struck (the vector env simulates many at once)."""
        if self.game.over:
            raise RuntimeError("the episode is over: reset() the env")
        if self.game.shooter != AGENT and not self.hotseat:
            raise RuntimeError("the agent is not to shoot (the practice episode ended): reset() the env")
        self._step_start = self.game.balls
        return self.game.strike(np.asarray(action, dtype=np.float64))

    def finish(self, record):
        """`step`'s second half, from the agent's shot's record: the opponent's innings, the reward."""
        self.agent_shots += 1
        self.step_records = []
        self._played(record)
        if record.error is not None:
            return self.observer.observe(self), 0.0, False, True, self._info(0, 0, True)
        points = int(bool(record.ruling.point))
        against, error = (0, False) if self.opponent is None else self._opponent_turn()
        passed = self.game.shooter != AGENT and not self.hotseat
        terminated = self.game.over or (self.opponent is None and passed)
        truncated = error or (not terminated and self.agent_shots >= self.max_shots)
        return (self.observer.observe(self), float(points - against), terminated, truncated,
                self._info(points, against, error))

    def _opponent_turn(self):
        """The opponent's shots while it is to shoot: (its points, a shot failed)."""
        points = 0
        while self.opponent is not None and not self.game.over and self.game.shooter == OPPONENT:
            record = self.game.play(self.opponent(self.observe(OPPONENT)))
            self._played(record)
            if record.error is not None:
                return points, True
            points += int(bool(record.ruling.point))
            if len(self.step_records) > 10 * self.max_shots:  # a perfect opponent: stop the episode
                return points, True
        return points, False

    def _played(self, record):
        """A shot was played: its record kept, the playback following it."""
        self.step_records.append(record)
        if record.error is None:
            self.playback.shot(record.result)
            self.playback.place(record.balls_after)

    def _info(self, points, against, error) -> dict:
        state = self.game.state
        return {"points": int(points), "opponent_points": int(against), "scores": np.array(state.scores),
                "innings": np.array(state.innings),
                "opponent_shots": sum(r.shooter == OPPONENT for r in self.step_records),
                "winner": WINNERS[state.winner], "draw": bool(state.ended and state.winner is None),
                "error": bool(error), "pocketed": np.zeros(len(self.game.balls), dtype=bool)}
