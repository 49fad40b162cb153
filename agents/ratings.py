"""A tournament's statistics from its game records: Elo ratings, each player's totals, each pairing's score."""

from __future__ import annotations

import math

import numpy as np

from .stats import wilson

ELO_BASE, ELO_SCALE = 1500.0, 400.0  # ratings average ELO_BASE; a gap of ELO_SCALE is 10:1 odds
ELO_METHOD = ("Bradley-Terry maximum likelihood on the Elo scale (P(i beats j) = 1 / (1 + 10^((R_j - R_i) / 400))), "
              "fitted by the minorize-maximize iteration over every game of the noise setting (a draw counts half a "
              "win each), with one virtual draw added between every two players that met so that a perfect record "
              "stays finite; ratings shifted to average 1500")


def elo(records: list[dict], players: list[str], iterations: int = 10_000, tol: float = 1e-10) -> dict[str, float]:
    """Elo ratings of `players` from game records (ELO_METHOD): {name: rating}."""
    index = {name: k for k, name in enumerate(players)}
    n = len(players)
    wins, met = np.zeros((n, n)), np.zeros((n, n), dtype=bool)
    for record in records:
        i, j = index[record["players"][0]], index[record["players"][1]]
        met[i, j] = met[j, i] = True
        if record["winner"] is None:
            wins[i, j] += 0.5
            wins[j, i] += 0.5
        else:
            w = index[record["winner"]]
            wins[w, j if w == i else i] += 1.0
    wins += 0.5 * met  # the virtual draw
    games = wins + wins.T
    strength = np.ones(n)
    for _ in range(iterations):
        pair = games / np.maximum(strength[:, None] + strength[None, :], 1e-300)
        new = np.where(games.sum(1) > 0, wins.sum(1) / np.maximum(pair.sum(1), 1e-300), 1.0)
        new /= math.exp(np.mean(np.log(new)))
        done = np.max(np.abs(np.log(new) - np.log(strength))) < tol
        strength = new
        if done:
            break
    ratings = ELO_SCALE * np.log10(strength)
    ratings += ELO_BASE - ratings.mean()
    return {name: float(ratings[index[name]]) for name in players}


def is_break_and_run(record: dict) -> bool:
    """The breaker won without the opponent ever coming to the table (won in the first turn)."""
    return record["winner"] == record["breaker"] and all(shot["by"] == record["breaker"] for shot in record["shots"])


def player_stats(records: list[dict], name: str, timer=None) -> dict:
    """One player's totals over the records of the games it played; with `timer` (a
    `tournament.Timed`: its decisions and seconds), its time per decision."""
    mine = [r for r in records if name in r["players"]]
    breaks = [r for r in mine if r["breaker"] == name]
    shots = [shot for r in mine for shot in r["shots"] if shot["by"] == name]
    turns = sum(1 for r in mine for k, shot in enumerate(r["shots"])
                if shot["by"] == name and (k == 0 or r["shots"][k - 1]["by"] != name))
    balls = sum(len([b for b in shot["pocketed"] if b != 0]) for shot in shots if shot["foul"] is None)
    fouls = sum(1 for shot in shots if shot["foul"] is not None)
    wins = sum(1 for r in mine if r["winner"] == name)
    draws = sum(1 for r in mine if r["winner"] is None)
    runs = sum(1 for r in breaks if is_break_and_run(r))
    out = {"games": len(mine), "wins": wins, "draws": draws, "score": (wins + 0.5 * draws) / max(len(mine), 1),
           "breaks": len(breaks), "break_and_runs": runs, "break_and_run_rate": runs / max(len(breaks), 1),
           "break_and_run_ci95": list(wilson(runs, len(breaks))), "shots": len(shots), "turns": turns,
           "balls": balls, "balls_per_turn": balls / max(turns, 1), "fouls": fouls,
           "fouls_per_game": fouls / max(len(mine), 1), "forfeits": sum(1 for r in mine if r.get("forfeit") == name)}
    if timer is not None:
        out.update(decisions=timer.decisions, seconds=timer.seconds,
                   seconds_per_decision=timer.seconds / max(timer.decisions, 1))
    return out


def pairing_stats(records: list[dict], a: str, b: str) -> dict:
    """A against B over their games: wins, draws, A's score ((wins + draws / 2) / games) with its Wilson interval."""
    mine = [r for r in records if set(r["players"]) == {a, b}]
    wins_a = sum(1 for r in mine if r["winner"] == a)
    wins_b = sum(1 for r in mine if r["winner"] == b)
    draws = len(mine) - wins_a - wins_b
    score = wins_a + 0.5 * draws
    return {"a": a, "b": b, "games": len(mine), "wins_a": wins_a, "wins_b": wins_b, "draws": draws,
            "win_rate_a": score / max(len(mine), 1), "ci95": list(wilson(score, len(mine)))}
