"""`search+value`: the search player with a learned win probability in place of its ghost-ball lookahead."""

from __future__ import annotations

import numpy as np

from pool_env import rules
from pool_env.game import GAME_BALLS, game_observation
from pool_env.players import game_of

from .learned import WEIGHTS, LearnedPlayer, ValueNet
from .search import IN_HAND_QUALITY, SearchAgent
from .value_leaf import LEAF, LEAF_TOP, leaf_features

MAX_SHOTS = 100  # the observation's shot-counter scale (the game envs' max_shots); the counter is left out
OBSERVATION_ROWS = 43  # a 9-ball observation without its shot counter: balls (30), legal (9), in hand (2), fouls (2)
POSITION_FEATURES = OBSERVATION_ROWS + 2  # ... and the shooter's best ghost-ball quality, the object balls left
ROUNDS = 4  # a position net's search: the budget in four rounds of sequential halving (docs/players.md)


def value_weights_path(game: str = "nine_ball"):
    """The shipped value net of a game (9-ball only: `agents.value_train` fits it)."""
    return WEIGHTS / f"{game}_value.npz"


def sigmoid(z: np.ndarray) -> np.ndarray:
    return 1.0 / (1.0 + np.exp(-np.clip(z, -60.0, 60.0)))


def position_features(search: SearchAgent, positions) -> np.ndarray:
    """(N, POSITION_FEATURES) float32 of positions (each (balls, rules state) with no winner yet),
    seen by the player to shoot: the game observation of that player (`game_observation`, the
    shot counter left out), the best ghost-ball quality of its next shot (`SearchAgent.qualities`,
    one planner batch; IN_HAND_QUALITY with ball in hand) and the object balls left, over 9."""
    out = np.zeros((len(positions), POSITION_FEATURES), dtype=np.float32)
    if not len(positions):
        return out
    table = search.table
    legals = [rules.legal_targets(state) for _, state in positions]
    for i, (balls, state) in enumerate(positions):
        out[i, :OBSERVATION_ROWS] = game_observation(balls, state, state.shooter, 0, MAX_SHOTS, table)[
            :OBSERVATION_ROWS]
        out[i, -1] = np.count_nonzero(~balls.pocketed[1:]) / 9.0
    in_hand = np.array([state.ball_in_hand is not None for _, state in positions])
    asked = np.flatnonzero(~in_hand)
    out[in_hand, OBSERVATION_ROWS] = IN_HAND_QUALITY
    if len(asked):
        out[asked, OBSERVATION_ROWS] = search.qualities([positions[i][0].xy for i in asked],
                                                        [~positions[i][0].pocketed for i in asked],
                                                        [legals[i] for i in asked])
    return out


def win_probability(net: ValueNet, features: np.ndarray) -> np.ndarray:
    """P(the player to shoot wins) of feature rows: the net's logit through a sigmoid."""
    return sigmoid(net(features).astype(np.float64))


class ValueSearchAgent(SearchAgent):
    """`SearchAgent` whose simulated outcomes are scored by a value net: the candidates, their
    simulations under the game's noise and the rules' judgement are the search's; each outcome
    is then worth 1 (a win), 0 (a loss or a shot the simulator could not finish), V (the shooter
    keeps the table) or 1 - V (the opponent to shoot, with ball in hand after a foul), V the
    net's win probability of the player to shoot there, all outcomes of a decision in one net
    evaluation. The net reads `position_features` (one planner batch a decision) or, if it is a
    leaf net (saved with LEAF), `value_leaf.leaf_features`: the learned player's best predicted
    shot value from each outcome (no simulation). `top` (a leaf net's default LEAF_TOP) limits
    the net's choice to the search's `top` best candidates by its own lookahead value. `blend`
    in [0, 1] mixes in the search's own value (its lookahead, mapped from [-1, 1] to [0, 1])
    with that weight (0: the net alone). The candidate with the best mean over its noise draws
    is played.

    With noise, a position net's search spends its budget in `rounds` (default ROUNDS) rounds
    of sequential halving (`SearchAgent.in_rounds`), every draw scored by the net, and with
    `common` random numbers (the candidates of a round under the same cue errors); `blend`,
    `every` and `top` are options of the single pass (`rounds=1`), which a leaf net takes by
    default."""

    name = "search+value"

    def __init__(self, game: str | None = "nine_ball", net: ValueNet | None = None, blend: float = 0.0,
                 every: bool = False, top: int | None = None, rounds: int | None = None, common: bool = True,
                 **options):
        if game not in GAME_BALLS:
            raise ValueError(f"unknown game {game!r}; choose one of {', '.join(GAME_BALLS)}")
        if net is None:  # a game without a shipped net is refused as the learned player's is (the tournament skips it)
            path = value_weights_path(game)
            if not path.exists():
                raise FileNotFoundError(f"no {game} value net is shipped ({path.name} is missing)")
            net = ValueNet.load(path)
        if game != "nine_ball":
            raise ValueError(f"search+value plays 9-ball only (its features are 9-ball's), got {game!r}")
        if not 0.0 <= float(blend) <= 1.0:
            raise ValueError(f"blend must be in [0, 1], got {blend!r}")
        if top is not None and int(top) < 1:
            raise ValueError(f"top must be >= 1 or None, got {top!r}")
        leaf = LEAF in getattr(net, "arrays", {})  # a net over `leaf_features`: the learned player reads the positions
        rounds = (1 if leaf else ROUNDS) if rounds is None else rounds
        if int(rounds) > 1 and (blend or every or top is not None):
            raise ValueError("blend, every and top are options of the single-pass search: give rounds=1 with them")
        super().__init__(game, rounds=rounds, common=common, **options)
        self.net, self.blend, self.every = net, float(blend), bool(every)
        self.learned = None
        if leaf:
            self.learned = LearnedPlayer(game, table=self.table, physics=self.physics, radius=self.radius)
            top = LEAF_TOP if top is None else top
        self.top = None if top is None else int(top)

    def evaluate(self, d, state, candidates, start) -> tuple[np.ndarray, int]:
        """(each candidate's value, the candidates simulated): simulated and judged as by
        `SearchAgent.evaluate` (with `seconds`, chunks until the time is up); the candidates its
        lookahead would score (`looked_at`; `every`: all simulated), or with `top` the `top` best
        of them by the search's own lookahead value, get the mean of `outcome_values` over their
        noise draws, blended with the search's lookahead value if `blend`; the rest stay below
        any of them."""
        s = self.noise_samples
        records, judged, plain = self.judged(d, state, candidates, start)
        done = len(records) // s
        chosen = np.arange(done) if self.every else self.looked_at(plain, done, d.legal)
        deep = plain - 10.0
        if self.blend > 0.0 or self.top is not None:
            self.look_ahead(deep, chosen, judged, start)
        if self.top is not None:
            chosen = np.argsort(-deep, kind="stable")[: min(self.top, len(chosen))]
        values = deep - 10.0
        won = self.outcome_values([records[c * s + k] for c in chosen for k in range(s)])
        values[chosen] = won.reshape(len(chosen), s).mean(axis=1)
        if self.blend > 0.0:
            values[chosen] = (1.0 - self.blend) * values[chosen] + self.blend * 0.5 * (deep[chosen] + 1.0)
        return values, done

    def draw_values(self, state, records) -> np.ndarray:
        """With `rounds`: each simulated shot worth its `outcome_values` (the net's lookahead)."""
        return self.outcome_values(records)

    def outcome_values(self, records) -> np.ndarray:
        """(R,) the shooter's win probability after each simulated shot (the class docstring)."""
        values = np.zeros(len(records))
        open_rows, positions = [], []
        for k, record in enumerate(records):
            if record.error is not None:
                continue
            winner = record.ruling.winner
            if winner is not None:
                values[k] = 1.0 if winner == 0 else 0.0
            else:
                open_rows.append(k)
                positions.append((record.balls_after, record.state_after))
        if open_rows:
            features = position_features(self, positions) if self.learned is None else \
                leaf_features(self.learned, positions)
            v = win_probability(self.net, features)
            mine = np.array([after.shooter == 0 for _, after in positions])
            values[open_rows] = np.where(mine, v, 1.0 - v)
        return values


def value_player(env, seed=None, **options) -> ValueSearchAgent:
    """The player registry's "search+value" (`pool_env.make_player("search+value", env)`)."""
    game = game_of(env)
    if not game.has_rules:
        raise TypeError("search+value plays the 9-ball game (PoolNineBall-v0)")
    return ValueSearchAgent(game.mode, table=game.base_table, physics=game.base_physics, noise=game.noise,
                            rule_options=game.rule_options, seed=0 if seed is None else seed, **options)
