"""`Table`: the playing area, its rails and its pockets (mouths, jaws, facings), immutable."""

from __future__ import annotations

import functools
import math

import numpy as np

from . import snooker  # the snooker table's figures
from .balls import BALL_RADIUS, read_only
from .frozen import unchecked
from .pocket_shape import PocketShape, as_rows
from .table_build import geometry, plan_of

# The carom table (UMB Sports Rules 2.1, "Billiard, cushion, cloth"): a free playing surface of
# 2.84 x 1.42 m (+-5 mm), cushions 37 mm (+-1 mm) high at their frontmost point (the nose).
CAROM_LENGTH, CAROM_WIDTH = 2.84, 1.42
CAROM_CUSHION_HEIGHT = 0.037


class Table:
    """A rectangular pool table: playing area `length` x `width` (m) inside the cushion noses.

    `pockets` is a sequence of (x, y, mouth) entries, or None (the same as `()`: no pockets,
    four straight rails): a pocket centred at a corner or on a rail, with the given mouth
    width (m, between the jaw points). Rails run between pockets; the rail ends at a mouth
    are jaw points a ball can hit. A ball drops when its centre enters the pocket's capture
    circle, which passes through the jaw points (radius mouth/2 on a rail; mouth/sqrt(2) at a
    corner, where the jaws sit that far along each rail from the corner). A mouth must fit
    the table: its jaw points lie on the rail (or both rails, at a corner) it sits on, and its
    capture circle does not reach past the opposite rail; so a rail pocket's mouth is at most
    twice its distance to the nearer end of its rail and twice the table's depth across it,
    and a corner mouth at most sqrt(2) times the shorter side. Mouths may touch but not overlap.

    `cushion_height` is the height of the cushion nose above the cloth (m), used by the
    `han2005` cushion model, which needs the nose below the top of every ball
    (`cushion_height < 2 R`); a lower ball would pass under the cushion. `rack` checks this.

    Immutable (its arrays are read-only, its attributes cannot be reassigned), so copies,
    shallow or deep, are the table itself, and a pickled table loads with read-only arrays.
    """

    def __init__(self, length, width, pockets=(), cushion_height=0.0363, corner_pocket=None, side_pocket=None):
        set_ = functools.partial(object.__setattr__, self)
        set_("length", float(length))
        set_("width", float(width))
        if not (math.isfinite(self.length) and math.isfinite(self.width) and self.length > 0 and self.width > 0):
            raise ValueError(f"table size must be finite and > 0, got {length!r} x {width!r}")
        set_("cushion_height", float(cushion_height))
        if not (math.isfinite(self.cushion_height) and self.cushion_height > 0):
            raise ValueError(f"cushion_height must be finite and > 0, got {cushion_height!r}")
        if pockets is None:
            pockets = ()
        try:
            pockets = list(pockets)
        except TypeError:
            raise ValueError(
                f"pockets must be a sequence of (x, y, mouth) entries, or None for no pockets, got {pockets!r}"
            ) from None
        corner_shape = _shape(corner_pocket, PocketShape.corner, "corner_pocket")
        side_shape = _shape(side_pocket, PocketShape.side, "side_pocket")
        set_("corner_pocket", corner_shape)
        set_("side_pocket", side_shape)
        entries = [_pocket_entry(k, p) for k, p in enumerate(pockets)]
        plan = plan_of(tuple((x, y) for x, y, _ in entries), (corner_shape, side_shape), (self.length, self.width))
        # The arrays of its pockets; pocket_entries, (x, y, mouth) each as given, is what Table(...)
        # needs to build this table again. Rails: the nose segments, then each pocket's two
        # facings (rail_pockets: -1 for a nose, else the facing's pocket; the engine looks at a
        # pocket's facings and jaw tips only when a ball can come near the pocket).
        self.__dict__.update(geometry(plan, as_rows(entries, 3)))
        self.__dict__["_plan"] = plan

    def variant(self, cushion_height=None, corner_mouth=None, side_mouth=None) -> Table:
        """This table with another cushion height, and every corner (side) pocket's mouth
        `corner_mouth` (`side_mouth`); None keeps this table's. The same as `Table(length, width,
        the entries with those mouths, cushion_height, corner_pocket, side_pocket)`, bit for bit
        but for each pocket's broad-phase radius (`pocket_reach`'s last column, which may differ
        from Table's in the last bit: it takes the C library's hypot, Table Python's), and the
        same ValueError for a value that does not fit; built in one compiled call on what this
        table worked out once (its pockets' places and shapes: what a randomized reset draws on)."""
        try:
            height = self.cushion_height if cushion_height is None else float(cushion_height)
            corner = math.nan if corner_mouth is None else float(corner_mouth)
            side = math.nan if side_mouth is None else float(side_mouth)
        except (TypeError, ValueError):
            raise ValueError(f"cushion_height, corner_mouth and side_mouth must be numbers, got "
                             f"{cushion_height!r}, {corner_mouth!r} and {side_mouth!r}") from None
        plan = self.__dict__.get("_plan") or self._the_plan()
        if not (0.0 < height < math.inf and (corner_mouth is None or 0.0 < corner < math.inf)
                and (side_mouth is None or 0.0 < side < math.inf)):  # Table says what is wrong, if anything
            entries = self.pocket_entries.copy()
            entries[plan.corner, 2] = entries[plan.corner, 2] if corner_mouth is None else corner
            entries[~plan.corner, 2] = entries[~plan.corner, 2] if side_mouth is None else side
            return Table(self.length, self.width, entries.tolist(), height, self.corner_pocket, self.side_pocket)
        state = {"length": self.length, "width": self.width, "cushion_height": height,
                 "corner_pocket": self.corner_pocket, "side_pocket": self.side_pocket}
        state.update(geometry(plan, self.pocket_entries, corner, side, exact=False))
        state["_plan"] = plan
        return unchecked(Table, state)

    @property
    def corner_pockets(self) -> np.ndarray:
        """Which pockets (in `pocket_entries` order) sit at a corner, shaped as `corner_pocket`;
        the others sit on a rail, shaped as `side_pocket`. (P,) bool, read-only."""
        return self._the_plan().corner

    def _the_plan(self):
        """This table's plan (table_build.Plan): kept since it was built, or worked out again
        for a table unpickled (its plan is not saved)."""
        plan = self.__dict__.get("_plan")
        if plan is None:
            places = tuple(map(tuple, self.pocket_entries[:, :2].tolist()))
            plan = plan_of(places, (self.corner_pocket, self.side_pocket), (self.length, self.width))
            self.__dict__["_plan"] = plan
        return plan

    def __setattr__(self, name, value):
        raise AttributeError(f"Table is immutable: cannot set {name!r} (make a new Table)")

    def __delattr__(self, name):
        raise AttributeError(f"Table is immutable: cannot delete {name!r}")

    def __copy__(self):
        return self

    def __deepcopy__(self, memo):
        # Immutable, so the table itself is its deep copy: its arrays stay read-only (a copied
        # array would be writable, and numba would compile the whole engine again for it).
        return self

    def __getstate__(self):
        # The engine's cached views of the arrays (bundles.bounds_of) and the plan are not
        # saved: a loaded table works them out again when it needs them.
        return {name: value for name, value in self.__dict__.items() if not name.startswith(("_bounds", "_plan"))}

    def __setstate__(self, state):
        # Unpickling: numpy loads arrays writable; make them read-only again (a pickle made
        # before __getstate__ may still hold the engine's cached views: they are dropped).
        for name, value in state.items():
            if name.startswith(("_bounds", "_plan")):
                continue
            object.__setattr__(self, name, read_only(value) if isinstance(value, np.ndarray) else value)

    def __repr__(self):
        return f"Table({self.length} x {self.width} m, {len(self.pockets)} pockets)"

    @classmethod
    def seed(cls) -> Table:
        """The seed report's table: 2.24 x 1.12 m, four straight rails, no pockets."""
        return cls(2.24, 1.12)

    @classmethod
    def eight_foot(cls) -> Table:
        """The same 2.24 x 1.12 m playing area with six regulation pockets: corner mouths
        4.5625 in (0.1159 m) and side mouths 5.0625 in (0.1286 m), the middles of the WPA
        ranges (corner 4.5-4.625 in, side 5-5.125 in; WPA Equipment Specifications), and a
        cushion nose at 63.5 % of the ball's diameter (same source)."""
        L, W = 2.24, 1.12
        corner, side = 0.1159, 0.1286
        pockets = [(0.0, 0.0, corner), (L, 0.0, corner), (0.0, W, corner), (L, W, corner),
                   (L / 2, 0.0, side), (L / 2, W, side)]
        return cls(L, W, pockets, cushion_height=0.635 * 2 * BALL_RADIUS)

    @classmethod
    def carom(cls) -> Table:
        """The match carom table (UMB Sports Rules 2.1): a 2.84 x 1.42 m playing surface inside
        the cushion noses, no pockets, the nose 37 mm above the cloth (60 % of a 61.5 mm carom
        ball's diameter: the ball meets it above its equator, as the han2005 model needs)."""
        return cls(CAROM_LENGTH, CAROM_WIDTH, (), cushion_height=CAROM_CUSHION_HEIGHT)

    @classmethod
    def snooker(cls) -> Table:
        """The WPBSA 12 ft snooker table, 3569 x 1778 mm, with snooker pockets (`physics.snooker`: the
        figures and their sources); x runs from the baulk (bottom) cushion at x = 0 to the top cushion."""
        L, W = snooker.SNOOKER_LENGTH, snooker.SNOOKER_WIDTH
        corner, middle = snooker.CORNER_MOUTH, snooker.MIDDLE_MOUTH
        pockets = [(0.0, 0.0, corner), (L, 0.0, corner), (0.0, W, corner), (L, W, corner),
                   (L / 2, 0.0, middle), (L / 2, W, middle)]
        return cls(L, W, pockets, cushion_height=snooker.CUSHION_HEIGHT, corner_pocket=snooker.CORNER_POCKET,
                   side_pocket=snooker.MIDDLE_POCKET)


def _shape(value, default, name):
    """A PocketShape argument: None for the default, else a PocketShape."""
    if value is None:
        return default()
    if not isinstance(value, PocketShape):
        raise ValueError(f"{name} must be a PocketShape or None, got {value!r}")
    return value


def _pocket_entry(number, pocket):
    """(x, y, mouth) of pocket `number`, checked: three finite numbers, mouth > 0."""
    try:
        entry = tuple(pocket)
    except TypeError:
        entry = ()
    try:
        x, y, mouth = (float(c) for c in entry)
    except (TypeError, ValueError):
        raise ValueError(
            f"pocket {number} must be an (x, y, mouth) entry: its centre (m), on a rail or at a corner, "
            f"and its mouth width (m); got {pocket!r}"
        ) from None
    if not (all(math.isfinite(c) for c in (x, y, mouth)) and mouth > 0):
        raise ValueError(f"pocket {number} must be finite (x, y, mouth > 0), got {pocket!r}")
    return x, y, mouth

