"""agents.ten_ball_fuzz on a few games: random 10-ball games end, every ball accounted for, valid starts."""

from __future__ import annotations

import pytest

from agents.ten_ball_fuzz import fuzz


@pytest.mark.parametrize("noise", [None, "olympiad"])
def test_random_ten_ball_games_end_with_valid_states(noise):
    out = fuzz(60, noise, first_seed=5_000)
    assert out["all_ended"] and out["games"] == 60
    assert out["decisions"] > 0 and out["push_outs"] > 0  # the decision turns were exercised
