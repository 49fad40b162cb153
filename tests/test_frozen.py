"""`physics.frozen.unchecked`: an instance built without __init__ is the checked one, in every way a caller sees."""

import copy
import dataclasses
import pickle

import pytest

from pool_env import rules
from pool_env.game import Shot
from pool_env.physics import Physics, Table
from pool_env.physics.frozen import unchecked


def fields_of(instance) -> dict:
    """An instance's fields by name, from its __dict__ or its __slots__."""
    if hasattr(instance, "__dict__"):
        return dict(vars(instance))
    return {f.name: getattr(instance, f.name) for f in dataclasses.fields(instance)}


def checked_instances():
    state = rules.new_game("nine_ball")
    return [Shot.aimed((0.6, 0.8), 2.0, (0.1, -0.2), place=(0.5, 0.6), pocket=3, ball=4),
            state,
            rules.Ruling(foul="no_rail", fouls=("no_rail",), turn_passed=True, ball_in_hand="anywhere",
                         messages=("foul: no rail after contact",)),
            Physics.standard(), Table.eight_foot()]


@pytest.mark.parametrize("checked", checked_instances(), ids=lambda x: type(x).__name__)
def test_an_unchecked_copy_is_the_checked_instance(checked):
    built = unchecked(type(checked), fields_of(checked))
    assert type(built) is type(checked) and built is not checked
    assert repr(built) == repr(checked)
    if dataclasses.is_dataclass(checked):
        assert built == checked and hash(built) == hash(checked)
        assert dataclasses.astuple(built) == dataclasses.astuple(checked)
    again = pickle.loads(pickle.dumps(built))
    assert repr(again) == repr(checked) and repr(copy.deepcopy(built)) == repr(checked)


def test_an_unchecked_instance_stays_frozen():
    shot = unchecked(Shot, fields_of(Shot.aimed((1.0, 0.0), 1.0)))
    with pytest.raises(dataclasses.FrozenInstanceError):
        shot.pocket = 2


def test_a_dict_instance_takes_the_fields_not_a_copy():
    fields = fields_of(rules.new_game("nine_ball"))
    assert vars(unchecked(rules.GameState, fields)) is fields
