"""`ShotOutcome`: what the rules read of a shot (first contact, drops, rails), built from a physics `Result`."""

from __future__ import annotations

from dataclasses import dataclass, field, fields

import numpy as np

from ..physics.jit import kernel
from ..physics.kinds import BALL_BALL, BALL_BALL_SETTLE, BALL_CUSHION, BALL_OFF_TABLE, BALL_POCKET, EVENT_KINDS

CUE = 0  # the cue ball's number


@dataclass(frozen=True)
class ShotOutcome:
    """The facts of one shot that the rules judge (ball numbers: 0 is the cue ball).

    | field | meaning |
    | --- | --- |
    | `first_contact` | the object ball the cue ball touched first, or None (it touched none) |
    | `pocketed` | the object balls that dropped, in the order they dropped (never the cue ball) |
    | `pocket_of` | ball -> pocket index (`Table.pockets` order) for every ball that dropped, the cue ball included |
    | `cue_pocketed` | the cue ball dropped (a scratch) |
    | `rail_after_contact` | some ball (cue or object) touched a cushion after the first cue-object contact |
    | `object_balls_to_rail` | object balls that touched a cushion at any time in the shot (the break's four) |
    | `off_table` | balls that left the table without dropping ("ball_off_table" events: through the air), in order |

    A cushion is any cushion body the engine has: the rail noses, the pockets' facings and
    their jaw tips (all "ball_cushion" events); a ball that touches a facing or a jaw tip in a
    pocket's mouth has touched a cushion (the WPA's "rail" is the cushion, definitions 8.x).
    A ball frozen to a cushion (touching it before the shot's contact with it) that is only
    pressed into it has not touched it (WPA 8.4, "driven to a rail"); one that leaves it and
    comes back has.
    """

    first_contact: int | None = None
    pocketed: tuple[int, ...] = ()
    pocket_of: dict = field(default_factory=dict)
    cue_pocketed: bool = False
    rail_after_contact: bool = False
    object_balls_to_rail: frozenset = frozenset()
    off_table: tuple[int, ...] = ()

    def __post_init__(self):
        _check_outcome(self)

    def __hash__(self):  # pocket_of is a dict: hash the rest
        return hash((self.first_contact, self.pocketed, tuple(sorted(self.pocket_of.items())), self.cue_pocketed,
                     self.rail_after_contact, self.object_balls_to_rail, self.off_table))

    @property
    def scratch(self) -> bool:
        """The cue ball dropped or left the table."""
        return self.cue_pocketed or CUE in self.off_table


OUTCOME_FIELDS = tuple(f.name for f in fields(ShotOutcome))


def _check_outcome(o: ShotOutcome) -> None:
    """ValueError for an outcome no shot can have (bad numbers, a ball dropped twice...)."""
    def number(b, what):
        if isinstance(b, bool) or not isinstance(b, int) or b < 0:
            raise ValueError(f"ShotOutcome: {what} must be a ball number (int >= 0), got {b!r}")

    if o.first_contact is not None:
        number(o.first_contact, "first_contact")
        if o.first_contact == CUE:
            raise ValueError("ShotOutcome: first_contact is an object ball, never the cue ball (0)")
    for b in o.pocketed:
        number(b, "each pocketed ball")
    if CUE in o.pocketed:
        raise ValueError("ShotOutcome: pocketed holds object balls only; the cue ball dropping is cue_pocketed=True")
    if len(set(o.pocketed)) != len(o.pocketed):
        raise ValueError(f"ShotOutcome: a ball dropped twice in pocketed={o.pocketed}")
    for b in o.off_table:
        number(b, "each off_table ball")
    both = set(o.pocketed) & set(o.off_table)
    if both or len(set(o.off_table)) != len(o.off_table):
        raise ValueError(f"ShotOutcome: ball {sorted(both or o.off_table)[0]} both dropped and left the table, "
                         "or left it twice")
    if o.cue_pocketed and CUE in o.off_table:
        raise ValueError("ShotOutcome: the cue ball cannot both drop and leave the table")
    for b, p in o.pocket_of.items():
        number(b, "each pocket_of key")
        number(p, "each pocket index in pocket_of")
    dropped = set(o.pocketed) | ({CUE} if o.cue_pocketed else set())
    if o.pocket_of and set(o.pocket_of) != dropped:
        raise ValueError(f"ShotOutcome: pocket_of names balls {sorted(o.pocket_of)} but the balls that dropped "
                         f"are {sorted(dropped)}")
    for b in o.object_balls_to_rail:
        number(b, "each object_balls_to_rail ball")
    if CUE in o.object_balls_to_rail:
        raise ValueError("ShotOutcome: object_balls_to_rail holds object balls only")
    if o.rail_after_contact and o.first_contact is None:
        raise ValueError("ShotOutcome: rail_after_contact needs a first contact")


def outcome_from_result(result) -> ShotOutcome:
    """The `ShotOutcome` of a simulated shot: read from `result.events` (a physics `Result`, or
    any object with an `events` list of `Event(time, kind, i, j)` in time order).

    Ball index = ball number (the racks in `pool_env.rules.racks` put ball k at index k).
    Contacts are the "ball_ball" kinds (a pressed "ball_ball_settle" contact included); a
    cushion contact is a "ball_cushion" event (rails, facings and jaw tips alike), except one
    that only presses a ball frozen to that cushion into it (`Result.pressed_cushion_events`:
    WPA 8.4, a ball touching a rail is driven to it only if it leaves it and comes back; an
    object without `event_arrays` has no such flag, and all its cushion events count); a drop
    is a "ball_pocket" event (j the pocket index); a ball leaving the table through the air
    is a "ball_off_table" event. Motion transitions and bounces on the slate are ignored."""
    arrays = getattr(result, "event_arrays", None)
    if arrays is not None:  # a physics Result: read in one compiled pass (`read_log`)
        return _outcome_of_log(arrays, result.pressed_cushion_events())
    events = result.events
    arrays = (None, *(np.array(column, dtype=np.int64).reshape(-1) for column in
                      ([EVENT_KINDS.index(event.kind) for event in events], [event.i for event in events],
                       [event.j for event in events])))
    return ShotOutcome(*_read(arrays, np.zeros(len(events), dtype=np.bool_)))


def _outcome_of_log(arrays, pressed) -> ShotOutcome:
    """The `ShotOutcome` of a Result's event arrays (t, kind, i, j) and pressed-cushion flags."""
    # The engine's events make a consistent outcome (a ball drops once, the cue ball never is
    # its own first contact...): built without the checks, which cost as much as the reading.
    outcome = object.__new__(ShotOutcome)
    outcome.__dict__.update(zip(OUTCOME_FIELDS, _read(arrays, pressed)))
    return outcome


def _read(arrays, pressed) -> tuple:
    """The `ShotOutcome`'s fields, in order, of event arrays (t, kind, i, j: `read_log`'s
    kinds, balls i and j, in time order) and their pressed-cushion flags."""
    _, kinds, i_s, j_s = arrays
    out = np.empty((4, len(kinds)), dtype=np.int64)
    first, rail_after, n_dropped, n_gone, n_rail = read_log(kinds, i_s, j_s, pressed, out)
    dropped = out[0, :n_dropped].tolist()
    return (None if first < 0 else first, tuple(b for b in dropped if b != CUE),
            dict(zip(dropped, out[1, :n_dropped].tolist())), CUE in dropped, rail_after,
            frozenset(out[3, :n_rail].tolist()), tuple(out[2, :n_gone].tolist()))


@kernel
def read_log(kinds, i_s, j_s, pressed, out):
    """`outcome_from_result`'s reading of the events (kind ids, balls i and j, pressed flags:
    (E,) each, in time order), in one pass: returns (the cue ball's first contact or -1, a
    cushion touched after it, how many balls dropped, left the table, reached a rail) and
    fills out (4, E): row 0 the balls that dropped in order, row 1 their pockets, row 2 the
    balls off the table in order, row 3 the object balls that reached a rail (each once)."""
    first, rail_after = -1, False
    n_dropped = n_gone = n_rail = 0
    for e in range(kinds.shape[0]):
        kind, i, j = kinds[e], i_s[e], j_s[e]
        if kind == BALL_BALL or kind == BALL_BALL_SETTLE:
            if first < 0 and (i == CUE or j == CUE):
                first = j if i == CUE else i
        elif kind == BALL_CUSHION:
            if pressed[e]:  # a ball frozen to this cushion pressed into it: not driven to it (WPA 8.4)
                continue
            rail_after = rail_after or first >= 0
            if i != CUE:
                seen = False
                for k in range(n_rail):
                    seen = seen or out[3, k] == i
                if not seen:
                    out[3, n_rail] = i
                    n_rail += 1
        elif kind == BALL_POCKET:
            out[0, n_dropped], out[1, n_dropped] = i, j
            n_dropped += 1
        elif kind == BALL_OFF_TABLE:
            out[2, n_gone] = i
            n_gone += 1
    return first, rail_after, n_dropped, n_gone, n_rail
