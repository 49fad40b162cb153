"""What every env shares: the option checks, render()'s guard, and a step driven as a generator of shots."""

from __future__ import annotations

import gymnasium as gym

from ..game import simulate_struck
from ..physics import Table


def run_step(shots, table: Table, physics):
    """Drive a step's generator of shots (an env's `step_shots`): simulate each `StruckShot` it
    yields, send the outcome back, and return what it returns (the step's 5-tuple)."""
    outcome = None
    while True:
        try:
            struck = shots.send(outcome)  # the first send (None) starts the generator
        except StopIteration as stop:
            return stop.value
        outcome = simulate_struck(struck, table, physics)


def check_env_options(render_mode, render_modes, max_shots) -> int:
    """The options every env checks alike (ValueError naming the bad one); returns `max_shots` as an int."""
    if render_mode is not None and render_mode not in render_modes:
        raise ValueError(f"render_mode must be None or one of {render_modes}, got {render_mode!r}")
    if int(max_shots) != max_shots or max_shots < 1:
        raise ValueError(f"max_shots must be an integer >= 1, got {max_shots!r}")
    return int(max_shots)


def can_render(render_mode, started: bool) -> bool:
    """render()'s preamble in every env: False (with Gymnasium's warning) without a render mode,
    RuntimeError before the first reset."""
    if render_mode is None:
        gym.logger.warn("render() called without a render_mode; pass render_mode='rgb_array' to the env")
        return False
    if not started:
        raise RuntimeError("call reset() before render()")
    return True


class StepsShots:
    """`step` of the env kinds whose step is a generator of shots (`step_shots`): it simulates
    them one by one and, in human mode, shows the step's frames."""

    def step(self, action):
        out = run_step(self.step_shots(action), self.table, self.physics)
        if self.render_mode == "human":
            self._show(self.shot_frames())
        return out


def check_reset_options(options, accepted) -> dict:
    """`reset`'s options checked: None (no options) or a dict whose keys are all `accepted`."""
    if options is None:
        return {}
    if not isinstance(options, dict):
        raise TypeError(f"options must be a dict or None, got {type(options).__name__}")
    unknown = [key for key in options if key not in accepted]
    if unknown:
        raise ValueError(f"unknown reset option {unknown[0]!r}; the accepted options are "
                         f"{', '.join(repr(key) for key in accepted)}")
    return options
