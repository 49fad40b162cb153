"""`PoolGameEnv`: 9-ball and 8-ball by the WPA rules against an opponent (PoolNineBall-v0, PoolEightBall-v0)."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
from gymnasium import logger, spaces

from .. import rules
from ..game import GAME_BALLS, Game, Shot, env_layout, game_observation, game_observation_size, game_view
from ..physics import Balls
from ..render.overlay import overlay
from ..render.playback import ShotPlayback, step_shot_frames
from ..render.table import game_palette
from ..render.window import HumanWindow
from ..rules import codes
from .captions import captioned, score_text, shot_caption
from .common import StepsShots, can_render, check_env_options, check_reset_options, run_step
from .infos import check_info_mode, no_shot_info, record_info, rich_info, sampled_info, score_info, winner_code
from .obs_types import Observer
from .opponents import OpponentDecision, resolve_opponent

SHAPING_BALL, SHAPING_FOUL = 0.1, 0.1  # shaping: + per ball the agent pockets legally, - per foul
RESET_OPTIONS = ("balls", "ball_in_hand", "agent_breaks")
OPPONENT = 1  # the opponent is player 1 of the game, the agent player 0


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
        self._opponent, self._opponent_player, self._opponent_name = resolve_opponent(opponent, self)
        if self._opponent is None and not self.agent_breaks:
            raise ValueError("practice (opponent=None) has no one to break: keep agent_breaks=True")
        if self.hotseat and self._opponent is not None:
            raise ValueError("hotseat is two people at one table: it takes opponent=None")
        self.render_size = (int(render_size[0]), int(render_size[1]))
        self.overlay = bool(overlay)
        self.playback = ShotPlayback(self.table, self.render_size, self.metadata["render_fps"],
                                     deferred=render_mode is not None, palette=game_palette(self.game.mode))
        self._started, self._done, self._shots, self._end_reason = False, True, 0, None
        self._quaternions, self._reset_records, self._reset_error = None, (), None
        self._window = None  # render_mode="human": a pool_env.render.window.Window
        self.batch_opponent = False  # True: step_shots yields an OpponentDecision for the opponent's shots
        self._window_title = f"pool_env: {game}"
        self._begin_step()

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
        if not agent_breaks and self._opponent is None:
            raise ValueError("practice (opponent=None) has no one to break: reset with agent_breaks True")
        try:
            self.game.reset(rng=self.np_random, balls=given, breaker=0 if agent_breaks else 1,
                            ball_in_hand=bool(options.get("ball_in_hand", False)))
        except ValueError as exc:
            raise ValueError(f"options['balls']: {exc}") from None
        self.table, self.physics = self.game.table, self.game.physics  # drawn afresh with randomize
        self._quaternions = self.np_random.normal(size=(self.n_balls, 4))
        opponent_seed = int(self.np_random.integers(2**63 - 1))
        if self._opponent_player is not None and hasattr(self._opponent_player, "reset"):
            self._opponent_player.reset(seed=opponent_seed)  # a built-in opponent plays the same for the same seed
        self._started, self._shots, self._done, self._end_reason = True, 0, False, None
        self.playback.reset(self.game.balls, self._quaternions)
        self._begin_step()
        run_step(self._reset_turn(), self.table, self.physics)  # the opponent's break and turn, if it breaks
        self._reset_records, self._reset_error = tuple(self._step_records), self._error
        self._reset_truncation, self._truncation = self._truncation, None  # the next step ends the episode
        self._step_records = []
        info = {**no_shot_info(self.game.balls, self.game.ball_in_hand, self._error), **sampled_info(self.game)}
        return self._info(info, self._reset_records)

    def _reset_turn(self):
        yield from self._opponent_turn()
        return None

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
        records = [record for record in self._step_records if record.error is None]
        if not records:
            return [self._annotate(frame) for frame in self.playback.shot_frames(fps)]
        shots = step_shot_frames(self.playback, self._step_start, self._quaternions, [r.result for r in records], fps)
        captions = [(shot_caption(self.game, record, who), list(record.ruling.messages))
                    for record, who in self._captions]
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
        return self._shots

    @property
    def reset_records(self) -> tuple:
        """The `ShotRecord`s of the opponent's turn inside the last `reset` (when it broke)."""
        return self._reset_records

    @property
    def step_records(self) -> tuple:
        """The `pool_env.game.ShotRecord`s of the last step (the agent's shot, then the
        opponent's; a shot that could not be simulated too, with its `error`); () after a reset."""
        return tuple(self._step_records)

    def observation(self, viewer: int = 0) -> np.ndarray:
        """The state observation now from player `viewer`'s side (0: the agent's), whatever `obs_type` is:
        a callable opponent is given its side's."""
        return game_observation(self.game.balls, self.game.state, viewer, self._shots, self.max_shots, self.table,
                                self.decisions)

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
        if self._done:
            raise RuntimeError("the game is over; call reset()")
        ended_at_reset, self._reset_error = self._reset_error, None
        self._begin_step()
        if self.game.over or ended_at_reset is not None:  # the opponent's turn at reset ended the game
            if not isinstance(action, Shot):
                self.game.decode(action)  # a bad action still raises
            self._error, self._truncation = ended_at_reset, self._reset_truncation
            return self._finish(observe)
        if self.game.pending is not None:  # the agent's decision (the decision entry picks it)
            self.game.decide(self.game.decode_decision(action))
            yield from self._opponent_turn()  # after a pass back, the opponent shoots
            return self._finish(observe)
        struck = self.game.strike(action)
        self._note(self.game.resolve(struck, (yield struck)), mine=True)
        yield from self._opponent_turn()
        return self._finish(observe)

    def _opponent_turn(self):
        """The opponent's shots while it is to shoot (a generator of StruckShots, as step_shots)."""
        game = self.game
        while self._error is None and not game.over and game.shooter == OPPONENT and self._opponent is not None:
            if self._opponent_shots >= self.max_shots:
                self._error = f"the opponent took {self.max_shots} shots in a row"
                self._truncation = "opponent_shot_limit"
                return
            player = self._opponent_player
            if game.pending is not None:  # a built-in player's choice (`choose`), else the default
                game.decide(player.choose(game) if hasattr(player, "choose") else game.pending.default)
                continue
            direct = player is not None and hasattr(player, "decide_batch")  # it reads the game, not an observation
            if direct:
                view = game_view(game.balls, game.state, OPPONENT, self._shots, self.max_shots, self.table)
                action = (yield OpponentDecision(player, view)) if self.batch_opponent else player.decide(view)
            else:
                action = self._opponent_action()
            try:  # a Shot plays as the action it would have encoded
                struck = game.strike_encoded(action) if direct else game.strike(action)
            except ValueError as exc:
                raise ValueError(f"the opponent ({self._opponent_name}) played a bad action: {exc}") from None
            self._note(game.resolve(struck, (yield struck)), mine=False)

    def _opponent_action(self):
        """The opponent's action for its observation (the built-in players cue level: with
        `elevation`, their action gets a level cue's entry)."""
        action = self._opponent(self.observation(OPPONENT))
        if self.elevation and np.shape(action) == (self.game.layout.size - 1,):
            action = np.append(action, np.float32(0.0))
        return action

    def _begin_step(self):
        self._captions, self._step_records = [], []
        self._step_start = self.game.balls if self._started else None
        self._reward, self._error, self._agent_info, self._opponent_shots = 0.0, None, None, 0
        self._truncation = None

    def _note(self, record, mine: bool):
        """A shot just played (`mine`: the stepping player's): the playback follows it, its
        caption, reward and info are noted."""
        if record.ball_in_hand is not None:
            self.playback.place(record.balls_before)
        self._step_records.append(record)
        if record.error is not None:
            self._error = record.error
            logger.warn(f"PoolGameEnv: a shot could not be simulated and the episode is truncated ({self._error})")
            return
        self.playback.shot(record.result)
        self.playback.place(record.balls_after)
        who = f"player {record.shooter + 1}" if self.hotseat else ("agent" if mine else "opponent")
        self._captions.append((record, who))  # captioned when frames are asked for
        self._end_reason = record.ruling.end_reason
        if mine:
            self._shots += 1
            self._agent_info = record_info(record)
            self._reward += self._shot_reward(record)
        else:
            self._opponent_shots += 1

    def _shot_reward(self, record) -> float:
        ruling = record.ruling
        legal = len(record.pocketed) if ruling.foul is None else 0
        if self._opponent is None:  # practice: a ball a point, a run-out one more
            return float(legal) + (1.0 if ruling.winner == record.shooter else 0.0)
        if not self.shaping:
            return 0.0
        return SHAPING_BALL * legal - (SHAPING_FOUL if ruling.foul is not None else 0.0)

    def _finish(self, observe=True):
        """The step's (observation, reward, terminated, truncated, info), every shot applied."""
        game, practice = self.game, self._opponent is None
        terminated = game.over or (practice and not self.hotseat and game.shooter != 0)
        truncated = not terminated and (self._error is not None or self._shots >= self.max_shots)
        if truncated and self._truncation is None:
            self._truncation = "shot_error" if self._error is not None else "shot_limit"
        reward = self._reward
        if not practice and game.winner is not None:
            reward += 1.0 if game.winner == 0 else -1.0
        self._done = terminated or truncated
        info = self._agent_info or no_shot_info(game.balls, game.ball_in_hand, self._error)
        return self.observer.observe(self) if observe else None, float(reward), bool(terminated), bool(truncated), \
            self._info(info, self._step_records)

    def _info(self, shot: dict, records) -> dict:
        """The info of a step or a reset: the agent's shot's entries (`shot`), then the
        opponent's shots, the winner, the end reason, the error and why the episode was
        truncated (`codes.TRUNCATIONS`; 0 if it was not); the records if rich."""
        game = self.game
        info = {**shot, "opponent_shots": self._opponent_shots, "winner": winner_code(game.winner),
                "end_reason": codes.encode("end_reason", self._end_reason if game.winner is not None else None),
                "error": self._error is not None, "truncation": codes.encode("truncation", self._truncation),
                **score_info(game.state)}
        return rich_info(info, records, self._error) if self.info_mode == "rich" else info
