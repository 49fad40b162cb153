"""`GameTurns`: a game env's play on its `Game`: the agent's shot, the opponent's turn, a step's reward and info."""

from __future__ import annotations

import numpy as np
from gymnasium import logger

from ..game import Shot, game_view
from ..rules import codes
from .common import run_step
from .infos import no_shot_info, record_info, rich_info, sampled_info, score_info, winner_code
from .opponents import OpponentDecision, resolve_opponent

SHAPING_BALL, SHAPING_FOUL = 0.1, 0.1  # shaping: + per ball the agent pockets legally, - per foul
OPPONENT = 1  # the opponent is player 1 of the game, the agent player 0


class GameTurns:
    """The play of a `PoolGameEnv`, `env`, on its `game`: a step as a generator of shots
    (`step`: the agent's shot, then the opponent's turn), an episode's start (`begin`: the
    opponent's break and turn when it breaks), and what they played: the last step's `records`
    (`ShotRecord`s), `captions` ((record, who) of each shot played), `start` (the balls before
    it), the agent's `shots` this episode, `reset_records` (the opponent's turn at the reset).
    The opponent is `opponent` resolved (`act`, `player`, `name`: `resolve_opponent`). The
    env's options (`max_shots`, `shaping`, `hotseat`, `elevation`, `info_mode`,
    `batch_opponent`) and its `playback`, `observer` and `observation` are read as needed."""

    def __init__(self, env, opponent):
        self.env = env
        self.act, self.player, self.name = resolve_opponent(opponent, env)
        self.shots, self.done, self.end_reason = 0, True, None
        self.reset_records, self.reset_error, self.reset_truncation = (), None, None
        self.begin_step(None)

    @property
    def practice(self) -> bool:
        """No opponent (`opponent=None`): the agent plays alone."""
        return self.act is None

    def reseed(self, seed: int) -> None:
        """A built-in opponent's player reseeded at a reset: it plays the same for the same seed."""
        if self.player is not None and hasattr(self.player, "reset"):
            self.player.reset(seed=seed)

    def begin(self) -> dict:
        """A new episode, the env's game just reset: the opponent's break and turn, if it breaks
        (the next step then ends the episode if they ended the game); returns reset's info."""
        env, game = self.env, self.env.game
        self.shots, self.done, self.end_reason = 0, False, None
        self.begin_step(game.balls)
        run_step(self.opponent_turn(), env.table, env.physics)
        self.reset_records, self.reset_error = tuple(self.records), self.error
        self.reset_truncation, self.truncation = self.truncation, None  # the next step ends the episode
        self.records = []
        info = {**no_shot_info(game.balls, game.ball_in_hand, self.error), **sampled_info(game)}
        return self.info(info, self.reset_records)

    def begin_step(self, start) -> None:
        """Nothing played yet in this step, from the balls `start` (None before the first reset)."""
        self.captions, self.records, self.start = [], [], start
        self.reward, self.error, self.agent_info, self.opponent_shots = 0.0, None, None, 0
        self.truncation = None

    def step(self, action, observe=True):
        """`PoolGameEnv.step_shots` once the env has been reset: see there."""
        if self.done:
            raise RuntimeError("the game is over; call reset()")
        game = self.env.game
        ended_at_reset, self.reset_error = self.reset_error, None
        self.begin_step(game.balls)
        if game.over or ended_at_reset is not None:  # the opponent's turn at reset ended the game
            if not isinstance(action, Shot):
                game.decode(action)  # a bad action still raises
            self.error, self.truncation = ended_at_reset, self.reset_truncation
            return self.finish(observe)
        if game.pending is not None:  # the agent's decision (the decision entry picks it)
            game.decide(game.decode_decision(action))
            yield from self.opponent_turn()  # after a pass back, the opponent shoots
            return self.finish(observe)
        struck = game.strike(action)
        self.note(game.resolve(struck, (yield struck)), mine=True)
        yield from self.opponent_turn()
        return self.finish(observe)

    def opponent_turn(self):
        """The opponent's shots while it is to shoot (a generator of StruckShots, as `step`)."""
        env, game = self.env, self.env.game
        while self.error is None and not game.over and game.shooter == OPPONENT and self.act is not None:
            if self.opponent_shots >= env.max_shots:
                self.error = f"the opponent took {env.max_shots} shots in a row"
                self.truncation = "opponent_shot_limit"
                return
            player = self.player
            if game.pending is not None:  # a built-in player's choice (`choose`), else the default
                game.decide(player.choose(game) if hasattr(player, "choose") else game.pending.default)
                continue
            direct = player is not None and hasattr(player, "decide_batch")  # it reads the game, not an observation
            if direct:
                view = game_view(game.balls, game.state, OPPONENT, self.shots, env.max_shots, env.table)
                action = (yield OpponentDecision(player, view)) if env.batch_opponent else player.decide(view)
            else:
                action = self.opponent_action()
            try:  # a Shot plays as the action it would have encoded
                struck = game.strike_encoded(action) if direct else game.strike(action)
            except ValueError as exc:
                raise ValueError(f"the opponent ({self.name}) played a bad action: {exc}") from None
            self.note(game.resolve(struck, (yield struck)), mine=False)

    def opponent_action(self):
        """The opponent's action for its observation (the built-in players cue level: with
        `elevation`, their action gets a level cue's entry)."""
        env = self.env
        action = self.act(env.observation(OPPONENT))
        if env.elevation and np.shape(action) == (env.game.layout.size - 1,):
            action = np.append(action, np.float32(0.0))
        return action

    def note(self, record, mine: bool) -> None:
        """A shot just played (`mine`: the stepping player's): the playback follows it, its
        caption, reward and info are noted."""
        env = self.env
        if record.ball_in_hand is not None:
            env.playback.place(record.balls_before)
        self.records.append(record)
        if record.error is not None:
            self.error = record.error
            logger.warn(f"PoolGameEnv: a shot could not be simulated and the episode is truncated ({self.error})")
            return
        env.playback.shot(record.result)
        env.playback.place(record.balls_after)
        who = f"player {record.shooter + 1}" if env.hotseat else ("agent" if mine else "opponent")
        self.captions.append((record, who))  # captioned when frames are asked for
        self.end_reason = record.ruling.end_reason
        if mine:
            self.shots += 1
            self.agent_info = record_info(record)
            self.reward += self.shot_reward(record)
        else:
            self.opponent_shots += 1

    def shot_reward(self, record) -> float:
        """The reward of a shot of the stepping player's: practice's or `shaping`'s, else 0."""
        ruling = record.ruling
        legal = len(record.pocketed) if ruling.foul is None else 0
        if self.practice:  # practice: a ball a point, a run-out one more
            return float(legal) + (1.0 if ruling.winner == record.shooter else 0.0)
        if not self.env.shaping:
            return 0.0
        return SHAPING_BALL * legal - (SHAPING_FOUL if ruling.foul is not None else 0.0)

    def finish(self, observe=True):
        """The step's (observation, reward, terminated, truncated, info), every shot applied."""
        env, game, practice = self.env, self.env.game, self.practice
        terminated = game.over or (practice and not env.hotseat and game.shooter != 0)
        truncated = not terminated and (self.error is not None or self.shots >= env.max_shots)
        if truncated and self.truncation is None:
            self.truncation = "shot_error" if self.error is not None else "shot_limit"
        reward = self.reward
        if not practice and game.winner is not None:
            reward += 1.0 if game.winner == 0 else -1.0
        self.done = terminated or truncated
        info = self.agent_info or no_shot_info(game.balls, game.ball_in_hand, self.error)
        return env.observer.observe(env) if observe else None, float(reward), bool(terminated), bool(truncated), \
            self.info(info, self.records)

    def info(self, shot: dict, records) -> dict:
        """The info of a step or a reset: the agent's shot's entries (`shot`), then the
        opponent's shots, the winner, the end reason, the error and why the episode was
        truncated (`codes.TRUNCATIONS`; 0 if it was not); the records if rich."""
        game = self.env.game
        info = {**shot, "opponent_shots": self.opponent_shots, "winner": winner_code(game.winner),
                "end_reason": codes.encode("end_reason", self.end_reason if game.winner is not None else None),
                "error": self.error is not None, "truncation": codes.encode("truncation", self.truncation),
                **score_info(game.state)}
        return rich_info(info, records, self.error) if self.env.info_mode == "rich" else info
