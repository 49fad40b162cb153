"""How the simulator's compiled code is compiled: six decorators, one home for their options.

Every compiled function is cached on disk (`cache=True`: only the first run on a machine pays
the compile). Functions that allocate no arrays are compiled without numba's reference
counting (`_nrt=False`): each array view or array argument otherwise costs an atomic
increment and decrement, which measured as about half the engine's time. Only the few
functions that allocate (the loop's entry points, and the rare group solves) keep it.
Functions called only from compiled code skip the CPython wrapper (it costs about 0.1 s of
cold compile each); calling one of those (`helper`, `allocating_helper`) from Python crashes
the interpreter, so a function a test or a user calls directly is a `kernel` or `allocating`.

Numba compiles a callee once per argument-type signature, and a constant argument (`f(x, 1)`,
`f(x, True)`, or a variable still holding its first constant) is typed as a literal: each
call site with another constant compiles the callee again. Such arguments are written
`np.int64(1)` or `np.bool_(True)`: typed, not literal, so one compiled version serves all.

When the ahead-of-time extension built at install is present and current, the decorators
make each function a compiled.Compiled (numba is imported only if a call needs the JIT); see
compiled.py.
"""

from .compiled import compiled_function


def _decorator(**options):
    return lambda func: compiled_function(func, dict(cache=True, **options))


# No allocation: no reference counting. Callable from Python and from compiled code.
kernel = _decorator(_nrt=False, no_cfunc_wrapper=True)
# No allocation, called only from compiled code.
helper = _decorator(_nrt=False, no_cpython_wrapper=True, no_cfunc_wrapper=True)
# Allocates arrays (np.empty and the like): reference counting on. Releases the GIL while it
# runs when called from Python (fixed.run, batch_run's), so threads simulate scenes in parallel.
allocating = _decorator(_nrt=True, nogil=True, no_cfunc_wrapper=True)
# The one call from Python per simulation (engine.simulate_scene): allocates nothing itself, so
# numba takes its array arguments without reference counting, which halves the dispatch of
# its 12 arrays (with it each array gets a fresh meminfo, made and freed on every call); what it
# calls allocates with reference counting on, as usual. Releases the GIL, as `allocating`.
entry = _decorator(_nrt=False, nogil=True, no_cfunc_wrapper=True)
# Allocates, called only from compiled code.
allocating_helper = _decorator(_nrt=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
# A `helper` with one caller, into which numba inlines it before typing: it gets no compiled
# library of its own. A function's library holds its callees' code too, optimised and emitted
# again, so each caller up a chain of big functions (engine.simulate_scene, the event loop
# engine.run, its _resolve, contacts.resolve_ball_ball) would compile the rest of the engine
# again; inlined, they are compiled once, in simulate_scene's library.
inlined = _decorator(_nrt=False, no_cpython_wrapper=True, no_cfunc_wrapper=True, inline="always")
