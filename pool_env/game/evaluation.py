"""`Game.evaluate`: K shots x M noise draws from one state; records=False simulates in compiled calls, judges once."""

from __future__ import annotations

import copy
from dataclasses import dataclass

import numpy as np

from .. import rules
from ..physics import Balls
from ..physics.batch_run import balls_at, simulate_level_batch
from ..physics.kinds import DONE, POCKETED
from .batch import simulate_struck, simulate_struck_batch
from .modes import Mode
from .shot import Shot
from .striking import check_can_shoot, shot_and_action, struck_or_failed

NORMALS_PER_DRAW = 4  # `shot.noisy_shot`'s: aim, speed, side, top (and the elevation of an elevated cue)


class DrawnNormals:
    """Stands in for a `numpy.random.Generator` in `shot.noisy_shot`, which asks it only for
    `normal(0, sigma)`: the normals of all of a shot's draws come from one `standard_normal`
    call, made at the first ask (`arm` says how many the shot takes; a shot that fails before
    its noise is drawn takes none). A Generator's `normal(loc, scale)` is loc + scale times
    its next standard normal, so the values, and the generator after them, are bit for bit
    those of the calls one by one. With `common_draws` (common random numbers) the normals of
    that many draws are taken from the generator once, as a (draws, NORMALS_PER_DRAW + 1)
    block, and every shot's draw j reads row j's first normals."""

    __slots__ = ("rng", "armed", "values", "at", "common")

    def __init__(self, rng: np.random.Generator, common_draws: int = 0):
        self.rng, self.armed, self.values, self.at = rng, 0, [], 0
        self.common = rng.standard_normal((common_draws, NORMALS_PER_DRAW + 1)) if common_draws else None

    def arm(self, count: int) -> None:
        """The next shot's draws take `count` normals in all."""
        if self.common is not None:  # a shot that failed before its noise may leave its row unread
            self.values, self.at = self.common[:, : count // len(self.common)].ravel().tolist(), 0
            return
        if self.at != len(self.values):
            raise RuntimeError(f"DrawnNormals: the last shot left {len(self.values) - self.at} normals unused")
        self.armed = count

    def normal(self, loc: float, scale: float) -> float:
        if self.at == len(self.values):
            if not self.armed:
                raise RuntimeError("DrawnNormals: no normals armed for this shot")
            self.values, self.at, self.armed = self.rng.standard_normal(self.armed).tolist(), 0, 0
        z = self.values[self.at]
        self.at += 1
        return loc + scale * z


def evaluation_rng(seed, game_rng: np.random.Generator) -> np.random.Generator:
    """The generator `Game.evaluate` draws its noise from: `seed` itself if it is a Generator, a
    new one seeded with it, or (None) a copy of the game's own `game_rng`, which stays as it is."""
    if isinstance(seed, np.random.Generator):
        return seed
    if seed is not None:
        return np.random.default_rng(seed)
    twin = np.random.Generator(type(game_rng.bit_generator)())
    twin.bit_generator.state = copy.deepcopy(game_rng.bit_generator.state)
    return twin


def normals_per_draw(shot: Shot, noise) -> int:
    """How many normals `shot.noisy_shot` takes for one draw of `shot` under `noise`."""
    return 0 if noise is None else NORMALS_PER_DRAW + (shot.elevation > 0.0)


class Layout:
    """Where the balls rest after a shot: `xy` (N, 2) and `pocketed` (N,) as a `Balls` holds
    them, and len() the number of balls (what the observations read of a `Balls`)."""

    __slots__ = ("xy", "pocketed")

    def __init__(self, xy: np.ndarray, pocketed: np.ndarray):
        self.xy, self.pocketed = xy, pocketed

    def __len__(self) -> int:
        return self.xy.shape[0]


@dataclass(eq=False, slots=True)
class JudgedShot:
    """What one shot of `Game.evaluate(..., records=False)` did, without its physics `Result`:
    `shot`, `error` (why it could not be simulated, else None), the rules' `outcome`, `ruling`
    and `state_after`, `over`, and `balls_after` (a `Layout`: the balls at rest, spotted balls
    back on the table), all as the `ShotRecord` of the same shot holds them."""

    shot: Shot
    error: str | None
    outcome: rules.ShotOutcome | None
    ruling: rules.Ruling | None
    state_after: rules.GameState | None
    over: bool
    balls_after: Layout

    @property
    def pocketed(self) -> tuple:
        """The object balls that dropped, in the order they dropped."""
        return () if self.outcome is None else self.outcome.pocketed

    @classmethod
    def of(cls, record) -> JudgedShot:
        """The `ShotRecord` `record` as a JudgedShot."""
        balls = record.balls_after
        return cls(record.shot, record.error, record.outcome, record.ruling, record.state_after, record.over,
                   Layout(balls.xy, balls.pocketed))


def lean(struck) -> list[int]:
    """The struck shots the compiled batch takes: struck (no error), every ball on the cloth,
    on the balls (pocketed flags, sizes) of the first such shot."""
    out, like = [], None
    for k, s in enumerate(struck):
        balls = s.balls
        if isinstance(balls, Balls) and balls.on_cloth:
            like = balls if like is None else like
            if all(a is b or np.array_equal(a, b) for a, b in ((balls.pocketed, like.pocketed),
                                                               (balls.radii, like.radii), (balls.masses, like.masses))):
                out.append(k)
    return out


def judge_batch(game, struck, threads: int | None = 1) -> list[JudgedShot]:
    """`game.judge` of every struck shot of a pool game (a `rules.GameState`), as JudgedShots:
    the level ones simulated in compiled calls (`simulate_level_batch`, `threads` as there), each distinct
    outcome (its event facts, called pocket and ball, push out) read and judged once; the
    others, and any the compiled run stopped, simulated and judged one by one."""
    state, table = game.state, game.table
    out: list[JudgedShot | None] = [None] * len(struck)
    fast = lean(struck)
    if fast:
        like = struck[fast[0]].balls
        S, st, codes, facts = simulate_level_batch(like, [struck[k].balls.xy for k in fast],
                                                   [struck[k].balls.v for k in fast],
                                                   [struck[k].balls.w for k in fast], table, game.physics,
                                                   threads)
        S.setflags(write=False)  # the layouts are views of it, read-only as a Balls' arrays are
        known: dict = {}
        for m, k in enumerate(fast):
            if codes[m] != DONE:
                continue
            s = struck[k]
            key = (facts[m].tobytes(), s.called_pocket, s.called_ball, s.push_out)
            judged = known.get(key)
            if judged is None:
                outcome = rules.outcome_of_facts(facts[m].tolist())
                after, ruling = rules.judge(state, outcome, s.called_pocket, s.called_ball, s.push_out)
                if not game.decisions and getattr(after, "pending", None) is not None:
                    after = rules.decide(after, after.pending.default)  # no re-rack is a default
                judged = known[key] = (outcome, ruling, after)
            outcome, ruling, after = judged
            if ruling.balls_to_spot:
                try:
                    balls = rules.settle(after, ruling, balls_at(s.balls, S[m], st[m]), table)[0]
                except ValueError:  # left to the one-by-one judging below, which records the failure
                    continue
                layout = Layout(balls.xy, balls.pocketed)
            else:
                layout = Layout(S[m, :, 0:2], st[m] == POCKETED)
            out[k] = JudgedShot(s.shot, None, outcome, ruling, after, after.over, layout)
    rulings: dict = {}
    for k, s in enumerate(struck):
        if out[k] is None:
            out[k] = JudgedShot.of(game.judge(s, simulate_struck(s, table, game.physics), rulings))
    return out


def evaluate_shots(game, mode: Mode, shots, draws: int = 1, seed=None, threads: int | None = 1,
                   records: bool = True, common: bool = False) -> list:
    """`Game.evaluate` of `game` (`mode` its mode), which does not change: see there."""
    shots = list(shots)
    if not shots:
        raise ValueError("evaluate needs at least one shot")
    if isinstance(draws, bool) or int(draws) != draws or draws < 1:
        raise ValueError(f"draws must be an integer >= 1, got {draws!r}")
    check_can_shoot(game)
    decoded = []
    for k, shot in enumerate(shots):
        try:
            decoded.append(shot_and_action(game, shot))
        except ValueError as exc:
            raise ValueError(f"shot {k}: {exc}") from None
    rng = evaluation_rng(seed, game.rng)
    placements: dict = {}  # candidate shots often place the cue ball on the same spot
    common_draws = int(draws) if common and game.noise is not None else 0
    normals, struck = DrawnNormals(rng, common_draws), []  # each shot's noise in one generator call
    for shot, action in decoded:
        normals.arm(int(draws) * normals_per_draw(shot, game.noise))
        struck += [struck_or_failed(game, mode, shot, action, normals, placements) for _ in range(int(draws))]
    if not records and type(game.state) is rules.GameState:
        return judge_batch(game, struck, threads)
    results = simulate_struck_batch(struck, game.table, game.physics, threads)
    rulings: dict = {}  # candidate shots often end alike: the rules judge each outcome once
    judged = [game.judge(s, r, rulings) for s, r in zip(struck, results)]
    return judged if records else [JudgedShot.of(record) for record in judged]
