"""`ThreeCushionEnv`: three-cushion billiards (UMB rules) against an opponent, or practice (ThreeCushion-v0)."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from ..game import CAROM_OBSERVATION_SIZE, ELEVATED, Game, carom_observation, simulate_struck
from ..render.overlay import overlay
from ..render.table import TableRenderer
from .game_env import resolve_opponent
from .infos import sampled_info

AGENT, OPPONENT = 0, 1
WINNERS = {None: -1, AGENT: 0, OPPONENT: 1}  # info["winner"]: -1 none (or a draw: info["draw"])


class ThreeCushionEnv(gym.Env):
    """Three-cushion (`pool_env.rules.ThreeCushion`, docs/games.md) on the carom table: one step
    is one shot of the agent (player 0, who plays the first inning with the white unless
    `agent_breaks=False`); the opponent's innings are played inside `step`.

    | argument | default | meaning |
    | --- | --- | --- |
    | `opponent` | `"carom_search"` | a player's name (`pool_env.make_player`), an agent with `act(observation)`,
      a callable, or None: practice, the episode ends when the inning passes |
    | `noise` | None | None, `"olympiad"` or a dict (`pool_env.game.NOISE_PRESETS`), on both players' shots |
    | `points`, `innings_limit`, `equalizing` | 15, None, True | the rules' options (`ThreeCushion`) |
    | `agent_breaks` | True | False: the opponent plays the first inning, inside `reset` |
    | `max_shots` | 200 | truncate after this many agent shots |
    | `elevation` | False | add the cue's elevation as the action's last entry (as the pool envs': masse, jumps) |
    | `table`, `physics` | the carom presets | |
    | `render_mode`, `render_size` | None, (640, 360) | "rgb_array": `render()` is the table now, with the score |

    Action `Box(-1, 1, (4,))` (5 with `elevation`): the "cue_spin" layout (force as a fraction of MAX_FORCE, tip
    side and top as fractions of the miscue limit), striking the agent's own cue ball.
    Observation `Box(-1, 1, (15,))`: `pool_env.game.carom_observation` from the agent's side
    (the balls, whose cue ball, score and innings). Reward: +1 per agent point, -1 per opponent
    point in the step. Info (numeric, the same keys every time): `points` and
    `opponent_points` (this step), `scores` and `innings` (agent, opponent), `opponent_shots`,
    `winner` (-1 none, 0 the agent, 1 the opponent), `draw`, `error` (a shot could not be
    simulated: the episode is truncated), `pocketed` (the pool envs' mask, always all False
    here: generic clients read it from every env). `env.unwrapped.step_records` holds the step's records.
    """

    metadata = {"render_modes": ["rgb_array"], "render_fps": 30}

    def __init__(self, opponent="carom_search", noise=None, points: int | None = 15, innings_limit: int | None = None,
                 equalizing: bool = True, agent_breaks: bool = True, max_shots: int = 200, table=None, physics=None,
                 render_mode=None, elevation: bool = False, render_size=(640, 360), randomize=None):
        if render_mode not in (None, *self.metadata["render_modes"]):
            raise ValueError(f"ThreeCushion-v0's render modes are {self.metadata['render_modes']}, got {render_mode!r}")
        if isinstance(max_shots, bool) or not isinstance(max_shots, int) or max_shots < 1:
            raise ValueError(f"max_shots must be an integer >= 1, got {max_shots!r}")
        self.game = Game("three_cushion", table=table, physics=physics, noise=noise, points=points,
                         innings_limit=innings_limit, equalizing=equalizing,
                         layout="cue_spin" + (ELEVATED if elevation else ""), randomize=randomize)
        self.agent_breaks, self.max_shots, self.render_mode = bool(agent_breaks), max_shots, render_mode
        self.render_size, self.renderer = (int(render_size[0]), int(render_size[1])), None
        self.observation_space = spaces.Box(-1.0, 1.0, (CAROM_OBSERVATION_SIZE,), np.float32)
        self.action_space = spaces.Box(-1.0, 1.0, (self.game.layout.size,), np.float32)
        self.opponent, self._seeded_opponent, self.opponent_name = resolve_opponent(opponent, self)
        self.agent_shots, self.step_records = 0, []

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

    def observe(self, viewer: int = AGENT) -> np.ndarray:
        g = self.game
        return carom_observation(g.balls, g.state, viewer, self.agent_shots, self.max_shots, g.table)

    def render(self):
        """The table now (uint8 (H, W, 3)) with the game's line on it: who is to shoot, the score, the innings."""
        if self.render_mode is None:
            return None
        if self.renderer is None:
            t = self.game.table
            self.renderer = TableRenderer(t.length, t.width, t.pockets, float(np.max(self.game.balls.radii)),
                                           self.render_size, palette="carom")
        balls, state = self.game.balls, self.game.state
        frame = self.renderer.draw(balls.xy, balls.pocketed)
        if state.ended:
            who = "draw" if state.winner is None else ("agent" if state.winner == AGENT else "opponent") + " wins"
        else:
            who = ("agent" if state.shooter == AGENT else "opponent") + " to shoot"
        score = f"score {state.scores[0]}-{state.scores[1]}, innings {state.innings[0]}-{state.innings[1]}"
        return overlay(frame, [f"three-cushion: {who}, {score}"])

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        if options:
            raise ValueError(f"ThreeCushion-v0's reset takes no options, got {sorted(options)}")
        self.game.reset(rng=np.random.default_rng(int(self.np_random.integers(2**63 - 1))),
                        breaker=AGENT if self.agent_breaks else OPPONENT)
        if self._seeded_opponent is not None:
            self._seeded_opponent.reset(int(self.np_random.integers(2**31)))
        self.agent_shots, self.step_records = 0, []
        against, error = self._opponent_turn()
        return self.observe(), {**self._info(0, against, error), **sampled_info(self.game)}

    def step(self, action):
        struck = self.strike(action)
        return self.finish(self.game.resolve(struck, simulate_struck(struck, self.game.table, self.game.physics)))

    def strike(self, action):
        """`step`'s first half: the agent's shot struck (the vector env simulates many at once)."""
        if self.game.over:
            raise RuntimeError("the episode is over: reset() the env")
        if self.game.shooter != AGENT:
            raise RuntimeError("the agent is not to shoot (the practice episode ended): reset() the env")
        return self.game.strike(np.asarray(action, dtype=np.float64))

    def finish(self, record):
        """`step`'s second half, from the agent's shot's record: the opponent's innings, the reward."""
        self.agent_shots += 1
        self.step_records = [record]
        if record.error is not None:
            return self.observe(), 0.0, False, True, self._info(0, 0, True)
        points = int(bool(record.ruling.point))
        against, error = (0, False) if self.opponent is None else self._opponent_turn()
        passed = self.game.shooter != AGENT
        terminated = self.game.over or (self.opponent is None and passed)
        truncated = error or (not terminated and self.agent_shots >= self.max_shots)
        return self.observe(), float(points - against), terminated, truncated, self._info(points, against, error)

    def _opponent_turn(self):
        """The opponent's shots while it is to shoot: (its points, a shot failed)."""
        points = 0
        while self.opponent is not None and not self.game.over and self.game.shooter == OPPONENT:
            record = self.game.play(self.opponent(self.observe(OPPONENT)))
            self.step_records.append(record)
            if record.error is not None:
                return points, True
            points += int(bool(record.ruling.point))
            if len(self.step_records) > 10 * self.max_shots:  # a perfect opponent: stop the episode
                return points, True
        return points, False

    def _info(self, points, against, error) -> dict:
        state = self.game.state
        return {"points": int(points), "opponent_points": int(against), "scores": np.array(state.scores),
                "innings": np.array(state.innings),
                "opponent_shots": sum(r.shooter == OPPONENT for r in self.step_records),
                "winner": WINNERS[state.winner], "draw": bool(state.ended and state.winner is None),
                "error": bool(error), "pocketed": np.zeros(len(self.game.balls), dtype=bool)}
