"""`python -m pool_env.build_aot`: compile the engine ahead of time (what `pip install` runs).

It runs a set of warm-up shots under numba's JIT, recording every call Python makes into the
physics' compiled code with its argument types, then compiles those functions with those
types into the extension module `engine_aot` with numba.pycc (for this machine's CPU), beside a
table of what it holds and the hash of the sources it was compiled from (compiled.py reads
both). The JIT compiles from scratch (an empty numba cache: pycc links the JIT's code, which
code loaded from the cache cannot be), so the build takes about as long as a cold compile.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numba

# numba.pycc warns of its pending deprecation on import: it works in the numba the build
# requires, and its output needs no numba at run time.
with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    from numba.pycc import CC, compiler

    from .physics import Balls, Physics, Table, compiled, rack, simulate, simulate_batch, strike, warm_up
    from .physics.batch_run import simulate_level_batch

PHYSICS = "pool_env.physics"  # the package whose calls are compiled (its sources are the hash's)


def warm_up_shots():
    """The shots whose calls into compiled code the extension serves: a break on each table
    (level), a 2-ball shot, shots with a ball in the air and off an elevated cue, the
    trajectory sampler, a batch, and a batch of level scenes in one compiled call (the search's)."""
    physics = Physics.standard()
    for table in (Table.eight_foot(), Table.seed(), Table.snooker(), Table.carom()):
        balls = rack(table, seed=0) if table.pockets.shape[0] else Balls([[0.5, 0.5], [1.0, 0.6], [1.5, 0.4]])
        read(simulate(strike(balls, force=(8 * 0.170097 / 0.005, 0.0)), table, physics)).at(0.05)
    table = Table.eight_foot()
    read(simulate(Balls([[0.5, 0.5], [1.0, 0.55]], v=[[2.0, 0.2], [0.0, 0.0]]), table, physics), final_first=True)
    read(simulate(strike(rack(table), force=(30.0, 0.0), elevation=0.3, offset=(0.0, 0.01)), table, physics))
    simulate_batch([strike(rack(table, seed=s), force=(200.0, 1.0)) for s in range(2)], table, physics, threads=2)
    struck = strike(rack(table), force=(30.0, 0.0))
    simulate_level_batch(struck, struck.xy[None], struck.v[None], struck.w[None], table, physics)
    warm_up()


def read(result, final_first=False):
    """`result` after reading what the envs and the rules read of every shot: the event facts
    and the balls at rest, in one compiled call; or (`final_first`) the balls at rest alone,
    then the facts, each a compiled call of its own."""
    if final_first:
        _ = result.final  # a property: read for its compiled call
    result.event_facts()
    _ = result.final
    return result


def record():
    """{function: {args key: numba signature}} of the calls the warm-up shots make (run under
    POOL_ENV_JIT=record)."""
    if compiled.RECORD is None:
        raise RuntimeError("build_aot records only under POOL_ENV_JIT=record")
    warm_up_shots()
    calls = {}
    for f, key, types in compiled.RECORD:
        if f.__module__.startswith(PHYSICS + "."):
            calls.setdefault(f, {})[key] = f.dispatcher.overloads[types].signature
    return calls


def _flags_per_function(options):
    """Make pycc compile each export's wrapper with its function's own numba options, as the
    JIT does (pycc's own flags are the same for every export): releasing the GIL (`nogil`),
    and reference counting only where the function allocates (`_nrt`: without it, each array
    argument costs a reference-counted wrapper per call). options: {Python function: options}."""
    original = compiler.compile_extra

    def compile_extra(typingctx, targetctx, func, args, return_type, flags, **kws):
        if func in options:
            flags = flags.copy()
            flags.release_gil = bool(options[func].get("nogil"))
            flags.nrt = options[func].get("_nrt", True)
        return original(typingctx, targetctx, func, args, return_type, flags, **kws)

    compiler.compile_extra = compile_extra


def build(output_dir: Path) -> dict:
    """Record, compile, and write the extension and its table into output_dir; the table."""
    start = time.process_time()
    calls = record()
    recorded = time.process_time() - start
    cc = CC(compiled.EXTENSION)
    cc.output_dir = str(output_dir)
    cc.target_cpu = "host"  # built on the machine it runs on (pip install), like the JIT
    exports, options = [], {}
    for f, signatures in sorted(calls.items(), key=lambda item: item[0].name):
        for key, signature in signatures.items():
            name = f"f{len(exports)}"
            cc.export(name, signature)(f.py_func)
            exports.append((f.name, repr(key), name))
            options[f.py_func] = f.options
    digest = compiled.sources_hash()
    hash_int = int(digest[:15], 16)
    namespace = {}
    exec(f"def source_hash():\n    return {hash_int}\n", namespace)  # the hash, compiled into the extension
    cc.export("source_hash", "int64()")(namespace["source_hash"])
    _flags_per_function(options)
    cc.compile()
    table = {"hash": digest, "hash_int": hash_int, "exports": exports, "numba": numba.__version__,
             "target_cpu": cc.target_cpu, "record_seconds": round(recorded, 1),
             "seconds": round(time.process_time() - start, 1)}
    (output_dir / compiled.TABLE.name).write_text(json.dumps(table, indent=1) + "\n")
    return table


def run_build(output_dir: Path) -> dict:
    """Build in a fresh interpreter (recording mode, empty numba cache); the table it wrote."""
    output_dir = Path(output_dir).resolve()
    output_dir.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, POOL_ENV_JIT="record", NUMBA_CACHE_DIR=cache)
        root = str(compiled.PACKAGE.parents[1])
        env["PYTHONPATH"] = os.pathsep.join(p for p in (root, env.get("PYTHONPATH")) if p)
        subprocess.run([sys.executable, "-m", __spec__.name, "--output-dir", str(output_dir), "--in-process"],
                       env=env, check=True)
    return json.loads((output_dir / compiled.TABLE.name).read_text())


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m pool_env.build_aot", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--output-dir", type=Path, default=compiled.PACKAGE,
                        help="where to write the extension and its table (default: beside the sources)")
    parser.add_argument("--in-process", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    wall = time.perf_counter()
    table = build(args.output_dir) if args.in_process else run_build(args.output_dir)
    if not args.in_process:
        print(f"pool_env: compiled the engine ahead of time ({len(table['exports'])} functions' versions, "
              f"numba {table['numba']}) in {time.perf_counter() - wall:.1f} s ({table['seconds']} s CPU) "
              f"into {args.output_dir}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
