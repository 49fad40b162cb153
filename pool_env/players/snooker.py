"""The built-in snooker player: ghost-ball pots of the ball on and safeties, chosen by `Game.evaluate`."""

from __future__ import annotations

import math

import numpy as np

from ..game import Game, Shot, decode_snooker_observation
from ..physics import BALL_MASS, Balls
from ..rules.snooker import SnookerState, next_ball_on
from ..rules.snooker_spots import REDS, baulk_x, d_radius
from .base import Agent, game_of
from .geometry import path_clear, pocket_aim, pockets_of, separated, start_speed, unit

MAX_CUT = math.radians(70.0)  # thinner cuts are not tried
ARRIVAL = 0.5  # m/s: the object ball's speed as it reaches the pocket's mouth
MAX_SPEED = 6.0  # m/s
TIPS = ((0.0, 0.0), (0.0, -0.3), (0.0, 0.3))  # centre, draw, follow (in R)
POTS_KEPT = 6  # the easiest pots evaluated (each with every tip and two speeds)
SAFETY_SPEEDS = (1.2, 2.0, 3.5)  # m/s
SAFETY_BALLS = 4  # the nearest balls on a safety is tried against
POSITION_BONUS = 0.6  # per easy pot left for the next shot (up to 3), after a scoring shot


class SnookerPlayer(Agent):
    """Plays the `Game` it is given (or an env's, `from_env`): `decide()` returns the `Shot` for
    the position now. Candidates: for every ball on and pocket with an open path (`pocket_aim`),
    the ghost-ball aim at two speeds and three tips, the easiest POTS_KEPT pots; and safeties,
    soft and medium hits on the nearest balls on. Every candidate is played once by
    `Game.evaluate` (the game's noise included) and the best is chosen: points scored, a bonus
    for keeping the visit and for easy pots left, minus the penalty of a foul; a shot that
    scores nothing is judged by how far the cue ball ends from the opponent's balls on. With
    the cue ball in hand it tries five spots of the D."""

    name = "snooker"

    def __init__(self, game: Game, seed: int | None = None):
        if not isinstance(game, Game) or game.mode != "snooker":
            raise ValueError(f"SnookerPlayer plays a snooker Game, got {game!r}")
        self.game = game
        self.planner = Game("snooker", table=game.base_table, physics=game.base_physics, noise=game.noise,
                            layout=game.layout.name, **game.rule_options)
        self.pockets = pockets_of(game.base_table)
        self.rng = np.random.default_rng(seed)

    @classmethod
    def from_env(cls, env, seed: int | None = None) -> SnookerPlayer:
        return cls(game_of(env), seed)

    def reset(self, seed: int | None = None) -> None:
        if seed is not None:
            self.rng = np.random.default_rng(seed)

    def act(self, observation=None) -> np.ndarray:
        """The action (the game's layout) of the shot to play: from the position `observation`
        shows (a snooker observation of the game's table, from the shooter's side), set up in a
        planning game of the player's own; without one, from its game's position now."""
        if observation is None:
            return self.game.encode(self.decide())
        self.planner.reset(balls=self.balls_seen(observation), state=self.state_seen(observation))
        return self.planner.encode(self.decide(self.planner))

    def decide(self, game: Game | None = None) -> Shot:
        """The shot to play from `game`'s position now (default: the player's game; it does not change)."""
        game = self.game if game is None else game
        candidates = self.candidates(game)
        records = game.evaluate(candidates, draws=1, seed=int(self.rng.integers(2**63 - 1)))
        values = [self.value(game, record) for record in records]
        return candidates[int(np.argmax(values))]

    def balls_seen(self, observation) -> Balls:
        """The balls an observation shows, its float32 rounding undone where two balls would overlap."""
        view = decode_snooker_observation(observation, self.game.table)
        radius = float(np.max(self.game.balls.radii))
        xy = separated(view.xy, ~view.on_table, radius)
        return Balls(xy, pocketed=~view.on_table, radius=radius, mass=float(self.game.balls.masses[0]))

    def state_seen(self, observation) -> SnookerState:
        """The frame an observation shows, the viewer as player 0 to shoot (the score as the
        observation gives it; a break-off when all 21 balls stand, 0-0, the cue ball in the D)."""
        view = decode_snooker_observation(observation, self.game.table)
        on_table = frozenset(int(b) for b in np.flatnonzero(view.on_table[1:]) + 1)
        is_break = view.in_hand and len(on_table) == 21 and view.scores == (0, 0)
        return SnookerState(self.game.state.rules, on_table, shooter=0, scores=view.scores, ball_on=view.ball_on,
                            ball_in_hand="in_d" if view.in_hand else None, free_ball=view.free_ball,
                            is_break=is_break, visit=view.visit)

    # --- candidates -------------------------------------------------------------------------
    def cue_spots(self, game: Game) -> list:
        balls = game.balls
        if game.ball_in_hand is None:
            return [balls.xy[0].copy()]
        cx, cy, r = baulk_x(game.table), 0.5 * game.table.width, d_radius(game.table) * 0.9
        return [np.array([cx - r * math.cos(a), cy + r * math.sin(a)]) for a in (-1.2, -0.6, 0.0, 0.6, 1.2)] \
            + [np.array([cx - 0.01, cy])]

    def candidates(self, game: Game) -> list:
        place = game.ball_in_hand is not None
        pots, safeties = [], []
        for cue in self.cue_spots(game):
            pots += self.pots(game, cue, place)
            safeties += self.safeties(game, cue, place)
        pots.sort(key=lambda p: p[0])
        shots = [shot for _, shots in pots[:POTS_KEPT] for shot in shots]
        return shots + safeties

    def pots(self, game: Game, cue, place) -> list:
        """(difficulty, shots) of each open pot of a ball on from `cue`."""
        balls = game.balls
        r = float(balls.radii[0])
        on = ~balls.pocketed
        on[0] = False
        out = []
        for target in sorted(game.legal_targets):
            obj = balls.xy[target]
            others = balls.xy[on & (np.arange(len(balls)) != target)]
            for pocket in self.pockets:
                aim = pocket_aim(obj, pocket, game.table, r, others, samples=11)
                if aim is None:
                    continue
                point, _ = aim
                to_pocket = unit(point - obj)
                ghost = obj - 2.0 * r * to_pocket
                line = ghost - cue
                d1, d2 = float(np.hypot(*line)), float(np.hypot(*(point - obj)))
                if d1 < 1e-6:
                    continue
                cut = math.acos(max(-1.0, min(1.0, float(np.dot(unit(line), to_pocket)))))
                if cut > MAX_CUT or not path_clear(cue, ghost, others, 2.0 * r * 1.02):
                    continue
                v_obj = start_speed(ARRIVAL, d2, game.physics)
                v_contact = v_obj / max(math.cos(cut), 0.3) / 0.98
                v0 = min(start_speed(v_contact, d1, game.physics), MAX_SPEED)
                shots = [self.shot(game, line, v, tip, cue if place else None)
                         for v in (v0, min(1.4 * v0, MAX_SPEED)) for tip in TIPS]
                out.append(((d1 + d2) * (1.0 + 3.0 * cut), shots))
        return out

    def safeties(self, game: Game, cue, place) -> list:
        balls = game.balls
        targets = sorted(game.legal_targets, key=lambda b: float(np.hypot(*(balls.xy[b] - cue))))
        out = []
        for target in targets[:SAFETY_BALLS]:
            line = balls.xy[target] - cue
            if float(np.hypot(*line)) < 1e-6:
                continue
            for v in SAFETY_SPEEDS:
                out.append(self.shot(game, line, v, (0.0, 0.0), cue if place else None))
        return out

    def shot(self, game: Game, direction, speed, tip, place) -> Shot:
        # Shot.aimed's speed is a pool ball's (its mass): scaled so a snooker ball leaves at `speed`.
        mass = float(game.balls.masses[0])
        return Shot.aimed(direction, speed * mass / BALL_MASS, tip, None if place is None else tuple(place))

    # --- judging ------------------------------------------------------------------------------
    def value(self, game: Game, record) -> float:
        if record.error is not None:
            return -100.0
        ruling, state = record.ruling, record.state_after
        if ruling.penalty:
            return -float(ruling.penalty)
        me = record.shooter
        if state.winner is not None:
            return 1000.0 if state.winner == me else -1000.0
        if ruling.points:
            return ruling.points + 1.0 + POSITION_BONUS * min(self.easy_pots(game, record), 3)
        return 0.3 * self.distance_left(record)

    def easy_pots(self, game: Game, record) -> int:
        """Open pots of the next ball on from where the cue ball stopped (a count, up to 3)."""
        balls, state = record.balls_after, record.state_after
        r = float(balls.radii[0])
        cue = balls.xy[0]
        on = ~balls.pocketed
        on[0] = False
        count = 0
        for target in sorted(game.state.rules.legal_targets(state))[:8]:
            others = balls.xy[on & (np.arange(len(balls)) != target)]
            obj = balls.xy[target]
            for pocket in self.pockets:
                aim = pocket_aim(obj, pocket, game.table, r, others, samples=7)
                if aim is None:
                    continue
                to_pocket = unit(aim[0] - obj)
                ghost = obj - 2.0 * r * to_pocket
                line = ghost - cue
                cut_ok = float(np.dot(unit(line), to_pocket)) > math.cos(MAX_CUT)
                if cut_ok and path_clear(cue, ghost, others, 2.04 * r):
                    count += 1
                    if count >= 3:
                        return count
        return count

    def distance_left(self, record) -> float:
        """How far (m, up to 1.5) the cue ball ends from the opponent's nearest ball on."""
        balls, state = record.balls_after, record.state_after
        if balls.pocketed[0]:
            return 0.0
        on = REDS & state.on_table if next_ball_on(state.on_table) == "red" else {next_ball_on(state.on_table)}
        d = [float(np.hypot(*(balls.xy[b] - balls.xy[0]))) for b in on]
        return min(min(d, default=0.0), 1.5)
