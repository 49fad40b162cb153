"""The env action layouts: one decoder (action vector to `Shot`) and one encoder (`Shot` to action vector) each."""

from __future__ import annotations

import math
from array import array
from dataclasses import dataclass, replace

import numpy as np

from ..physics import BALL_MASS
from .shot import CONTACT_TIME, MAX_ELEVATION, MAX_FORCE, MAX_SPEED, MAX_TIP_OFFSET, Shot, valid_shot

MIN_MAGNITUDE = 0.02  # weaker cue-force entries are raised to this (0.24 m/s)


@dataclass(frozen=True)
class ActionLayout:
    """An action vector's layout: `size` entries in [-1, 1]; `spin` has the tip entries (2-3);
    `placement` the ball-in-hand entries (4-5); `called_pocket` the pocket entry (6);
    `called_ball` the called-ball entry (7: 8-ball with called ball and pocket, WPA 1.6);
    `decision` the decision entry, after those (a "_decide" layout: on a shot that may be a
    push out, > 0 declares one; at a pending decision it picks the option, `decode_decision`);
    `elevation` the cue-elevation entry, the last one (a layout's "+elevation" variant)."""

    name: str
    size: int
    spin: bool
    placement: bool = False
    called_pocket: bool = False
    elevation: bool = False
    called_ball: bool = False
    decision: bool = False

    @property
    def decision_index(self) -> int:
        """The decision entry's index (the last but the elevation's)."""
        if not self.decision:
            raise ValueError(f"layout {self.name!r} has no decision entry")
        return self.size - 1 - int(self.elevation)


_LEVEL = {
    "cue": ActionLayout("cue", 2, spin=False),
    "cue_spin": ActionLayout("cue_spin", 4, spin=True),
    "nine_ball": ActionLayout("nine_ball", 6, spin=True, placement=True),
    "snooker": ActionLayout("snooker", 6, spin=True, placement=True),  # entries 4-5 map onto the D
    # 8-ball with `calling="eight_only"`: a pocket, read at the 8 only.
    "eight_ball": ActionLayout("eight_ball", 7, spin=True, placement=True, called_pocket=True),
    # 8-ball by default (`calling="ball_and_pocket"`, WPA 1.6): a ball and a pocket every shot but the break.
    "eight_ball_call": ActionLayout("eight_ball_call", 8, spin=True, placement=True, called_pocket=True,
                                    called_ball=True),
    # 10-ball: every shot but the break calls a ball (any on the table) and a pocket (WPA Ten Ball 5).
    "ten_ball": ActionLayout("ten_ball", 8, spin=True, placement=True, called_pocket=True, called_ball=True),
    # The layouts with the decision entry (`Game` waits for its decisions: `Game.decide`).
    "nine_ball_decide": ActionLayout("nine_ball_decide", 7, spin=True, placement=True, decision=True),
    "eight_ball_decide": ActionLayout("eight_ball_decide", 8, spin=True, placement=True, called_pocket=True,
                                      decision=True),
    "eight_ball_call_decide": ActionLayout("eight_ball_call_decide", 9, spin=True, placement=True,
                                           called_pocket=True, called_ball=True, decision=True),
    "ten_ball_decide": ActionLayout("ten_ball_decide", 9, spin=True, placement=True, called_pocket=True,
                                    called_ball=True, decision=True),
}
ELEVATED = "+elevation"  # the suffix of a layout's variant with the cue-elevation entry last
LAYOUTS = {**_LEVEL, **{name + ELEVATED: replace(layout, name=name + ELEVATED, size=layout.size + 1, elevation=True)
                        for name, layout in _LEVEL.items()}}


def env_layout(game: str, elevation: bool = False, decisions: bool = False, calling: str | None = None) -> str | None:
    """The action layout's name of a game env of `game` with the elevation entry and the
    decision entry as asked (None: the mode's default); 8-ball's has the called-ball entry
    unless `calling` is "eight_only" (the rules' option; None: their default, ball and pocket)."""
    if not (elevation or decisions):
        return None
    base = "eight_ball_call" if game == "eight_ball" and calling != "eight_only" else game
    return base + ("_decide" if decisions else "") + (ELEVATED if elevation else "")


def elevation_entry(entry: float) -> float:
    """The cue's elevation (rad) of an elevation entry: entries <= 0 are a level cue (so the
    zero action, and half of a centred policy's draws, play level), (0, 1] maps linearly
    onto (0, MAX_ELEVATION] (85 deg)."""
    return MAX_ELEVATION * min(max(entry, 0.0), 1.0)


def cue_force(action, spin: bool):
    """(force (2,) N, tip offset (2,) R) of the cue entries: a[0:2] the force as a fraction of
    MAX_FORCE (clipped to [-1, 1], scaled to length 1 if longer, raised to MIN_MAGNITUDE if
    shorter; the zero action strikes along +x), a[2:4] with `spin` the tip (side, top) as a
    fraction of MAX_TIP_OFFSET (scaled back onto it if longer). ValueError for another shape
    than (2,) / (4,) or a non-finite entry."""
    a = np.asarray(action, dtype=np.float64)
    size = 4 if spin else 2
    if a.shape != (size,):  # not reshaped: a (1, 2) batch is a mistake of the caller's, not an action
        raise ValueError(f"action must have shape ({size},) ({size} entries, the action space's shape), "
                         f"got shape {a.shape}")
    values = a.tolist()  # Python floats: the same IEEE arithmetic as numpy's, without its per-call cost
    if not all(math.isfinite(v) for v in values):
        raise ValueError(f"action must be finite, got {values}")
    force, tip = cue_entries(clip_entries(values), spin)
    return np.array(force), np.array(tip)


def cue_entries(values, spin: bool) -> tuple:
    """`cue_force` of entries already checked and clipped (Python floats): ((fx, fy), (side, top))."""
    dx, dy = values[0], values[1]
    magnitude = math.hypot(dx, dy)
    if magnitude == 0.0:
        dx, dy = MIN_MAGNITUDE, 0.0
    elif magnitude > 1.0:
        dx, dy = dx / magnitude, dy / magnitude
    elif magnitude < MIN_MAGNITUDE:
        scale = MIN_MAGNITUDE / magnitude
        dx, dy = dx * scale, dy * scale
    side = top = 0.0
    if spin:
        side, top = MAX_TIP_OFFSET * values[2], MAX_TIP_OFFSET * values[3]
        length = math.hypot(side, top)
        if length > MAX_TIP_OFFSET:
            scale = MAX_TIP_OFFSET / length
            side, top = side * scale, top * scale
    return (MAX_FORCE * dx, MAX_FORCE * dy), (side, top)


def decode_action(layout: ActionLayout, action, area=None, n_pockets: int = 6, targets=(), push_out=False) -> Shot:
    """The `Shot` an action of `layout` means. `area` (x_lo, x_hi, y_lo, y_hi) is where the
    cue ball may be placed (ball in hand; None: it plays from where it lies, and entries 4-5
    are ignored): entries 4-5 map linearly onto it. Entry 6 cuts [-1, 1] into `n_pockets`
    equal bins, pocket k in bin k. Entry 7 (`called_ball`) cuts [-1, 1] into len(`targets`)
    equal bins, targets[k] (the balls the shooter may call, ascending) in bin k; no targets, no
    called ball. The decision entry (`decision`) > 0 declares a push out when `push_out` (the
    shooter may). An elevated layout's last entry is the cue's elevation (`elevation_entry`).
    ValueError for a wrong shape or a non-finite entry."""
    if not (layout.placement or layout.elevation):
        force, tip = cue_force(action, layout.spin)
        return Shot(tuple(force.tolist()), tuple(tip.tolist()))
    a = np.asarray(action, dtype=np.float64)
    if a.shape != (layout.size,):
        raise ValueError(f"action must have shape ({layout.size},), got shape {a.shape}")
    values = a.tolist()  # Python floats: the same IEEE arithmetic as numpy's, without its per-call cost
    if not all(math.isfinite(v) for v in values):
        raise ValueError(f"action must be finite, got {values}")
    return decode_entries(layout, values, area, n_pockets, targets, push_out)


def checked_entries(layout: ActionLayout, action) -> list:
    """An action's entries as Python floats; ValueError for a wrong shape or a non-finite entry."""
    a = np.asarray(action, dtype=np.float64)
    if a.shape != (layout.size,):
        raise ValueError(f"action must have shape ({layout.size},), got shape {a.shape}")
    values = a.tolist()
    if not all(math.isfinite(v) for v in values):
        raise ValueError(f"action must be finite, got {values}")
    return values


def decode_decision(layout: ActionLayout, action, options) -> str:
    """The option an action of a layout with the decision entry picks at a pending decision:
    the entry cuts [-1, 1] into len(`options`) equal bins, options[k] in bin k (the other
    entries are ignored). ValueError for a layout without the entry or a bad action."""
    index = layout.decision_index
    entry = min(max(checked_entries(layout, action)[index], -1.0), 1.0)
    return options[min(int((entry + 1.0) * 0.5 * len(options)), len(options) - 1)]


def encode_decision(layout: ActionLayout, option, options) -> np.ndarray:
    """The action (float32) that `decode_decision` reads back as `option`: zeros but the
    decision entry, the middle of the option's bin. ValueError for an option not in `options`."""
    if option not in options:
        raise ValueError(f"{option!r} is not one of the options {tuple(options)}")
    action = np.zeros(layout.size, dtype=np.float32)
    action[layout.decision_index] = -1.0 + (2.0 * list(options).index(option) + 1.0) / len(options)
    return action


def clip_entries(values) -> list:
    """`np.clip(values, -1, 1)` of Python floats as a list: an entry in range (nearly all) is
    kept after one chained comparison, the others (NaN too) go through min and max as before."""
    return [v if -1.0 <= v <= 1.0 else min(max(v, -1.0), 1.0) for v in values]


def decode_entries(layout: ActionLayout, values, area=None, n_pockets: int = 6, targets=(), push_out=False,
                   clipped=False) -> Shot:
    """`decode_action` of an action's entries already checked (`layout.size` finite Python floats;
    `clipped`: already in [-1, 1], as `encoded_entries` makes them)."""
    a = values if clipped else clip_entries(values)
    spin = layout.spin or layout.placement
    force, tip = cue_entries(a[0:4] if spin else a[0:2], spin)
    elevation = elevation_entry(a[-1]) if layout.elevation else 0.0
    place = None
    if layout.placement and area is not None:
        if hasattr(area, "point"):  # a half circle (snooker's D: placement.HalfDisc)
            place = area.point(a[4], a[5])
        else:
            x_lo, x_hi, y_lo, y_hi = area
            place = (x_lo + 0.5 * (a[4] + 1.0) * (x_hi - x_lo), y_lo + 0.5 * (a[5] + 1.0) * (y_hi - y_lo))
    pocket = min(int((a[6] + 1.0) * 0.5 * n_pockets), n_pockets - 1) if layout.called_pocket else None
    ball = None
    if layout.called_ball and len(targets):
        ball = int(targets[min(int((a[7] + 1.0) * 0.5 * len(targets)), len(targets) - 1)])
    pushed = bool(layout.decision and push_out and a[layout.decision_index] > 0.0)
    # cue_entries keeps the force and tip in range and elevation_entry the elevation: the Shot
    # is valid, and its checks are left out when the other fields are as a Shot keeps them.
    if (place is None or (type(place[0]) is float and type(place[1]) is float)) \
            and (pocket is None or pocket >= 0) and (ball is None or ball >= 1):
        return valid_shot(force, tip, place, pocket, elevation, ball, pushed)
    return Shot(force, tip, place, pocket, elevation, ball, pushed)


def encode_action(layout: ActionLayout, shot: Shot, area=None, n_pockets: int = 6, targets=()) -> np.ndarray:
    """The action of `layout` (float32, in [-1, 1]) that `decode_action` reads back as `shot`
    (to float32 rounding): the force as a fraction of MAX_FORCE, the tip of MAX_TIP_OFFSET, the
    spot's place in `area` (0, 0 when `area` or the spot is None), the middle of the pocket's bin,
    the middle of the called ball's bin among `targets` (the first's when the ball is None or
    not a target), the elevation as a fraction of MAX_ELEVATION."""
    return np.clip(np.array(action_entries(layout, shot, area, n_pockets, targets), dtype=np.float32), -1.0, 1.0)


def encoded_entries(layout: ActionLayout, shot: Shot, area=None, n_pockets: int = 6, targets=()) -> list:
    """`encode_action`'s entries as Python floats (each rounded to float32 and clipped, as the
    action holds them), without building the array: `decode_entries` of them is the shot an
    env plays for the action of `shot`."""
    rounded = array("f", action_entries(layout, shot, area, n_pockets, targets)).tolist()  # as numpy's float32 cast
    return clip_entries(rounded)


def action_entries(layout: ActionLayout, shot: Shot, area=None, n_pockets: int = 6, targets=()) -> list:
    """The entries of `encode_action` before their float32 rounding and clipping (Python floats)."""
    if not isinstance(shot, Shot):
        raise TypeError(f"shot must be a pool_env.game.Shot, got {type(shot).__name__}")
    fx, fy = shot.force
    length = math.hypot(fx, fy)
    scale = min(length * CONTACT_TIME / BALL_MASS / MAX_SPEED, 1.0)  # shot.speed / MAX_SPEED
    entries = [fx / length * scale, fy / length * scale]  # shot.direction * scale
    if layout.spin:
        entries += [shot.tip[0] / MAX_TIP_OFFSET, shot.tip[1] / MAX_TIP_OFFSET]
    if layout.placement:
        place = (0.0, 0.0)
        if area is not None and shot.place is not None and hasattr(area, "entries"):
            place = area.entries(shot.place)
        elif area is not None and shot.place is not None:
            x_lo, x_hi, y_lo, y_hi = area
            place = ((shot.place[0] - x_lo) / (x_hi - x_lo) * 2.0 - 1.0,
                     (shot.place[1] - y_lo) / (y_hi - y_lo) * 2.0 - 1.0)
        entries += list(place)
    if layout.called_pocket:
        n = max(int(n_pockets), 1)
        entries.append(-1.0 + (2.0 * (shot.pocket if shot.pocket is not None else 0) + 1.0) / n)
    if layout.called_ball:
        called = list(targets)
        k = called.index(shot.ball) if shot.ball in called else 0
        entries.append(-1.0 + (2.0 * k + 1.0) / max(len(called), 1))
    if layout.decision:  # a push out declared, or not
        entries.append(0.5 if shot.push_out else -0.5)
    if layout.elevation:
        entries.append(shot.elevation / MAX_ELEVATION)
    return entries
