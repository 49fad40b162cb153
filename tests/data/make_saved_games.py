"""Re-record the saved games of tests/data/saved_games that the ghost-ball player played (run after a
deliberate change of the rules or the game, never to paper over a regression):

    PYTHONPATH=$PWD python tests/data/make_saved_games.py [name ...]

Each game is the env id and kwargs, the seed and the player already in its file: the rule-aware
ghost-ball player (`GameGhostBallAgent.from_env`) as the agent, the env's own opponent. The other
saved games (a random break, a random agent, a run) are kept as their earlier versions wrote them.
"""

import json
import sys
from pathlib import Path

import gymnasium as gym

import pool_env  # noqa: F401  (registers the envs)
from pool_env.players import GameGhostBallAgent
from pool_env.records.saved import record_game, save_game

FOLDER = Path(__file__).parent / "saved_games"
GHOST_GAMES = ("eight_ball_ghost_vs_ghost", "eight_ball_opponent_breaks_olympiad", "nine_ball_ghost_vs_ghost",
               "nine_ball_practice")


def rerecord(name: str) -> Path:
    """Play the saved game `name` again with its env, seed and player, and write it over the file."""
    path = FOLDER / f"{name}.json"
    old = json.loads(path.read_text())
    env = gym.make(old["env_id"], **old["env_kwargs"])
    record = record_game(env, GameGhostBallAgent.from_env(env), seed=old["seed"])
    env.close()
    return save_game(path, record)


if __name__ == "__main__":
    for name in sys.argv[1:] or GHOST_GAMES:
        if name not in GHOST_GAMES:
            raise SystemExit(f"{name!r} is not a ghost-ball saved game; choose from {', '.join(GHOST_GAMES)}")
        print("re-recorded", rerecord(name))
