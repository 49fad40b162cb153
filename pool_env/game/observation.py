"""The observation layouts of the break envs and of the games: one encoder and one decoder each."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import rules
from ..physics import Balls, Table
from ..physics.frozen import unchecked
from ..physics.jit import helper, kernel
from .snooker_observation import SNOOKER_OBS_SIZE, decode_snooker_observation, snooker_observation

N_BALLS = 16  # the break envs' balls: the cue ball and 15 object balls
GAME_BALLS = {"nine_ball": 10, "eight_ball": 16, "snooker": 22, "ten_ball": 11}  # balls in play, the cue ball included


# --- the break envs (PoolBreak-v0, PoolBreakRun-v0) ---------------------------------------------
def break_observations(xy, pocketed, shots, max_shots, table: Table, out):
    """Write the observations (see PoolBreakEnv) of n envs into `out` (n, 49) float32,
    C-contiguous, from the balls' positions xy (n, 16, 2), their pocketed flags (n, 16) and the
    shots taken (n,) of `max_shots` (n,)."""
    if not out.flags.c_contiguous:
        raise ValueError("out must be C-contiguous (its per-ball view must not be a copy)")
    per_ball = out[:, :-1].reshape(out.shape[0], N_BALLS, 3)
    # Centres on the cloth map into (-1, 1); a ball hanging in a pocket's mouth has its centre
    # up to a few cm past the nose line, clipped to the edge (the decoder puts it on the nose line).
    per_ball[:, :, 0:2] = xy * (2.0 / table.length, 2.0 / table.width) - 1.0
    np.clip(per_ball[:, :, 0:2], -1.0, 1.0, out=per_ball[:, :, 0:2])
    per_ball[:, :, 2] = 1.0
    per_ball[pocketed] = (0.0, 0.0, -1.0)
    out[:, -1] = 2.0 * shots / max_shots - 1.0
    return out


def break_observation(balls: Balls, shots: int, max_shots: int, table: Table) -> np.ndarray:
    """One break env's observation (49,) float32."""
    obs = np.empty(3 * N_BALLS + 1, dtype=np.float32)
    break_observations(balls.xy[None], balls.pocketed[None], shots, max_shots, table, obs[None])
    return obs


def decode_observation(obs, table: Table):
    """A break env's observation read back: (xy (16, 2) in metres, on_table (16,) bool).
    Pocketed balls get xy = NaN."""
    obs = np.asarray(obs, dtype=np.float64)
    balls = obs[: 3 * N_BALLS].reshape(N_BALLS, 3)
    on_table = balls[:, 2] > 0
    xy = np.empty((N_BALLS, 2))
    xy[:, 0] = (balls[:, 0] + 1.0) * 0.5 * table.length
    xy[:, 1] = (balls[:, 1] + 1.0) * 0.5 * table.width
    xy[~on_table] = np.nan
    return xy, on_table


# --- the games (PoolNineBall-v0, PoolEightBall-v0, the two-player envs) -------------------------
DECISION_ENTRIES = len(rules.DECISIONS) + 1  # with decisions: one flag per decision, then "may push out"


def game_observation_size(game: str, decisions: bool = False) -> int:
    if game == "snooker":
        return SNOOKER_OBS_SIZE
    n = GAME_BALLS[game]
    return 3 * n + (n - 1) + 4 + (3 if game == "eight_ball" else 0) + DECISION_ENTRIES * bool(decisions) + 1


def decision_entries(state, viewer: int) -> list:
    """The decision flags of `viewer`'s observation: +1 for the decision he is to make now (one
    per `rules.DECISIONS`, in order), then +1 if he may push out on his shot; -1 otherwise."""
    mine = state.shooter == viewer and state.winner is None
    pending = getattr(state, "pending", None) if mine else None
    flags = [1.0 if pending is not None and pending.name == name else -1.0 for name in rules.DECISIONS]
    return flags + [1.0 if mine and getattr(state, "push_out", False) else -1.0]


@helper
def position_entry(v, scale):
    """A centre's coordinate as the observation keeps it: scaled onto [-1, 1] (clipped: a ball
    hanging in a mouth), rounded to float32."""
    return np.float32(min(max(v * scale - 1.0, -1.0), 1.0))


@kernel
def observed_balls(xy, pocketed, length, width, out):
    """The observation's entries of the balls (xy (n, 2), pocketed (n,)) into out (n, 3)
    float32: x, y scaled (`position_entry`), +1; a pocketed ball (0, 0, -1)."""
    sx, sy = 2.0 / length, 2.0 / width
    for k in range(xy.shape[0]):
        if pocketed[k]:
            out[k, 0], out[k, 1], out[k, 2] = 0.0, 0.0, -1.0
        else:
            out[k, 0], out[k, 1], out[k, 2] = position_entry(xy[k, 0], sx), position_entry(xy[k, 1], sy), 1.0


@kernel
def viewed_balls(xy, pocketed, length, width, out):
    """The balls' positions (n, 2) as `decode_game_observation` reads them back from the
    observation's entries (`observed_balls`), into out (n, 2) float64."""
    sx, sy = 2.0 / length, 2.0 / width
    for k in range(xy.shape[0]):
        ex = ey = 0.0
        if not pocketed[k]:
            ex, ey = np.float64(position_entry(xy[k, 0], sx)), np.float64(position_entry(xy[k, 1], sy))
        out[k, 0], out[k, 1] = (ex + 1.0) * 0.5 * length, (ey + 1.0) * 0.5 * width


def game_observation(balls: Balls, state, viewer: int, shots: int, max_shots: int, table: Table,
                     decisions: bool = False) -> np.ndarray:
    """The observation of `viewer` (0 or 1) as PoolGameEnv documents it, float32 in [-1, 1]
    (`decisions`: with the decision flags, `decision_entries`, before the shot counter)."""
    if state.kind == "snooker":
        return snooker_observation(balls, state, viewer, shots, max_shots, table)
    n = len(balls)
    out = np.empty(game_observation_size(state.kind, decisions), dtype=np.float32)
    observed_balls(balls.xy, balls.pocketed, table.length, table.width, out[: 3 * n].reshape(n, 3))
    legal = out[3 * n: 4 * n - 1]
    legal[:] = -1.0
    if state.winner is None:
        legal[[ball - 1 for ball in rules.legal_targets(state)]] = 1.0
    in_hand = state.ball_in_hand if state.shooter == viewer else None
    tail = [1.0 if in_hand == "anywhere" else -1.0, 1.0 if in_hand == "behind_head_string" else -1.0,
            min(state.fouls[viewer], 2) - 1.0, min(state.fouls[1 - viewer], 2) - 1.0]  # a third foul ends the game
    if state.kind == "eight_ball":
        group = state.groups[viewer]
        tail += [1.0 if group is None else -1.0, 1.0 if group == "solids" else -1.0,
                 1.0 if group == "stripes" else -1.0]
    if decisions:
        tail += decision_entries(state, viewer)
    tail.append(2.0 * min(shots, max_shots) / max_shots - 1.0)
    out[4 * n - 1:] = tail
    return out


@dataclass(frozen=True)
class GameView:
    """A game observation read back (`decode_game_observation`), from the viewer's side:
    positions (n, 2) in metres (a pocketed ball's are meaningless), on-table flags (n,), the
    legal first contacts (object balls), ball in hand for the viewer (None, "anywhere",
    "behind_head_string"), consecutive fouls (viewer, opponent; 2 means two or more), the
    viewer's 8-ball group (None while open, and in 9-ball), the shot counter entry; with the
    decision entries, the name of the decision the viewer is to make (`pending`, else None)
    and whether he may push out."""

    xy: np.ndarray
    on_table: np.ndarray
    legal: frozenset
    ball_in_hand: str | None = None
    fouls: tuple = (0, 0)
    group: str | None = None
    counter: float = -1.0
    pending: str | None = None
    push_out: bool = False

    @property
    def legal_mask(self) -> np.ndarray:
        """(n - 1,) bool: object ball k + 1 is a legal first contact."""
        mask = np.zeros(len(self.on_table) - 1, dtype=bool)
        for ball in self.legal:
            mask[ball - 1] = True
        return mask


def decode_game_observation(obs, game: str, table: Table) -> GameView:
    """The `GameView` of a game observation of `game` ("nine_ball", "eight_ball"; "snooker": a
    `SnookerView`), with or without the decision entries (told by its length)."""
    if game == "snooker":
        return decode_snooker_observation(obs, table)
    n = GAME_BALLS[game]
    obs = np.asarray(obs, dtype=np.float64)
    sizes = (game_observation_size(game), game_observation_size(game, True))
    if obs.shape not in ((sizes[0],), (sizes[1],)):
        raise ValueError(f"a {game} observation has shape ({sizes[0]},) (or ({sizes[1]},) with the decision "
                         f"entries), got {obs.shape}")
    per_ball = obs[: 3 * n].reshape(n, 3)
    on_table = per_ball[:, 2] > 0
    xy = np.column_stack([(per_ball[:, 0] + 1.0) * 0.5 * table.length, (per_ball[:, 1] + 1.0) * 0.5 * table.width])
    legal = frozenset(int(b) + 1 for b in np.flatnonzero(obs[3 * n: 4 * n - 1] > 0))
    hand = obs[4 * n - 1: 4 * n + 1]
    in_hand = "anywhere" if hand[0] > 0 else ("behind_head_string" if hand[1] > 0 else None)
    fouls = tuple(int(round(f + 1.0)) for f in obs[4 * n + 1: 4 * n + 3])
    group = None
    if game == "eight_ball":
        flags = obs[4 * n + 3: 4 * n + 6]
        group = "solids" if flags[1] > 0 else ("stripes" if flags[2] > 0 else None)
    pending, push_out = None, False
    if obs.shape == (sizes[1],):
        flags = obs[-1 - DECISION_ENTRIES: -1]
        pending = next((name for name, f in zip(rules.DECISIONS, flags) if f > 0), None)
        push_out = bool(flags[-1] > 0)
    return GameView(xy, on_table, legal, in_hand, fouls, group, float(obs[-1]), pending, push_out)


def game_view(balls: Balls, state, viewer: int, shots: int, max_shots: int, table: Table,
              decisions: bool = False) -> GameView:
    """The `GameView` that `decode_game_observation` reads from `game_observation(balls, state,
    viewer, shots, max_shots, table)`, bit for bit (the positions rounded to float32 and back,
    as the observation keeps them), without building the observation: for players that read
    the game's state directly."""
    xy = np.empty((len(balls), 2))
    viewed_balls(balls.xy, balls.pocketed, table.length, table.width, xy)
    legal = rules.legal_targets(state) if state.winner is None else frozenset()
    in_hand = state.ball_in_hand if state.shooter == viewer else None
    fouls = (min(state.fouls[viewer], 2), min(state.fouls[1 - viewer], 2))
    group = state.groups[viewer] if state.kind == "eight_ball" else None
    counter = float(np.float32(2.0 * min(shots, max_shots) / max_shots - 1.0))
    pending, push_out = None, False
    if decisions:
        flags = decision_entries(state, viewer)
        pending = next((name for name, f in zip(rules.DECISIONS, flags) if f > 0), None)
        push_out = flags[-1] > 0
    # Built without the frozen dataclass's __init__ (a field at a time through object.__setattr__):
    # the game envs make one for every shot of their built-in opponent, of fields made here.
    return unchecked(GameView, {"xy": xy, "on_table": ~balls.pocketed, "legal": legal, "ball_in_hand": in_hand,
                                "fouls": fouls, "group": group, "counter": counter, "pending": pending,
                                "push_out": push_out})
