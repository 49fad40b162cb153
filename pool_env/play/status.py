"""The play window's text: whose turn, ball in hand, called pockets, scores, and the rules' messages of a step."""

from __future__ import annotations

from .games import NAMES


def player_name(state, two_players: bool, shooter=None) -> str:
    """A player's name (default: the shooter now): "you" and "opponent", or "player 1" and "player
    2"; "you" in the break envs (no rules' `state`)."""
    if state is None:
        return "you"
    shooter = state.shooter if shooter is None else shooter
    if two_players:
        return f"player {shooter + 1}"
    return "you" if shooter == 0 else "opponent"


def shot_lines(session, info, shooter) -> list[str]:
    """The rules' messages of a session's step (both players' shots, from its records), or what a break shot did."""
    if session.state is None:
        pocketed = info["pocketed"][1:].nonzero()[0] + 1  # the mask's object balls
        return [f"pocketed: {', '.join(map(str, pocketed)) or 'none'}"] + (["scratch"] if info["scratch"] else [])
    lines = []
    for k, record in enumerate(session.base.step_records):
        who = session.player(shooter) if k == 0 else "opponent"
        lines += [f"{who}: {m}" for m in (record.ruling.messages if record.ruling is not None else ())]
    return lines


def status_lines(session) -> list[str]:
    """The lines of text on a session's table: the game, whose turn, ball in hand, the last shot's messages."""
    name = NAMES[session.game]
    if session.busy:  # the rules' state is the worker's until the step is over
        return [f"{name}: {session.thinking}"]
    if session.state is None:
        head = f"{name}: shot {len(session.actions) + 1}" + (" - over, R for a new rack" if session.done else "")
        return [head, *session.lines]
    state, player = session.state, session.player
    if state.winner is not None:
        head = f"{name}: {player(state.winner)} {'win' if player(state.winner) == 'you' else 'wins'}"
    elif session.done:
        head = f"{name}: game stopped"
    else:
        who = player()
        head = f"{name}  shot {state.shot + 1}: {who} {'shoot' if who == 'you' else 'shoots'}"
        if state.ball_in_hand:
            head += f", ball in hand ({state.ball_in_hand.replace('_', ' ')}): drag the cue ball"
    lines = [head]
    if session.game == "eight_ball" and state.groups[state.shooter] is not None:
        lines.append(f"group: {state.groups[state.shooter]}")
    if session.game in ("snooker", "three_cushion"):
        lines.append(f"score: {player(0)} {state.scores[0]}, {player(1)} {state.scores[1]}")
    if session.game == "three_cushion":
        ball = "white" if session.cue_index == 0 else "yellow"
        lines.append(f"{ball} cue ball, innings {state.innings[0]}-{state.innings[1]}")
    if session.needs_call:
        called = session.called is not None
        ball = session.called_ball
        ball = "the ball you aim at" if ball is None else f"the {ball}"
        lines.append(f"{ball} called in pocket {session.called}" if called else f"click a pocket to call {ball}")
    return lines + session.lines
