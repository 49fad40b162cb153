"""Invariants every simulation must satisfy, checked at every event.

The hard-case suite (tests/test_hard_cases.py), the property tests and
`python -m pool_env.bench stability` all use `check` / `run_checked`. At every event instant
t the exact states just before t and just after it are sampled (`Result.sample` at
`nextafter(t, -inf)` and at t; just before t = 0 is the input itself), and:

- `non_finite`: every position, velocity and spin is finite;
- `overlap`: no two balls on the table overlap by more than OVERLAP_TOL (1 nm), their
  centres measured in 3D (at heights R + z: an airborne ball may pass over another);
- `off_table`: no ball on the cloth is inside a rail, a facing or a jaw tip by more than
  RAIL_TOL, or has its centre outside the table's rectangle and every pocket's throat (a ball
  leaves only into a pocket, or through the air: a "ball_off_table" event); no airborne ball
  is nearer than R - RAIL_TOL to a rail's or facing's nose edge (airborne.py's cushion) with
  its centre in front of it;
- `energy`: the mechanical energy (translation, with the vertical velocity, plus rotation,
  plus the potential m g z of a ball's height above its resting height) never increases from
  one sample to the next. The seed models are the documented exception: they set a ball rolling at
  once after a collision (as the seed report does), which recasts translational energy as
  rotational energy and can add some, so an instant with an event of a seed model
  (ball-ball events when `ball_ball="seed"`, cushion events when `cushion="seed"`) is not
  checked; every other step of such a simulation is;
- `momentum`: across an instant made only of "ball_ball" events (collisions) of a
  momentum-conserving model (`elastic`, `frictional`), the balls' total linear momentum is
  unchanged ("ball_ball_settle" events involve the cloth and are not collisions: see
  settle.py), to MOMENTUM_RTOL plus what the cloth's friction can change over the one-ulp
  gap between the samples before and at the instant;
- `event_cap` / `error`: the simulation raised (see `run_checked`);
- `nondeterministic`: a re-run gave different events or a different final state.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .airborne import edge_offset
from .config import cushion_reach
from .kinds import AIRBORNE, BALL_BALL, BALL_BALL_KINDS, BALL_CUSHION, POCKETED, VX, VY, VZ, WX, WZ, X, Y, Z
from .objects import kinetic_energy
from .result import SimulationError
from .simulate import simulate

OVERLAP_TOL = 1e-9  # m
RAIL_TOL = 1e-9  # m
ENERGY_RTOL = 1e-12  # of the initial kinetic energy
MOMENTUM_RTOL = 1e-12  # of the sum of |m v| before and after the instant

KINDS = ("non_finite", "overlap", "off_table", "energy", "momentum", "event_cap", "error", "nondeterministic")
MOMENTUM_MODELS = ("elastic", "frictional")


class Violation(NamedTuple):
    """One broken invariant: its kind (see KINDS), the time (s) and a description."""

    kind: str
    time: float
    detail: str


def samples(result, balls=None):
    """(instants, kind ids per instant, times, rows, states): the distinct event times, and
    the states at t = 0 and just before and just after each instant (sample 2k + 1 is just
    before instant k, 2k + 2 just after). With `balls`, the input replaces the states before
    t = 0."""
    ev_t, ev_kind = result.event_arrays[:2]
    instants, first = np.unique(ev_t, return_index=True)
    kinds = [set(g.tolist()) for g in np.split(ev_kind, first[1:])] if ev_t.size else []
    before = np.maximum(np.nextafter(instants, -np.inf), 0.0)
    times = np.concatenate(([0.0], np.column_stack((before, instants)).ravel()))
    rows, states = result.sample(times)
    if balls is not None:
        starts = [0, 1] if instants.size and instants[0] == 0.0 else [0]
        for s in starts:
            rows[s, :, X:Y + 1], rows[s, :, VX:VY + 1], rows[s, :, WX:WZ + 1] = balls.xy, balls.v, balls.w
            rows[s, :, Z], rows[s, :, VZ] = balls.z, balls.vz
            states[s] = np.where(balls.pocketed, POCKETED, np.where(balls.airborne, AIRBORNE, 0))
    return instants, kinds, times, rows, states


def check(result, balls=None, first_only=False) -> list[Violation]:
    """Every invariant violation of a `Result` (empty if none). `balls` is the simulated
    input (without it, events at t = 0 are checked against the state after them). With
    first_only, only the first violation of each kind is reported."""
    out = []

    def add(kind, t, detail):
        if not (first_only and any(v.kind == kind for v in out)):
            out.append(Violation(kind, float(t), detail))

    radii = np.asarray(result.final.radii, dtype=np.float64)
    masses = np.asarray(result.final.masses, dtype=np.float64)
    instants, kinds, times, rows, states = samples(result, balls)
    bad = ~np.isfinite(rows)
    if bad.any():
        s = int(np.argwhere(bad)[0, 0])
        add("non_finite", times[s], f"non-finite state at t = {times[s]!r}")
        rows = np.where(bad, 0.0, rows)
    sampled = (times, rows, states, radii, masses)
    _overlaps(sampled, add)
    _off_table(result, sampled, add)
    _energy(result, sampled, kinds, add)
    if result.physics.ball_ball in MOMENTUM_MODELS:
        _momentum(result, sampled, (instants, kinds), add)
    return out


def _overlaps(sampled, add):
    """`overlap`: balls on the table deeper into each other than OVERLAP_TOL (centres in 3D)."""
    times, rows, states, radii, _ = sampled
    n = rows.shape[1]
    if n < 2:
        return
    on = states != POCKETED
    x, y, z = rows[..., X], rows[..., Y], radii + rows[..., Z]
    iu, ju = np.triu_indices(n, 1)
    d = np.sqrt((x[:, iu] - x[:, ju]) ** 2 + (y[:, iu] - y[:, ju]) ** 2 + (z[:, iu] - z[:, ju]) ** 2)
    depth = np.where(on[:, iu] & on[:, ju], radii[iu] + radii[ju] - d, -np.inf)
    s, p = np.unravel_index(np.argmax(depth), depth.shape)
    if depth[s, p] > OVERLAP_TOL:
        add("overlap", times[s], f"balls {iu[p]} and {ju[p]} overlap by {depth[s, p]:.3g} m at t = {times[s]!r}")


def _off_table(result, sampled, add):
    """`off_table`: balls on the cloth inside a cushion or off the playing area; airborne balls
    inside a nose edge (see the module docstring)."""
    table, physics = result.table, result.physics
    times, rows, states, radii, _ = sampled
    air = states == AIRBORNE
    on = (states != POCKETED) & ~air
    x, y, z = rows[..., X], rows[..., Y], rows[..., Z]
    reach = np.asarray(cushion_reach(radii, table.cushion_height, physics.cushion), dtype=np.float64)
    off = np.array([edge_offset(float(r), float(rc), float(table.cushion_height)) for r, rc in zip(radii, reach)])
    for c, (x1, y1, x2, y2, nx, ny) in enumerate(np.asarray(table.rails)):
        s = nx * (x - x1) + ny * (y - y1)
        gap = s - reach
        along = ((x - x1) * (x2 - x1) + (y - y1) * (y2 - y1)) / ((x2 - x1) ** 2 + (y2 - y1) ** 2)
        alongside = (along >= 0.0) & (along <= 1.0)
        # A facing's line runs on across the table: only a centre in front of it (gap above
        # -reach) can be inside it.
        inside = on & alongside & (gap < -RAIL_TOL) & (gap >= -reach)
        inside |= air & alongside & (s >= 0.0) & (np.hypot(s, z - off) < radii - RAIL_TOL)
        if inside.any():
            s, i = np.argwhere(inside)[0]
            add("off_table", times[s], f"ball {i} is {-gap[s, i]:.3g} m inside rail {c} at t = {times[s]!r}")
    for p, (jx, jy, jr) in enumerate(np.asarray(table.jaws)):
        inside = on & (np.hypot(x - jx, y - jy) < reach + jr - RAIL_TOL)
        if inside.any():
            s, i = np.argwhere(inside)[0]
            add("off_table", times[s], f"ball {i} is inside jaw tip {p} at t = {times[s]!r}")
    outside = on & ((x < -RAIL_TOL) | (x > table.length + RAIL_TOL) | (y < -RAIL_TOL) | (y > table.width + RAIL_TOL))
    for cx, cy, cr in np.asarray(table.pocket_reach):
        outside &= np.hypot(x - cx, y - cy) >= cr  # in a pocket's throat is on the table
    if outside.any():
        s, i = np.argwhere(outside)[0]
        add("off_table", times[s], f"ball {i} left the table at ({x[s, i]:.6g}, {y[s, i]:.6g}) at t = {times[s]!r}")


def mechanical_energy(rows, radii, masses, g) -> np.ndarray:
    """Each ball's energy (J) in state rows (..., N, ROW_WIDTH): kinetic (translation with vz,
    and rotation) plus the potential m g z of its height above where it rests."""
    kinetic = kinetic_energy(rows[..., VX:VY + 1], rows[..., WX:WZ + 1], radii, masses)
    return kinetic + masses * (0.5 * rows[..., VZ] ** 2 + g * rows[..., Z])


def _energy(result, sampled, kinds, add):
    """`energy`: the total mechanical energy of the balls on the table rising anywhere."""
    physics = result.physics
    times, rows, states, radii, masses = sampled
    on = states != POCKETED
    total = np.sum(np.where(on, mechanical_energy(rows, radii, masses, physics.g), 0.0), axis=-1)
    rise = np.diff(total)
    for k, ks in enumerate(kinds):  # rise[2k + 1] is across instant k
        seeded_bb = physics.ball_ball == "seed" and any(kind in ks for kind in BALL_BALL_KINDS)
        if seeded_bb or (physics.cushion == "seed" and BALL_CUSHION in ks):
            rise[2 * k + 1] = 0.0
    tol = ENERGY_RTOL * max(total[0], 1e-300) + 1e-300
    if (rise > tol).any():
        s = int(np.argmax(rise > tol))
        add("energy", times[s + 1], f"mechanical energy rose by {rise[s]:.3g} J at t = {times[s + 1]!r}")


def _momentum(result, sampled, events, add):
    """`momentum`: the balls' horizontal momentum changed across an instant of collisions only."""
    physics = result.physics
    times, rows, states, _, masses = sampled
    instants, kinds = events
    on = states != POCKETED
    p = masses[:, None] * rows[..., VX:VY + 1] * on[..., None]
    for k, ks in enumerate(kinds):
        if ks == {BALL_BALL}:
            change = np.hypot(*(p[2 * k + 2].sum(axis=0) - p[2 * k + 1].sum(axis=0)))
            scale = np.abs(p[2 * k + 1]).sum() + np.abs(p[2 * k + 2]).sum()
            # The cloth's friction acts across the sample gap too (the instant minus the
            # float before it): at most mu_s g per ball, which for balls crawling at mm/s
            # is as large as the round-off the relative tolerance allows.
            gap = float(times[2 * k + 2] - times[2 * k + 1])
            friction = physics.mu_s * physics.g * gap * float(np.sum(masses * on[2 * k + 1]))
            if change > MOMENTUM_RTOL * scale + friction + 1e-300:
                add("momentum", instants[k], f"momentum changed by {change:.3g} kg m/s at t = {instants[k]!r}")


def same_result(a, b) -> bool:
    """True if two results have bit-identical events and final states."""
    return (all(np.array_equal(x, y) for x, y in zip(a.event_arrays, b.event_arrays))
            and all(np.array_equal(getattr(a.final, f), getattr(b.final, f)) for f in ("xy", "v", "w", "pocketed")))


def run_checked(balls, table, physics, rerun=False, **kwargs):
    """Simulate and check: (result or None, violations). A SimulationError (the event cap)
    becomes an `event_cap` violation and any other exception an `error` one; with rerun, a
    second run must give the same result (`nondeterministic` otherwise)."""
    try:
        result = simulate(balls, table, physics, **kwargs)
    except SimulationError as exc:
        return None, [Violation("event_cap", float("nan"), str(exc))]
    except Exception as exc:  # noqa: BLE001 - a crash is a finding: reported, not swallowed
        return None, [Violation("error", float("nan"), f"{type(exc).__name__}: {exc}")]
    out = check(result, balls)
    if rerun and not same_result(result, simulate(balls, table, physics, **kwargs)):
        out.append(Violation("nondeterministic", float("nan"), "a re-run gave a different result"))
    return result, out
