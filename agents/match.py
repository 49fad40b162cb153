"""Head-to-head games of two players: who breaks on which seed, a game played in an env or on a `Game`, its points."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from pool_env.game import Game, game_observation

MAX_SHOTS = 100  # each player's shots in a game on a `Game`, as the game envs' max_shots


class Step(NamedTuple):
    """One env step's outcome (the last of an episode: how it ended)."""

    reward: float
    terminated: bool
    truncated: bool
    info: dict


def player_seed(seed: int, slot: int) -> int:
    """The seed a player's randomness gets for the game on `seed` (slot 0: the breaker, 1: the
    other): its own, whatever process plays the game."""
    return int(np.random.SeedSequence([int(seed), slot]).generate_state(1)[0])


def alternate(seeds, a, b, first: int = 0) -> list[tuple]:
    """(seed, breaker, other) of each game on `seeds`: `a` breaks game k when first + k is even.
    `first` numbers the first game in a longer match (one split over processes)."""
    return [(seed, a, b) if (first + k) % 2 == 0 else (seed, b, a) for k, seed in enumerate(seeds)]


def run_episode(env, act, seed, on_step=None, skip_finished: bool = False) -> Step:
    """One episode of `env` from `reset(seed=seed)`: `act(observation)` plays the env's agent
    (the env plays its opponent) until the episode ends, `on_step(step)` after each `Step`.
    Returns the last Step. With `skip_finished`, a game the env's opponent already won in
    `reset` (it broke and ran out) takes no step (the reset's info, reward 0, is returned); else
    it is stepped once, as gymnasium's protocol has it: the env ends it without playing the
    action `act` was asked for."""
    obs, info = env.reset(seed=seed)
    last = Step(0.0, False, False, info)
    if skip_finished and info.get("winner", -1) >= 0:
        return last
    while not (last.terminated or last.truncated):
        obs, reward, terminated, truncated, info = env.step(act(obs))
        last = Step(reward, terminated, truncated, info)
        if on_step is not None:
            on_step(last)
    return last


def env_winner(info: dict, breaker, other):
    """The winner of a game in an env whose agent (player 0) broke: `breaker`, `other`, or None."""
    return {0: breaker, 1: other}.get(info.get("winner"))


def observe(game: Game, counts) -> np.ndarray:
    """The shooter's observation, as the game envs give it."""
    return game_observation(game.balls, game.state, game.shooter, counts[game.shooter], MAX_SHOTS, game.table)


def play_game(game: Game, players, seed: int, breaker: int, on_decision=None) -> int | None:
    """One game on `game` (reset with `seed`, `breaker` breaking) between two players with `act`;
    `on_decision(observation, shooter)` may return an action to play instead. The winner (0, 1) or
    None: a shot the simulator could not finish, or MAX_SHOTS shots of one player."""
    game.reset(seed=seed, breaker=breaker)
    counts = [0, 0]
    while not game.over and max(counts) < MAX_SHOTS:
        obs = observe(game, counts)
        who = game.shooter
        action = on_decision(obs, who) if on_decision is not None else None
        record = game.play(players[who].act(obs) if action is None else action)
        counts[who] += 1
        if record.error is not None:
            return None
    return game.winner


def points(winner, seat) -> float:
    """A game's points for the player in `seat` (or of that name): 1 a win, 0 a loss, 1/2 no winner."""
    return 0.5 if winner is None else float(winner == seat)
