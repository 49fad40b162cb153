"""The `search+value` recipe: search self-play positions labelled by their winner, a win-probability net, a match."""

from __future__ import annotations

import argparse
import json
import os
import time
from concurrent.futures import ProcessPoolExecutor
from multiprocessing import get_context
from pathlib import Path

import numpy as np

from pool_env.game import Game

from .learned import LearnedPlayer, ValueNet
from .learned_mlp import torch_mlp
from .learned_train import value_net
from .match import alternate, play_game, player_seed, points
from .search import SearchAgent
from .stats import wilson
from .value import POSITION_FEATURES, ROUNDS, ValueSearchAgent, position_features, win_probability
from .value_leaf import LEAF_FEATURES, fit_leaf, leaf_features, logistic

GAME, NOISE = "nine_ball", "olympiad"
DATA_SEED, EVAL_SEED = 0, 1_000_000  # game k of the data is seeded DATA_SEED + k, of the evaluation EVAL_SEED + k
HIDDEN = (32,)  # one tanh layer: more fit the games' noise (held-out log loss, docs/players.md)
HELD_OUT = 0.1  # the share of the data games (the last ones) kept out of the fit to measure it
# The nets' matrices are small: BLAS threads in each worker only contend for the cores (on a
# shared machine they made a decision several times slower).
BLAS_THREADS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
OUTCOME_WEIGHT = 0.0  # the game's result in the fitted label, the rest the search's calibrated value (docs/players.md)
SELF_PLAY = {"rounds": ROUNDS, "common": True}  # the self-play searchers: search+value's allocation, no net


def self_play(games: int, seed: int = DATA_SEED, noise=NOISE, budget: int = 600, log=None, leaf: bool = False,
              search: dict | None = None) -> dict:
    """`SearchAgent` (`search`: its options beyond the budget and noise; default SELF_PLAY)
    against itself on games seeded seed .. seed + games - 1 (breaks alternating):
    every position before a shot, its `position_features`, labelled 1 if the player to shoot
    there went on to win (games with no winner are left out), and the search's own value of its
    decision there (`last_stats["value"]`, in the search's units). Arrays features (N, F),
    label (N,), search_value (N,), game (N,) (the game's seed); with `leaf`, leaf (N,
    LEAF_FEATURES) (their `leaf_features`: the learned player reads every position)."""
    sim = Game(GAME, noise=noise)
    players = [SearchAgent(GAME, noise=noise, budget=budget, **(SELF_PLAY if search is None else search))
               for _ in range(2)]
    learned = LearnedPlayer(GAME) if leaf else None
    feats, labels, values, seeds, leaves = [], [], [], [], []
    start = time.perf_counter()
    for k in range(games):
        for seat, player in enumerate(players):
            player.reset(seed=player_seed(seed + k, seat))
        positions, shooters, decided = [], [], []

        def on_decision(obs, who, positions=positions, shooters=shooters, decided=decided):
            if shooters:  # the previous decision is made: keep its value
                decided.append(players[shooters[-1]].last_stats["value"])
            positions.append((sim.balls, sim.state))
            shooters.append(who)

        winner = play_game(sim, players, seed + k, k % 2, on_decision)
        if winner is not None and positions:
            decided.append(players[shooters[-1]].last_stats["value"])
            feats.append(position_features(players[0], positions))
            if learned is not None:
                leaves.append(leaf_features(learned, positions))
            labels.append((np.array(shooters) == winner).astype(np.float32))
            values.append(np.array(decided, dtype=np.float32))
            seeds.append(np.full(len(positions), seed + k, dtype=np.int64))
        if log is not None and (k + 1) % 10 == 0:
            log(f"self-play: {k + 1}/{games} games, {sum(map(len, labels))} positions, "
                f"{time.perf_counter() - start:.0f} s")

    def joined(parts, dtype):
        return np.concatenate(parts) if parts else np.zeros(0, dtype)

    data = {"features": np.concatenate(feats) if feats else np.zeros((0, POSITION_FEATURES), np.float32),
            "label": joined(labels, np.float32), "search_value": joined(values, np.float32),
            "game": joined(seeds, np.int64)}
    if leaf:
        data["leaf"] = np.concatenate(leaves) if leaves else np.zeros((0, LEAF_FEATURES), np.float32)
    return data


def _self_play_part(job) -> dict:
    games, seed, noise, budget, leaf = job
    return self_play(games, seed, noise, budget, log=print if seed == DATA_SEED else None, leaf=leaf)


def parallel_self_play(games: int, seed: int = DATA_SEED, workers: int = 2, noise=NOISE, budget: int = 600,
                       leaf: bool = False) -> dict:
    """`self_play` split over `workers` processes (part k: the games seeded from seed + k * share),
    joined in seed order: the same data whatever process finishes first."""
    share = -(-games // workers)
    jobs = [(min(share, games - k * share), seed + k * share, noise, budget, leaf)
            for k in range(workers) if games - k * share > 0]
    if len(jobs) == 1:
        return _self_play_part(jobs[0])
    with ProcessPoolExecutor(len(jobs), mp_context=get_context("spawn")) as pool:
        parts = list(pool.map(_self_play_part, jobs))
    return {key: np.concatenate([p[key] for p in parts]) for key in parts[0]}


def split(data: dict, held_out: float = HELD_OUT) -> tuple[dict, dict]:
    """(fit, held-out) parts of the data: the last `held_out` share of its games held out."""
    games = np.unique(data["game"])
    fitted = min(len(games) - 1, max(1, int(round(len(games) * (1.0 - held_out)))))  # at least one game each side
    cut = games[fitted] if held_out > 0 and len(games) > 1 else np.inf
    keep = data["game"] < cut
    return ({k: v[keep] for k, v in data.items()}, {k: v[~keep] for k, v in data.items()})


def calibration(data: dict) -> tuple[float, float]:
    """(a, b) of the logistic map P(the shooter wins) = sigmoid(a + b v) from the search's own
    decision value v to the labelled outcomes (maximum likelihood: `value_leaf.logistic`)."""
    a, b = logistic(np.asarray(data["search_value"], dtype=np.float64)[:, None], data["label"])
    return float(a), float(b)


def targets(data: dict, outcome_weight: float = OUTCOME_WEIGHT, calibrated: tuple | None = None) -> dict:
    """The data with its label replaced by the fitted target: `outcome_weight` x the game's result
    + the rest x the search's decision value mapped to a win probability (`calibration`, fitted
    on this data unless given). The search's value scores the position one decision deeper
    than the net will, with far less variance than the result of a whole game under noise."""
    if outcome_weight >= 1.0:
        return data
    a, b = calibration(data) if calibrated is None else calibrated
    searched = 1.0 / (1.0 + np.exp(-(a + b * np.asarray(data["search_value"], dtype=np.float64))))
    label = outcome_weight * np.asarray(data["label"], dtype=np.float64) + (1.0 - outcome_weight) * searched
    return {**data, "label": label.astype(np.float32)}


def fit(data: dict, hidden=HIDDEN, epochs: int = 10, seed: int = 0, lr: float = 1e-3, batch: int = 256,
        weight_decay: float = 1e-4, log=print) -> ValueNet:
    """A win-probability net (`ValueNet` arrays: tanh MLP, its output a logit) fitted with torch:
    binary cross-entropy of the labels, Adam, minibatches of `batch` positions."""
    import torch

    torch.set_num_threads(1)  # the same sums in the same order on any machine: the same net from the same data
    torch.manual_seed(seed)
    xt, mean, std, model = torch_mlp(data["features"], hidden)
    yt = torch.from_numpy(np.asarray(data["label"], dtype=np.float32))
    opt = torch.optim.AdamW(model.parameters(), lr=lr, weight_decay=weight_decay)
    loss_fn = torch.nn.BCEWithLogitsLoss()
    gen = torch.Generator().manual_seed(seed)
    for epoch in range(epochs):
        total = 0.0
        order = torch.randperm(len(xt), generator=gen)
        for at in range(0, len(xt), batch):
            idx = order[at:at + batch]
            loss = loss_fn(model(xt[idx])[:, 0], yt[idx])
            opt.zero_grad()
            loss.backward()
            opt.step()
            total += float(loss.detach()) * len(idx)
        if log is not None and (epoch + 1) % 10 == 0:
            log(f"fit: epoch {epoch + 1}/{epochs}, log loss {total / len(xt):.4f}")
    return value_net(model, mean, std)


def scores(net: ValueNet, data: dict) -> dict:
    """Log loss and Brier score of the net's probabilities on labelled positions, beside those of
    the labels' base rate (a constant guess)."""
    p = np.clip(win_probability(net, data["features"]), 1e-6, 1 - 1e-6)
    y = data["label"]
    base = np.clip(np.full(len(y), y.mean() if len(y) else 0.5), 1e-6, 1 - 1e-6)

    def log_loss(q):
        return float(-np.mean(y * np.log(q) + (1 - y) * np.log(1 - q)))

    return {"positions": len(y), "log_loss": log_loss(p), "brier": float(np.mean((p - y) ** 2)),
            "base_log_loss": log_loss(base), "base_brier": float(np.mean((base - y) ** 2))}


def challenger(net: ValueNet | None, noise, budget: int, options: dict, ghost_ball: bool = False) -> SearchAgent:
    """The player measured against the plain search: search+value with `net` (None: the
    shipped one) and `options`, or with `ghost_ball` the search itself with the same options
    (its allocation of the budget, `rounds` and `common`, without the net: what the net adds)."""
    if ghost_ball:
        return SearchAgent(GAME, noise=noise, budget=budget, **options)
    return ValueSearchAgent(GAME, net=net, noise=noise, budget=budget, **options)


def versus(games: int, seed: int = EVAL_SEED, noise=NOISE, budget: int = 600, net: ValueNet | None = None,
           options: dict | None = None, clock: dict | None = None, ghost_ball: bool = False,
           opponent: dict | None = None) -> list:
    """search+value (`challenger`) against search (`opponent`: its options, default none: the
    plain search) on games seeded seed + k, search+value breaking the even k (seats and breaks
    alternate), both with `budget` simulations a decision (`options`: more of
    `ValueSearchAgent`'s: rounds, common, blend, every, top): for each game 1 (search+value
    won), 0 or 0.5 (no winner). `clock`, if given, gets each side's decisions and CPU seconds
    ([n, s] under "search+value" and "search")."""
    sim = Game(GAME, noise=noise)
    value = challenger(net, noise, budget, options or {}, ghost_ball)
    plain = SearchAgent(GAME, noise=noise, budget=budget, **(opponent or {}))
    clock = {} if clock is None else clock
    out = []
    for game_seed, breaker, other in alternate(range(seed, seed + games), value, plain, first=seed):
        seats = (breaker, other)
        for seat, player in enumerate(seats):
            player.reset(seed=player_seed(game_seed, seat))

        def timed(obs, who, seats=seats):
            start = time.process_time()
            action = seats[who].act(obs)
            spent = clock.setdefault("search+value" if seats[who] is value else "search", [0, 0.0])
            spent[0] += 1
            spent[1] += time.process_time() - start
            return action

        winner = play_game(sim, seats, game_seed, 0, timed)  # seat 0 breaks
        out.append(points(winner, 0 if breaker is value else 1))
    return out


def _versus_part(job) -> tuple:
    games, seed, noise, budget, arrays, options, ghost_ball, opponent = job
    clock = {}
    net = None if arrays is None else ValueNet(arrays)
    results = versus(games, seed, noise, budget, net, options, clock, ghost_ball, opponent)
    return results, clock


def match(games: int = 400, seed: int = EVAL_SEED, workers: int = 2, noise=NOISE, budget: int = 600,
          net: ValueNet | None = None, options: dict | None = None, ghost_ball: bool = False,
          opponent: dict | None = None) -> dict:
    """`versus` split over `workers` processes: wins, the win rate and its 95 % Wilson interval,
    each player's decisions and decisions per CPU second."""
    share = -(-games // workers)
    arrays = None if net is None else net.arrays
    jobs = [(min(share, games - k * share), seed + k * share, noise, budget, arrays, options, ghost_ball, opponent)
            for k in range(workers) if games - k * share > 0]
    if len(jobs) == 1:
        parts = [_versus_part(jobs[0])]
    else:
        with ProcessPoolExecutor(len(jobs), mp_context=get_context("spawn")) as pool:
            parts = list(pool.map(_versus_part, jobs))
    wins = float(sum(r for results, _ in parts for r in results))
    lo, hi = wilson(wins, games)
    decisions = {name: sum(c[name][0] for _, c in parts if name in c) for name in ("search+value", "search")}
    cpu = {name: sum(c[name][1] for _, c in parts if name in c) for name in ("search+value", "search")}
    per_second = {name: decisions[name] / cpu[name] if cpu[name] > 0 else None for name in cpu}
    return {"games": games, "wins": wins, "win_rate": wins / games, "ci95": [lo, hi], "seeds": [seed, seed + games - 1],
            "budget": budget, "options": options or {}, "ghost_ball": ghost_ball, "opponent": opponent or {},
            "noise": noise, "decisions": decisions, "decisions_per_cpu_second": per_second}


def fitted_net(data: dict, outcome_weight: float, leaf: bool, log=print) -> ValueNet:
    """The net the recipe fits to `targets`: over `position_features` (`fit`) or, with `leaf`,
    the logistic leaf net over `leaf_features` (`value_leaf.fit_leaf`)."""
    labelled = targets(data, outcome_weight)
    if not leaf:
        return fit(labelled, log=log)
    game = np.asarray(data["game"])
    played = np.r_[False, game[1:] == game[:-1]]  # each game's first position is the rack, never a leaf
    return fit_leaf(data["leaf"][played], labelled["label"][played])


def recipe(data_games: int, eval_games: int, out, workers: int = 2, budget: int = 600, data=None, log=print,
           outcome_weight: float = OUTCOME_WEIGHT, leaf: bool = False) -> dict:
    """The whole recipe: `data_games` search self-play games (olympiad noise, `workers` processes),
    a net fitted (`fitted_net`; `leaf`: the leaf net) on all but the held-out games (scored there
    against their outcomes), then fitted on every game and played against search for
    `eval_games` games. Writes value.npz, value-data.npz and value.json into `out`; returns the
    result."""
    if outcome_weight < 1.0 and data is not None and "search_value" not in data:
        raise ValueError("this data has no search_value (made before the search's values were kept): "
                         "fit it with --outcome-weight 1 or play new data")
    if leaf and data is not None and "leaf" not in data:
        raise ValueError("this data has no leaf features (made before they were kept): play new data")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    timing, t = {}, time.perf_counter()
    if data is None:
        data = parallel_self_play(data_games, workers=workers, budget=budget, leaf=leaf)
        np.savez_compressed(out / "value-data.npz", **data)
    timing["data"] = time.perf_counter() - t
    log(f"data: {len(data['label'])} positions of {len(np.unique(data['game']))} games in {timing['data']:.0f} s")
    t = time.perf_counter()
    train, held = split(data)
    shown = {**held, "features": held["leaf"]} if leaf else held
    held_scores = scores(fitted_net(train, outcome_weight, leaf, log), shown) if len(held["label"]) else {}
    log(f"held out: {held_scores}")
    net = fitted_net(data, outcome_weight, leaf, log)
    net.save(out / "value.npz")
    timing["fit"] = time.perf_counter() - t
    t = time.perf_counter()
    result = match(eval_games, workers=workers, budget=budget, net=net) if eval_games else {}
    timing["evaluation"] = time.perf_counter() - t
    result = {**result, "data_games": int(len(np.unique(data["game"]))), "positions": int(len(data["label"])),
              "outcome_weight": outcome_weight, "leaf": leaf,
              "held_out": held_scores, "seconds": timing, "workers": workers}
    (out / "value.json").write_text(json.dumps(result, indent=2) + "\n")
    if eval_games:
        log(f"search+value against search: {result['wins']:g}/{result['games']} = {result['win_rate']:.1%} "
            f"[{result['ci95'][0]:.1%}, {result['ci95'][1]:.1%}]")
    return result


def player_options(args) -> dict:
    """search+value's options from the command line (with --ghost-ball, the search's: its
    rounds default to search+value's)."""
    options = {"common": not args.no_common}
    if args.rounds is not None or args.ghost_ball:
        options["rounds"] = ROUNDS if args.rounds is None else args.rounds
    if args.blend is not None:
        options["blend"] = args.blend
    if args.every:
        options["every"] = True
    if args.top is not None:
        options["top"] = args.top
    return options


def main(argv=None) -> dict:
    for name in BLAS_THREADS:  # the worker processes inherit these: one BLAS thread each
        os.environ.setdefault(name, "1")
    parser = argparse.ArgumentParser(prog="python -m agents.value_train", description=__doc__)
    parser.add_argument("--games", type=int, default=800, help="search self-play games for the data")
    parser.add_argument("--eval-games", type=int, default=400, help="games of search+value against search (0: none)")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--budget", type=int, default=600, help="simulations a decision, both players")
    parser.add_argument("--data", default=None, help="a value-data.npz to fit on instead of playing")
    parser.add_argument("--out", default="runs/value")
    parser.add_argument("--net", default=None,
                        help="only play this value net (a path, or 'shipped') against search (--eval-games games)")
    parser.add_argument("--ghost-ball", action="store_true",
                        help="only play the search with search+value's rounds and common draws but its ghost-ball "
                             "lookahead (no net) against search: what the net adds")
    parser.add_argument("--rounds", type=int, default=None,
                        help=f"search+value's rounds of sequential halving (default {ROUNDS}; a leaf net's 1)")
    parser.add_argument("--no-common", action="store_true", help="search+value's draws independent, not common")
    parser.add_argument("--opponent-rounds", type=int, default=1,
                        help="the search's rounds (default 1: the plain search)")
    parser.add_argument("--opponent-common", action="store_true", help="the search's draws common")
    parser.add_argument("--blend", type=float, default=None,
                        help="with --net --rounds 1: the search's own value's weight")
    parser.add_argument("--every", action="store_true",
                        help="with --net --rounds 1: score every candidate, not the lookahead's")
    parser.add_argument("--top", type=int, default=None,
                        help="with --net --rounds 1: rescore only the search's best TOP candidates "
                             "(a leaf net's default: 5)")
    parser.add_argument("--leaf", action="store_true",
                        help="fit the leaf net (the learned player's best shot value, balls left, ball in hand)")
    parser.add_argument("--eval-seed", type=int, default=EVAL_SEED)
    parser.add_argument("--outcome-weight", type=float, default=OUTCOME_WEIGHT,
                        help="the game's result in the label (0: the search's calibrated value alone, 1: the result)")
    args = parser.parse_args(argv)
    if args.net is not None or args.ghost_ball:
        result = match(args.eval_games, args.eval_seed, args.workers, budget=args.budget,
                       net=None if args.net in (None, "shipped") else ValueNet.load(args.net),
                       options=player_options(args), ghost_ball=args.ghost_ball,
                       opponent={"rounds": args.opponent_rounds, "common": args.opponent_common})
        print(json.dumps(result))
        return result
    if args.games < 1 or args.eval_games < 0 or args.workers < 1 or not 0.0 <= args.outcome_weight <= 1.0:
        parser.exit(2, f"{parser.prog}: --games and --workers must be >= 1, --eval-games >= 0, "
                       "--outcome-weight in [0, 1]\n")
    data = None
    if args.data is not None:
        with np.load(args.data) as f:
            data = dict(f)
    return recipe(args.games, args.eval_games, args.out, args.workers, args.budget, data,
                  outcome_weight=args.outcome_weight, leaf=args.leaf)


if __name__ == "__main__":
    main()
