"""Random three-cushion games (agents.carom_fuzz): every game ends, the scores add up, every state is valid."""

import pytest

from agents.carom_fuzz import fuzz


@pytest.mark.parametrize("noise", [None, "olympiad"])
def test_random_games_end_with_valid_states_and_scores_that_add_up(noise):
    out = fuzz(150, noise, first_seed=10_000)
    assert out["all_ended"] and out["games"] == 150
    assert out["draws"] < 150  # some games are decided (random play does score)
