"""The table and the last shots in words (for language agents): balls, the rules' state, each shot's events."""

from __future__ import annotations

import string

import numpy as np

from ..physics.kinds import BALL_CUSHION
from ..rules.snooker_spots import COLOUR_NAMES

# The characters a description is made of (gymnasium's Text space of the "text" observations).
TEXT_CHARSET = frozenset(string.ascii_letters + string.digits + string.punctuation + " \n")
TEXT_MAX_LENGTH = 8192  # a description's longest, by construction (`MAX_SHOTS_LISTED` keeps it short)
MAX_SHOTS_LISTED = 8  # a step's shots described one by one; the rest are counted
CAROM_NAMES = ("white", "yellow", "red")


def ball_name(mode: str, ball: int) -> str:
    """A ball's name in `mode`: "cue ball", "ball 9"; snooker's "red 3", "pink"; carom's "white"."""
    if mode == "three_cushion":
        return CAROM_NAMES[ball]
    if ball == 0:
        return "cue ball"
    if mode == "snooker":
        return f"red {ball}" if ball <= 15 else COLOUR_NAMES[ball]
    return f"ball {ball}"


def shot_events(mode: str, record) -> list[str]:
    """The events of one shot: first contact, cushion contacts, balls pocketed (and where), the
    referee's call."""
    if record.error is not None:
        return [f"the shot could not be simulated ({record.error}); the balls did not move"]
    name = lambda ball: ball_name(mode, ball)  # noqa: E731
    outcome = record.outcome
    _, kinds, i_s, _ = (a.tolist() for a in record.result.event_arrays)
    cue = getattr(outcome, "cue_ball", 0)
    cushions = sum(kind == BALL_CUSHION for kind in kinds)
    cue_cushions = sum(kind == BALL_CUSHION and i == cue for kind, i in zip(kinds, i_s))
    if mode == "three_cushion":
        first, second = outcome.first_ball, outcome.second_ball
        lines = [f"cue ball: the {name(cue)}",
                 f"first contact: {'none' if first is None else 'the ' + name(first)}",
                 f"second object ball: {'none' if second is None else 'the ' + name(second)}",
                 f"cue ball's cushion contacts: {outcome.cushions} ({outcome.cushions_before_second} "
                 "before the second object ball)"]
    else:
        first = outcome.first_contact
        dropped = [f"{name(b)} in pocket {p}" for b, p in sorted(outcome.pocket_of.items())]
        lines = [f"first contact: {'none' if first is None else name(first)}",
                 f"cushion contacts: {cushions} (cue ball {cue_cushions})",
                 f"pocketed: {', '.join(dropped) if dropped else 'none'}"]
    if outcome.off_table:
        lines.append(f"off the table: {', '.join(name(b) for b in outcome.off_table)}")
    ruling = record.ruling
    if ruling is not None:
        lines.append(f"foul: {', '.join(ruling.fouls) if ruling.fouls else 'none'}")
        lines += [f"referee: {message}" for message in ruling.messages]
    elif outcome.cue_pocketed:
        lines.append("foul: scratch (the cue ball dropped)")
    return lines


def describe_shots(mode: str, records, who) -> list[str]:
    """Lines for a step's shots (`who(record)`: "agent", "opponent"), the first `MAX_SHOTS_LISTED`
    in full, the rest counted."""
    if not records:
        return ["last shot: none yet"]
    lines = []
    for k, record in enumerate(records[:MAX_SHOTS_LISTED]):
        lines.append(f"shot {k + 1} of the last step, by the {who(record)}:")
        lines += [f"  {line}" for line in shot_events(mode, record)]
    if len(records) > MAX_SHOTS_LISTED:
        lines.append(f"and {len(records) - MAX_SHOTS_LISTED} more shots by the opponent")
    return lines


def describe_state(game, agent: int = 0) -> list[str]:
    """Who is to shoot and what the rules allow now (player `agent` is the agent)."""
    state = game.state
    if state is None:
        return []
    role = lambda player: "agent" if player == agent else "opponent"  # noqa: E731
    if game.over:
        winner = getattr(state, "winner", None)
        return ["the game is over: " + ("a draw" if winner is None else f"the {role(winner)} wins")]
    lines = [f"to shoot: the {role(game.shooter)}" + (f", ball in hand ({game.ball_in_hand.replace('_', ' ')})"
                                                       if game.ball_in_hand else "")]
    scores = getattr(state, "scores", None)
    if scores is not None:
        lines.append(f"score: agent {scores[agent]}, opponent {scores[1 - agent]}")
    if game.mode == "three_cushion":
        lines.append(f"innings: agent {state.innings[agent]}, opponent {state.innings[1 - agent]}")
        return lines
    targets = sorted(game.legal_targets)
    if targets:
        lines.append(f"legal first contact: {', '.join(ball_name(game.mode, b) for b in targets)}")
    groups = getattr(state, "groups", None)
    if game.mode == "eight_ball" and groups is not None:
        lines.append(f"agent's group: {groups[agent] or 'open table'}")
    return lines


def describe(game, records, shots: int, max_shots: int, agent: int = 0, counted: str = "agent's shots") -> str:
    """The text observation: the table, the last step's shots (`records`, `ShotRecord`s), the
    rules' state and the balls now (positions in metres from the corner at x = y = 0, x along the
    length), all in the characters of `TEXT_CHARSET`, from the side of player `agent` ("the
    agent"; the other is "the opponent"); `counted` names what `shots` counts against `max_shots`."""
    table, balls, mode = game.table, game.balls, game.mode
    who = lambda record: "agent" if record.shooter == agent else "opponent"  # noqa: E731
    lines = [f"{game.label}, table {table.length:.3f} m x {table.width:.3f} m inside the cushion noses, "
             f"{counted} {shots} of {max_shots}" + (f"; player {agent} is the agent" if game.state else "")]
    if len(table.pockets):
        lines.append("pockets (x, y in m): " + "; ".join(f"{k} ({x:.3f}, {y:.3f})" for k, (x, y, _)
                                                         in enumerate(np.asarray(table.pockets).tolist())))
    lines += describe_shots(mode, list(records), who)
    lines += describe_state(game, agent)
    on = [f"{ball_name(mode, b)} ({x:.3f}, {y:.3f})" for b, ((x, y), down) in
          enumerate(zip(np.asarray(balls.xy).tolist(), balls.pocketed.tolist())) if not down]
    off = [ball_name(mode, b) for b, down in enumerate(balls.pocketed.tolist()) if down]
    lines.append(f"on the table (x, y in m): {'; '.join(on) if on else 'none'}")
    lines.append(f"pocketed: {', '.join(off) if off else 'none'}")
    text = "\n".join(lines)
    if len(text) > TEXT_MAX_LENGTH or not set(text) <= TEXT_CHARSET:
        raise ValueError(f"a description must be at most {TEXT_MAX_LENGTH} characters of TEXT_CHARSET: {text[:200]!r}")
    return text
