"""The leaf features of `search+value`: the learned player's best predicted shot value at a position, and more."""

from __future__ import annotations

import numpy as np

from pool_env.game import game_observation

from .learned import LearnedPlayer, ValueNet, menu

MAX_SHOTS = 100  # the observation's shot-counter scale (the game envs' max_shots)
LEAF_FEATURES = 3  # the learned player's best predicted value, the object balls left / 9, ball in hand
LEAF = "leaf"  # the array a net over `leaf_features` saves (1): `ValueSearchAgent` then reads positions with them
LEAF_TOP = 5  # the candidates (the search's best by its own lookahead) a leaf net rescores at a decision
NO_SHOT = -1.0  # the value of a position with no candidate shot (none is expected: safeties are always offered)


def best_values(learned: LearnedPlayer, positions) -> np.ndarray:
    """(N,) float64: for each position ((balls, rules state), no winner yet) the learned player's
    best predicted value of the next shot, in the search's units (a win 1, a loss -1): its shot
    net over the search's candidates from there, seen by the player to shoot."""
    out = np.full(len(positions), NO_SHOT)
    search = learned.search
    for i, (balls, state) in enumerate(positions):
        obs = game_observation(balls, state, state.shooter, 0, MAX_SHOTS, search.table)
        m, _ = menu(search, obs, learned.game, learned.net.layout, learned.net.pots, learned.net.safeties)
        if len(m.candidates):
            out[i] = float(np.max(learned.net.score(m.features)))
    return out


def leaf_features(learned: LearnedPlayer, positions) -> np.ndarray:
    """(N, LEAF_FEATURES) float32 of positions, seen by the player to shoot: `best_values`, the
    object balls left over 9, and whether that player has ball in hand."""
    out = np.zeros((len(positions), LEAF_FEATURES), dtype=np.float32)
    if not len(positions):
        return out
    out[:, 0] = best_values(learned, positions)
    out[:, 1] = [np.count_nonzero(~balls.pocketed[1:]) / 9.0 for balls, _ in positions]
    out[:, 2] = [state.ball_in_hand is not None for _, state in positions]
    return out


def logistic(x: np.ndarray, y: np.ndarray, steps: int = 50, ridge: float = 1e-6) -> np.ndarray:
    """The weights w (intercept first) of P(y) = sigmoid(w0 + x w[1:]) by maximum likelihood
    (Newton's method; `y` may be soft labels in [0, 1]; a tiny ridge keeps the steps defined)."""
    x1 = np.concatenate([np.ones((len(x), 1)), np.asarray(x, dtype=np.float64)], axis=1)
    y = np.asarray(y, dtype=np.float64)
    w = np.zeros(x1.shape[1])
    for _ in range(steps):
        p = 1.0 / (1.0 + np.exp(-np.clip(x1 @ w, -60.0, 60.0)))
        hessian = (x1 * (p * (1.0 - p))[:, None]).T @ x1 + ridge * np.eye(len(w))
        w -= np.linalg.solve(hessian, x1.T @ (p - y) + ridge * w)
    return w


def fit_leaf(features: np.ndarray, label: np.ndarray) -> ValueNet:
    """A leaf net: the logistic map (`logistic`) from `leaf_features` rows to P(the player to
    shoot wins), fitted to `label`, as a `ValueNet` with no hidden layer (its output the logit)
    marked LEAF."""
    x = np.asarray(features, dtype=np.float64)
    mean, std = x.mean(axis=0), x.std(axis=0) + 1e-3
    w = logistic((x - mean) / std, label)
    return ValueNet({"mean": mean, "std": std, "w0": w[1:, None], "b0": w[:1], LEAF: np.float32(1.0)})
