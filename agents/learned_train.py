"""The learned player's recipe: positions from games, the search's values as labels, a fitted value net, games."""

from __future__ import annotations

import json
import time
from concurrent.futures import ProcessPoolExecutor
from multiprocessing import get_context
from pathlib import Path

import numpy as np

from pool_env.game import Game
from pool_env.players import GameGhostBallAgent

from .learned import (
    CANDIDATE_FEATURES,
    EXPLORE,
    KINDS,
    LABEL_LAYOUT,
    LAYOUT,
    LearnedPlayer,
    ValueNet,
    game_ball_of,
    menu,
    pot_columns,
)
from .learned_combos import COMBO_COLUMNS, combo_columns
from .learned_features import OUTCOME_FEATURES
from .learned_game_pots import parallel_game_pot_data
from .learned_mlp import descend, mlp_arrays, torch_mlp
from .learned_pots import POT_COLUMNS, PotNet, fit_pots, fit_rest_errors, parallel_pot_data
from .learned_safeties import SAFE_COLUMNS, SafetyNet, fit_safeties, parallel_safe_data
from .match import alternate, play_game, points
from .search import SearchAgent, balls_of, game_state
from .search_position import decode
from .stats import wilson

ROUND_SEEDS = 100_000  # round r's games are seeded seed + r * ROUND_SEEDS + k (train.py's games start at 1,000,000)
POT_EPOCHS = 20  # the pot net's epochs in `recipe`
EVAL_NOISES = (None, "olympiad")  # the recipe's evaluations: the published figures
BREAK_COLUMNS, BREAK_HIDDEN, BREAK_EPOCHS = 17, (32,), 60  # the break net: its inputs, layers, epochs


def labels(search: SearchAgent, observation, game: str) -> tuple:
    """(the decision's `Menu`, its decoded view, values (K,)): the search's value of every menu
    candidate (its judged outcome with the depth-1 lookahead, the mean over its noise draws).
    The rows are of LABEL_LAYOUT: a pot net's columns are added at fit time (`with_pots`)."""
    m, d = menu(search, observation, game, LABEL_LAYOUT)
    state = game_state(d, game, search.rule_options)
    s = search.noise_samples
    search.sim.reset(balls=balls_of(d, search.radius), state=state)
    shots = [search.sim.decode(search.action(c, d.ball_in_hand)) for c in m.candidates]
    records = search.sim.evaluate(shots, draws=s, seed=search.rng)
    values = np.array([search.deep_value(*search.judge(state, r, m.candidates[k // s]))
                       for k, r in enumerate(records)]).reshape(len(m.candidates), s).mean(axis=1)
    return m, d, values.astype(np.float32)


def make_dataset(game: str = "nine_ball", noise=None, games: int = 200, seed: int = 0, log=print,
                 net: ValueNet | None = None) -> dict:
    """Positions from games (seeds `seed`...): ghost-ball self-play, or with `net` the learned
    player against the ghost-ball player (its own positions: a second round); a share EXPLORE of
    the shots replaced by a random menu candidate. Every decision is labelled by `labels`.
    Returns arrays features (N, F), values (N,), decision (N,) (which decision each row is of)."""
    sim = Game(game, noise=noise)
    ghost = GameGhostBallAgent.from_env(sim)
    players = (ghost, ghost) if net is None else (LearnedPlayer(game, net), ghost)
    search = SearchAgent(game, noise=noise, seed=seed)
    rng = np.random.default_rng(seed)
    feats, values, decision = [], [], []
    start = time.perf_counter()

    def on_decision(obs, who):
        m, d, v = labels(search, obs, game)
        feats.append(m.features)
        values.append(v)
        decision.append(np.full(len(v), len(values) - 1, dtype=np.int32))
        if rng.random() < EXPLORE:  # a random candidate of the menu, as the search would play it
            return search.action(m.candidates[int(rng.integers(len(m.candidates)))], d.ball_in_hand)
        return None

    for k in range(games):
        play_game(sim, players if k % 4 < 2 else players[::-1], seed + k, k % 2, on_decision)
        if log is not None and (k + 1) % 10 == 0:
            log(f"data: {k + 1}/{games} games, {len(values)} decisions, {time.perf_counter() - start:.0f} s")
    return {"features": np.concatenate(feats), "values": np.concatenate(values),
            "decision": np.concatenate(decision)}


def _dataset_part(job) -> dict:
    game, noise, games, seed, net = job
    return make_dataset(game, noise, games, seed, log=None, net=None if net is None else ValueNet(net))


def parallel_dataset(game: str, noise, games: int, seed: int, workers: int = 2, net: ValueNet | None = None) -> dict:
    """`make_dataset` split over `workers` processes (part k: the games seeded from seed + k *
    ceil(games / workers)), joined in order: the same data whatever process finishes first."""
    share = -(-games // workers)
    jobs = [(game, noise, min(share, games - k * share), seed + k * share, None if net is None else net.all_arrays())
            for k in range(workers) if games - k * share > 0]
    with ProcessPoolExecutor(len(jobs), mp_context=get_context("spawn")) as pool:
        parts = list(pool.map(_dataset_part, jobs))
    return join(parts)


def join(parts) -> dict:
    """Datasets one after another (decision numbers renumbered)."""
    out, offset = {"features": [], "values": [], "decision": []}, 0
    for part in parts:
        out["features"].append(part["features"])
        out["values"].append(part["values"])
        out["decision"].append(part["decision"] + offset)
        offset += int(part["decision"].max()) + 1 if len(part["decision"]) else 0
    return {k: np.concatenate(v) for k, v in out.items()}


def padded(decision: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rows grouped by decision: (index (D, K) into the rows, mask (D, K)), K the largest menu."""
    starts = np.flatnonzero(np.r_[True, decision[1:] != decision[:-1]])
    sizes = np.diff(np.r_[starts, len(decision)])
    k = np.arange(sizes.max())
    mask = k[None, :] < sizes[:, None]
    index = np.where(mask, starts[:, None] + k[None, :], 0)
    return index, mask


def decision_batches(decision: np.ndarray, size: int) -> list:
    """Minibatches of `size` decisions of similar menu sizes (sorted by size, so little padding):
    each (row index (B, K), mask (B, K)) as torch tensors."""
    import torch

    index, mask = padded(decision)
    order = np.argsort(mask.sum(axis=1), kind="stable")
    out = []
    for i in range(0, len(order), size):
        rows = order[i:i + size]
        k = int(mask[rows].sum(axis=1).max())
        out.append((torch.from_numpy(index[rows, :k]), torch.from_numpy(mask[rows, :k])))
    return out


def fit(data: dict, hidden=(128, 128), epochs: int = 30, seed: int = 0, lr: float = 1e-3, log=print) -> ValueNet:
    """A value net fitted to the labels with torch: the mean squared error, Adam, minibatches of
    64 decisions. (Adding a listwise cross-entropy of each decision's softmax, which weighs the
    ranking, chose worse shots in our trials: 56.5 % against 58.5 % of 200 games.)"""
    import torch

    torch.set_num_threads(1)  # the same sums in the same order on any machine: the same net from the same data
    torch.manual_seed(seed)
    xt, mean, std, model = torch_mlp(data["features"], hidden)
    yt = torch.from_numpy(np.asarray(data["values"], dtype=np.float32))
    opt = torch.optim.Adam(model.parameters(), lr=lr)
    batches = decision_batches(np.asarray(data["decision"]), 64)
    gen = torch.Generator().manual_seed(seed)
    for epoch in range(epochs):
        total = 0.0
        for b in torch.randperm(len(batches), generator=gen).tolist():
            idx, m = batches[b]
            pred, target = model(xt[idx])[..., 0], yt[idx]
            total += descend(opt, torch.sum(((pred - target) ** 2) * m) / m.sum())
        if log is not None and (epoch + 1) % 5 == 0:
            log(f"fit: epoch {epoch + 1}/{epochs}, loss {total / len(batches):.4f}")
    return value_net(model, mean, std)


def with_pots(data: dict, pots: PotNet | None, game: str = "nine_ball", safeties: SafetyNet | None = None,
              combos: bool = False) -> dict:
    """A dataset of LABEL_LAYOUT rows with the pot net's columns (`learned.pot_columns`) added,
    with `safeties` the safety net's (`SafetyNet.columns`) after them and with `combos` the
    third balls' (`learned_combos.combo_columns`) after those, each decision's position read
    back from its rows' observation: the rows `menu` makes of layout 3, 4 or 5 (unchanged
    without a pot net)."""
    if pots is None or (combos and safeties is None):
        if safeties is not None or combos:
            raise ValueError("the safety net's columns follow the pot net's, the combos' the safety net's: "
                             "pass them all")
        return data
    search = SearchAgent(game, noise=None)
    features = np.asarray(data["features"])
    safe_width = 0 if safeties is None else SAFE_COLUMNS
    width = POT_COLUMNS + 2 + safe_width + (COMBO_COLUMNS if combos else 0)
    extra = np.zeros((len(features), width), dtype=np.float32)
    start = CANDIDATE_FEATURES + OUTCOME_FEATURES
    decision = np.asarray(data["decision"])
    edges = np.flatnonzero(np.r_[True, decision[1:] != decision[:-1], True])
    for a, b in zip(edges[:-1], edges[1:]):
        d = decode(features[a, start:], search.n_balls, search.table)
        state, rows = game_state(d, game), features[a:b, :CANDIDATE_FEATURES]
        extra[a:b, :POT_COLUMNS + 2] = pot_columns(search, pots, d, state, rows)
        if safeties is not None:
            extra[a:b, POT_COLUMNS + 2:POT_COLUMNS + 2 + safe_width] = safeties.columns(search, rows, d, state)
        if combos:
            extra[a:b, POT_COLUMNS + 2 + safe_width:] = combo_columns(search, rows, d, game_ball_of(game))
    return {**data, "features": np.concatenate([features, extra], axis=1)}


def fit_player(data: dict, hidden=(256, 256), epochs: int = 30, seed: int = 0, log=print,
               pots: PotNet | None = None, game: str = "nine_ball", safeties: SafetyNet | None = None,
               combos: bool = False) -> ValueNet:
    """The learned player's nets: `fit` of the shot net on every decision but the break, and
    of a break net (`ValueNet.breaks`, one layer of BREAK_HIDDEN) on the breaks' candidates that
    reads only their own shot (BREAK_COLUMNS: kind, speed, tip, direction, spot, aim offset): the rack is the
    same but for its jitter, so the break net learns each break's mean value. With `pots` the
    shot net reads the rows of layout 3 (the pot net's columns added, `with_pots`; the rows of
    `game`), with `safeties` too those of layout 4 (the safety net's columns after them), and
    with `combos` those of layout 5 (LAYOUT: the third balls' columns after those)."""
    rows = np.asarray(data["features"][:, KINDS.index("break")] == 1.0)
    shot = fit(with_pots(subset(data, ~rows), pots, game, safeties, combos), hidden, epochs, seed, log=log)
    layout = LABEL_LAYOUT if pots is None else 3 if safeties is None else LAYOUT if combos else 4
    shot = ValueNet({**shot.arrays, "layout": np.float32(layout)}, pots=pots, safeties=safeties)
    if not rows.any():
        return shot
    breaks = rack_means(subset(data, rows))
    breaks["features"] = breaks["features"][:, :BREAK_COLUMNS]
    net = fit(breaks, BREAK_HIDDEN, BREAK_EPOCHS, seed, log=None)
    return ValueNet(shot.arrays, breaks=ValueNet({**net.arrays, "columns": np.float32(BREAK_COLUMNS)}), pots=pots,
                    safeties=safeties)


def rack_means(breaks: dict) -> dict:
    """The break decisions with each candidate's label replaced by its mean over all the racks:
    every break menu holds the same candidates in the same order (`SearchAgent.break_candidates`),
    and one rack's simulated value of a break is mostly the rack's jitter, which the break net
    cannot see (it halved the held-out regret of the break net's choice, 0.86 to 0.66)."""
    decision = np.asarray(breaks["decision"])
    index, mask = padded(decision)
    if not mask.all():  # menus of different sizes: no candidate order to average over
        return breaks
    values = np.asarray(breaks["values"])[index].mean(axis=0)
    out = dict(breaks)
    out["values"] = np.empty(index.size, dtype=np.float32)
    out["values"][index.reshape(-1)] = np.broadcast_to(values, index.shape).reshape(-1)
    return out


def subset(data: dict, rows) -> dict:
    """The rows `rows` (a mask) of a dataset."""
    return {k: np.asarray(v)[rows] for k, v in data.items()}


def value_net(model, mean, std) -> ValueNet:
    """The NumPy `ValueNet` of a `torch_mlp` model and its inputs' standardisation."""

    return ValueNet({**mlp_arrays(model, mean, std), "layout": np.float32(LABEL_LAYOUT)})


def regret(net: ValueNet, data: dict) -> dict:
    """How far the net's choices fall below the best label of each decision: mean regret, the
    share of decisions where it picks the best (within 0.01), the labels' own spread."""
    index, mask = padded(np.asarray(data["decision"]))
    pred = np.where(mask, net(data["features"])[index], -np.inf)
    y = np.where(mask, data["values"][index], -np.inf)
    chosen = y[np.arange(len(y)), np.argmax(pred, axis=1)]
    best = y.max(axis=1)
    mean_value = np.nanmean(np.where(mask, y, np.nan), axis=1)
    return {"regret": float(np.mean(best - chosen)), "best_share": float(np.mean(best - chosen < 0.01)),
            "random_regret": float(np.mean(best - mean_value)), "decisions": len(y)}


def match(player, game: str = "nine_ball", noise=None, games: int = 400, seed: int = 1_000_000) -> dict:
    """`player` against the ghost-ball player, game k seeded `seed + k`, the player breaking the
    even-numbered games: wins (an unfinished game half a win), the win rate and its 95 % interval."""
    sim = Game(game, noise=noise)
    ghost = GameGhostBallAgent.from_env(sim)
    wins = 0.0
    for game_seed, breaker, other in alternate(range(seed, seed + games), player, ghost):
        winner = play_game(sim, (breaker, other), game_seed, 0)  # seat 0 breaks
        wins += points(winner, 0 if breaker is player else 1)
    lo, hi = wilson(wins, games)
    return {"games": games, "wins": wins, "win_rate": wins / games, "ci95": (lo, hi)}


def shot_models(pot_positions: int, safe_positions: int, seed: int, workers: int, out, log, timing: dict,
                pot_games: int = 0) -> tuple:
    """`recipe`'s pot net and safety net (either None when its positions are 0; no safety net
    without a pot net), their data saved into `out` and their seconds into `timing`. The pot
    net's data: the pots of `pot_positions` random two-ball positions, then with `pot_games` the
    menus' pots of that many ghost-ball games (`learned_game_pots`), each simulated alone."""
    pots = safeties = None
    Path(out).mkdir(parents=True, exist_ok=True)
    if pot_positions:
        t = time.perf_counter()
        parts = [parallel_pot_data(pot_positions, seed, workers)]
        if pot_games:
            parts.append(parallel_game_pot_data(pot_games, seed, workers))
        pot_data = {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}
        pots = fit_pots(pot_data, epochs=POT_EPOCHS, seed=seed, log=log)
        pots = fit_rest_errors(pots, pot_data, SearchAgent("nine_ball", noise=None).table, seed=seed, log=log)
        np.savez_compressed(Path(out) / "pots-data.npz", **pot_data)
        timing["pots"] = time.perf_counter() - t
        log(f"pot net: {len(pot_data['labels'])} simulated pots, fitted in {timing['pots']:.0f} s")
    if pot_positions and safe_positions:
        t = time.perf_counter()
        safe_data = parallel_safe_data(safe_positions, seed + 1, workers)
        safeties = fit_safeties(safe_data, seed=seed, log=log)
        np.savez_compressed(Path(out) / "safe-data.npz", **safe_data)
        timing["safeties"] = time.perf_counter() - t
        log(f"safety net: {len(safe_data['labels'])} simulated safeties and kicks, "
            f"fitted in {timing['safeties']:.0f} s")
    return pots, safeties


def recipe(game: str, noise, data_games: int, rounds: int, eval_seeds, seed: int, workers: int, out, log=print,
           epochs: int = 30, pot_positions: int = 0, safe_positions: int = 0, combos: bool = False,
           pot_games: int = 0) -> dict:
    """The learned player, start to finish: `data_games` ghost-ball self-play games labelled
    (`parallel_dataset`), a value net fitted; then `rounds - 1` times as many games again of
    that net against the ghost-ball player, labelled and added, the net fitted anew; the last
    net against the ghost-ball player on `eval_seeds`, without noise and with olympiad noise
    (`EVAL_NOISES`; the top-level figures are those at `noise`). Writes the net (`learned.npz`),
    the labelled data (`learned-data.npz`) and the result (`learned.json`) into `out`; returns
    the result. With `pot_positions`, first a pot net (`learned_pots`) fitted to the pots
    planned from that many random positions (simulated on `workers` processes, seeded `seed`),
    and with `pot_games` the menus' pots of that many ghost-ball games (`learned_game_pots`),
    whose columns the value nets then read (layout 3; its data saved as `pots-data.npz`); and
    with `safe_positions` too, a safety net (`learned_safeties`) fitted to the safeties and kicks
    planned from that many random positions (seeded `seed` + 1), whose columns follow (layout 4;
    its data saved as `safe-data.npz`); and with `combos` too, the third balls' columns
    (`learned_combos`, no data of their own) after those (layout 5)."""
    started, net, parts, timing = time.perf_counter(), None, [], {}
    pots, safeties = shot_models(pot_positions, safe_positions, seed, workers, out, log, timing, pot_games)
    for r in range(rounds):
        t = time.perf_counter()
        parts.append(parallel_dataset(game, noise, data_games, seed + ROUND_SEEDS * r, workers, net))
        data = join(parts)
        timing[f"data_round_{r}"] = time.perf_counter() - t
        log(f"round {r}: {int(data['decision'].max()) + 1} decisions labelled in {timing[f'data_round_{r}']:.0f} s")
        t = time.perf_counter()
        net = fit_player(data, epochs=epochs, seed=seed, log=log, pots=pots, game=game, safeties=safeties,
                         combos=combos and safeties is not None)
        timing[f"fit_round_{r}"] = time.perf_counter() - t
    Path(out).mkdir(parents=True, exist_ok=True)
    net.save(Path(out) / "learned.npz")
    np.savez_compressed(Path(out) / "learned-data.npz", **data)
    t = time.perf_counter()
    by_noise = {str(n or "none"): match(LearnedPlayer(game, net), game, n, len(eval_seeds), int(eval_seeds[0]))
                for n in dict.fromkeys((noise, *EVAL_NOISES))}
    timing["evaluation"], timing["total"] = time.perf_counter() - t, time.perf_counter() - started
    result = {**by_noise[str(noise or "none")], "game": game, "noise": noise, "data_games": data_games,
              "rounds": rounds, "epochs": epochs, "pot_positions": pot_positions, "pot_games": pot_games,
              "safe_positions": safe_positions,
              "combos": combos and safeties is not None,
              "decisions": int(data["decision"].max()) + 1,
              "rows": len(data["values"]), "by_noise": by_noise, "seconds": timing}
    (Path(out) / "learned.json").write_text(json.dumps(result, indent=2))
    for name, r in by_noise.items():
        log(f"learned player against ghost_ball ({name}): {r['wins']:g}/{r['games']} = {r['win_rate']:.1%} "
            f"[{r['ci95'][0]:.1%}, {r['ci95'][1]:.1%}]")
    log(f"{timing['total']:.0f} s in all")
    return result


if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(description="make the learned player's data, fit it, play it")
    parser.add_argument("--games", type=int, default=100)
    parser.add_argument("--eval-games", type=int, default=100)
    parser.add_argument("--noise", default=None)
    parser.add_argument("--out", default="/tmp/learned")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--data-only", action="store_true")
    parser.add_argument("--net", default=None, help="positions from this net's games against the ghost-ball player")
    args = parser.parse_args()
    net = None if args.net is None else ValueNet.load(args.net)
    data = make_dataset("nine_ball", args.noise, args.games, seed=args.seed, net=net)
    np.savez_compressed(args.out + "-data.npz", **data)
    if args.data_only:
        raise SystemExit(0)
    net = fit_player(data)
    net.save(args.out + ".npz")
    print(match(LearnedPlayer("nine_ball", net), noise=args.noise, games=args.eval_games))
