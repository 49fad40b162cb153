"""`Balls`: positions, velocities, spins, sizes and masses of a set of balls, checked and read-only."""

from __future__ import annotations

import functools
import math

import numpy as np

from .jit import kernel
from .placement import nearest_to, overlapping
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


def read_only(a):
    """`a`, made read-only (in place)."""
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
    return read_only(arr.copy()), arr.copy()


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
        # read_only's setflags inline: Balls are made several times a shot
        xy.setflags(write=False)
        v.setflags(write=False)
        w.setflags(write=False)
        pocketed.setflags(write=False)
        self.xy, self.v, self.w, self.pocketed = xy, v, w, pocketed
        self._radii, self._masses = radii, masses
        if air is None:
            air = _on_cloth(xy.shape[0])
        else:
            air.setflags(write=False)
        self.air = air

    @classmethod
    def _trusted(cls, xy, v, w, pocketed, like, air=None):
        """Balls from arrays the engine produced (already valid): no checks, no copies. `air`
        (N, 2) holds each ball's z and vz (None: every ball on the cloth)."""
        out = cls.__new__(cls)
        out.radius, out.mass, out._radii, out._masses = like.radius, like.mass, like._radii, like._masses
        # read_only's setflags on the new arrays only: those of `like` are read-only already
        # (a struck cue ball keeps the positions, a placed one the velocities and spins)
        if xy is not like.xy:
            xy.setflags(write=False)
        if v is not like.v:
            v.setflags(write=False)
        if w is not like.w:
            w.setflags(write=False)
        if pocketed is not like.pocketed:
            pocketed.setflags(write=False)
        if air is None:
            air = _on_cloth(xy.shape[0])
        elif air is not like.air:
            air.setflags(write=False)
        out.xy, out.v, out.w, out.pocketed, out.air = xy, v, w, pocketed, air
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
        """True if every ball is on the cloth (no z, no vz): no ball can leave the cloth then (see engine.run).
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
    out.radius = read_only(radius) if isinstance(radius, np.ndarray) else radius
    out.mass = read_only(mass) if isinstance(mass, np.ndarray) else mass
    out._set(xy, v, w, pocketed, radii, masses, None if air is None else np.array(air))
    return out


@functools.lru_cache(maxsize=64)
def _on_cloth(n):
    """The air array of n balls on the cloth (zeros), one read-only array per n: shared by
    every such Balls, and always the array type the compiled engine was compiled for."""
    return read_only(np.zeros((n, 2)))


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

