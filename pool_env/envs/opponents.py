"""The game envs' opponent: a player's name, an agent or a callable made one callable, and the
decision a vector env's driver answers for many sub-envs at once."""

from __future__ import annotations

from dataclasses import dataclass

from ..players import make_player


@dataclass(frozen=True)
class OpponentDecision:
    """What `step_shots` yields (with `batch_opponent` on) when a built-in player that decides
    from the game's state (`decide_batch` of `pool_env.game.GameView`s) is to shoot: its driver
    sends back `player.decide(view)`, the `Shot`, which it may compute for many sub-envs in one
    `decide_batch` call."""

    player: object
    view: object


def resolve_opponent(opponent, env):
    """(the opponent as a callable observation -> action, the player to reseed at each reset
    (a built-in name's), its name); (None, None, None) for practice."""
    if opponent is None:
        return None, None, None
    if isinstance(opponent, str):
        try:
            player = make_player(opponent, env)
        except ValueError as exc:
            raise ValueError(str(exc).replace("unknown player", "unknown opponent", 1)) from None
        return player.act, player, opponent
    name = getattr(opponent, "name", type(opponent).__name__)
    if hasattr(opponent, "act") and callable(opponent.act):
        return opponent.act, None, name
    if callable(opponent):
        return opponent, None, getattr(opponent, "__name__", name)
    raise ValueError(f"opponent must be a name, None, an agent with act(observation) or a callable, got {opponent!r}")
