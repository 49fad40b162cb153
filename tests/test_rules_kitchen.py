"""The kitchen (WPA 8.1): a cue ball in hand behind the head string goes strictly behind it.

WPA 8.1 defines "behind the head string" as the area between the head rail and the head
string, the string itself not included; a ball counts as behind it by where its base (the
point it stands on, under its centre) is. So no placement of a ball in hand behind the head
string may put the centre on the string (x = L/4), whatever the action asks: not the
clipped extreme entry (+1), not a spot asked for on or past the string, not the break's
default spot (the head spot, which is on the string).
"""

from __future__ import annotations

import numpy as np
import pytest

from pool_env import rules
from pool_env.game import LAYOUTS, Game, Shot, decode_action, place_cue_ball, placement_area
from pool_env.physics import Physics, Table

TABLE = Table.eight_foot()
STRING = rules.head_string_x(TABLE)


def test_the_area_ends_short_of_the_head_string():
    x_lo, x_hi, _, _ = placement_area(TABLE, "behind_head_string")
    assert x_lo < x_hi < STRING
    assert placement_area(TABLE, "anywhere")[1] > STRING  # ball in hand anywhere may cross it


@pytest.mark.parametrize("name", ["nine_ball", "eight_ball", "nine_ball+elevation"])
def test_the_extreme_placement_entry_is_behind_the_string(name):
    layout = LAYOUTS[name]
    area = placement_area(TABLE, "behind_head_string")
    for entry in (1.0, 1.5, 1e9):  # +1 and entries the decoder clips to +1
        action = np.zeros(layout.size)
        action[4] = entry
        shot = decode_action(layout, action, area)
        assert shot.place[0] < STRING


@pytest.mark.parametrize("wanted_x", [STRING, STRING + 1e-9, STRING + 0.3])
def test_a_spot_on_or_past_the_string_is_moved_behind_it(wanted_x):
    game = Game("nine_ball", seed=0)
    placed = place_cue_ball(game.balls, TABLE, Physics.standard(), "behind_head_string", (wanted_x, 0.3))
    assert placed.xy[0, 0] < STRING


@pytest.mark.parametrize("mode", ["nine_ball", "eight_ball"])
def test_the_break_from_the_head_spot_is_played_from_behind_the_string(mode):
    # The rack leaves the cue ball on the head spot (on the string); the break with no spot
    # asked for plays from the nearest spot behind the string.
    game = Game(mode, seed=1)
    assert game.balls.xy[0, 0] == pytest.approx(STRING)
    record = game.play(Shot.aimed((1.0, 0.0), 9.0))
    assert record.balls_before.xy[0, 0] < STRING
    assert record.balls_before.xy[0, 1] == pytest.approx(TABLE.width / 2)
