"""Which compiled engine runs: the ahead-of-time extension built at install, else numba's JIT.

`pip install` builds the extension `engine_aot` (pool_env/build_aot.py: numba.pycc compiles every
compiled function Python calls in a set of warm-up shots, with the argument types those calls
had). When it is present, was built from these very sources (a hash of the physics package's
sources, stored beside it, matches) and POOL_ENV_JIT is not set, the decorators of jit.py make
each compiled function a `Compiled`: a call from Python with argument types the extension was
built for runs the extension's code, and numba is not even imported; any other call
(other types, a function the extension lacks) compiles it with numba's JIT on first use, as
without the extension. Otherwise the decorators are numba's own.
"""

from __future__ import annotations

import ast
import hashlib
import importlib
import json
import os
from pathlib import Path

import numpy as np

PACKAGE = Path(__file__).resolve().parent
EXTENSION = "engine_aot"  # the extension module's name, in this package
TABLE = PACKAGE / f"{EXTENSION}.json"  # its exports, the sources' hash, how it was built
# The sources the extension is compiled from: every module of the package (a change to any
# makes the extension stale), and jit.py's decorators' options with them.
SOURCES = sorted(p.name for p in PACKAGE.glob("*.py"))


def sources_hash() -> str:
    """The hash of the physics package's sources (names and contents), as the build stores it."""
    h = hashlib.sha256()
    for name in SOURCES:
        h.update(name.encode() + b"\0" + (PACKAGE / name).read_bytes() + b"\0")
    return h.hexdigest()


# The types keyed by their name alone, looked up first (a shot's call into the engine is four
# tuples and None or True).
_NAMED = {t: t.__name__ for t in (tuple, type(None), bool, int, float)}


def arg_key(a):
    """A Python value's type as far as choosing among compiled versions goes (after numba's
    typeof for what the engine takes: arrays by dtype, dimensions, layout and writability;
    None, bools, ints, floats and numpy scalars by type). A tuple is keyed as a tuple, whatever
    it holds: the functions Python passes tuples to (engine.simulate_scene, the engine's
    entry, and batch_run's; packed.final_arrays and facts.final_facts, which copy a run's
    final state and facts) are called from modules that build them with fixed types (the
    physics tuple's model ids None exactly when `full` is None: see engine.run, so that
    argument tells the two apart); checking each of their ~30 items would cost more than a
    2-ball shot's whole simulation."""
    t = type(a)
    if t is np.ndarray:
        flags = a.flags
        layout = "C" if flags.c_contiguous else ("F" if flags.f_contiguous else "A")
        return a.dtype.char, a.ndim, layout, flags.writeable
    if t in _NAMED:
        return _NAMED[t]
    if isinstance(a, np.generic):
        return "np", a.dtype.char
    return t.__module__, t.__qualname__, id(t)  # matches nothing the build stored: the JIT runs


def args_key(args) -> tuple:
    """All of a call's arguments' key (the build stores its repr)."""
    return tuple([_NAMED.get(type(a)) or arg_key(a) for a in args])


def extension():
    """The extension's exports {function's qualified name: {args key: function}} and "aot"; or
    None and why it cannot run: "not built", "not importable (...)", "stale" (built from other
    sources than these)."""
    try:
        table = json.loads(TABLE.read_text())
    except (OSError, ValueError):
        return None, "not built"
    try:
        module = importlib.import_module(f"{__package__}.{EXTENSION}")
    except ImportError as e:
        return None, f"not importable ({e})"
    if table.get("hash") != sources_hash() or module.source_hash() != table["hash_int"]:
        return None, "stale"
    exports = {}
    for function, key, name in table["exports"]:
        exports.setdefault(function, {})[ast.literal_eval(key)] = getattr(module, name)
    return exports, "aot"


def _load():
    """extension(), unless POOL_ENV_JIT asks for the JIT (or the build is recording). A stale
    extension is set aside without a word (WHY says so): after an edit of the physics, its
    tests and commands run as before, under the JIT, until the extension is rebuilt."""
    mode = os.environ.get("POOL_ENV_JIT", "")
    if mode == "record":
        return None, "recording the calls to build the extension"
    if mode not in ("", "0"):
        return None, "POOL_ENV_JIT is set"
    return extension()


# The extension's exports, or None when the JIT runs; and why (bench speed reports it).
EXPORTS, WHY = _load()
# The calls recorded (the function, its args key, the numba signature the call ran) while
# pool_env.build_aot runs its warm-up shots, under POOL_ENV_JIT=record; else None.
RECORD: list | None = [] if WHY.startswith("recording") else None


def engine() -> str:
    """Which engine runs Python's calls into compiled code: "aot" or "jit"."""
    return "jit" if EXPORTS is None else "aot"


class Compiled:
    """A compiled function in the ahead-of-time mode: the extension's code for the argument
    types it was built for, numba's JIT (made on first need) for any other. Numba's compiled
    code calling it sees the JIT dispatcher (`_numba_type_`), so a JIT-compiled caller links
    the JIT version; every other attribute is the dispatcher's."""

    def __init__(self, func, options):
        self.py_func, self.options = func, options
        self.__name__, self.__qualname__, self.__module__ = func.__name__, func.__qualname__, func.__module__
        self.__doc__, self.__wrapped__ = func.__doc__, func
        self.name = f"{func.__module__}.{func.__qualname__}"
        self.aot = EXPORTS.get(self.name, {}) if EXPORTS is not None else {}
        self._dispatcher = None

    @property
    def dispatcher(self):
        """numba's JIT dispatcher of this function (numba imported, and it made, on first use)."""
        if self._dispatcher is None:
            from numba import njit

            self._dispatcher = njit(**self.options)(self.py_func)
        return self._dispatcher

    @property
    def _numba_type_(self):
        return self.dispatcher._numba_type_

    def __call__(self, *args):
        if self.aot:
            f = self.aot.get(args_key(args))
            if f is not None:
                return f(*args)
        if RECORD is not None:
            return _recorded(self, args)
        d = self._dispatcher  # once made, without the property's call (the players' kernels come here every call)
        return (self.dispatcher if d is None else d)(*args)

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        return getattr(self.dispatcher, name)

    def __reduce__(self):  # pickled by name, as numba's dispatchers are
        return self.__qualname__

    def __repr__(self):
        return f"<pool_env compiled function {self.name} ({len(self.aot)} ahead-of-time versions)>"


def _recorded(f, args):
    """Run a call under the JIT and record its types and the signature numba ran it with."""
    out = f.dispatcher(*args)
    types = tuple(f.dispatcher.typeof_pyval(a) for a in args)
    if types in f.dispatcher.overloads:
        RECORD.append((f, args_key(args), types))
    return out


def compiled_function(func, options):
    """What jit.py's decorators make of `func`: numba's dispatcher when the JIT runs, else (the
    extension runs, or the build records its calls) a `Compiled`."""
    if EXPORTS is None and RECORD is None:
        from numba import njit

        return njit(**options)(func)
    return Compiled(func, options)
