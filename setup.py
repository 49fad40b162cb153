"""Compiles the physics engine ahead of time at install (pool_env/build_aot.py); pyproject.toml has the rest.

The build runs `python -m pool_env.build_aot` on the sources being installed, with the
build environment's numba (pyproject.toml's build-system requires). If it fails (or
POOL_ENV_NO_AOT=1 skips it) the install still succeeds, and the engine runs under numba's JIT.
"""

import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
NAME = "pool_env.physics.engine_aot"
TABLE = "engine_aot.json"  # written beside the extension (pool_env/physics/compiled.py reads it)


class BuildEngine(build_ext):
    """build_ext for the one extension, made by build_aot instead of a C compiler run."""

    def build_extension(self, ext):
        target = Path(self.get_ext_fullpath(ext.name))
        if os.environ.get("POOL_ENV_NO_AOT", "") not in ("", "0"):
            print("pool_env: POOL_ENV_NO_AOT is set: the engine will run under numba's JIT", file=sys.stderr)
            return
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH")) if p))
        start = time.perf_counter()
        out = subprocess.run([sys.executable, "-m", "pool_env.build_aot", "--output-dir", str(target.parent)],
                             cwd=ROOT, env=env, capture_output=True, text=True)
        if out.returncode != 0 or not target.is_file():
            print(f"pool_env: WARNING: compiling the engine ahead of time failed; it will run under numba's JIT "
                  f"(compiled on first use).\n{(out.stdout + out.stderr)[-3000:]}", file=sys.stderr)
            return
        print(out.stdout.strip() or f"pool_env: engine compiled in {time.perf_counter() - start:.0f} s",
              file=sys.stderr)

    def copy_extensions_to_source(self):
        """In place (an editable install): the extension and its table, if they were built."""
        for ext in self.extensions:
            inplace, self.inplace = self.inplace, False
            built = Path(self.get_ext_fullpath(ext.name))
            self.inplace = inplace
            if built.is_file():
                target = Path(self.get_ext_fullpath(ext.name))
                for path, copy in ((built, target), (built.with_name(TABLE), target.with_name(TABLE))):
                    shutil.copyfile(path, copy)

    def get_outputs(self):  # only what was built: a failed build leaves the JIT, not a broken install
        return [p for p in super().get_outputs() if Path(p).is_file()]

    def get_output_mapping(self):
        return {k: v for k, v in super().get_output_mapping().items() if Path(k).is_file()}

setup(ext_modules=[Extension(NAME, sources=[])], cmdclass={"build_ext": BuildEngine})
