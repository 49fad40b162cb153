"""How well a learned net ranks the search's menu on held-out decisions, and the menu's own ceiling."""

from __future__ import annotations

import numpy as np

from .learned import KINDS, ValueNet, weights_path
from .learned_train import labels, make_dataset, match, padded, with_pots
from .search import SearchAgent

HELD_OUT_SEED = 700_000  # the held-out games: apart from the recipe's (0-199,999) and the matches' (1,000,000 on)


def decision_kinds(features: np.ndarray, index: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """(D,) each decision's type: "break", "ball in hand", "pot on" (some pot in the menu) or "no pot"."""
    kinds = features[:, :len(KINDS)].argmax(axis=1)
    out = []
    for rows in (index[d][mask[d]] for d in range(len(index))):
        if (kinds[rows] == KINDS.index("break")).all():
            out.append("break")
        elif features[rows[0], 9] == 1.0:  # column 9: the cue ball placed (ball in hand)
            out.append("ball in hand")
        else:
            out.append("pot on" if (kinds[rows] == KINDS.index("pot")).any() else "no pot")
    return np.array(out)


def ranking(net: ValueNet, data: dict) -> dict:
    """Per decision type and per kind of the search's best candidate: decisions, the share where
    the net picks the search's best (top-1), the mean regret (the best label minus the label of
    the net's pick), the best label's mean and the pick's; "all" over every decision."""
    features, values, decision = data["features"], np.asarray(data["values"]), np.asarray(data["decision"])
    index, mask = padded(decision)
    scores = np.concatenate([net.score(features[decision == k]) for k in np.unique(decision)])
    y = np.where(mask, values[index], -np.inf)
    rows = np.arange(len(y))
    pick, best = np.argmax(np.where(mask, scores[index], -np.inf), axis=1), np.argmax(y, axis=1)
    picked, top = y[rows, pick], y[rows, best]
    groups = {"all": np.ones(len(y), dtype=bool)}
    types = decision_kinds(features, index, mask)
    best_kind = np.array(KINDS)[features[index[rows, best], :len(KINDS)].argmax(axis=1)]
    groups |= {f"decision: {t}": types == t for t in sorted(set(types))}
    groups |= {f"best: {k}": best_kind == k for k in sorted(set(best_kind))}
    return {name: {"decisions": int(s.sum()), "top1": float(np.mean(picked[s] == top[s])),
                   "regret": float(np.mean(top[s] - picked[s])), "best": float(np.mean(top[s])),
                   "picked": float(np.mean(picked[s]))} for name, s in groups.items() if s.any()}


class MenuOracle:
    """Plays the menu's best candidate by the search's simulated value (`labels`): the ceiling a
    learned net over this menu could reach. A measurement only: it simulates every candidate."""

    def __init__(self, game: str = "nine_ball", seed: int = 1):
        self.game, self.search = game, SearchAgent(game, noise=None, seed=seed)

    def act(self, observation) -> np.ndarray:
        m, d, v = labels(self.search, observation, self.game)
        return self.search.action(m.candidates[int(np.argmax(v))], d.ball_in_hand)


if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(description="a learned net's ranking of held-out menus; the menu's ceiling")
    parser.add_argument("--games", type=int, default=40, help="held-out ghost-ball self-play games to label")
    parser.add_argument("--net", default=str(weights_path("nine_ball")))
    parser.add_argument("--oracle-games", type=int, default=0, help="games of MenuOracle against ghost_ball")
    args = parser.parse_args()
    held = make_dataset("nine_ball", None, args.games, seed=HELD_OUT_SEED, log=None)
    net = ValueNet.load(args.net)
    for name, r in ranking(net, with_pots(held, net.pots, safeties=net.safeties)).items():
        print(f"{name:24s} {r['decisions']:5d} decisions  top-1 {r['top1']:.3f}  regret {r['regret']:.3f}  "
              f"best {r['best']:.3f}  picked {r['picked']:.3f}")
    if args.oracle_games:
        print("menu oracle against ghost_ball:", match(MenuOracle(), games=args.oracle_games))
