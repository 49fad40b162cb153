"""`PoolGameEnv`: 9-ball and 8-ball by the WPA rules against an opponent (PoolNineBall-v0, PoolEightBall-v0)."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from .. import rules
from ..game import GAME_BALLS, Game, env_layout, game_observation, game_observation_size
from ..physics import Balls
from ..render.overlay import overlay
from ..render.playback import ShotPlayback, step_shot_frames
from ..render.table import game_palette
from ..render.window import HumanWindow
from .captions import captioned, score_text, shot_caption
from .common import StepsShots, can_render, check_env_options, check_reset_options
from .game_turns import OPPONENT as OPPONENT  # re-exported (OPPONENT, SHAPING_*): they were defined here
from .game_turns import SHAPING_BALL as SHAPING_BALL
from .game_turns import SHAPING_FOUL as SHAPING_FOUL
from .game_turns import GameTurns
from .infos import check_info_mode
from .obs_types import Observer

RESET_OPTIONS = ("balls", "ball_in_hand", "agent_breaks")


class PoolGameEnv(StepsShots, HumanWindow, gym.Env):
    """9-ball or 8-ball by the WPA rules (`pool_env.rules`, docs/rules.md): one step is one shot
    of the agent; the opponent's shots are played inside `step` until the agent is to shoot
    again or the game ends.

    ```python
    import gymnasium as gym
    import pool_env

    env = gym.make("PoolNineBall-v0")                  # the agent breaks; the ghost-ball player replies
    obs, info = env.reset(seed=0)
    obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
    print(info["foul"], info["pocketed"], info["opponent_shots"], info["winner"])  # codes, a mask, counts
    ```

    ## Arguments

    | argument | default | meaning |
    | --- | --- | --- |
    | `game` | `"nine_ball"` | `"nine_ball"` (PoolNineBall-v0: 10 balls), `"eight_ball"` (PoolEightBall-v0: 16) or
      `"ten_ball"` (PoolTenBall-v0: 11; the action as 8-ball's, its entry 7 the called ball among those on the
      table, ascending; observation 48 entries) |
    | `opponent` | `"ghost_ball"` | a player's name (`pool_env.make_player`: `"ghost_ball"`, the rule-aware
      `pool_env.players.GameGhostBallAgent`, `"random"`, `"search"`, a saved model's path), an agent with
      `act(observation)`, a callable `observation -> action`, or None: practice (below). A built-in name's player
      that decides from views (`decide_batch`) reads the game's state instead (`pool_env.game.game_view`, the view
      its observation would decode to) and hands the game its `Shot` (`Game.strike_encoded`): the same shots |
    | `noise` | None | None, `"olympiad"` (`NOISE_PRESETS`) or a dict of standard deviations (`angle` rad,
      `speed` m/s, `side`, `top` in R, `elevation` rad: elevated shots only) on every executed shot, both
      players'; deterministic given the seed |
    | `agent_breaks` | True | the agent breaks every game (False: the opponent does, inside `reset`) |
    | `shaping` | False | add +0.1 per ball the agent pockets legally and -0.1 per agent foul |
    | `max_shots` | 100 | truncate after this many agent shots (a game of misses would never end) |
    | `rule_options` | None | the rule set's options (`NineBall(three_foul_rule=...)`, `EightBall(illegal_break=...)`;
      `{"calling": "eight_only"}`: 8-ball calls the 8's pocket only, and the action loses entry 7) |
    | `table`, `physics`, `render_mode`, `render_size`, `randomize` | as `PoolBreakEnv` | |
    | `info_mode` | `"numeric"` | `"rich"` adds the step's shot records to `info` (below) |
    | `obs_type`, `obs_size`, `grayscale` | as `PoolBreakEnv` | `"state"` (below), `"pixels"`, `"dict"`, `"text"`
      (docs/observations.md); `render_mode="ansi"` renders the text |
    | `overlay` | True | frames carry text: the game, whose shot, ball in hand, the called pocket; at the end
      of each shot the rules' messages (fouls, the winner) |
    | `hotseat` | False | with `opponent=None`: two people at one table, each step the shot of whoever is to
      shoot, the episode going on when the turn passes until the game ends (`python -m pool_env.play
      --two-players`); observations from player 0's side |
    | `elevation` | False | add the cue's elevation to the action (its last entry, below): jump and masse shots |
    | `decisions` | False | decision turns (docs/rules.md): the action gains the decision entry and the
      observation the decision flags (below); the 9-ball push out and its reply, 8-ball's choices after an
      illegal break or the 8 on the break. Without, a decision's default applies (docs/rules.md) |

    ## Action Space

    `Box(-1, 1, (6,), float32)` (9-ball) or `(8,)` (8-ball; `(7,)` with `calling="eight_only"`):

    | index | meaning |
    | --- | --- |
    | 0-1 | the cue force vector, mapped as `PoolBreakEnv` maps it (at most 12 m/s) |
    | 2-3 | the tip offset (side, top), mapped as `PoolBreakEnv(spin=True)` (within the miscue limit, 0.5 R) |
    | 4-5 | with ball in hand, where to place the cue ball: (x, y) mapped linearly onto the area it may go
      (`placement_area`: the cloth, or behind the head string, x at most L/4 - 0.1 mm); ignored otherwise. A spot on
      a ball or outside the area moves to the nearest free one (`place_cue_ball`) |
    | 6 | 8-ball: the called pocket (WPA 1.6: every shot but the break calls a ball and a pocket): [-1, 1]
      cut into six equal bins, pocket k (`Table.pockets` order) in bin k; with `calling="eight_only"` read
      only when the agent shoots at the 8 |
    | 7 | 8-ball: the called ball, [-1, 1] cut into as many equal bins as there are legal targets
      (`Game.called_targets`, ascending), the k-th in bin k; only the called ball in the called pocket keeps
      the table (and on an open table decides the groups); not there with `calling="eight_only"` |
    | 6 (9-ball), 8 (8-ball) | with `decisions=True`: the decision entry. On a shot that may be a push out
      (the shot right after a legal 9-ball break, WPA 2.4), > 0 declares one; when the agent has a decision
      to make (the observation's flags), the step is that decision: the entry cuts [-1, 1] into as many
      equal bins as the decision has options (`rules.DECISIONS` order: after a push out "shoot", "pass";
      after an illegal 8-ball break "ball_in_hand", "accept_table", "rerack_and_break",
      "rerack_opponent_breaks"; after the 8 on the break "spot_eight", "rebreak"), option k in bin k, and the
      other entries are ignored (`Game.encode_decision` / `decode_decision`). The built-in opponents decide
      by their `choose` |
    | last | with `elevation=True` (7 entries in 9-ball, 9 in 8-ball; one more with `decisions`): the cue's
      elevation, 85 deg * a for a > 0, a level cue for a <= 0 (`PoolBreakEnv`'s); a jump over a blocking
      ball is legal (the WPA's jump shot: made by elevating the cue), a ball driven off the table a foul
      (WPA 6.5, 6.1 for the cue ball). The built-in opponents cue level |

    ## Observation Space

    `Box(-1, 1, (44,), float32)` (9-ball) or `(71,)` (8-ball), from the shooter's point of view:

    | entries | meaning |
    | --- | --- |
    | 3 per ball (ball k at 3k) | x, y scaled to [-1, 1] over the table (clipped: a ball hanging in a
      mouth), on-table flag (+1; a pocketed ball is (0, 0, -1)) |
    | one per object ball | +1 if it is a legal first contact now (`rules.legal_targets`), else -1 |
    | 2 | ball in hand for the shooter: anywhere, behind the head string (+1 / -1 each) |
    | 2 | the shooter's consecutive fouls, then the opponent's: 0, 1, 2 as -1, 0, 1 |
    | 3 (8-ball) | the shooter's group: open, solids, stripes (one +1) |
    | 5 (`decisions=True`: 49 in 9-ball, 76 in 8-ball) | +1 for the decision the viewer is to make now, one
      per `rules.DECISIONS` (push-out reply, illegal break, the 8 on the break, 10-ball's reply to a ball
      pocketed not as called), then +1 if he may push out |
    | 1 | the agent's shots this episode, 2 shots / max_shots - 1 |

    ## Rewards

    +1 when the agent wins, -1 when it loses (on the step that ends the game), 0 otherwise;
    `shaping=True` adds the terms above. Practice (`opponent=None`): +1 per ball the agent
    pockets legally and +1 more for winning the rack; the episode ends as soon as the turn
    would pass (a miss or a foul), or the game ends.

    ## Episode End

    Terminated when the game ends (or, in practice, when the turn passes); truncated after
    `max_shots` agent shots, when the opponent takes `max_shots` shots in a row, or when a shot
    cannot be simulated (`info["error"]`); `info["truncation"]` says which. The shot limit
    stands in for the WPA's stalemate (1.12), which is not declared (docs/rules.md).

    ## Starting State

    `reset` racks (9-ball diamond, 8-ball triangle, WPA racking with seeded randomness) and the
    agent breaks with the cue ball in hand behind the head string (the placement entries place
    it), unless `agent_breaks=False`: then the opponent breaks inside `reset` and plays its
    turn. A game the opponent wins in that turn (a break and run) is not racked again: `reset`
    reports it in its info (`winner` "opponent", `end_reason`) and the next step ends the
    episode as a loss (reward -1, `terminated`) without playing its action.
    `reset(options={"balls": balls})` starts from a given layout (16 or 10 balls by number, at
    rest, the cue ball on the table, pocketed balls allowed; bad layouts raise ValueError): the
    agent to shoot on an open table, with ball in hand anywhere if
    `options={"ball_in_hand": True}`. `options={"agent_breaks": False}` lets the opponent break
    this game (or, with a layout, shoot first).

    ## Info

    `reset` and every `step` return an `info` with the same keys, each a number, a bool or a
    fixed-shape array (docs/env.md lists them with dtypes and code tables): the agent's shot's
    `foul` (a code: 0 none, else `pool_env.rules.codes.FOUL_CODES`), `pocketed` (bool array
    of the game's balls, (10,) or (16,): ball k dropped into a pocket), `ball_in_hand` (the
    next shooter's, a code of `BALL_IN_HAND_CODES`), `turn_passed`; `opponent_shots` (how many
    shots the opponent played in the step, or in `reset` when it broke), `winner` (-1 while
    the game goes on, 0 the agent, 1 the opponent), `end_reason` (0, or a code of
    `END_REASON_CODES` once the game is over), `error` (a shot could not be simulated),
    `truncation` (0, or a code of `TRUNCATION_CODES` on the step that truncates), and the
    agent's shot's `first_contact`, `cushion_hits`, `scratch`, `events`, `shot_duration`,
    `balls_left` as `PoolBreakEnv` reports them. A step without an agent shot (the game ended
    in `reset`) and `reset` itself report no shot: nothing pocketed, no foul.
    `pool_env.rules.codes.decode_info(info)` turns the codes into names. The rules' messages
    and every shot's details are in `env.unwrapped.step_records`; with `info_mode="rich"` the
    info also holds them (`records`) and `error_message` (why a shot failed, or None).

    The game is `env.unwrapped.game` (a `pool_env.game.Game`: its state, snapshots, `evaluate`;
    the agent is player 0), with `state` (`rules.GameState`) and `balls` also on the env;
    `env.unwrapped.step_records` holds the `ShotRecord`s of the last step (the agent's shot,
    then the opponent's). Rendering as `PoolBreakEnv`: "rgb_array" the table now,
    "rgb_array_list" (and `shot_frames(fps)`) every shot of the last step, both players';
    "human" a pygame window (`pip install 'pool-env[play]'`) animating every shot of each step
    (and of `reset`, when the opponent breaks) at `metadata["render_fps"]`, `render()` showing
    the table now, `close()` closing it (no display: set `SDL_VIDEODRIVER=dummy`).
    `python -m pool_env.play --game nine_ball --opponent ghost_ball` plays a game with the mouse.
    """

    metadata = {"render_modes": ["human", "rgb_array", "rgb_array_list", "ansi"], "render_fps": 30}

    def __init__(self, game="nine_ball", opponent="ghost_ball", render_mode=None, table=None, physics=None,
                 noise=None, agent_breaks=True, shaping=False, max_shots=100, rule_options=None,
                 render_size=(640, 360), overlay=True, hotseat=False, info_mode="numeric", elevation=False,
                 decisions=False, obs_type="state", obs_size=(84, 84), grayscale=False, randomize=None):
        self.info_mode = check_info_mode(info_mode)
        if game not in GAME_BALLS:
            raise ValueError(f"unknown game {game!r}; choose one of {', '.join(GAME_BALLS)}")
        self.render_mode = render_mode
        self.max_shots = check_env_options(render_mode, self.metadata["render_modes"], max_shots)
        self.rule_options = dict(rule_options or {})
        self.elevation, self.decisions = bool(elevation), bool(decisions)
        layout = env_layout(game, self.elevation, self.decisions, self.rule_options.get("calling"))
        self.game = Game(game, table, physics, noise, layout=layout, randomize=randomize, **self.rule_options)
        self.table, self.physics, self.noise = self.game.table, self.game.physics, self.game.noise
        self.agent_breaks, self.shaping, self.hotseat = bool(agent_breaks), bool(shaping), bool(hotseat)
        self.n_balls = self.game.n_balls
        self.action_space = spaces.Box(-1.0, 1.0, (self.game.layout.size,), np.float32)
        self.observation_space = spaces.Box(-1.0, 1.0, (game_observation_size(game, self.decisions),), np.float32)
        self.observer = Observer(self, obs_type, type(self).observation, obs_size, grayscale, self.decisions)
        self.observation_space, self.obs_type = self.observer.space, obs_type
        self.text_observer = Observer(self, "text", None)  # render_mode="ansi"
        self.opponent = opponent
        self._turns = GameTurns(self, opponent)  # the play: the agent's shot, the opponent's turn, reward and info
        if self._turns.practice and not self.agent_breaks:
            raise ValueError("practice (opponent=None) has no one to break: keep agent_breaks=True")
        if self.hotseat and not self._turns.practice:
            raise ValueError("hotseat is two people at one table: it takes opponent=None")
        self.render_size = (int(render_size[0]), int(render_size[1]))
        self.overlay = bool(overlay)
        self.playback = ShotPlayback(self.table, self.render_size, self.metadata["render_fps"],
                                     deferred=render_mode is not None, palette=game_palette(self.game.mode))
        self._started, self._quaternions = False, None
        self._window = None  # render_mode="human": a pool_env.render.window.Window
        self.batch_opponent = False  # True: step_shots yields an OpponentDecision for the opponent's shots
        self._window_title = f"pool_env: {game}"

    # --- Gymnasium API ----------------------------------------------------------------------
    def reset(self, *, seed=None, options=None):
        info = self.begin(seed=seed, options=options)
        if self.render_mode == "human":
            self._show(self.shot_frames())
        return self.observer.observe(self), info

    def begin(self, seed=None, options=None) -> dict:
        """`reset` without building the observation (a vector env builds all of its sub-envs'
        at once) and without showing a window; returns reset's info."""
        options = check_reset_options(options, RESET_OPTIONS)
        super().reset(seed=seed)
        given = options.get("balls")
        agent_breaks = bool(options.get("agent_breaks", self.agent_breaks))
        if not agent_breaks and self._turns.practice:
            raise ValueError("practice (opponent=None) has no one to break: reset with agent_breaks True")
        try:
            self.game.reset(rng=self.np_random, balls=given, breaker=0 if agent_breaks else 1,
                            ball_in_hand=bool(options.get("ball_in_hand", False)))
        except ValueError as exc:
            raise ValueError(f"options['balls']: {exc}") from None
        self.table, self.physics = self.game.table, self.game.physics  # drawn afresh with randomize
        self._quaternions = self.np_random.normal(size=(self.n_balls, 4))
        self._turns.reseed(int(self.np_random.integers(2**63 - 1)))
        self._started = True
        self.playback.reset(self.game.balls, self._quaternions)
        return self._turns.begin()  # the opponent's break and turn, if it breaks

    def render(self):
        if not can_render(self.render_mode, self._started):
            return None
        if self.render_mode == "human":
            return self._show([self._annotate(self.playback.frame())])
        if self.render_mode == "ansi":
            return self.text_observer.observe(self)
        return self._annotate(self.playback.frame()) if self.render_mode == "rgb_array" else self.shot_frames()

    def shot_frames(self, fps=None) -> list[np.ndarray]:
        """Every shot of the last step (the agent's, then the opponent's) sampled at `fps`; after
        `reset` the starting frame (and the opponent's shots, when it broke)."""
        if not self._started:
            raise RuntimeError("call reset() before shot_frames()")
        records = [record for record in self._turns.records if record.error is None]
        if not records:
            return [self._annotate(frame) for frame in self.playback.shot_frames(fps)]
        shots = step_shot_frames(self.playback, self._turns.start, self._quaternions, [r.result for r in records], fps)
        captions = [(shot_caption(self.game, record, who), list(record.ruling.messages))
                    for record, who in self._turns.captions]
        return captioned(shots, captions, self.overlay)

    def _annotate(self, frame):
        """The table now with the game's state on it (when `overlay`)."""
        if not self.overlay:
            return frame
        game = self.game
        if game.winner is not None:
            winner = "agent" if game.winner == 0 else "opponent"
            return overlay(frame, [f"{game.label}: {winner} wins{score_text(game.state)}"])
        who = "agent" if game.shooter == 0 else "opponent"
        hand = f", ball in hand ({game.ball_in_hand.replace('_', ' ')})" if game.ball_in_hand else ""
        return overlay(frame, [f"{game.label}: {who} to shoot{hand}{score_text(game.state)}"])

    # --- state --------------------------------------------------------------------------------
    @property
    def balls(self) -> Balls | None:
        """The balls now (at rest), by number; None before the first reset."""
        return self.game.balls if self._started else None

    @property
    def state(self) -> rules.GameState | None:
        """The rules' state (the agent is player 0); None before the first reset."""
        return self.game.state if self._started else None

    @property
    def shots(self) -> int:
        """The agent's shots this episode."""
        return self._turns.shots

    @property
    def reset_records(self) -> tuple:
        """The `ShotRecord`s of the opponent's turn inside the last `reset` (when it broke)."""
        return self._turns.reset_records

    @property
    def step_records(self) -> tuple:
        """The `pool_env.game.ShotRecord`s of the last step (the agent's shot, then the
        opponent's; a shot that could not be simulated too, with its `error`); () after a reset."""
        return tuple(self._turns.records)

    def observation(self, viewer: int = 0) -> np.ndarray:
        """The state observation now from player `viewer`'s side (0: the agent's), whatever `obs_type` is:
        a callable opponent is given its side's."""
        return game_observation(self.game.balls, self.game.state, viewer, self._turns.shots, self.max_shots,
                                self.table, self.decisions)

    # --- a step, as a generator of shots (vector envs simulate many envs' shots at once) --------
    def step_shots(self, action, observe=True):
        """`step` as a generator: it yields each `pool_env.game.StruckShot` of the step (the
        agent's, then the opponent's), is sent its outcome (the `Result`, or the SimulationError
        or ValueError it raised), and returns the step's (observation, reward, terminated,
        truncated, info); the observation is None with `observe=False`. `action` may also be a
        `pool_env.game.Shot`. With `batch_opponent` set, a built-in opponent's shot is asked of
        the driver: the generator yields an `OpponentDecision` and is sent the Shot."""
        if not self._started:
            raise RuntimeError("call reset() before step()")
        return (yield from self._turns.step(action, observe))
