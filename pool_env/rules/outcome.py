"""`ShotOutcome`: what the rules read of a shot (first contact, drops, rails), built from a physics `Result`."""

from __future__ import annotations

from dataclasses import dataclass, field, fields

from ..physics.facts import DROPS, FIRST, GONE, HEAD, RAIL_AFTER, RAILS
from ..physics.frozen import unchecked
from ..physics.kinds import BALL_BALL_KINDS, BALL_CUSHION, BALL_OFF_TABLE, BALL_POCKET, CUE, EVENT_KINDS


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
    is a "ball_off_table" event. Motion transitions and bounces on the slate are ignored.
    A physics `Result` of the event engine reads all of it in one compiled call
    (`Result.event_facts`, the same reading; `outcome_of_facts`)."""
    facts = getattr(result, "event_facts", None)
    row = None if facts is None else facts()
    if row is not None:
        return outcome_of_facts(row)
    arrays = getattr(result, "event_arrays", None)
    if arrays is not None:  # a physics Result: its arrays as lists, without an Event object per event
        _, kinds, i_s, j_s = arrays
        kinds, i_s, j_s = kinds.tolist(), i_s.tolist(), j_s.tolist()
        pressed = result.pressed_cushion_events().tolist() if BALL_CUSHION in kinds else None
    else:
        kinds = [EVENT_KINDS.index(event.kind) for event in result.events]
        i_s, j_s = [int(event.i) for event in result.events], [int(event.j) for event in result.events]
        pressed = None
    if pressed is None:
        pressed = [False] * len(kinds)
    read = _read_events(kinds, i_s, j_s, pressed)
    if arrays is None:
        return ShotOutcome(*read)
    # The engine's events make a consistent outcome (a ball drops once, the cue ball never is
    # its own first contact...): built without the checks, which cost as much as the reading.
    return unchecked(ShotOutcome, dict(zip(OUTCOME_FIELDS, read)))


def outcome_of_facts(row: list) -> ShotOutcome:
    """The `ShotOutcome` of a run's event facts (`physics.facts`' row, as a list of ints).
    The engine's events make a consistent outcome: built without the checks."""
    n, first, d, g, r = (len(row) - HEAD) // 4, row[FIRST], row[DROPS], row[GONE], row[RAILS]
    pocketed, pocket_of, scratch = (), {}, False
    if d:  # most shots drop nothing
        dropped, pockets = row[HEAD:HEAD + 2 * d:2], row[HEAD + 1:HEAD + 2 * d:2]
        scratch, pocket_of = CUE in dropped, dict(zip(dropped, pockets))
        pocketed = tuple(b for b in dropped if b != CUE) if scratch else tuple(dropped)
    # frozenset of a set filled in the order the balls reached a cushion, as `_read_events`
    # makes it: the same table, so the same order of iteration (and repr)
    to_rail = frozenset(set(row[HEAD + 3 * n:HEAD + 3 * n + r])) if r else frozenset()
    return unchecked(ShotOutcome, {"first_contact": None if first < 0 else first, "pocketed": pocketed,
                                   "pocket_of": pocket_of, "cue_pocketed": scratch,
                                   "rail_after_contact": bool(row[RAIL_AFTER]), "object_balls_to_rail": to_rail,
                                   "off_table": tuple(row[HEAD + 2 * n:HEAD + 2 * n + g])})


def _read_events(kinds, i_s, j_s, pressed) -> tuple:
    """`outcome_from_result`'s reading of the events (kind ids, balls i and j, pressed flags,
    lists in time order): the `ShotOutcome`'s fields, in order."""
    first, contact_seen, rail_after = None, False, False
    to_rail, dropped, pockets, gone = set(), [], [], []
    for kind, i, j, frozen in zip(kinds, i_s, j_s, pressed):
        if kind in BALL_BALL_KINDS:
            if not contact_seen and CUE in (i, j):
                first, contact_seen = (j if i == CUE else i), True
        elif kind == BALL_CUSHION:
            if frozen:  # a ball frozen to this cushion pressed into it: not driven to it (WPA 8.4)
                continue
            rail_after = rail_after or contact_seen
            if i != CUE:
                to_rail.add(i)
        elif kind == BALL_POCKET:
            dropped.append(i)
            pockets.append(j)
        elif kind == BALL_OFF_TABLE:
            gone.append(i)
    pocketed = tuple(b for b in dropped if b != CUE)
    return first, pocketed, dict(zip(dropped, pockets)), CUE in dropped, rail_after, frozenset(to_rail), tuple(gone)
