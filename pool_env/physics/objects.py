"""The things on the table: `Balls` (positions, velocities, spins) and `Table` (rails, pockets), and `rack`."""

from __future__ import annotations

import functools
import math

import numpy as np

from . import snooker  # the snooker table's figures
from .bundles import bounds_of
from .jit import kernel
from .placement import first_misplaced, nearest_to, overlapping
from .pocket_shape import PocketShape, as_rows
from .table_build import geometry, plan_of
from .tolerances import CONTACT_TOLERANCE

# Regulation pool ball (WPA equipment specifications): 2.25 in diameter, 5.5-6 oz.
BALL_RADIUS = 0.028575
BALL_MASS = 0.170097
# The seed report's ball (its table 3.1).
SEED_RADIUS = 0.025
SEED_MASS = 0.15
# Carom ball (UMB Sports Rules 2.2, "Balls": 61-61.5 mm in diameter, 205-220 g): the 61.5 mm
# diameter of tournament sets and the 210 g typical weight (also pooltool's BILLIARD_GENERIC
# ball mass, pooltool.objects.ball.params; its radius there, 30.48 mm, is 2.4 in, below the
# UMB range, so we keep the UMB figure).
CAROM_RADIUS = 0.03075
CAROM_MASS = 0.210
# The carom table (UMB Sports Rules 2.1, "Billiard, cushion, cloth"): a free playing surface of
# 2.84 x 1.42 m (+-5 mm), cushions 37 mm (+-1 mm) high at their frontmost point (the nose).
CAROM_LENGTH, CAROM_WIDTH = 2.84, 1.42
CAROM_CUSHION_HEIGHT = 0.037



def _readonly(a):
    a.setflags(write=False)
    return a


def _per_ball(value, n, name):
    if type(value) is float and math.isfinite(value) and value > 0:  # one size for all: the common case
        return value, np.full(n, value)
    arr = np.asarray(value, dtype=np.float64)
    if arr.ndim == 0:
        if not (math.isfinite(float(arr)) and float(arr) > 0):
            raise ValueError(f"ball {name} must be a finite number > 0, got {float(arr)!r}")
        return float(arr), np.full(n, float(arr))
    if arr.shape != (n,):
        raise ValueError(f"ball {name} must be a number or an array of shape ({n},), got shape {arr.shape}")
    if not (np.minimum.reduce(arr) > 0.0 and np.maximum.reduce(arr) < math.inf):  # a NaN fails both
        bad = np.flatnonzero(~(np.isfinite(arr) & (arr > 0)))
        raise ValueError(f"ball {bad[0]} has {name} {float(arr[bad[0]])!r}; it must be finite and > 0")
    return _readonly(arr.copy()), arr.copy()


def _array(value, n, cols, name):
    if value is None:
        return np.zeros((n, cols))
    arr = np.array(value, dtype=np.float64)
    if arr.shape != (n, cols):
        raise ValueError(f"{name} must have shape ({n}, {cols}), got {arr.shape}")
    if np.isfinite(arr).all():
        return arr
    bad = np.argwhere(~np.isfinite(arr))
    if bad.size:
        i = bad[0, 0]
        raise ValueError(f"ball {i} has a non-finite {name}: {arr[i].tolist()}")
    return arr


class Balls:
    """A set of balls: ball 0 is the cue ball. SI units; arrays are read-only.

    | attribute | shape | meaning |
    | --- | --- | --- |
    | `xy` | (N, 2) | centre positions (m), origin at a table corner |
    | `v` | (N, 2) | velocities (m/s) |
    | `w` | (N, 3) | angular velocities (rad/s); z up, a ball rolling along +x has w_y = v/R |
    | `radius`, `mass` | float or (N,) | radius (m) and mass (kg) |
    | `pocketed` | (N,) bool | off the table |
    | `z`, `vz` | (N,) | centre's height above its rest on the cloth (m, >= 0), vertical velocity (m/s) |

    z and vz (the `air` array (N, 2), read-only) are zeros for a ball on the cloth; a ball with
    either non-zero is airborne (its centre at height R + z).
    """

    __slots__ = ("xy", "v", "w", "radius", "mass", "pocketed", "air", "_radii", "_masses")

    def __init__(self, xy, v=None, w=None, radius=BALL_RADIUS, mass=BALL_MASS, pocketed=None, z=None, vz=None):
        xy = np.array(xy, dtype=np.float64)
        if xy.ndim != 2 or xy.shape[1] != 2 or xy.shape[0] == 0:
            raise ValueError(f"xy must have shape (N, 2) with N >= 1, got {xy.shape}")
        n = xy.shape[0]
        xy = _array(xy, n, 2, "position")
        v = _array(v, n, 2, "velocity")
        w = _array(w, n, 3, "angular velocity")
        self.radius, radii = _per_ball(radius, n, "radius")
        self.mass, masses = _per_ball(mass, n, "mass")
        if pocketed is None:
            pocketed = np.zeros(n, dtype=bool)
        pocketed = np.array(pocketed, dtype=bool)
        if pocketed.shape != (n,):
            raise ValueError(f"pocketed must have shape ({n},), got {pocketed.shape}")
        air = _air(z, vz, n)
        _check_overlaps(xy, radii, pocketed, air[:, 0])
        self._set(xy, v, w, pocketed, radii, masses, air)

    def _set(self, xy, v, w, pocketed, radii, masses, air=None):
        self.xy, self.v, self.w = _readonly(xy), _readonly(v), _readonly(w)
        self.pocketed = _readonly(pocketed)
        self._radii, self._masses = radii, masses
        self.air = _on_cloth(xy.shape[0]) if air is None else _readonly(air)

    @classmethod
    def _trusted(cls, xy, v, w, pocketed, like, air=None):
        """Balls from arrays the engine produced (already valid): no checks, no copies. `air`
        (N, 2) holds each ball's z and vz (None: every ball on the cloth)."""
        out = cls.__new__(cls)
        out.radius, out.mass = like.radius, like.mass
        out._set(xy, v, w, pocketed, like._radii, like._masses, air)
        return out

    @property
    def z(self) -> np.ndarray:
        """Height of each centre above where it rests on the cloth (m), shape (N,)."""
        return self.air[:, 0]

    @property
    def vz(self) -> np.ndarray:
        """Vertical velocity of each ball (m/s), shape (N,)."""
        return self.air[:, 1]

    @property
    def airborne(self) -> np.ndarray:
        """Which balls are in the air (above the cloth, or leaving it), shape (N,) bool."""
        return (self.air[:, 0] > 0.0) | (self.air[:, 1] != 0.0)

    @property
    def on_cloth(self) -> bool:
        """True if every ball is on the cloth (no z, no vz): the level engine can simulate them.
        Balls made without z and vz share one zeros array, so this is an identity test."""
        return self.air is _on_cloth(self.air.shape[0]) or not np.count_nonzero(self.air)

    def __reduce__(self):
        # copy.copy, copy.deepcopy and pickle all rebuild through _rebuild_balls, which marks
        # the arrays read-only again (a plain copy of a read-only array is writable, and numba
        # would then compile the whole engine a second time for writable arrays).
        return _rebuild_balls, (self.xy, self.v, self.w, self.pocketed, self.radius, self.mass,
                                self._radii, self._masses, self.air)

    def __len__(self):
        return self.xy.shape[0]

    def __repr__(self):
        moving = int(np.count_nonzero(np.any(self.v != 0, axis=1)))
        return f"Balls(n={len(self)}, moving={moving}, pocketed={int(self.pocketed.sum())})"

    @property
    def radii(self) -> np.ndarray:
        """Radius of every ball, shape (N,)."""
        return self._radii

    @property
    def masses(self) -> np.ndarray:
        """Mass of every ball, shape (N,)."""
        return self._masses

    def with_ball_at(self, k: int, xy) -> Balls:
        """These balls (at rest) with ball `k` on the table at `xy` (m), the others as they are:
        what placing the cue ball in hand does. Checks only ball k (finite, overlapping no
        ball on the table beyond the contact tolerance), so it costs O(N); ValueError otherwise."""
        x, y = float(xy[0]), float(xy[1])
        if not (math.isfinite(x) and math.isfinite(y)):
            raise ValueError(f"ball {k}'s position must be finite, got {(x, y)}")
        _, gap, other = nearest_to(self.xy, self._radii, self.pocketed, k, x, y)
        gap -= self._radii[k]
        if gap < -CONTACT_TOLERANCE:
            i, j = sorted((k, other))
            raise ValueError(f"balls {i} and {j} overlap by {-gap * 1000:.3g} mm")
        xy_new, pocketed = self.xy.copy(), self.pocketed.copy()
        xy_new[k], pocketed[k] = (x, y), False
        return Balls._trusted(xy_new, self.v, self.w, pocketed, self, self.air)

    def sized(self, radii, masses) -> Balls:
        """These balls with each ball's radius and mass replaced ((N,) arrays, finite and > 0).
        Larger balls need more room: the balls on the table are spread about their centre by
        g, the largest new radius over the smallest old one. Every centre distance grows by g
        and every sum of two radii by at most g, so the gap between two balls (distance minus
        radii) is at least g times what it was: balls apart stay apart (no check needed), and
        these balls, checked when made, overlap by at most g times the contact tolerance."""
        n = len(self)
        given = np.asarray(radii, dtype=np.float64), np.asarray(masses, dtype=np.float64)
        if given[0].shape == given[1].shape == (n,):
            # One compiled call checks them, copies them (a read-only copy for `radius` and
            # `mass`, the engine's own) and spreads the balls: `fixed` holds the positions,
            # radius and mass (read-only), `own` the engine's radii and masses.
            fixed, own = np.empty(4 * n), np.empty(2 * n)
            grow = _resized(self.xy, self.pocketed, self._radii, given[0], given[1], fixed, own)
            if grow >= 0.0:
                fixed.setflags(write=False)  # and so every view of it below
                out = Balls.__new__(Balls)
                out.radius, out.mass = fixed[2 * n:3 * n], fixed[3 * n:]
                out.xy = fixed[:2 * n].reshape(n, 2) if grow > 1.0 else self.xy
                out.v, out.w, out.pocketed, out.air = self.v, self.w, self.pocketed, self.air
                out._radii, out._masses = own[:n], own[n:]
                return out
        radius, new_radii = _per_ball(radii, n, "radius")  # a number, or a bad value: named here
        mass, new_masses = _per_ball(masses, n, "mass")
        xy = np.empty((n, 2))
        grow = _spread(self.xy, self.pocketed, self._radii, new_radii, xy)
        out = Balls.__new__(Balls)
        out.radius, out.mass = radius, mass
        out._set(xy if grow > 1.0 else self.xy, self.v, self.w, self.pocketed, new_radii, new_masses, self.air)
        return out

    def energy(self) -> float:
        """Kinetic energy (translation, vz included, and rotation) of the balls on the table (J)."""
        kinetic = kinetic_energy(self.v, self.w, self._radii, self._masses) + 0.5 * self._masses * self.air[:, 1] ** 2
        return float(np.sum(kinetic[~self.pocketed]))


@kernel
def _resized(xy, pocketed, old_radii, radii, masses, fixed, own):
    """`Balls.sized` of (N,) radii and masses: -1 if one is not finite and > 0; else fixed (4N,)
    holds the spread positions (2N, `_spread`: written only if its factor g > 1), the radii and
    the masses, own (2N,) the radii and the masses again, and g is returned."""
    n = xy.shape[0]
    for i in range(n):
        if not (0.0 < radii[i] < math.inf and 0.0 < masses[i] < math.inf):
            return -1.0
        fixed[2 * n + i], fixed[3 * n + i], own[i], own[n + i] = radii[i], masses[i], radii[i], masses[i]
    return _spread(xy, pocketed, old_radii, radii, fixed[:2 * n].reshape((n, 2)))


@kernel
def _spread(xy, pocketed, old_radii, new_radii, out):
    """`Balls.sized`'s spread: g = max(new_radii) / min(old_radii); if g > 1, `out` (N, 2) is xy
    with the balls on the table spread about their mean position by g (a pocketed ball's row
    as it was). Returns g. The arithmetic of numpy's xy[on].mean(axis=0) (a running sum,
    row by row, over the count) and of centre + (xy - centre) * g."""
    largest, smallest = new_radii[0], old_radii[0]
    for i in range(1, xy.shape[0]):
        largest, smallest = max(largest, new_radii[i]), min(smallest, old_radii[i])
    grow = largest / smallest
    if grow <= 1.0:
        return grow
    cx = cy = 0.0
    count = 0
    for i in range(xy.shape[0]):
        if not pocketed[i]:
            cx, cy = (xy[i, 0], xy[i, 1]) if count == 0 else (cx + xy[i, 0], cy + xy[i, 1])
            count += 1
    cx, cy = cx / count, cy / count
    for i in range(xy.shape[0]):
        if pocketed[i]:
            out[i, 0], out[i, 1] = xy[i, 0], xy[i, 1]
        else:
            out[i, 0], out[i, 1] = cx + (xy[i, 0] - cx) * grow, cy + (xy[i, 1] - cy) * grow
    return grow


def kinetic_energy(v, w, radii, masses) -> np.ndarray:
    """Kinetic energy (J) of each ball, translation plus rotation (a solid ball: I = 2/5 m R^2).

    v (..., N, 2) velocities and w (..., N, 3) spins, any leading axes (the samples of a
    trajectory, say); radii and masses (N,). Pocketed balls count like any other: callers
    mask them (`Balls.energy`, `invariants.check`)."""
    return 0.5 * masses * np.sum(v**2, axis=-1) + 0.2 * masses * radii**2 * np.sum(w**2, axis=-1)


def _rebuild_balls(xy, v, w, pocketed, radius, mass, radii, masses, air=None):
    """Balls from the state `Balls.__reduce__` saved, with the flags `Balls.__init__` gives."""
    out = Balls.__new__(Balls)
    out.radius = _readonly(radius) if isinstance(radius, np.ndarray) else radius
    out.mass = _readonly(mass) if isinstance(mass, np.ndarray) else mass
    out._set(xy, v, w, pocketed, radii, masses, None if air is None else np.array(air))
    return out


@functools.lru_cache(maxsize=64)
def _on_cloth(n):
    """The air array of n balls on the cloth (zeros), one read-only array per n: shared by
    every such Balls, and always the array type the compiled engine was compiled for."""
    return _readonly(np.zeros((n, 2)))


def _air(z, vz, n):
    """Balls' (z, vz) as an (N, 2) array (None for both: on the cloth), checked."""
    if z is None and vz is None:
        return _on_cloth(n)
    air = np.zeros((n, 2))
    for col, (value, name) in enumerate(((z, "height z"), (vz, "vertical velocity vz"))):
        if value is None:
            continue
        arr = np.asarray(value, dtype=np.float64)
        if arr.shape != (n,):
            raise ValueError(f"{name} must have shape ({n},), got {arr.shape}")
        bad = np.flatnonzero(~np.isfinite(arr) | ((arr < 0.0) if col == 0 else False))
        if bad.size:
            raise ValueError(f"ball {bad[0]} has {name} {float(arr[bad[0]])!r}; it must be finite"
                             + (" and >= 0 (m above the cloth)" if col == 0 else ""))
        air[:, col] = arr
    return air


def _check_overlaps(xy, radii, pocketed, z):
    if not overlapping(xy, radii, pocketed, np.ascontiguousarray(z), CONTACT_TOLERANCE):
        return  # the common case, compiled; the pair that overlaps most is named below
    on = np.flatnonzero(~pocketed)
    if on.size < 2:
        return
    p = xy[on]
    if z is not None and np.any(z != 0.0):  # balls in the air may pass over others: centres in 3D
        p = np.column_stack((p, radii[on] + z[on]))
    d = np.sqrt(np.sum((p[:, None, :] - p[None, :, :]) ** 2, axis=-1))
    overlap = radii[on][:, None] + radii[on][None, :] - d
    np.fill_diagonal(overlap, -np.inf)
    a, b = np.unravel_index(np.argmax(overlap), overlap.shape)
    if overlap[a, b] > CONTACT_TOLERANCE:
        i, j = sorted((on[a], on[b]))
        raise ValueError(f"balls {i} and {j} overlap by {overlap[a, b] * 1000:.3g} mm")


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
        out = Table.__new__(Table)
        state = out.__dict__
        state.update(length=self.length, width=self.width, cushion_height=height, corner_pocket=self.corner_pocket,
                     side_pocket=self.side_pocket)
        state.update(geometry(plan, self.pocket_entries, corner, side, exact=False))
        state["_plan"] = plan
        return out

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
            object.__setattr__(self, name, _readonly(value) if isinstance(value, np.ndarray) else value)

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


# The standard 8-ball rack read from the apex row by row (8 in the middle, a solid and a
# stripe in the back corners).
RACK_ORDER = ((1,), (9, 2), (10, 8, 3), (11, 7, 14, 4), (5, 13, 15, 6, 12))


def rack(table: Table, seed=None, jitter=None, radius=BALL_RADIUS, mass=BALL_MASS, cue_xy=None) -> Balls:
    """The report's triangle of 15 object balls with its apex on the foot spot (3/4 of the
    length, mid-width) and the cue ball on the head spot (1/4 of the length) unless `cue_xy`.

    `jitter` (m) is how far each object ball may sit from its ideal spot, drawn uniformly in a
    disc from `numpy.random.default_rng(seed)`; the ideal spots are spaced 2R + 2 jitter, so
    jittered balls never overlap. It defaults to 0.2 mm when a seed is given and to 0 (a
    perfect frozen rack, every neighbour touching) when it is not.

    `radius` (one number: every ball the same size) and `mass` default to regulation balls;
    any size works that fits the table. Raises ValueError when it does not: the rack (with
    its jitter) must lie inside the rails and off every pocket's capture circle, whatever the
    seed, which takes a playing area of at least 4 (2 sqrt(3) s + R + jitter) x
    2 (2 s + R + jitter) (s = 2R + 2 jitter; 0.913 x 0.288 m for regulation balls and the
    default jitter); and the balls must stand taller than the table's cushion nose
    (2R > `table.cushion_height`), or they would pass under the cushions.
    """
    if not isinstance(table, Table):
        raise TypeError(f"table must be pool_env.physics.Table, got {type(table).__name__}")
    if jitter is None:
        jitter = 2e-4 if seed is not None else 0.0
    if not (math.isfinite(jitter) and jitter >= 0):
        raise ValueError(f"jitter must be finite and >= 0, got {jitter!r}")
    if np.ndim(radius) != 0 or not (math.isfinite(float(radius)) and float(radius) > 0):
        raise ValueError(f"rack's radius must be one finite number > 0 (every ball the same size), got {radius!r}")
    radius = float(radius)
    if 2.0 * radius <= table.cushion_height:
        raise ValueError(
            f"balls of radius {radius} m are too small for this table: its cushion nose is "
            f"{table.cushion_height} m above the cloth, at or above the top of the balls ({2.0 * radius:.4g} m), "
            "so they would pass under the cushions; use balls with 2R > cushion_height, or a lower cushion_height"
        )
    if cue_xy is None and np.ndim(mass) == 0:
        spots, template = _rack_layout(table, radius, jitter, float(mass))
        xy = spots.copy()
    else:
        xy = _rack_spots(table, radius, jitter, cue_xy)
        _check_rack_fits(table, xy, radius, jitter, cue_xy is None)
        template = None
    if jitter > 0:
        rng = np.random.default_rng(seed)
        angle = rng.uniform(0.0, 2.0 * math.pi, 15)
        dist = jitter * np.sqrt(rng.uniform(0.0, 1.0, 15))
        xy[1:, 0] += dist * np.cos(angle)
        xy[1:, 1] += dist * np.sin(angle)
    if template is None:
        return Balls(xy, radius=radius, mass=mass)
    # Spots 2R + 2 jitter apart, each ball within jitter of its spot: no overlap to look for.
    # The per-ball radii and masses are the compiled engine's inputs (writable, like every
    # Balls' own): each rack gets its own copy, so no two racks share one.
    balls = Balls._trusted(xy, template.v, template.w, template.pocketed, template)
    balls._radii, balls._masses = template._radii.copy(), template._masses.copy()
    return balls


def _rack_spots(table, radius, jitter, cue_xy):
    """The cue ball's spot and the 15 object balls' ideal spots (before the jitter)."""
    spacing = 2.0 * radius + 2.0 * jitter
    L, W = table.length, table.width
    apex_x, mid_y = 0.75 * L, 0.5 * W
    xy = np.zeros((16, 2))
    xy[0] = cue_xy if cue_xy is not None else (0.25 * L, mid_y)
    for row, numbers in enumerate(RACK_ORDER):
        for k, number in enumerate(numbers):
            xy[number] = (apex_x + row * spacing * math.sqrt(3.0) / 2.0, mid_y + (k - row / 2.0) * spacing)
    return xy


@functools.lru_cache(maxsize=32)
def _rack_layout(table, radius, jitter, mass):
    """The default rack's spots on a table, checked once to fit, and a resting Balls on them
    whose radius, mass and zero velocities every rack of the same layout shares (`rack` runs
    at every env reset: this saves it the checks and the array building each time)."""
    spots = _rack_spots(table, radius, jitter, None)
    _check_rack_fits(table, spots, radius, jitter, True)
    return _readonly(spots), Balls(spots, radius=radius, mass=mass)


def _check_rack_fits(table, xy, radius, jitter, check_cue):
    """Raise ValueError if a rack ball could sit outside the rails or over a pocket: the 15
    object balls anywhere within `jitter` of their spots, and the cue ball on the head spot
    (when `check_cue`; a cue_xy the caller chose is checked where it is simulated). Scalar
    arithmetic first (`rack` runs at every env reset): the exact check per ball only runs
    when a pocket comes near the rack's bounding box."""
    L, W = table.length, table.width
    s, reach, tol = 2.0 * radius + 2.0 * jitter, radius + jitter, CONTACT_TOLERANCE
    # The object balls' spots span x in [0.75 L, 0.75 L + 2 sqrt(3) s], y in W/2 +- 2 s.
    x_lo, x_hi = 0.75 * L - reach, 0.75 * L + 2.0 * math.sqrt(3.0) * s + reach
    y_lo, y_hi = 0.5 * W - 2.0 * s - reach, 0.5 * W + 2.0 * s + reach
    if x_lo < -tol or x_hi > L + tol or y_lo < -tol or y_hi > W + tol or (check_cue and 0.25 * L < radius - tol):
        raise ValueError(
            f"the {L} x {W} m table is too small for a rack of balls of radius {radius} m "
            f"(jitter {jitter} m): the rack needs a playing area of at least "
            f"{_up(4.0 * (2.0 * math.sqrt(3.0) * s + reach))} x {_up(2.0 * (2.0 * s + reach))} m"
        )
    for px, py, pr in table.pocket_reach.tolist():
        near = math.hypot(max(x_lo - px, 0.0, px - x_hi), max(y_lo - py, 0.0, py - y_hi)) < pr
        if check_cue:
            near = near or math.hypot(xy[0, 0] - px, xy[0, 1] - py) < pr + radius
        if near:
            break
    else:
        return
    first = 0 if check_cue else 1
    spots = np.ascontiguousarray(xy[first:])
    # Each ball anywhere within the jitter of its spot: a ball of radius R + jitter on it
    # must keep off every cushion and opening (R: the widest cushion reach of any model).
    n = len(spots)
    code, i, k = first_misplaced(spots, np.full(n, radius), np.full(n, radius + jitter), jitter,
                                 np.zeros(n, dtype=np.bool_), bounds_of(table), 0.0)
    if code != 0:
        x, y = spots[i]
        where = f"over pocket {k}" if code == 2 else "against a pocket's jaws"
        raise ValueError(
            f"the {L} x {W} m table is too small for a rack with these pockets: ball {i + first}'s spot "
            f"({x:.4f}, {y:.4f}) m is {where} or within the jitter ({jitter} m) of it"
        )


def _up(length):
    """A length rounded up to 0.1 mm, for messages stating a minimum."""
    return f"{math.ceil(length * 1e4 - 1e-9) / 1e4:.4f}"
