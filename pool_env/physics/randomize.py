"""Domain randomization: a validated spec of physics, table and ball parameters to draw, and the draws."""

from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np

from .config import Physics
from .frozen import unchecked
from .objects import BALL_MASS, BALL_RADIUS, CAROM_MASS, CAROM_RADIUS, Balls, Table
from .snooker import SNOOKER_BALL_MASS, SNOOKER_BALL_RADIUS

INCH, OUNCE = 0.0254, 0.028349523125

# The Physics coefficients a spec may draw (every float field: the model names and `spin` stay).
PHYSICS_NAMES = tuple(f.name for f in dataclasses.fields(Physics) if f.type in (float, "float"))
# The table's equipment: the cushion nose's height and the corner and side (middle) pockets' mouths.
TABLE_NAMES = ("cushion_height", "corner_mouth", "side_mouth")
# Per ball: every ball draws its own radius and mass.
BALL_NAMES = ("ball_radius", "ball_mass")
NAMES = PHYSICS_NAMES + TABLE_NAMES + BALL_NAMES

# Measured cloth, ball and cushion values, in D. G. Alciatore's approximate pool-equipment
# properties (billiards.colostate.edu/threads/physics.html, "physical properties"): ball-cloth sliding
# friction 0.15-0.4, rolling resistance 0.005-0.015, spin deceleration 5-15 rad/s^2 (mu_sp =
# 2 R alpha / (5 g): 0.0058-0.0175 for a 2.25 in ball), ball-ball restitution 0.92-0.98,
# ball-rail restitution 0.6-0.9. The cushion's friction (f_c) 0.1-0.3 brackets our 0.2 (Han
# 2005's fitted values lie there); the slate's e_t and mu_t are left fixed (one value, no range).
CLOTH = {"mu_s": (0.15, 0.4), "mu_r": (0.005, 0.015), "mu_sp": (0.0058, 0.0175), "e_b": (0.92, 0.98)}
# WPA Equipment Specifications: balls 2.25 in (+-0.005 in) across and 5.5-6 oz; corner mouths
# 4.5-4.625 in, side mouths 5-5.125 in; the cushion nose at 62.5-64.5 % of the ball's diameter.
POOL = {**CLOTH, "e_c": (0.6, 0.9), "f_c": (0.1, 0.3),
        "cushion_height": (0.625 * 2 * BALL_RADIUS, 0.645 * 2 * BALL_RADIUS),
        "corner_mouth": (4.5 * INCH, 4.625 * INCH), "side_mouth": (5.0 * INCH, 5.125 * INCH),
        "ball_radius": (BALL_RADIUS - 0.0025 * INCH, BALL_RADIUS + 0.0025 * INCH),
        "ball_mass": (5.5 * OUNCE, 6.0 * OUNCE)}
# UMB Sports Rules 2.1-2.2: balls 61-61.5 mm across and 205-220 g, the cushion nose 37 +- 1 mm
# high. The carom cushion's restitution and grip (e_c 0.85, f_c 0.5) have no measured spread we
# know of: 0.75-0.9 and 0.4-0.6 are our bracket around them. No pockets.
CAROM = {**CLOTH, "e_c": (0.75, 0.9), "f_c": (0.4, 0.6), "cushion_height": (0.036, 0.038),
         "ball_radius": (0.0305, CAROM_RADIUS), "ball_mass": (0.205, 0.220)}
# WPBSA Section 1 Rule 2: balls 52.5 mm (+-0.05 mm) across, a set's weights within 3 g (our
# spread: 3 g around SNOOKER_BALL_MASS). The pockets and cushion of `Table.snooker` stay fixed.
SNOOKER = {**CLOTH, "e_c": (0.6, 0.9), "f_c": (0.1, 0.3),
           "ball_radius": (SNOOKER_BALL_RADIUS - 0.000025, SNOOKER_BALL_RADIUS + 0.000025),
           "ball_mass": (SNOOKER_BALL_MASS - 0.0015, SNOOKER_BALL_MASS + 0.0015)}
DEFAULTS = {"pool": POOL, "carom": CAROM, "snooker": SNOOKER}
REGULATION = {"pool": (BALL_RADIUS, BALL_MASS), "carom": (CAROM_RADIUS, CAROM_MASS),
              "snooker": (SNOOKER_BALL_RADIUS, SNOOKER_BALL_MASS)}


@dataclasses.dataclass(frozen=True)
class Draw:
    """One parameter's distribution: uniform on [low, high], or normal(mean, sd) clipped to it."""

    name: str
    low: float
    high: float
    mean: float | None = None
    sd: float | None = None

    def sample(self, rng: np.random.Generator, size=None):
        if self.sd is None:
            return rng.uniform(self.low, self.high, size)
        return np.clip(rng.normal(self.mean, self.sd, size), self.low, self.high)


def _number(name, value, what):
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"randomize[{name!r}]: {what} must be a number, got {value!r}") from None
    if not math.isfinite(value):
        raise ValueError(f"randomize[{name!r}]: {what} must be finite, got {value!r}")
    return value


def _pair(name, value, what):
    if isinstance(value, (str, bytes, dict)) or not hasattr(value, "__len__") or len(value) != 2:
        raise ValueError(f"randomize[{name!r}]: {what} must be a pair of numbers, got {value!r}")
    return _number(name, value[0], what + "[0]"), _number(name, value[1], what + "[1]")


def draw_of(name: str, value) -> Draw:
    """The `Draw` a spec entry means: (low, high) uniform, {"uniform": (low, high)}, or
    {"normal": (mean, sd), "clip": (low, high)}. ValueError naming what is wrong."""
    if name not in NAMES:
        raise ValueError(f"randomize: unknown parameter {name!r}; choose among {', '.join(NAMES)}")
    mean = sd = None
    if isinstance(value, dict):
        keys = set(value)
        if keys == {"uniform"}:
            low, high = _pair(name, value["uniform"], "uniform")
        elif keys == {"normal", "clip"}:
            mean, sd = _pair(name, value["normal"], "normal")
            low, high = _pair(name, value["clip"], "clip")
            if not sd > 0:
                raise ValueError(f"randomize[{name!r}]: the normal's sd must be > 0, got {sd!r}")
            if not low <= mean <= high:
                raise ValueError(f"randomize[{name!r}]: the normal's mean {mean} is outside its clip [{low}, {high}]")
        else:
            raise ValueError(f"randomize[{name!r}]: a dict is {{'uniform': (low, high)}} or "
                             f"{{'normal': (mean, sd), 'clip': (low, high)}}, got keys {sorted(keys)}")
    else:
        low, high = _pair(name, value, "the range")
    if not low < high:
        raise ValueError(f"randomize[{name!r}]: the range [{low}, {high}] is empty or inverted (low < high "
                         "needed; a fixed value belongs in Physics or Table)")
    return Draw(name, low, high, mean, sd)


@dataclasses.dataclass(frozen=True)
class Sample:
    """One draw: the table and physics to play on, every ball's radius and mass (None: the rack's
    own), and the drawn values, `drawn` (in NAMES order, per-ball names one entry per ball; see
    `values` for them by name)."""

    table: Table
    physics: Physics
    radii: np.ndarray | None
    masses: np.ndarray | None
    drawn: np.ndarray
    randomization: Randomization

    @classmethod
    def of(cls, table, physics, radii, masses, drawn, randomization, scalars=None) -> Sample:
        """Sample(...), without the frozen dataclass's set-up (one per randomized reset); `scalars`:
        drawn's physics and table values as a list, if known (for `info`)."""
        return unchecked(cls, {"table": table, "physics": physics, "radii": radii, "masses": masses, "drawn": drawn,
                               "randomization": randomization, "_scalars": scalars})

    @functools.cached_property
    def values(self) -> dict:
        """The drawn values by name (per-ball names: a tuple, one per ball)."""
        out, at = {}, 0
        for d, n in zip(self.randomization.draws, self.randomization.counts, strict=True):
            part = self.drawn[at:at + n].tolist()
            out[d.name] = tuple(part) if d.name in BALL_NAMES else part[0]
            at += n
        return out

    def info(self) -> dict:
        """What reset's info reports: `physics` (every Physics coefficient), `table` (the
        TABLE_NAMES), and `ball_radius`/`ball_mass` arrays when those are drawn. Plain floats."""
        base = self.randomization
        scalars = self.__dict__.get("_scalars") or self.drawn[:base.scalars].tolist()
        physics, table = base.physics_info.copy(), base.table_info.copy()
        physics.update(zip(base.physics_names, scalars))
        table.update(zip(base.table_names, scalars[len(base.physics_names):]))
        out = {"physics": physics, "table": table}
        if self.radii is not None:
            out["ball_radius"] = self.radii.copy()
        if self.masses is not None:
            out["ball_mass"] = self.masses.copy()
        return out

    def sized(self, balls: Balls) -> Balls:
        """`balls` (a rack) with the drawn radii and masses. Larger balls need more room: the
        layout is spread about its centre by the largest radius over the smallest given one,
        which scales every gap at least as much as any ball grew (no new overlaps)."""
        if self.radii is None and self.masses is None:
            return balls
        return balls.sized(balls.radii if self.radii is None else self.radii,
                           balls.masses if self.masses is None else self.masses)


def table_values(table: Table) -> dict:
    """The TABLE_NAMES of a table: its cushion height, and its first corner and side mouths
    (the mouths only when it has such pockets)."""
    corner = table.corner_pockets
    out = {"cushion_height": float(table.cushion_height)}
    if corner.any():
        out["corner_mouth"] = float(table.pocket_entries[corner][0, 2])
    if (~corner).any():
        out["side_mouth"] = float(table.pocket_entries[~corner][0, 2])
    return out


class Randomization:
    """A checked spec of what to draw at each reset, bound to a game's table, physics and balls.

    `spec`: a dict {name: range or distribution} (see `draw_of`; names in NAMES), or "default"
    (DEFAULTS[equipment]: the measured ranges). Every parameter's whole range must make a valid
    Physics and Table and balls that stand above the cushion nose: ValueError otherwise, here."""

    def __init__(self, spec, table: Table, physics: Physics, n_balls: int, equipment: str = "pool"):
        if isinstance(spec, str):
            if spec != "default":
                raise ValueError(f"randomize must be None, 'default' or a dict of ranges, got {spec!r}")
            spec = DEFAULTS[equipment]
        if not isinstance(spec, dict) or not spec:
            raise ValueError(f"randomize must be None, 'default' or a non-empty dict of ranges, got {spec!r}")
        self.draws = tuple(draw_of(name, spec[name]) for name in NAMES if name in spec)
        unknown = sorted(set(spec) - set(NAMES), key=str)
        if unknown:
            draw_of(unknown[0], None)  # raises, naming it
        self.table, self.physics, self.n_balls = table, physics, int(n_balls)
        self.by_name = {d.name: d for d in self.draws}
        self._check()
        # What `sample` and `Sample` need, worked out once: each draw's entries, the scalar
        # (physics and table) names first, every entry's low end and width, the base's info.
        self.counts = tuple(self.n_balls if d.name in BALL_NAMES else 1 for d in self.draws)
        self.size = sum(self.counts)
        self.physics_names = tuple(d.name for d in self.draws if d.name in PHYSICS_NAMES)
        self.table_names = tuple(d.name for d in self.draws if d.name in TABLE_NAMES)
        self.scalars = len(self.physics_names) + len(self.table_names)
        self._physics_count = len(self.physics_names)
        at = {name: slice(self.scalars + k * self.n_balls, self.scalars + (k + 1) * self.n_balls)
              for k, name in enumerate(d.name for d in self.draws if d.name in BALL_NAMES)}
        self._radii, self._masses = at.get("ball_radius"), at.get("ball_mass")
        self._low = np.repeat([d.low for d in self.draws], self.counts)
        self._width = np.repeat([d.high - d.low for d in self.draws], self.counts)
        self._uniform = all(d.sd is None for d in self.draws)
        self.physics_info = {name: float(getattr(physics, name)) for name in PHYSICS_NAMES}
        self.table_info = table_values(table)

    def _check(self):
        for end in ("low", "high"):
            values = {d.name: getattr(d, end) for d in self.draws}
            phys = {k: v for k, v in values.items() if k in PHYSICS_NAMES}
            try:
                dataclasses.replace(self.physics, **phys)
                table = self.table.variant(**{k: v for k, v in values.items() if k in TABLE_NAMES})
            except ValueError as exc:
                raise ValueError(f"randomize: the ranges' {end} ends make an invalid game: {exc}") from None
        for name in BALL_NAMES:
            if name in self.by_name and not self.by_name[name].low > 0:
                raise ValueError(f"randomize[{name!r}]: every ball's {name[5:]} must be > 0, "
                                 f"got a range from {self.by_name[name].low}")
        lowest = self.by_name["ball_radius"].low if "ball_radius" in self.by_name else None
        highest_nose = self.by_name["cushion_height"].high if "cushion_height" in self.by_name \
            else self.table.cushion_height
        if lowest is not None and not 2.0 * lowest > highest_nose:
            raise ValueError(f"randomize: balls of radius {lowest} m would pass under a cushion nose "
                             f"{highest_nose} m high (2 R > cushion_height needed)")
        if "corner_mouth" in self.by_name or "side_mouth" in self.by_name:
            if not table.pocket_entries.size:
                raise ValueError("randomize: the table has no pockets to size")

    def sample(self, rng: np.random.Generator) -> Sample:
        """Every parameter drawn from `rng`, in NAMES order (per-ball names: one draw per ball).
        Uniform ranges alone (the defaults): one call of rng.random for them all, the same
        values as rng.uniform(low, high) for each in turn."""
        if self._uniform:
            drawn = rng.random(self.size)
            drawn *= self._width
            drawn += self._low
        else:
            drawn = np.concatenate([np.atleast_1d(d.sample(rng, n if d.name in BALL_NAMES else None))
                                    for d, n in zip(self.draws, self.counts, strict=True)])
        scalars = drawn[:self.scalars].tolist()
        # Each coefficient's valid values are a range, whose ends `_check` tried: a draw
        # between them needs no check.
        k = self._physics_count
        physics = self.physics._with(dict(zip(self.physics_names, scalars))) if k else self.physics
        table = self.table.variant(**dict(zip(self.table_names, scalars[k:]))) if self.table_names else self.table
        radii = None if self._radii is None else drawn[self._radii]
        masses = None if self._masses is None else drawn[self._masses]
        return Sample.of(table, physics, radii, masses, drawn, self, scalars)

    def scaled(self, sample: Sample) -> np.ndarray:
        """The drawn values mapped from their ranges onto [-1, 1] (float32), in NAMES order,
        per-ball names one entry per ball: what an observation may carry."""
        return (2.0 * (sample.drawn - self._low) / self._width - 1.0).astype(np.float32)

    def unscaled(self, scaled) -> dict:
        """`scaled`'s decoder: the drawn values by name (per-ball names: tuples), from its [-1, 1] entries."""
        scaled, values, at = np.asarray(scaled, dtype=np.float64), {}, 0
        for d in self.draws:
            n = self.n_balls if d.name in BALL_NAMES else 1
            value = d.low + 0.5 * (scaled[at:at + n] + 1.0) * (d.high - d.low)
            values[d.name] = tuple(value.tolist()) if n > 1 or d.name in BALL_NAMES else float(value[0])
            at += n
        if at != scaled.shape[0]:
            raise ValueError(f"unscaled takes {at} entries (this spec's size), got {scaled.shape[0]}")
        return values
