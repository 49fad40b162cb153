"""`SearchAgent`: a PickPocket-style player that simulates candidate shots in one batch and plays the best."""

from __future__ import annotations

import math
import time

import gymnasium as gym
import numpy as np

import pool_env  # noqa: F401  (registers the envs)
from pool_env import rules
from pool_env.game import (
    GAME_BALLS,
    MAX_SPEED,
    Game,
    GameView,
    Shot,
    decode_action,
    encode_action,
    env_layout,
    placement_area,
)
from pool_env.physics import BALL_RADIUS, Physics, Table
from pool_env.players import Agent, GhostBallAgent, game_of

from .match import alternate, run_episode
from .search_candidates import Candidate, CandidateShots
from .search_plan import SearchPlanner
from .search_position import balls_of, decode, game_state, legal_mask
from .stats import wilson

# Values of an outcome (the shooter's view): a win, a pot with the position it leaves (from
# CONTINUE up to 1 with the best next shot's quality), a miss leaving the opponent a shot,
# a foul (ball in hand for the opponent), a loss.
WIN, CONTINUE, MISS, FOUL, LOSS = 1.0, 0.35, -0.55, -0.75, -1.0
PUSH_OUT_SPEEDS = (0.6, 1.3)  # m/s: the push outs tried, soft rolls of the cue ball ...
PUSH_OUT_TURNS = tuple(math.radians(a) for a in range(0, 360, 45))  # ... in eight directions
IN_HAND_QUALITY = 1.0  # the next shooter's quality with ball in hand
LOOKAHEAD_WORK = 150  # outcomes x legal balls the lookahead scores per decision (best plain value first)
SIMULATION_CHUNK, LOOKAHEAD_CHUNK = 64, 4  # with `seconds`: candidates simulated, looked ahead, between time checks
ROUND_KEEP = 0.25  # with rounds > 1: the share of the candidates (best mean value first) each round keeps


class SearchAgent(CandidateShots, Agent):
    """Plays by simulation (PickPocket-style): candidate shots (ghost-ball pots of every legal
    ball into every pocket at three speeds with stun, follow and draw and small aim
    corrections; kicks off each rail when no pot is on; safeties; with ball in hand, the
    best-ranked spots times their shots; on the break, spots x aims x speeds) are all
    simulated in one `simulate_batch` call (`noise_samples` draws each when the env has
    noise), judged by the rules and scored: a win, a pot plus the quality of the position it
    leaves (depth-1 lookahead: the best ghost-ball score of the next legal ball), a miss minus
    the opponent's best shot, a foul, a loss. The best mean value is played.

    The pots, the ball-in-hand spots' ranking and the lookahead's qualities are planned in
    batches on the compiled ghost-ball planner (`SearchPlanner`).

    `budget` caps the simulated shots per decision (candidates x noise samples); the lookahead
    covers the best candidates by their plain value (`LOOKAHEAD_WORK`). `seconds` (optional)
    caps the decision's wall time: the candidates (best prior first) are simulated
    `SIMULATION_CHUNK` at a time and the lookahead takes `LOOKAHEAD_CHUNK` candidates at a
    time, each batch only while the decision has used less than `seconds` (the first batch of
    simulations always runs; a candidate left unsimulated is not chosen). Decisions then depend
    on the machine's speed; without it they depend only on the seed and the observation.
    With noise, `rounds` > 1 spends the budget in that many rounds of sequential halving
    (`in_rounds`) and `common=True` gives the candidates of a batch the same noise draws
    (`Game.evaluate(common=True)`); both are off by default (docs/players.md measures them).
    `last_stats` holds the last decision's candidates, simulations, seconds and value."""

    name = "search"

    def __init__(self, game: str | None = "nine_ball", table: Table | None = None, physics: Physics | None = None,
                 noise: dict | None = None, spin: bool = True, budget: int = 600, noise_samples: int = 6,
                 seed: int | None = 0, lookahead: bool = True, threads: int = 1, seconds: float | None = None,
                 rule_options: dict | None = None, radius: float = BALL_RADIUS, decisions: bool = False,
                 rounds: int = 1, common: bool = False):
        if game is not None and game not in GAME_BALLS:
            raise ValueError(f"unknown game {game!r}; choose one of {', '.join(GAME_BALLS)} or None (PoolBreakRun-v0)")
        if int(budget) < 1 or int(noise_samples) < 1:
            raise ValueError(f"budget and noise_samples must be >= 1, got {budget!r}, {noise_samples!r}")
        if int(rounds) < 1 or (int(rounds) > 1 and seconds is not None):
            raise ValueError(f"rounds must be >= 1, and 1 with a time budget (seconds), got {rounds!r}")
        self.game, self.n_balls = game, GAME_BALLS.get(game, 16)
        self.table = Table.eight_foot() if table is None else table
        self.physics = Physics.standard() if physics is None else physics
        self.noise, self.spin, self.radius = noise, bool(spin or game is not None), radius
        self.budget, self.noise_samples = int(budget), int(noise_samples) if noise else 1
        self.lookahead, self.threads, self.seconds = bool(lookahead), int(threads), seconds
        self.rule_options = dict(rule_options or {})
        self.rounds, self.common = int(rounds), bool(common)
        self.plans = SearchPlanner(self.table, self.physics, radius)  # the pots, qualities and spots, at once
        self.scorer = GhostBallAgent(self.table, self.physics, radius=radius)  # its break shots (PoolBreakRun-v0)
        self.pockets = self.scorer.pockets
        self.seed = seed
        self.rng = np.random.default_rng(seed)
        self.last_stats: dict = {}
        # The game it plans on: the env's own rules and strike, at the position it decodes.
        layout = ("cue_spin" if self.spin else "cue") if game is None else \
            env_layout(game, decisions=decisions, calling=self.rule_options.get("calling"))
        self.sim = Game(game or "run", self.table, self.physics, noise, layout=layout, **self.rule_options)

    @classmethod
    def from_env(cls, env, **options) -> SearchAgent:
        """For a game env (PoolNineBall-v0, PoolEightBall-v0, the PettingZoo AEC envs), PoolBreakRun-v0 or a Game."""
        game = game_of(env)
        if game.has_rules:
            return cls(game=game.mode, table=game.base_table, physics=game.base_physics, noise=game.noise,
                       rule_options=game.rule_options, decisions=game.layout.decision, **options)
        return cls(game=None, table=game.base_table, physics=game.base_physics, spin=game.layout.spin, **options)

    def reset(self, seed: int | None = None) -> None:
        if seed is not None:
            self.seed = seed
        self.rng = np.random.default_rng(self.seed)

    # --- a decision ----------------------------------------------------------------------------
    def act(self, observation) -> np.ndarray:
        start = time.perf_counter()
        d = decode(observation, self.n_balls, self.table, game=self.game is not None)
        state = game_state(d, self.game, self.rule_options) if self.game is not None else None
        candidates = self.candidates(d, state)[: max(1, self.budget // self.noise_samples)]
        if self.rounds > 1 and self.noise:
            values, simulations = self.in_rounds(d, state, candidates)
        else:
            values, simulated = self.evaluate(d, state, candidates, start)
            simulations = simulated * self.noise_samples
        best = int(np.argmax(values))
        self.last_stats = {"candidates": len(candidates), "simulations": simulations,
                           "seconds": time.perf_counter() - start, "value": float(values[best]),
                           "kind": candidates[best].kind}
        if d.push_out:  # WPA 2.4: a push out, if one scores better than the best shot
            value, shot = self.push_out(d, state)
            if value > values[best]:
                self.last_stats.update(value=value, kind="push_out")
                return self.sim.encode(shot)
        return self.action(candidates[best], d.ball_in_hand)

    def push_out(self, d: GameView, state) -> tuple[float, Shot]:
        """(the mean value, the Shot) of the best push out from the decoded position: soft rolls
        of the cue ball (`PUSH_OUT_SPEEDS` x `PUSH_OUT_TURNS`) simulated with the noise draws;
        each legal one scored for both replies the opponent has (WPA 2.4): he shoots, worth
        MISS x q to us (q the shooter's best ghost-ball quality from there), or passes it back,
        worth CONTINUE + (1 - CONTINUE) q; he takes the one worse for us. A foul scores FOUL."""
        self.sim.reset(balls=balls_of(d, self.radius), state=state)
        shots = [Shot.aimed((math.cos(t), math.sin(t)), v, push_out=True)
                 for v in PUSH_OUT_SPEEDS for t in PUSH_OUT_TURNS]
        records = self.sim.evaluate(shots, draws=self.noise_samples, seed=self.rng, threads=self.threads)
        values = []
        for record in records:
            if record.error is not None or record.ruling.foul is not None:
                values.append(FOUL)
                continue
            balls = record.balls_after
            q = self.quality(balls.xy, ~balls.pocketed, rules.legal_targets(record.state_after))
            values.append(min(MISS * q, CONTINUE + (1.0 - CONTINUE) * q))
        means = np.array(values).reshape(len(shots), self.noise_samples).mean(axis=1)
        best = int(np.argmax(means))
        return float(means[best]), shots[best]

    # --- evaluation ------------------------------------------------------------------------------
    def evaluate(self, d: GameView, state, candidates, start) -> tuple[np.ndarray, int]:
        """(the mean value of each candidate over its noise samples, the candidates simulated):
        `Game.evaluate` of the candidates' actions (as the env reads them) from the decoded
        position, in one batch (with `seconds`, in chunks until the time is up; a candidate
        left unsimulated gets -inf)."""
        records, judged, plain = self.judged(d, state, candidates, start)
        done = len(records) // self.noise_samples
        if not self.lookahead:
            return plain, done
        values = plain - 10.0  # only the candidates that get the lookahead can be chosen
        self.look_ahead(values, self.looked_at(plain, done, d.legal), judged, start)
        return values, done

    def in_rounds(self, d: GameView, state, candidates) -> tuple[np.ndarray, int]:
        """(each candidate's mean value over its draws, the simulations made): the budget spent
        in `rounds` equal rounds (sequential halving). Round 1 simulates every candidate, each
        later round the best ROUND_KEEP of the last round's by their mean so far, each with as
        many noise draws as its share of the round's budget allows (at least one). Only the last
        round's candidates can be chosen (-inf for the rest): they have the most draws. Each
        draw is worth `draw_values`."""
        share = min(self.budget, len(candidates) * self.noise_samples) // self.rounds  # no more than one pass spends
        sums, counts = np.zeros(len(candidates)), np.zeros(len(candidates))
        alive = np.arange(len(candidates))
        for r in range(self.rounds):
            if r:
                best = np.argsort(-(sums[alive] / counts[alive]), kind="stable")
                alive = alive[best[: max(1, math.ceil(ROUND_KEEP * len(alive)))]]
            draws = max(1, share // len(alive))
            records = self.simulate(d, state, [candidates[c] for c in alive], None, draws)
            sums[alive] += self.draw_values(state, records).reshape(len(alive), draws).sum(axis=1)
            counts[alive] += draws
        values = np.full(len(candidates), -np.inf)
        values[alive] = sums[alive] / counts[alive]
        return values, int(counts.sum())

    def draw_values(self, state, records) -> np.ndarray:
        """(R,) the value of each simulated shot: `judge`d, then with the lookahead `deep_values`."""
        judged = [self.judge(state, record, None) for record in records]
        return self.deep_values(judged) if self.lookahead else np.array([v for v, _ in judged])

    def judged(self, d: GameView, state, candidates, start) -> tuple[list, list, np.ndarray]:
        """(the `simulate` records, each judged (`judge`), each candidate's mean plain value
        over its draws: -inf if left unsimulated)."""
        s = self.noise_samples
        records = self.simulate(d, state, candidates, start)
        judged = [self.judge(state, records[k], candidates[k // s]) for k in range(len(records))]
        plain = np.full(len(candidates), -np.inf)
        plain[: len(records) // s] = np.array([v for v, _ in judged]).reshape(-1, s).mean(axis=1)
        return records, judged, plain

    def looked_at(self, plain, done: int, legal) -> np.ndarray:
        """The candidates the lookahead scores: the best by their plain value, as many as
        LOOKAHEAD_WORK outcomes x legal balls allow (at least 4), among the `done` simulated."""
        return np.argsort(-plain)[: max(4, LOOKAHEAD_WORK // (self.noise_samples * max(1, len(legal))))][:done]

    def simulate(self, d: GameView, state, candidates, start, draws: int | None = None) -> list:
        """The `ShotRecord`s of the candidates' actions (as the env reads them) from the decoded
        position, `draws` (default `noise_samples`) draws each, candidate major: `Game.evaluate`
        in one batch (with `seconds`, `SIMULATION_CHUNK` candidates at a time while the time
        lasts)."""
        self.sim.reset(balls=balls_of(d, self.radius), state=state)
        area, pockets = self.sim.placement_area(), self.table.pockets.shape[0]  # as sim.decode reads them
        targets = self.sim.called_targets  # 10-ball: a pot calls the first, the lowest ball (its target)
        shots = [decode_action(self.sim.layout, self.action(cand, d.ball_in_hand, area), area, pockets, targets)
                 for cand in candidates]
        chunk = len(shots) if self.seconds is None else SIMULATION_CHUNK
        records = []
        for at in range(0, len(shots), chunk):
            if records and time.perf_counter() - start > self.seconds:
                break
            records += self.sim.evaluate(shots[at:at + chunk], draws=draws or self.noise_samples, seed=self.rng,
                                         threads=self.threads, records=False, common=self.common)
        return records

    def look_ahead(self, values, chosen, judged, start) -> None:
        """values[c] for each chosen candidate: its mean `deep_value`, the qualities of all their
        outcomes planned at once (with `seconds`, a few candidates at a time until the time is up)."""
        s = self.noise_samples
        chunk = len(chosen) if self.seconds is None else LOOKAHEAD_CHUNK
        for at in range(0, len(chosen), chunk):
            if self.seconds is not None and time.perf_counter() - start > self.seconds:
                break
            part = chosen[at:at + chunk]
            deep = self.deep_values([judged[c * s + k] for c in part for k in range(s)])
            for j, c in enumerate(part):
                values[c] = np.mean(deep[j * s:(j + 1) * s])

    def deep_values(self, judged) -> np.ndarray:
        """(R,) the `deep_value` of each judged shot ((plain value, info) as `judge` gives), the
        qualities of all the outcomes that need one planned in one batch."""
        asked = [i for _, i in judged if i is not None and (i[0] == "miss" or i[3] is None)]
        qualities = iter(self.qualities([i[1].xy for i in asked], [~i[1].pocketed for i in asked],
                                        [i[2] for i in asked]) if asked else ())
        return np.array([self.deep_value(v, info, qualities) for v, info in judged])

    def judge(self, state, record, cand):
        """(plain value, what the lookahead needs) of one simulated shot (a `ShotRecord`)."""
        if record.error is not None:
            return FOUL, None
        if state is None:  # PoolBreakRun-v0: no rules, a scratch ends the episode
            if record.outcome.cue_pocketed:
                return LOSS, None
            final = record.balls_after
            left = np.count_nonzero(~final.pocketed[1:])
            if left == 0:
                return WIN, None
            on = frozenset(int(b) for b in np.flatnonzero(~final.pocketed[1:]) + 1)
            kept = len(record.pocketed) > 0
            return (CONTINUE + 0.5 * (1 - CONTINUE)) if kept else MISS, ("self" if kept else "miss", final, on, None)
        after, ruling = record.state_after, record.ruling
        if ruling.winner is not None:
            return (WIN if ruling.winner == 0 else LOSS), None
        balls = record.balls_after
        legal = rules.legal_targets(after)
        if not ruling.turn_passed:
            return CONTINUE + 0.5 * (1 - CONTINUE), ("self", balls, legal, after.ball_in_hand)
        if ruling.foul is not None:
            return FOUL - (0.15 if after.fouls[0] >= 2 else 0.0), None
        return MISS * 0.5, ("opponent", balls, legal, None)

    def deep_value(self, value, info, qualities=None) -> float:
        """The value with the depth-1 lookahead: the next shooter's best ghost-ball quality
        (`qualities`: an iterator of the qualities of the outcomes that need one, in order;
        None: planned here)."""
        if info is None:
            return value
        who, balls, legal, in_hand = info
        if who != "miss" and in_hand is not None:
            q = IN_HAND_QUALITY
        else:
            q = self.quality(balls.xy, ~balls.pocketed, legal) if qualities is None else next(qualities)
        if who == "miss":  # PoolBreakRun-v0: our turn again after a miss
            return MISS + 0.5 * q
        return CONTINUE + (1.0 - CONTINUE) * q if who == "self" else MISS * q

    def quality(self, xy, on_table, legal) -> float:
        """The best ghost-ball score (capped at 1) of a legal ball into any pocket from this layout."""
        return float(self.qualities([xy], [on_table], [legal])[0])

    def qualities(self, xys, on_tables, legals) -> np.ndarray:
        """`quality` of many layouts (each an xy, on-table flags and legal balls), planned at once."""
        on = np.array(on_tables, dtype=bool)
        masks = np.array([legal_mask(legal, on.shape[1]) for legal in legals]).reshape(on.shape)
        return self.plans.qualities(np.array(xys, dtype=np.float64), on, masks, IN_HAND_QUALITY)

    def choose(self, game) -> str:
        """Its option of `game`'s pending decision (a `pool_env.game.Game` with decisions).
        After a push out it scores both replies from the position: shooting is worth its own
        best ghost-ball quality q there, passing leaves the opponent that shot (1 - q for it):
        it shoots when q >= 1/2. After an illegal 8-ball break it takes ball in hand; after the
        8 on the break it spots it."""
        pending = game.pending
        if pending is None:
            raise ValueError("no decision is pending")
        if pending.name == "push_out_reply":
            balls = game.balls
            q = self.quality(balls.xy, ~balls.pocketed, game.legal_targets)
            return "shoot" if q >= 1.0 - q else "pass"
        return {"illegal_break": "ball_in_hand", "eight_on_break": "spot_eight"}[pending.name]

    # --- the action ------------------------------------------------------------------------------
    def action(self, cand: Candidate, in_hand, area=False) -> np.ndarray:
        """The env's action for a candidate (`pool_env.game.encode_action` of its shot); `area`
        the placement area of `in_hand` if already known."""
        shot = Shot.aimed(cand.direction, min(cand.speed, MAX_SPEED), cand.tip, place=cand.spot, pocket=cand.pocket,
                          ball=cand.ball)
        if area is False:
            area = None if in_hand is None else placement_area(self.table, in_hand, self.radius)
        targets = self.sim.called_targets if self.sim.has_rules else ()  # the position's (simulate reset it)
        return encode_action(self.sim.layout, shot, area, max(self.table.pockets.shape[0], 1), targets)


# --- measuring ---------------------------------------------------------------------------------
def head_to_head(games: int = 20, seed: int = 0, env_id: str = "PoolNineBall-v0", noise=None, **options) -> dict:
    """`SearchAgent` against the env's ghost-ball opponent, alternating breaks, game k seeded
    `seed + k`: wins, the win rate and its 95 % interval, break-and-run rate (games the agent
    broke and won in its first turn), seconds per decision (median, p95)."""
    wins = breaks = runs = 0
    seconds = []
    for game_seed, agent_breaks, _ in alternate(range(seed, seed + games), True, False):
        won, first_turn = _head_to_head_game(env_id, noise, game_seed, agent_breaks, seconds, options)
        wins += won
        breaks += agent_breaks
        runs += won and first_turn and agent_breaks
    lo, hi = wilson(wins, games)
    return {"games": games, "wins": wins, "win_rate": wins / max(games, 1), "ci95": (lo, hi),
            "breaks": breaks, "break_and_runs": runs, "break_and_run_rate": runs / max(breaks, 1),
            "decisions": len(seconds), "median_seconds": float(np.median(seconds)) if seconds else 0.0,
            "p95_seconds": float(np.percentile(seconds, 95)) if seconds else 0.0}


def _head_to_head_game(env_id: str, noise, seed: int, agent_breaks: bool, seconds: list, options: dict) -> tuple:
    """One game of `head_to_head` on `seed`: (the agent won, it won in its first turn); each
    decision's seconds appended to `seconds`."""
    env = gym.make(env_id, opponent="ghost_ball", noise=noise, agent_breaks=agent_breaks)
    agent = SearchAgent.from_env(env, seed=seed, **options)
    opponent_shot = []

    def stepped(step):
        seconds.append(agent.last_stats["seconds"])
        if not (step.terminated or step.truncated) and step.info["opponent_shots"]:
            opponent_shot.append(True)

    end = run_episode(env, agent.act, seed, stepped, skip_finished=True)  # the opponent may run out in reset
    env.close()
    return end.info.get("winner") == 0, not opponent_shot  # the agent is player 0 (-1: no winner)


def clear_rate(episodes: int = 20, seed: int = 0, **options) -> dict:
    """`SearchAgent` in PoolBreakRun-v0: racks cleared (every object ball down, no scratch) and
    balls pocketed per episode, episode k seeded `seed + k`."""
    cleared, balls = 0, []
    for k in range(episodes):
        env = gym.make("PoolBreakRun-v0")
        agent = SearchAgent.from_env(env, seed=seed + k, **options)
        info = run_episode(env, agent.act, seed + k).info
        cleared += info["balls_left"] == 0 and not info["scratch"]
        balls.append(15 - info["balls_left"])
        env.close()
    lo, hi = wilson(cleared, episodes)
    return {"episodes": episodes, "cleared": cleared, "clear_rate": cleared / max(episodes, 1), "ci95": (lo, hi),
            "balls_per_episode": float(np.mean(balls)) if balls else 0.0}


def search_player(env, seed=None, **options) -> SearchAgent:
    """The player registry's "search" (`pool_env.make_player("search", env)`)."""
    return SearchAgent.from_env(env, seed=0 if seed is None else seed, **options)


if __name__ == "__main__":
    import argparse
    import json

    parser = argparse.ArgumentParser(description="SearchAgent against the ghost-ball player")
    parser.add_argument("--games", type=int, default=20)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--env-id", default="PoolNineBall-v0")
    parser.add_argument("--noise", default=None)
    args = parser.parse_args()
    if args.env_id == "PoolBreakRun-v0":
        print(json.dumps(clear_rate(args.games, args.seed), indent=1))
    else:
        print(json.dumps(head_to_head(args.games, args.seed, args.env_id, args.noise), indent=1))
