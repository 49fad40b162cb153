"""`python -m agents.tournament`: a round-robin of named players at 9-ball, 8-ball or three-cushion: win rates, Elo."""

from __future__ import annotations

import argparse
import itertools
import json
import os
import sys
import time
from pathlib import Path

from pool_env.envs.carom_env import ThreeCushionEnv
from pool_env.envs.game_env import PoolGameEnv
from pool_env.players import make_player as registry_player
from pool_env.records.saved import RECORDED, GameRecorder, save_game
from pool_env.rules import codes

from .match import alternate, env_winner, player_seed, run_episode
from .ratings import ELO_METHOD, elo, pairing_stats, player_stats

NOISES = {"none": None, "olympiad": "olympiad"}
BUILTIN = ("random", "ghost_ball", "search", "learned", "search+value")  # the registry's players, by name
TIMING_KEYS = ("seconds", "seconds_per_decision", "wall_seconds")  # the only entries that differ between runs


ENV_IDS = {"nine_ball": "PoolNineBall-v0", "eight_ball": "PoolEightBall-v0", "ten_ball": "PoolTenBall-v0",
           "three_cushion": "ThreeCushion-v0", "snooker": "Snooker-v0"}
MAX_SHOTS = {"snooker": 300}  # the agent's shots before a game is stopped unfinished; else 100 (a frame is long)


def game_env(game: str, **kwargs):
    """The env a tournament game of `game` is played in: PoolGameEnv, or ThreeCushionEnv (to its
    default distance, 15 points) for three-cushion."""
    return ThreeCushionEnv(**kwargs) if game == "three_cushion" else PoolGameEnv(game, **kwargs)


class PlayerError(Exception):
    """A player's act() raised: it forfeits the game (`play_game`)."""

    def __init__(self, name: str, error: Exception):
        super().__init__(f"{name}: {type(error).__name__}: {error}")
        self.name = name


class Timed:
    """A player's act() with its decisions counted and timed (perf_counter); an exception in it
    becomes a PlayerError naming the player."""

    def __init__(self, agent, name: str = "player"):
        self.agent, self.name, self.decisions, self.seconds = agent, name, 0, 0.0

    def __call__(self, observation):
        start = time.perf_counter()
        try:
            action = self.agent.act(observation)
        except Exception as exc:
            raise PlayerError(self.name, exc) from exc
        finally:
            self.seconds += time.perf_counter() - start
            self.decisions += 1
        return action


# --- players ------------------------------------------------------------------------------------
def display_name(spec: str) -> str:
    """A player's name in the tables: the built-in name, or runs/<name>/model.zip -> <name>."""
    if spec in BUILTIN:
        return spec
    path = Path(spec)
    return path.parent.name if path.stem in ("model", "best_model", "last_model") and path.parent.name else path.stem


def make_player(spec: str, env):
    """The agent named `spec` for `env` (a PoolGameEnv): `pool_env.make_player`'s (a built-in
    name, "search", a saved model's path), or raises ValueError saying why not."""
    return registry_player(spec, env, seed=0)


def make_players(specs: list[str], game: str, noise) -> tuple[dict, dict]:
    """({name: agent}, {name: why it was skipped}) for one game and noise setting. A name no
    player answers to is an error (ValueError naming the choices); a player that is built but
    fails its warm-up is skipped, saying why."""
    env = game_env(game, opponent=None, noise=noise)
    players, skipped = {}, {}
    for spec in specs:
        name = display_name(spec)
        agent = make_player(spec, env)  # an unknown name or a missing model file raises here
        try:
            agent.act(env.reset(seed=0)[0])  # warm-up, untimed (compiles, caches); reset before each game
            players[name] = agent
        except Exception as exc:  # noqa: BLE001 (a player whose warm-up fails is skipped, saying why)
            skipped[name] = f"{type(exc).__name__}: {exc}"
            print(f"tournament: skipping player {name!r} ({skipped[name]})", file=sys.stderr)
    env.close()
    return players, skipped


# --- playing -------------------------------------------------------------------------------------
def play_game(game: str, breaker: str, other: str, players: dict, timers: dict, seed: int, noise,
              max_shots: int | None = None, save_to=None) -> dict:
    """One game on `seed`: the breaker is the env's agent (it breaks), the other its opponent, so each
    sees the observation from its own side (so the breaker never plays inside the env's reset:
    its break-and-runs all count).
    `save_to`: also save the game there (`game_recorder`). `max_shots`: the agent's shot limit
    (default `MAX_SHOTS` of the game, else 100)."""
    max_shots = MAX_SHOTS.get(game, 100) if max_shots is None else max_shots
    for slot, name in enumerate((breaker, other)):
        if hasattr(players[name], "reset"):
            players[name].reset(seed=player_seed(seed, slot))
    env = game_env(game, opponent=timers[other], noise=noise, agent_breaks=True, max_shots=max_shots)
    recorder = None if save_to is None else game_recorder(env, seed, noise, max_shots)
    shots = []

    def act(obs):
        action = timers[breaker](obs)
        return action if recorder is None else recorder.action(action)

    def stepped(step):
        if recorder is not None:
            recorder.stepped(*step)
        shots.extend(step_shots(env.step_records, breaker, other))

    try:
        info, forfeit = run_episode(env, act, seed, stepped).info, None
    except PlayerError as exc:  # the player that raised forfeits (this step's shots are lost)
        forfeit = exc
    env.close()
    if recorder is not None:
        save_game(save_to, {**recorder.record(), "players": [breaker, other]})
    if forfeit is not None:
        winner, reason = (other if forfeit.name == breaker else breaker), f"forfeit ({forfeit})"
        return {"seed": int(seed), "players": [breaker, other], "breaker": breaker, "winner": winner,
                "end_reason": reason, "forfeit": forfeit.name, "shots": shots}
    winner = env_winner(info, breaker, other)
    if winner is not None:  # three-cushion's infos carry no end-reason code: its last ruling says
        reason = codes.decode("end_reason", info["end_reason"]) if "end_reason" in info \
            else env.step_records[-1].ruling.end_reason
    else:
        reason = "error" if info.get("error") else ("draw" if info.get("draw") else "max_shots")
    return {"seed": int(seed), "players": [breaker, other], "breaker": breaker, "winner": winner,
            "end_reason": reason, "shots": shots}


def step_shots(records, breaker: str, other: str) -> list[dict]:
    """The shots of one env step as the tournament logs them (who, the foul's name, the object
    balls pocketed), from its `ShotRecord`s: the breaker's (the env's agent, player 0) first,
    then the opponent's that were played (a shot that failed ends the step)."""
    if not records:  # no shot of the agent (its game ended in reset)
        return [{"by": breaker, "foul": None, "pocketed": []}]
    return [{"by": breaker if r.shooter == 0 else other, "foul": r.foul, "pocketed": [int(b) for b in r.pocketed]}
            for r in records if r is records[0] or r.error is None]


def game_recorder(env, seed: int, noise, max_shots: int):
    """A `pool_env.records.saved.GameRecorder` for a tournament game: the breaker's actions and the other
    player's (as the recorded opponent), under the env id and kwargs that replay it exactly
    (`pool_env.records.replay`, `python -m pool_env.records.replay`: the breaker is the agent)."""
    env_id = ENV_IDS[env.game.mode]
    kwargs = {"game": env.game.mode, "opponent": RECORDED, "noise": noise, "agent_breaks": True, "max_shots": max_shots}
    if env.game.mode == "three_cushion":  # ThreeCushion-v0 plays one game
        del kwargs["game"]
    return GameRecorder(env, seed, record_opponent=True, env_id=env_id, env_kwargs=kwargs)


def play_pairing(game: str, a: str, b: str, players: dict, timers: dict, games: int, seed: int, noise,
                 save_games=None) -> list[dict]:
    """Games k = 0 .. games - 1 of A against B on seeds seed + k; A breaks the even ones. With
    `save_games` (a folder) each is saved as <breaker>-vs-<other>-seed<seed>.json."""
    records = []
    for game_seed, breaker, other in alternate(range(seed, seed + games), a, b):
        save_to = None if save_games is None else Path(save_games) / f"{breaker}-vs-{other}-seed{game_seed}.json"
        records.append(play_game(game, breaker, other, players, timers, game_seed, noise, save_to=save_to))
    return records


def run_setting(game: str, specs: list[str], games: int, seed: int, noise_name: str, log=None,
                save_games=None) -> dict:
    """The round-robin for one noise setting: pairings, Elo, per-player statistics, game records."""
    players, skipped = make_players(specs, game, NOISES[noise_name])
    names = list(players)
    if len(names) < 2:
        raise ValueError(f"need at least two players, got {names} (skipped: {skipped})")
    timers = {name: Timed(agent, name) for name, agent in players.items()}
    records, pairings = [], []
    for a, b in itertools.combinations(names, 2):
        start = time.perf_counter()
        folder = None if save_games is None else Path(save_games) / game / noise_name
        mine = play_pairing(game, a, b, players, timers, games, seed, NOISES[noise_name], folder)
        records += mine
        pairings.append(pairing_stats(mine, a, b))
        if log is not None:
            p = pairings[-1]
            log(f"[{noise_name}] {a} vs {b}: {p['wins_a']}-{p['wins_b']} (draws {p['draws']}) "
                f"in {time.perf_counter() - start:.1f} s")
    ratings = elo(records, names)
    stats = {name: {"elo": ratings[name], **player_stats(records, name, timers[name])} for name in names}
    return {"players": names, "skipped": skipped, "pairings": pairings, "elo": ratings, "stats": stats,
            "records": records}


def tournament(game: str = "nine_ball", players=("random", "ghost_ball"), games: int = 20, noise: str = "none",
               seed: int = 0, log=None, save_games=None) -> dict:
    """The whole tournament (the content of tournament.json): one round-robin per noise setting
    (`noise`: "none", "olympiad" or "both"), every pairing on seeds seed .. seed + games - 1.
    `save_games`: a folder; every game is saved in <folder>/<game>/<noise>/ (`play_pairing`)."""
    if game not in ENV_IDS:
        raise ValueError(f"unknown game {game!r}; choose one of {', '.join(ENV_IDS)}")
    settings = list(NOISES) if noise == "both" else [noise]
    if any(s not in NOISES for s in settings):
        raise ValueError(f"noise must be 'none', 'olympiad' or 'both', got {noise!r}")
    if int(games) != games or games < 1:
        raise ValueError(f"games must be an integer >= 1, got {games!r}")
    start = time.perf_counter()
    results = {s: run_setting(game, list(players), int(games), int(seed), s, log, save_games) for s in settings}
    return {"game": game, "games_per_pairing": int(games), "seed": int(seed),
            "seeds": [int(seed), int(seed) + games - 1], "noise": settings, "player_specs": list(players),
            "elo_method": ELO_METHOD,
            "win_rate": "(wins + draws / 2) / games, 95 % Wilson score interval",
            "break_and_run": "games the breaker won without the opponent ever shooting, over the games it broke",
            "balls_per_turn": "object balls pocketed on shots without a foul, over the player's turns at the table",
            "results": results, "wall_seconds": time.perf_counter() - start}


def strip_timings(data):
    """`data` without the TIMING_KEYS (what two runs on the same seeds share exactly)."""
    if isinstance(data, dict):
        return {k: strip_timings(v) for k, v in data.items() if k not in TIMING_KEYS}
    if isinstance(data, list):
        return [strip_timings(v) for v in data]
    return data


def percent(p: float, ci=None) -> str:
    """A proportion as a whole percentage, with its interval in brackets if given: "45 % [36, 55]"."""
    return f"{100 * p:.0f} %" + (f" [{100 * ci[0]:.0f}, {100 * ci[1]:.0f}]" if ci is not None else "")


def markdown(result: dict) -> str:
    """The tournament as markdown: per noise setting, the pairings and the players' table."""
    game = {"nine_ball": "9-ball", "eight_ball": "8-ball"}.get(result["game"], result["game"])
    lines = [f"# Tournament: {game}, {result['games_per_pairing']} games per pairing, "
             f"seeds {result['seeds'][0]}-{result['seeds'][1]}, breaks alternating", ""]
    for setting, r in result["results"].items():
        lines += [f"## Noise: {setting}", "", "| A | B | games | A wins | B wins | draws | A's win rate [95 % CI] |",
                  "| --- | --- | ---: | ---: | ---: | ---: | --- |"]
        lines += [f"| {p['a']} | {p['b']} | {p['games']} | {p['wins_a']} | {p['wins_b']} | {p['draws']} | "
                  f"{percent(p['win_rate_a'], p['ci95'])} |" for p in r["pairings"]]
        lines += ["", "| player | Elo | games | score | break-and-run [95 % CI] | fouls / game | balls / turn "
                  "| s / decision |", "| --- | ---: | ---: | ---: | --- | ---: | ---: | ---: |"]
        for name in sorted(r["players"], key=lambda n: -r["elo"][n]):
            s = r["stats"][name]
            runs = percent(s["break_and_run_rate"], s["break_and_run_ci95"])
            lines.append(f"| {name} | {s['elo']:.0f} | {s['games']} | {percent(s['score'])} | "
                         f"{s['break_and_runs']}/{s['breaks']} = {runs} | {s['fouls_per_game']:.2f} | "
                         f"{s['balls_per_turn']:.2f} | "
                         f"{s.get('seconds_per_decision', float('nan')):.4f} |")
        forfeits = {name: r["stats"][name]["forfeits"] for name in r["players"] if r["stats"][name]["forfeits"]}
        if forfeits:
            lines += ["", "Forfeits (games lost because the player's act() raised): "
                      + ", ".join(f"{name} {n}" for name, n in forfeits.items())]
        if r["skipped"]:
            lines += [""] + [f"Skipped {name}: {why}" for name, why in r["skipped"].items()]
        lines.append("")
    lines += [f"Elo: {result['elo_method']}.", ""]
    return "\n".join(lines)


def write(result: dict, out) -> tuple[Path, Path]:
    """tournament.json and tournament.md in the folder `out` (created)."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "tournament.json").write_text(json.dumps(result, indent=1) + "\n")
    (out / "tournament.md").write_text(markdown(result))
    return out / "tournament.json", out / "tournament.md"


PROG = "python -m agents.tournament"


def main(argv=None) -> dict:
    """The command: the options checked before any game (a bad one, or an error later, ends in one
    line on stderr and exit status 2; --debug or POOL_ENV_DEBUG=1: the traceback); returns the result."""
    parser = argparse.ArgumentParser(prog=PROG, description=__doc__)
    parser.add_argument("--game", default="nine_ball", choices=tuple(ENV_IDS))
    parser.add_argument("--players", default="random,ghost_ball,search,learned,search+value",
                        help="comma list: random, ghost_ball, search, learned, search+value (9-ball), carom_search "
                        "(three-cushion), or an SB3 model's path (runs/<name>/model.zip)")
    parser.add_argument("--games", type=int, default=20, help="games per pairing (breaks alternate)")
    parser.add_argument("--noise", default="both", choices=("none", "olympiad", "both"))
    parser.add_argument("--seed", type=int, default=0, help="game k of every pairing is played on seed + k")
    parser.add_argument("--out", default="runs/tournament", help="folder for tournament.json and tournament.md")
    parser.add_argument("--save-games", metavar="DIR", help="save every game (pool_env.save_game) in "
                        "DIR/<game>/<noise>/<breaker>-vs-<other>-seed<seed>.json "
                        "(python -m pool_env.records.replay replays it)")
    parser.add_argument("--debug", action="store_true", help="on an error, the full traceback instead of one line "
                        "(also POOL_ENV_DEBUG=1)")
    args = parser.parse_args(argv)
    players = [p.strip() for p in args.players.split(",") if p.strip()]
    log = lambda message: print(message, file=sys.stderr, flush=True)
    try:
        check_args(args, players)
        result = tournament(args.game, players, args.games, args.noise, args.seed, log, args.save_games)
        paths = write(result, args.out)
    except (ValueError, OSError) as exc:  # a bad option or player name; --out or --save-games not writable
        if args.debug or os.environ.get("POOL_ENV_DEBUG", "") not in ("", "0"):
            raise
        parser.exit(2, f"{PROG}: {exc}\n")
    print(markdown(result))
    log(f"wrote {paths[0]} and {paths[1]} in {result['wall_seconds']:.1f} s")
    return result


def check_args(args, specs: list[str]) -> None:
    """ValueError naming what is wrong with the options, before any game is played: a player name
    that `pool_env.make_player` does not resolve (make_players would only skip it), fewer than two
    players, a name given twice, --games under 1."""
    if args.games < 1:
        raise ValueError(f"--games must be >= 1, got {args.games}")
    names = [display_name(spec) for spec in specs]
    twice = sorted({name for name in names if names.count(name) > 1})
    if twice:
        raise ValueError(f"--players names {', '.join(twice)} more than once")
    if len(names) < 2:
        raise ValueError(f"--players needs at least two players, got {', '.join(names) or 'none'}")
    env = game_env(args.game, opponent=None)
    for spec in specs:
        try:
            make_player(spec, env)  # the name resolved and the player built; its warm-up (a compile) waits
        except ValueError as exc:
            raise ValueError(f"--players: {exc}") from exc
        except Exception:  # noqa: BLE001 (built but broken: make_players skips it, saying why, as before)
            pass
    env.close()


if __name__ == "__main__":
    main()
