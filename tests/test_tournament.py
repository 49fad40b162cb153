"""agents.tournament: the JSON keys, the counts, Wilson and Elo by hand, break-and-run counting, determinism."""

import json
import math

import pytest

from agents import ratings as rating
from agents import tournament as tour
from agents.stats import wilson

GAMES = 4


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """random against ghost_ball, 4 games of 9-ball without noise, through the command line."""
    out = tmp_path_factory.mktemp("tournament")
    tour.main(["--game", "nine_ball", "--players", "random,ghost_ball", "--games", str(GAMES), "--noise", "none",
               "--seed", "7", "--out", str(out)])
    return json.loads((out / "tournament.json").read_text()), (out / "tournament.md").read_text()


def test_json_has_the_documented_keys(run):
    data, md = run
    for key in ("game", "games_per_pairing", "seed", "seeds", "noise", "player_specs", "elo_method", "results"):
        assert key in data
    assert data["game"] == "nine_ball" and data["noise"] == ["none"] and data["seeds"] == [7, 7 + GAMES - 1]
    result = data["results"]["none"]
    assert set(result) >= {"players", "skipped", "pairings", "elo", "stats", "records"}
    assert result["players"] == ["random", "ghost_ball"]
    for stats in result["stats"].values():
        for key in ("elo", "games", "wins", "breaks", "break_and_runs", "break_and_run_rate", "fouls_per_game",
                    "balls_per_turn", "decisions", "seconds_per_decision"):
            assert key in stats
    assert "| ghost_ball |" in md and "A's win rate" in md


def test_counts_add_up(run):
    result = run[0]["results"]["none"]
    (pairing,) = result["pairings"]
    assert pairing["games"] == GAMES
    assert pairing["wins_a"] + pairing["wins_b"] + pairing["draws"] == GAMES
    assert pairing["draws"] == 0  # random loses, by fouls or the ghost-ball player's run
    assert pairing["wins_a"] + pairing["wins_b"] == GAMES
    lo, hi = pairing["ci95"]
    assert lo <= pairing["win_rate_a"] <= hi
    assert [r["seed"] for r in result["records"]] == list(range(7, 7 + GAMES))
    assert [r["breaker"] for r in result["records"]] == ["random", "ghost_ball"] * (GAMES // 2)
    for name, stats in result["stats"].items():
        assert stats["games"] == GAMES and stats["breaks"] == GAMES // 2
        assert stats["decisions"] == sum(1 for r in result["records"] for s in r["shots"] if s["by"] == name)
        lo, hi = stats["break_and_run_ci95"]
        assert lo <= stats["break_and_run_rate"] <= hi


def test_wilson_by_hand():
    z = 1.959964
    # 5 of 10: centre 1/2; half-width z / (1 + z^2/10) * sqrt(0.25/10 + z^2/400)
    half = z / (1 + z * z / 10) * math.sqrt(0.025 + z * z / 400)
    assert wilson(5, 10) == pytest.approx((0.5 - half, 0.5 + half), abs=1e-12)
    assert half == pytest.approx(0.263407, abs=1e-6)
    # 0 of 4: the lower end is 0, the upper z^2 / (n + z^2)
    assert wilson(0, 4) == pytest.approx((0.0, z * z / (4 + z * z)), abs=1e-12)
    assert wilson(0, 0) == (0.0, 1.0)


def _record(a, b, winner):
    return {"players": [a, b], "breaker": a, "winner": winner, "shots": []}


def test_elo_ranks_the_stronger_player_higher(run):
    elo = run[0]["results"]["none"]["elo"]
    assert elo["ghost_ball"] > elo["random"]
    assert (elo["ghost_ball"] + elo["random"]) / 2 == pytest.approx(1500.0)
    # 4-0 with the virtual draw: 4.5 to 0.5, odds 9, a gap of 400 log10(9)
    ratings = rating.elo([_record("x", "y", "x") for _ in range(4)], ["x", "y"])
    assert ratings["x"] - ratings["y"] == pytest.approx(400 * math.log10(9), abs=1e-6)
    # a cycle of equal records: equal ratings, average 1500
    cycle = rating.elo([_record("x", "y", "x"), _record("y", "z", "y"), _record("z", "x", "z")], ["x", "y", "z"])
    assert all(r == pytest.approx(1500.0) for r in cycle.values())


def test_break_and_run_on_a_hand_built_record():
    shot = lambda by, foul=None, pocketed=(): {"by": by, "foul": foul, "pocketed": list(pocketed)}
    run_out = {"players": ["a", "b"], "breaker": "a", "winner": "a",
               "shots": [shot("a", pocketed=[2]), shot("a", pocketed=[1]), shot("a", pocketed=[3, 9])]}
    came_back = {"players": ["b", "a"], "breaker": "b", "winner": "b",
                 "shots": [shot("b"), shot("a", foul="scratch", pocketed=[0]), shot("b", pocketed=[9])]}
    lost_break = {"players": ["a", "b"], "breaker": "a", "winner": "b",
                  "shots": [shot("a", pocketed=[4]), shot("a"), shot("b", pocketed=[1, 9])]}
    assert rating.is_break_and_run(run_out)
    assert not rating.is_break_and_run(came_back) and not rating.is_break_and_run(lost_break)
    records = [run_out, came_back, lost_break]
    a, b = rating.player_stats(records, "a"), rating.player_stats(records, "b")
    assert (a["breaks"], a["break_and_runs"], a["break_and_run_rate"]) == (2, 1, 0.5)
    assert (b["breaks"], b["break_and_runs"]) == (1, 0)
    assert (a["wins"], b["wins"]) == (1, 2)
    # a: turns 1 + 1 + 1, balls 4 + 0 (the scratch's cue ball is no ball, and a foul pots nothing) + 1
    assert (a["turns"], a["balls"], a["fouls"]) == (3, 5, 1)
    assert a["balls_per_turn"] == pytest.approx(5 / 3) and a["fouls_per_game"] == pytest.approx(1 / 3)
    # b: turns 2 (came_back) + 1, balls 1 + 2
    assert (b["turns"], b["balls"], b["fouls"]) == (3, 3, 0)


def test_deterministic_apart_from_timings(run):
    again = tour.tournament("nine_ball", ["random", "ghost_ball"], games=GAMES, noise="none", seed=7)
    assert tour.strip_timings(json.loads(json.dumps(again))) == tour.strip_timings(run[0])


def test_an_unknown_player_is_an_error_naming_the_choices():
    with pytest.raises(ValueError, match="unknown player 'no/such/model.zip'"):
        tour.make_players(["random", "no/such/model.zip"], "nine_ball", None)
    choices = "carom_search, ghost_ball, learned, random, search"
    with pytest.raises(ValueError, match=f"unknown player 'serch'; choose one of {choices}"):
        tour.tournament("nine_ball", ["random", "serch"], games=1, noise="none")


def test_a_player_that_raises_forfeits():
    from pool_env.envs.game_env import PoolGameEnv
    from pool_env.players.base import RandomAgent

    class Broken(RandomAgent):
        def act(self, observation):
            raise ValueError("bug")

    env = PoolGameEnv("nine_ball", opponent=None)
    players = {"random": RandomAgent(env.action_space), "broken": Broken(env.action_space)}
    timers = {name: tour.Timed(agent, name) for name, agent in players.items()}
    record = tour.play_game("nine_ball", "random", "broken", players, timers, seed=0, noise=None)
    assert record["winner"] == "random" and record["forfeit"] == "broken"
    assert "ValueError: bug" in record["end_reason"]
    assert rating.player_stats([record], "broken")["forfeits"] == 1


def test_ten_ball_tournament_runs(tmp_path):
    # python -m agents.tournament --game ten_ball: the ghost-ball player beats the random one.
    tour.main(["--game", "ten_ball", "--players", "random,ghost_ball", "--games", "2", "--noise", "none",
               "--out", str(tmp_path)])
    elo = json.loads((tmp_path / "tournament.json").read_text())["results"]["none"]["elo"]
    assert elo["ghost_ball"] > elo["random"]
