"""A `Game`'s snapshots: the key a snapshot must match, taking one, and checking one before it is restored."""

from __future__ import annotations

import copy

from ..physics import Table
from .shot_record import GameSnapshot


def table_key(table: Table) -> tuple:
    """What makes two tables the same table."""
    return (table.length, table.width, table.pocket_entries.tobytes(), table.cushion_height,
            table.corner_pocket, table.side_pocket)


def game_key(game) -> tuple:
    """`Game.key`: `game`'s mode, table, physics, noise, rule options and whether choices wait for `decide`."""
    noise = None if game.noise is None else tuple(sorted(game.noise.items()))
    return (game.mode, table_key(game.table), game.physics, noise, tuple(sorted(game.rule_options.items())),
            game.decisions)


def snapshot_of(game) -> GameSnapshot:
    """`Game.snapshot`: `game`'s whole state now, its noise generator's included."""
    return GameSnapshot(game.key, game.balls, game.state, game.shots, game.over,
                        copy.deepcopy(game.rng.bit_generator.state))


def check_snapshot(game, snapshot) -> None:
    """`snapshot` checked before `game` restores it: TypeError if it is no `GameSnapshot`,
    ValueError if it is another game's (naming what differs) or of another noise generator."""
    if not isinstance(snapshot, GameSnapshot):
        raise TypeError(f"restore takes a GameSnapshot, got {type(snapshot).__name__}")
    if snapshot.key != game.key:
        theirs, ours = snapshot.key, game.key
        names = ("mode", "table", "physics", "noise", "rule options", "decisions")
        what = [name for name, a, b in zip(names, theirs, ours) if a != b]
        raise ValueError(f"the snapshot is of another game: its {', '.join(what)} differ from this game's")
    ours = type(game.rng.bit_generator).__name__
    if snapshot.rng_state["bit_generator"] != ours:
        raise ValueError(f"the snapshot's noise generator is a {snapshot.rng_state['bit_generator']}, "
                         f"this game's a {ours}")
