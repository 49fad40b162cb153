"""`unchecked`: a frozen dataclass built from fields its caller has made valid, skipping `__init__`."""

from __future__ import annotations


def unchecked(cls, fields: dict):
    """An instance of `cls` (a frozen dataclass, or another class whose instances hold their
    fields as attributes, as `Table`) with `fields` (every field, by name) set as given,
    built without `__init__` and `__post_init__`. A class with a `__dict__` takes `fields` as
    it (not copied); a class with `__slots__` gets them one by one.

    For the hot paths only, where the fields are valid by construction (decoded, read from the
    engine, derived from a checked instance) so the checks would change nothing, yet cost as much
    as the work around them. Each caller says in its docstring why its fields are valid. The
    result compares, hashes, prints and pickles as the checked instance would: a dataclass
    reads its fields by name, never through `__init__`."""
    out = object.__new__(cls)
    if cls.__dictoffset__:
        object.__setattr__(out, "__dict__", fields)
    else:
        for name, value in fields.items():
            object.__setattr__(out, name, value)
    return out
