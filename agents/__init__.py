"""Players for `pool_env`: baselines that use the table's geometry, and trained SB3 models.

Every agent has `act(observation) -> action` (and `reset(seed)`), so the evaluator treats
them alike:

| agent | what it does |
| --- | --- |
| `RandomAgent(action_space, seed)` | uniformly random actions |
| `BreakAgent(table, spin)` | full-power break a tenth of a radius off the head ball's centre |
| `GhostBallAgent(table, physics, spin)` | breaks, then pots by the ghost-ball method (multi-shot env) |
| `GameGhostBallAgent(game, table, physics)` | the game envs' rule-aware ghost-ball player (their default opponent) |
| `SearchAgent.from_env(env, budget, seed)` | simulates candidate shots in a batch, plays the best by the rules |
| `LearnedPlayer.from_env(env)` | scores the search's candidate shots with a shipped value net (9-ball) |
| `ValueSearchAgent` (`"search+value"`) | the search, its outcomes scored by a shipped win-probability net (9-ball) |
| `SB3Agent(model)` / `SB3Agent.load(path)` | a Stable-Baselines3 model; `load_model` reads the algorithm from the zip |

```python
import gymnasium as gym
import pool_env
from agents import GhostBallAgent, evaluate

env = gym.make("PoolBreakRun-v0")
agent = GhostBallAgent.from_env(env)
print(evaluate(agent, "PoolBreakRun-v0", seeds=range(20))["pocketed_per_episode"])
```
"""

from pool_env.players import Agent, BreakAgent, GameGhostBallAgent, GhostBallAgent, Pot, RandomAgent

from .evaluate import baselines, evaluate, format_table, heuristic_for, paired_difference, play_episode, summarize
from .learned import LearnedPlayer
from .sb3 import SB3Agent, algorithm_of, load_model
from .search import SearchAgent
from .value import ValueSearchAgent

__all__ = [
    "Agent", "RandomAgent", "BreakAgent", "GhostBallAgent", "GameGhostBallAgent", "SearchAgent", "LearnedPlayer", "Pot",
    "ValueSearchAgent",
    "SB3Agent",
    "load_model", "algorithm_of",
    "evaluate", "play_episode", "summarize", "paired_difference", "format_table", "baselines", "heuristic_for",
]
