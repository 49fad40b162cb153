"""`python -m pool_env.bench stability`: random scenes through the engine, invariants checked per event.

The invariants are pool_env.physics.invariants'; failures are counted by kind.

Each shot is a random break: a rack with random jitter (sometimes frozen, every ball
touching its neighbours), a few extra balls dropped anywhere on the cloth without overlap,
the cue ball on the head spot or anywhere free, struck at 0.5-15 m/s with random English,
follow or draw, aimed at the head ball or anywhere. Shot k draws everything from
numpy.random.default_rng([seed, k]), so any shot can be rerun alone (`--first k --shots 1`).
`--physics` picks the physics: the standard preset, the seed preset, a mix (default: half
standard, the rest the seed preset or random model switches with realistic coefficients),
or `extreme` (any model, restitution anywhere in [0, 1], friction from a tenth to twice the
standard values). `--elevated` raises the cue of every shot: half the shots at 0-30 degrees
(swerves and jumps), half at 30-85 (masse), at a cue speed redrawn in 0.5-6 m/s (harder
elevated hits mostly fly off the table), with the slate's e_t in [0.2, 0.8] and mu_t in
[0.05, 0.4] unless the physics is the standard preset; those draws come after the rest, so
shot k's scene is the level sweep's shot k with the cue raised.

Reported: failures by kind (see invariants.KINDS) with the first few shots of each (a shot
the engine refuses as a state it does not model, `not_modelled`, is listed apart and is no
failure), events
per shot (median, p99, max), contacts per pair (the most contacts between two bodies in one
shot: a chattering pair shows up here), and the worst case. When pooltool is importable,
the same breaks (standard physics, six-pocket table, balls on the table) also run through
pooltool, and its events per shot and chattering pairs are printed beside ours.
"""

from __future__ import annotations

import argparse
import collections
import dataclasses
import math
import time

import numpy as np

CHATTER = 20  # contacts between the same two bodies in one shot that count as chatter
PHYSICS_CHOICES = ("standard", "seed", "mixed", "extreme")


def random_physics(rng, kind):
    """The physics of one shot (see the module docstring)."""
    from pool_env.physics import Physics
    from pool_env.physics.config import BALL_BALL_MODELS, CUSHION_MODELS

    if kind == "mixed":
        kind = rng.choice(["standard", "standard", "seed", "realistic"])
    if kind == "standard":
        return Physics.standard()
    if kind == "seed":
        return Physics.seed()
    std = Physics.standard()
    if kind == "realistic":
        return dataclasses.replace(
            std, ball_ball=str(rng.choice(BALL_BALL_MODELS)), cushion=str(rng.choice(CUSHION_MODELS)),
            e_b=float(rng.uniform(0.8, 1.0)), e_c=float(rng.uniform(0.5, 0.95)), mu_s=float(rng.uniform(0.1, 0.3)),
            mu_r=float(rng.uniform(0.005, 0.02)), f_c=float(rng.uniform(0.05, 0.3)), spin=bool(rng.random() < 0.9))
    scale = lambda: float(np.exp(rng.uniform(np.log(0.1), np.log(2.0))))  # noqa: E731
    return dataclasses.replace(
        std, ball_ball=str(rng.choice(BALL_BALL_MODELS)), cushion=str(rng.choice(CUSHION_MODELS)),
        e_b=float(rng.uniform(0.0, 1.0)), e_c=float(rng.uniform(0.0, 1.0)), mu_s=std.mu_s * scale(),
        mu_r=std.mu_r * scale(), mu_sp=std.mu_sp * scale(), f_c=std.f_c * scale(), spin=bool(rng.random() < 0.9))


def _free_spot(rng, xy, table, radius, tries=200):
    """A uniformly random spot on the cloth where a ball overlaps no other, clears the rails
    by 1 mm and sits over no pocket; None if none was found."""
    for _ in range(tries):
        p = rng.uniform((radius + 1e-3, radius + 1e-3), (table.length - radius - 1e-3, table.width - radius - 1e-3))
        if xy.size and np.min(np.hypot(*(xy - p).T)) < 2 * radius + 1e-6:
            continue
        if table.pockets.size and np.any(np.hypot(*(table.pockets[:, :2] - p).T) < table.pockets[:, 2] + 1e-3):
            continue
        return p
    return None


def random_break(rng, physics="mixed", elevated=False):
    """(balls, table, physics, description) of one random shot (see the module docstring)."""
    from pool_env.physics import BALL_MASS, BALL_RADIUS, Balls, Physics, Table, rack, strike
    from pool_env.physics.cue import MAX_ELEVATION, MISCUE_LIMIT

    table = Table.eight_foot() if rng.random() < 0.8 else Table.seed()
    jitter = float(rng.choice([0.0, 1e-6, 1e-5, 2e-4, 1e-3]))
    balls = rack(table, seed=int(rng.integers(2**31)), jitter=jitter)
    xy = balls.xy.copy()
    if rng.random() < 0.3:  # the cue ball anywhere free
        spot = _free_spot(rng, xy[1:], table, BALL_RADIUS)
        if spot is not None:
            xy[0] = spot
    extra = int(rng.integers(0, 5))
    for _ in range(extra):
        spot = _free_spot(rng, xy, table, BALL_RADIUS)
        if spot is not None:
            xy = np.vstack([xy, spot])
    balls = Balls(xy)
    aim = xy[1] - xy[0]
    angle = math.atan2(aim[1], aim[0]) + rng.normal(0.0, 0.05) if rng.random() < 0.8 else rng.uniform(0, 2 * math.pi)
    speed = float(rng.uniform(0.5, 15.0))
    force = speed * BALL_MASS / 0.005
    r, a = MISCUE_LIMIT * math.sqrt(rng.random()), rng.uniform(0, 2 * math.pi)  # any tip offset short of a miscue
    offset = (r * math.cos(a), r * math.sin(a))
    phys = random_physics(rng, physics)
    elevation = 0.0
    if elevated:
        low, high = (math.radians(30.0), MAX_ELEVATION) if rng.random() < 0.5 else (0.0, math.radians(30.0))
        elevation = float(rng.uniform(low, high))
        speed = float(rng.uniform(0.5, 6.0))
        force = speed * BALL_MASS / 0.005
        if phys != Physics.standard():
            phys = dataclasses.replace(phys, e_t=float(rng.uniform(0.2, 0.8)), mu_t=float(rng.uniform(0.05, 0.4)))
    balls = strike(balls, force=(force * math.cos(angle), force * math.sin(angle)), offset=offset,
                   elevation=elevation, physics=phys)
    description = (f"{len(xy)} balls (rack jitter {jitter:g} m, {len(xy) - 16} extra) on the "
                   f"{table.length} x {table.width} m table with {len(table.pockets)} pockets; cue ball at "
                   f"({xy[0, 0]:.3f}, {xy[0, 1]:.3f}) struck at {speed:.2f} m/s towards {math.degrees(angle):.1f} deg, "
                   f"tip offset ({offset[0]:.2f}, {offset[1]:.2f}), elevation {math.degrees(elevation):.1f} deg; "
                   f"{phys}")
    return balls, table, phys, description


def most_contacts(result):
    """The most contact events between the same two bodies (balls, or a ball and a cushion)."""
    from pool_env.physics.kinds import BALL_BALL_KINDS, BALL_CUSHION

    _, kinds, ei, ej = result.event_arrays
    contact = np.isin(kinds, (*BALL_BALL_KINDS, BALL_CUSHION))
    if not contact.any():
        return 0
    cushion = kinds[contact] == BALL_CUSHION
    keys = np.stack([ei[contact], np.where(cushion, -1 - ej[contact], ej[contact])], axis=1)
    return int(np.unique(keys, axis=0, return_counts=True)[1].max())


def run(shots, seed=0, first=0, physics="mixed", rerun_every=10, show=3, verbose=True, elevated=False):
    """Run the sweep; returns a summary dict (see `main` for what it prints)."""
    from pool_env.physics.invariants import run_checked
    from pool_env.physics.kinds import BALL_BALL_SETTLE

    failures = collections.defaultdict(list)
    events, settles, contacts = [], [], []
    worst = None
    wall = time.perf_counter()
    for k in range(first, first + shots):
        rng = np.random.default_rng([seed, k])
        balls, table, phys, description = random_break(rng, physics, elevated)
        result, violations = run_checked(balls, table, phys, rerun=rerun_every > 0 and k % rerun_every == 0)
        for v in violations:
            failures[v.kind].append((k, v, description))
        if result is None:
            continue
        n = len(result.event_times)
        events.append(n)
        settles.append(int(np.count_nonzero(result.event_arrays[1] == BALL_BALL_SETTLE)))
        contacts.append(most_contacts(result))
        if worst is None or n > worst[1]:
            worst = (k, n, description)
        if verbose and (k - first + 1) % 1000 == 0:
            print(f"  {k - first + 1} shots, {time.perf_counter() - wall:.0f} s", flush=True)
    return {
        "shots": shots, "seed": seed, "first": first, "physics": physics, "wall": time.perf_counter() - wall,
        "failures": dict(failures), "events": np.array(events), "settles": np.array(settles),
        "contacts": np.array(contacts), "worst": worst,
    }


def distribution(values):
    values = np.asarray(values)
    if values.size == 0:
        return "none"
    return f"median {np.median(values):.0f}, p99 {np.percentile(values, 99):.0f}, max {values.max()}"


def pooltool_sweep(shots, seed=0, first=0):
    """The same breaks (standard physics, six-pocket table only) through pooltool: (events per
    shot, most contacts per pair per shot, shots skipped), or None with the reason if
    pooltool is not importable."""
    try:
        import pooltool as pt  # noqa: F401
    except Exception as exc:  # noqa: BLE001 - any import failure means: no comparison
        return None, f"{type(exc).__name__}: {exc}"
    from pool_env.bench.speed_pooltool import pooltool_system

    events, chatter, skipped = [], [], 0
    for k in range(first, first + shots):
        balls, table, _, _ = random_break(np.random.default_rng([seed, k]), "standard")
        if len(table.pockets) != 6:
            skipped += 1
            continue
        system = pooltool_system(balls, table)
        pt.simulate(system, inplace=True)
        pairs = collections.Counter()
        for event in system.events:
            kind = str(event.event_type.value)
            if kind in ("ball_ball", "ball_linear_cushion", "ball_circular_cushion"):
                pairs[tuple(sorted(event.ids))] += 1
        events.append(sum(str(e.event_type.value) != "none" for e in system.events))
        chatter.append(max(pairs.values(), default=0))
    return (np.array(events), np.array(chatter), skipped), None


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m pool_env.bench stability", description=__doc__.split("\n")[0])
    parser.add_argument("--shots", type=int, default=1000, help="number of random breaks (default 1000)")
    parser.add_argument("--seed", type=int, default=0, help="sweep seed: shot k uses default_rng([seed, k])")
    parser.add_argument("--first", type=int, default=0, help="index of the first shot (to rerun one: --shots 1)")
    parser.add_argument("--physics", choices=PHYSICS_CHOICES, default="mixed", help="physics of the shots")
    parser.add_argument("--rerun-every", type=int, default=10,
                        help="re-simulate every n-th shot and require an identical result (0: never)")
    parser.add_argument("--show", type=int, default=3, help="failing shots listed per kind")
    parser.add_argument("--elevated", action="store_true",
                        help="raise the cue of every shot to a random elevation (0-85 deg): balls in the air")
    parser.add_argument("--no-pooltool", action="store_true", help="skip the pooltool comparison")
    parser.add_argument("--multi-shot", action="store_true",
                        help="random shot sequences from wherever the balls stop (bench/sequences.py): --shots "
                             "sequences of --length shots, standard physics")
    parser.add_argument("--length", type=int, default=20, help="shots per sequence with --multi-shot (default 20)")
    parser.add_argument("--check-every", type=int, default=100,
                        help="with --multi-shot, check every invariant at every event of every n-th shot")
    args = parser.parse_args(argv)
    if args.multi_shot:
        from pool_env.bench import sequences

        print(f"stability --multi-shot: {args.shots} sequences of up to {args.length} shots (seed {args.seed}); "
              f"every final state must be a valid start, invariants on every {args.check_every}-th shot")
        return 1 if sequences.report(sequences.run(args.shots, args.length, args.seed, None, args.check_every)) else 0

    print(f"stability: {args.shots} random {'elevated ' if args.elevated else ''}breaks (seed {args.seed}, shots "
          f"{args.first}-{args.first + args.shots - 1}, physics {args.physics}), invariants checked at every event")
    s = run(args.shots, args.seed, args.first, args.physics, args.rerun_every, args.show, elevated=args.elevated)
    print(f"wall time {s['wall']:.1f} s ({1e3 * s['wall'] / max(args.shots, 1):.2f} ms a shot, checks included)")
    refused = s["failures"].pop("not_modelled", [])
    total = sum(len(v) for v in s["failures"].values())
    if not total:
        print("failures: none")
    else:
        failing = len({k for v in s["failures"].values() for k, _, _ in v})
        print(f"failures: {total} in {failing} shots")
    for kind, items in sorted(s["failures"].items()) + ([("refused, not modelled", refused)] if refused else []):
        print(f"  {kind}: {len(items)}")
        for k, v, description in items[: args.show]:
            print(f"    shot {k}: {v.detail}\n      {description}")
    print(f"events per shot: {distribution(s['events'])}")
    print(f"ball_ball_settle events per shot: {distribution(s['settles'])}")
    print(f"most contacts between two bodies in a shot: {distribution(s['contacts'])}; "
          f"shots with {CHATTER} or more: {int(np.count_nonzero(s['contacts'] >= CHATTER))}")
    if s["worst"] is not None:
        k, n, description = s["worst"]
        print(f"worst case: shot {k}, {n} events: {description}\n  rerun: python -m pool_env.bench stability "
              f"--seed {args.seed} --first {k} --shots 1 --physics {args.physics}"
              + (" --elevated" if args.elevated else ""))
    if not args.no_pooltool and not args.elevated:
        figures, reason = pooltool_sweep(args.shots, args.seed, args.first)
        if figures is None:
            print(f"pooltool: not importable ({reason}); comparison skipped")
        else:
            events, chatter, skipped = figures
            print(f"pooltool (standard physics, {len(events)} six-pocket shots, {skipped} skipped): events per shot "
                  f"{distribution(events)}; shots with a pair of {CHATTER}+ contacts: "
                  f"{int(np.count_nonzero(chatter >= CHATTER))}")
    return 1 if total else 0
