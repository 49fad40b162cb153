"""The pot net's game data: the learned player's menu pots in ghost-ball games' positions, each simulated alone."""

from __future__ import annotations

import dataclasses

import numpy as np

from pool_env.game import Game
from pool_env.players import GameGhostBallAgent

from .learned import EXPLORE, shot_menu
from .learned_pots import BALL, POT_INPUTS, parallel_chunks, pot_examples
from .match import play_game
from .search import SearchAgent
from .search_position import decode, game_state

GAME_SEEDS = 500_000  # game k is seeded GAME_SEEDS + seed + k: apart from the labelled games (0 on),
# the published evaluation (1,000,000 on) and the tuning games (2,000,000 on)
GAME_CHUNK = 10  # games a worker is handed at a time (`parallel_game_pot_data`)


def menu_pots(d, cands, rows) -> tuple:
    """(positions (P, 2, 2), rows (M, 6), candidates (M,)) as `learned_pots.planned_pots` gives
    them, of every pot of a decision's menu (`learned.shot_menu`'s candidates and planner rows,
    ball-in-hand spots included): the cue ball where it lies or on the pot's spot, the pot's
    ball at its place as BALL."""
    pots = [(c, r) for c, r in zip(cands, rows, strict=True) if r is not None]
    if not pots:
        return np.zeros((0, 2, 2)), np.zeros((0, 6)), []
    pairs = np.array([[*(d.xy[0] if c.spot is None else c.spot), *d.xy[r[0]]] for c, r in pots])
    positions, which = np.unique(pairs, axis=0, return_inverse=True)
    which = which.reshape(-1)
    order = np.argsort(which, kind="stable")  # grouped by position, as `two_ball_records` reads them
    out = np.array([[which[i], pots[i][1][1], pots[i][1][2], pots[i][0].speed, pots[i][0].tip[1],
                     pots[i][1][4]] for i in order])
    return positions.reshape(-1, 2, 2), out, [dataclasses.replace(pots[i][0], spot=None, ball=BALL) for i in order]


def make_game_pot_data(games: int = 100, seed: int = 0, log=print, first_chunk: int = 0) -> dict:
    """The menus' pots of `games` ghost-ball self-play games without noise (game k, from
    `first_chunk` * GAME_CHUNK on, seeded GAME_SEEDS + seed + k, a share EXPLORE of its shots a random
    menu candidate drawn from a generator seeded (seed, k)), at every decision but the break:
    arrays inputs and labels as `learned_pots.make_pot_data` gives them."""
    sim = Game("nine_ball", noise=None)
    ghost = GameGhostBallAgent.from_env(sim)
    search = SearchAgent("nine_ball", noise=None, seed=seed)
    inputs, labels = [], []
    for k in range(first_chunk * GAME_CHUNK, first_chunk * GAME_CHUNK + games):
        rng = np.random.default_rng([seed, k])

        def on_decision(obs, who, rng=rng):
            d = decode(obs, search.n_balls, search.table, game=True)
            state = game_state(d, "nine_ball", search.rule_options)
            cands, rows = shot_menu(search, d, state)
            positions, pot_rows, pots = menu_pots(d, cands, rows)
            if len(pot_rows):
                x, y = pot_examples(search, positions, pot_rows, pots)
                inputs.append(x)
                labels.append(y)
            if cands and rng.random() < EXPLORE:
                return search.action(cands[int(rng.integers(len(cands)))], d.ball_in_hand)
            return None

        play_game(sim, (ghost, ghost), GAME_SEEDS + seed + k, k % 2, on_decision)
        if log is not None and (k + 1) % 100 == 0:
            log(f"game pots: {k + 1 - first_chunk * GAME_CHUNK}/{games} games, {sum(map(len, labels))} pots")
    if not inputs:
        return {"inputs": np.zeros((0, POT_INPUTS), dtype=np.float32), "labels": np.zeros((0, 4), dtype=np.float32)}
    return {"inputs": np.concatenate(inputs), "labels": np.concatenate(labels)}


def parallel_game_pot_data(games: int, seed: int = 0, workers: int = 2) -> dict:
    """`make_game_pot_data` on `workers` processes (`learned_pots.parallel_chunks`, GAME_CHUNK
    games a chunk): the same data on any number of processes."""
    return parallel_chunks(make_game_pot_data, games, seed, workers, GAME_CHUNK)
