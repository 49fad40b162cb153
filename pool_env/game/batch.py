"""Struck shots simulated, one at a time or many in one `simulate_batch` call, and `play_batch` over games."""

from __future__ import annotations

from ..physics import Physics, SimulationError, Table, simulate, simulate_batch
from .shot_record import ShotRecord, StruckShot

SHOT_ERRORS = (SimulationError, ValueError)  # a shot that cannot be struck or simulated: recorded, not raised


def simulate_struck(struck: StruckShot, table: Table, physics: Physics):
    """The `Result` of a struck shot, or the SimulationError or ValueError it raised (a shot
    that could not be struck passes its ValueError on)."""
    if isinstance(struck.balls, Exception):
        return struck.balls
    try:
        return simulate(struck.balls, table, physics)
    except SHOT_ERRORS as exc:
        return exc


def simulate_struck_batch(struck, table, physics, threads: int | None = None) -> list:
    """`simulate_struck` of many shots on one table (or a table and physics per shot: sequences
    as long as `struck`), the playable ones in one `simulate_batch` call."""
    playable = [k for k, s in enumerate(struck) if not isinstance(s.balls, Exception)]
    out = [s.balls for s in struck]
    if playable:
        if not isinstance(table, Table):
            table = [table[k] for k in playable]
        if not isinstance(physics, Physics):
            physics = [physics[k] for k in playable]
        for k, result in zip(playable, simulate_batch([struck[k].balls for k in playable], table, physics,
                                                      threads=threads)):
            out[k] = result
    return out


def play_batch(games, shots, threads: int | None = None) -> list[ShotRecord]:
    """`games[k].play(shots[k])` for every k, the simulations in one `simulate_batch` call (each
    on its game's table and physics). The records, in order."""
    games, shots = list(games), list(shots)
    if len(games) != len(shots):
        raise ValueError(f"play_batch needs one shot per game, got {len(games)} games and {len(shots)} shots")
    struck = [game.strike(shot) for game, shot in zip(games, shots)]
    if games and all(g.table is games[0].table and g.physics == games[0].physics for g in games):
        results = simulate_struck_batch(struck, games[0].table, games[0].physics, threads)
    else:  # randomized equipment, or games on other tables: each shot on its game's
        results = simulate_struck_batch(struck, [g.table for g in games], [g.physics for g in games], threads)
    return [game.resolve(s, r) for game, s, r in zip(games, struck, results)]
