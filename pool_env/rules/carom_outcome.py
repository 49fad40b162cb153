"""`CaromOutcome`: what the three-cushion rules read of a shot (the cue ball's contacts), from a `Result`."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..physics.kinds import BALL_BALL_KINDS, BALL_CUSHION, BALL_OFF_TABLE, BALL_POCKET
from ..physics.tolerances import CONTACT_TOLERANCE

CAROM_BALLS = 3  # white (0), yellow (1), red (2)
RED = 2


@dataclass(frozen=True)
class CaromOutcome:
    """The facts of one carom shot that the three-cushion rules judge (balls 0 white, 1 yellow, 2 red).

    | field | meaning |
    | --- | --- |
    | `cue_ball` | the ball the shooter struck (0 or 1) |
    | `first_ball` | the object ball the cue ball touched first, or None |
    | `second_ball` | the other object ball, when the cue ball touched it after the first, else None |
    | `cushions_before_second` | the cue ball's cushion contacts until it first touched the second ball (below) |
    | `cushions` | the cue ball's cushion contacts in the whole shot |
    | `off_table` | balls that left the table (through the air), in order |
    | `touching` | pairs (i, j), i < j, of balls touching each other when the balls came to rest |

    `cushions_before_second` counts the contacts up to the instant the cue ball first touched
    the second ball, that instant's included, and all of them when it touched no second ball.
    A cushion contact is a "ball_cushion" event of the cue ball, except one that only presses
    a ball frozen to a cushion into it (`Result.pressed_cushion_events`); the same cushion hit
    twice counts twice (the three cushion contacts need not be on three cushions).
    """

    cue_ball: int = 0
    first_ball: int | None = None
    second_ball: int | None = None
    cushions_before_second: int = 0
    cushions: int = 0
    off_table: tuple = ()
    touching: frozenset = frozenset()

    def __post_init__(self):
        object.__setattr__(self, "off_table", tuple(self.off_table))
        object.__setattr__(self, "touching", frozenset(tuple(p) for p in self.touching))
        _check(self)

    @property
    def pocketed(self) -> tuple:
        """No ball drops on a carom table (the game's records read this of any outcome)."""
        return ()

    @property
    def scratch(self) -> bool:
        """The cue ball left the table."""
        return self.cue_ball in self.off_table

    @property
    def point(self) -> bool:
        """A valid three-cushion carom (UMB Sports Rules, three cushion): both object balls
        touched, and at least three cushion contacts before (or at) the contact with the second."""
        return self.second_ball is not None and self.cushions_before_second >= 3


def _check(o: CaromOutcome) -> None:
    """ValueError for an outcome no carom shot can have."""
    if o.cue_ball not in (0, 1) or isinstance(o.cue_ball, bool):
        raise ValueError(f"CaromOutcome: cue_ball must be 0 (white) or 1 (yellow), got {o.cue_ball!r}")
    objects = {0, 1, 2} - {o.cue_ball}
    for name in ("first_ball", "second_ball"):
        ball = getattr(o, name)
        if ball is not None and ball not in objects:
            raise ValueError(f"CaromOutcome: {name} must be one of the object balls {sorted(objects)}, got {ball!r}")
    if o.second_ball is not None and (o.first_ball is None or o.second_ball == o.first_ball):
        raise ValueError("CaromOutcome: a second ball needs a first ball, and another one")
    for name in ("cushions_before_second", "cushions"):
        value = getattr(o, name)
        if isinstance(value, bool) or not isinstance(value, int) or value < 0:
            raise ValueError(f"CaromOutcome: {name} must be an integer >= 0, got {value!r}")
    if o.cushions_before_second > o.cushions:
        raise ValueError("CaromOutcome: more cushions before the second ball than in the whole shot")
    if o.second_ball is None and o.cushions_before_second != o.cushions:
        raise ValueError("CaromOutcome: without a second ball, cushions_before_second counts every cushion")
    for b in o.off_table:
        if b not in (0, 1, 2) or isinstance(b, bool):
            raise ValueError(f"CaromOutcome: off_table holds balls 0-2, got {b!r}")
    if len(set(o.off_table)) != len(o.off_table):
        raise ValueError(f"CaromOutcome: a ball left the table twice in off_table={o.off_table}")
    for pair in o.touching:
        if len(pair) != 2 or not (0 <= pair[0] < pair[1] <= 2):
            raise ValueError(f"CaromOutcome: touching holds pairs (i, j) of balls 0-2 with i < j, got {pair!r}")


def carom_outcome(result, cue_ball: int) -> CaromOutcome:
    """The `CaromOutcome` of a simulated shot whose cue ball is `cue_ball` (0 white, 1 yellow),
    read from `result.events` in time order: the cue ball's ball-ball contacts (the "ball_ball"
    kinds) name the first and second ball; its cushion contacts ("ball_cushion", pressed ones
    left out) are counted up to the time of the first contact with the second ball, those at
    that same instant included (UMB: three cushions "before" the second ball; a simultaneous
    one is not after it); "ball_off_table" events name the balls that left the table. A
    pocket event (a table with pockets) counts as leaving the table."""
    times, kinds, i_s, j_s = (a.tolist() for a in result.event_arrays)
    pressed = result.pressed_cushion_events().tolist() if BALL_CUSHION in kinds else [False] * len(kinds)
    first = second = None
    second_time = None
    cushion_times, gone = [], []
    for t, kind, i, j, frozen in zip(times, kinds, i_s, j_s, pressed):
        if kind in BALL_BALL_KINDS and cue_ball in (i, j):
            other = j if i == cue_ball else i
            if first is None:
                first = other
            elif other != first and second is None:
                second, second_time = other, t
        elif kind == BALL_CUSHION and i == cue_ball and not frozen:
            cushion_times.append(t)
        elif kind in (BALL_OFF_TABLE, BALL_POCKET) and i not in gone:
            gone.append(i)
    before = len(cushion_times) if second_time is None else sum(1 for t in cushion_times if t <= second_time)
    return CaromOutcome(cue_ball, first, second, before, len(cushion_times), tuple(gone),
                        touching_pairs(result.final))


def touching_pairs(balls) -> frozenset:
    """Pairs (i, j) of balls on the table whose surfaces touch (gap within CONTACT_TOLERANCE)."""
    on = np.flatnonzero(~balls.pocketed)
    out = set()
    for a in range(len(on)):
        for b in range(a + 1, len(on)):
            i, j = int(on[a]), int(on[b])
            gap = float(np.hypot(*(balls.xy[i] - balls.xy[j]))) - balls.radii[i] - balls.radii[j]
            if gap <= CONTACT_TOLERANCE:
                out.add((i, j))
    return frozenset(out)

