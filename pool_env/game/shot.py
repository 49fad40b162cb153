"""`Shot`: one cue shot as a player means it (force, tip, elevation, ball in hand, called pocket, ball); its noise."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..physics import BALL_MASS, BALL_RADIUS
from ..physics.cue import MAX_ELEVATION, MISCUE_LIMIT
from ..physics.frozen import unchecked

CONTACT_TIME = 0.005  # s, the seed report's cue contact time: a force F gives the cue ball F dt / m
MAX_SPEED = 12.0  # m/s, the cue ball's speed at full power: a strong break
MAX_FORCE = MAX_SPEED * BALL_MASS / CONTACT_TIME  # N (about 408 N)
MAX_TIP_OFFSET = MISCUE_LIMIT  # in ball radii: the tip may go as far as the miscue limit, 0.5 R
SPEED_SLACK = 1e-9  # relative: a force a rounding above MAX_FORCE is still full power
# Noise on the executed shot: standard deviations of the aim angle (rad), the cue ball's speed
# (m/s), the tip offsets (in ball radii) and the cue's elevation (rad). "olympiad": FastFiz's
# GaussianNoise defaults, the Computational Pool Olympiad's (phi 0.125 deg, v 0.075 m/s, a and
# b 0.5 mm, theta 0.1 deg). The elevation noise acts on elevated shots only: a level cue stays
# level (a player keeps the cue on the rail's plane; and level shots draw what they always drew).
NOISE_PRESETS = {
    "olympiad": {"angle": math.radians(0.125), "speed": 0.075, "side": 0.5e-3 / BALL_RADIUS,
                 "top": 0.5e-3 / BALL_RADIUS, "elevation": math.radians(0.1)},
}
NOISE_KEYS = ("angle", "speed", "side", "top", "elevation")
MIN_NOISY_SPEED = 0.01  # m/s: the noise never turns a shot round (a speed below zero)


def _pair(value, what) -> tuple[float, float]:
    if type(value) is tuple and len(value) == 2 and type(value[0]) is float and type(value[1]) is float:
        if not (math.isfinite(value[0]) and math.isfinite(value[1])):  # two floats (most shots): as they are
            raise ValueError(f"{what} must be finite, got {value!r}")
        return value
    try:
        a, b = value
        a, b = float(a), float(b)
    except (TypeError, ValueError):
        raise ValueError(f"{what} must be two numbers, got {value!r}") from None
    if not (math.isfinite(a) and math.isfinite(b)):
        raise ValueError(f"{what} must be finite, got {value!r}")
    return a, b


@dataclass(frozen=True, slots=True)
class Shot:
    """One cue shot, before the table's noise.

    - `force` (N, (fx, fy)): the cue's force on the cue ball in the table frame, for
      `CONTACT_TIME` (5 ms): the cue ball leaves at `force` x 5 ms / 0.17 kg, at most
      `MAX_SPEED` (12 m/s).
    - `tip` (ball radii, (side, top)): where the tip meets the ball, seen from behind the cue:
      side > 0 right English, top > 0 follow, < 0 draw; at most `MAX_TIP_OFFSET` (0.5 R, the
      miscue limit) from the centre.
    - `place` (m, (x, y), or None): with ball in hand, where the shooter puts the cue ball (the
      free spot nearest it in the area the rules allow); ignored otherwise. None: where it
      lies, or the area's middle if it was pocketed.
    - `pocket` (an index in `Table.pockets`, or None): the called pocket (8-ball, at the 8;
      every shot with `calling="ball_and_pocket"`).
    - `ball` (an object ball's number, or None): the called ball (8-ball with
      `calling="ball_and_pocket"`, WPA 1.6; None at the 8 means the 8); ignored otherwise.
    - `elevation` (rad, 0 to `MAX_ELEVATION`, 85 deg): the cue's angle above the table; 0 is a
      level cue. An elevated cue drives the ball into the slate: it swerves, masses or jumps
      (`pool_env.physics.strike`). `force` keeps its meaning: its direction is the aim seen
      from above, its length the push along the cue.
    - `push_out` (bool): the shooter declares a push out (9-ball and 10-ball, the shot right
      after a legal break, `Game.may_push_out`: WPA 2.4); ValueError from `Game` elsewhere.

    `Shot.aimed(direction, speed, ...)` builds one from a direction and a speed in m/s. A
    non-finite entry, a zero or too strong force, a tip past the miscue limit, an elevation
    out of range or a negative pocket or ball raises ValueError."""

    force: tuple[float, float]
    tip: tuple[float, float] = (0.0, 0.0)
    place: tuple[float, float] | None = None
    pocket: int | None = None
    elevation: float = 0.0
    ball: int | None = None
    push_out: bool = False

    def __post_init__(self):
        force = _pair(self.force, "Shot.force")
        magnitude = math.hypot(*force)
        if not 0.0 < magnitude <= MAX_FORCE * (1.0 + SPEED_SLACK):
            raise ValueError(f"Shot.force must be longer than 0 and at most MAX_FORCE = {MAX_FORCE:.1f} N "
                             f"(12 m/s), got {magnitude!r} N")
        tip = _pair(self.tip, "Shot.tip")
        if math.hypot(*tip) > MAX_TIP_OFFSET * (1.0 + SPEED_SLACK):
            raise ValueError(f"Shot.tip {tip} is past the miscue limit ({MAX_TIP_OFFSET} R from the centre)")
        elevation = float(self.elevation)
        if not (math.isfinite(elevation) and 0.0 <= elevation <= MAX_ELEVATION):
            raise ValueError(f"Shot.elevation must be in [0, MAX_ELEVATION = {MAX_ELEVATION:.4f}] rad (0 to 85 deg), "
                             f"got {self.elevation!r}")
        # Each field normalised (a float, a tuple of floats, an int, a bool), set again only when
        # it is not already that: a Shot is made for every shot, and setting a field costs.
        set_ = object.__setattr__
        if force is not self.force:
            set_(self, "force", force)
        if tip is not self.tip:
            set_(self, "tip", tip)
        if type(self.elevation) is not float:
            set_(self, "elevation", elevation)
        if self.place is not None:
            place = _pair(self.place, "Shot.place")
            if place is not self.place:
                set_(self, "place", place)
        if self.pocket is not None:
            if isinstance(self.pocket, bool) or int(self.pocket) != self.pocket or self.pocket < 0:
                raise ValueError(f"Shot.pocket must be None or a pocket's index (an integer >= 0), got {self.pocket!r}")
            if type(self.pocket) is not int:
                set_(self, "pocket", int(self.pocket))
        if self.ball is not None:
            if isinstance(self.ball, bool) or int(self.ball) != self.ball or self.ball < 1:
                raise ValueError(f"Shot.ball must be None or an object ball's number (an integer >= 1), "
                                 f"got {self.ball!r}")
            if type(self.ball) is not int:
                set_(self, "ball", int(self.ball))
        if type(self.push_out) is not bool:
            if not isinstance(self.push_out, np.bool_):
                raise ValueError(f"Shot.push_out must be a bool, got {self.push_out!r}")
            set_(self, "push_out", bool(self.push_out))

    @classmethod
    def aimed(cls, direction, speed: float, tip=(0.0, 0.0), place=None, pocket=None, elevation=0.0,
              ball=None, push_out=False, mass=BALL_MASS) -> Shot:
        """The cue ball sent along `direction` (any length) at `speed` m/s (the push along the
        cue: an elevated cue's ball leaves slower along the table, driven into the slate);
        `mass` (kg) the cue ball's, a pool ball's by default (a carom ball is heavier)."""
        dx, dy = _pair(direction, "direction")
        length = math.hypot(dx, dy)
        if length == 0.0:
            raise ValueError("direction must not be zero")
        scale = float(speed) * float(mass) / CONTACT_TIME / length
        return cls((dx * scale, dy * scale), tip, place, pocket, elevation, ball, push_out)

    @property
    def speed(self) -> float:
        """The cue ball's speed as it leaves the tip (m/s)."""
        return math.hypot(*self.force) * CONTACT_TIME / BALL_MASS

    @property
    def direction(self) -> np.ndarray:
        """The unit vector of the force."""
        return np.asarray(self.force) / math.hypot(*self.force)


def noise_of(noise) -> dict | None:
    """The noise's standard deviations (see NOISE_PRESETS), checked; None for none."""
    if noise is None:
        return None
    if isinstance(noise, str):
        if noise not in NOISE_PRESETS:
            raise ValueError(f"unknown noise preset {noise!r}; choose one of {', '.join(NOISE_PRESETS)} or a dict")
        return dict(NOISE_PRESETS[noise])
    if not isinstance(noise, dict) or set(noise) - set(NOISE_KEYS):
        raise ValueError(f"noise must be None, a preset name or a dict with keys from {NOISE_KEYS}, got {noise!r}")
    out = {key: float(noise.get(key, 0.0)) for key in NOISE_KEYS}
    if not all(math.isfinite(v) and v >= 0 for v in out.values()):
        raise ValueError(f"noise standard deviations must be finite and >= 0, got {noise!r}")
    return out


def noisy_shot(force, offset, noise, rng, elevation=0.0):
    """The shot (force (2,) N, tip offset (2,) R, elevation rad) with Gaussian noise on its aim
    angle, its speed and its tip offset (clamped back to the miscue limit and a positive speed),
    and on an elevated shot's elevation (clamped to [0, MAX_ELEVATION]): four normal draws from
    `rng`, a fifth if elevated, none without noise."""
    if noise is None:
        return force, offset, elevation
    speed = math.hypot(*force) * CONTACT_TIME / BALL_MASS
    angle = math.atan2(force[1], force[0]) + rng.normal(0.0, noise["angle"])
    speed = max(speed + rng.normal(0.0, noise["speed"]), MIN_NOISY_SPEED)
    side, top = offset[0] + rng.normal(0.0, noise["side"]), offset[1] + rng.normal(0.0, noise["top"])
    length = math.hypot(side, top)
    if length > MAX_TIP_OFFSET:
        side, top = side * MAX_TIP_OFFSET / length, top * MAX_TIP_OFFSET / length
    if elevation > 0.0:
        elevation = min(max(elevation + rng.normal(0.0, noise["elevation"]), 0.0), MAX_ELEVATION)
    magnitude = speed * BALL_MASS / CONTACT_TIME
    return np.array((magnitude * math.cos(angle), magnitude * math.sin(angle))), np.array((side, top)), elevation


def valid_shot(force, tip, place, pocket, elevation, ball, push_out) -> Shot:
    """The `Shot` of fields a decoder made valid and normalised already (floats within range,
    tuples of floats, an int pocket >= 0 and ball >= 1 or None, a bool): built without
    `Shot.__post_init__`'s checks, which would change nothing (every env shot is decoded)."""
    return unchecked(Shot, {"force": force, "tip": tip, "place": place, "pocket": pocket, "elevation": elevation,
                            "ball": ball, "push_out": push_out})
