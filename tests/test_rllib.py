"""examples/rllib_ppo.py: Ray RLlib's PPO trains on PoolBreak-v0, the env unchanged.

ray[rllib] pins gymnasium==1.2.2, so it lives in its own virtualenv (docs/env.md, "Scaling out"),
where .ci/run runs this file. In an environment without ray[rllib] the tests are skipped, unless
POOL_ENV_REQUIRE_RLLIB=1 (as .ci/run sets in the rllib venv): then a missing ray fails them.
"""

import importlib.util
import math
import os
import re
import secrets
import shutil
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "rllib_ppo.py"

if importlib.util.find_spec("ray") is None or importlib.util.find_spec("ray.rllib") is None:
    if os.environ.get("POOL_ENV_REQUIRE_RLLIB") == "1":
        raise ImportError("POOL_ENV_REQUIRE_RLLIB=1 but ray[rllib] is not importable in this environment")
    pytest.skip("ray[rllib] is not installed: it pins gymnasium==1.2.2, so it has its own venv "
                "(docs/env.md, 'Scaling out'; .ci/run runs this file there)", allow_module_level=True)


def ray_env(tmp):
    """The environment for Ray here: session files under tmp (short: Ray's socket paths must fit
    107 bytes), token authentication with a token of our own (nothing written to ~/.ray), no usage
    statistics, no cluster that the environment points at, and this machine's Ray on 127.0.0.1."""
    env = dict(os.environ, RAY_TMPDIR=tmp, RAY_USAGE_STATS_ENABLED="0", RAY_AUTH_MODE="token",
               RAY_AUTH_TOKEN=secrets.token_hex(32), RAY_ENABLE_WINDOWS_OR_OSX_CLUSTER="0")
    env.pop("RAY_ADDRESS", None)
    return env


@pytest.fixture
def ray_tmp():
    tmp = tempfile.mkdtemp(prefix="ray")
    yield tmp
    shutil.rmtree(tmp, ignore_errors=True)


def run_example(*args, env=None, timeout=420):
    return subprocess.run([sys.executable, str(EXAMPLE), *args], cwd=ROOT, env=env, capture_output=True, text=True,
                          timeout=timeout)


def check_output(out, iterations, runners, envs):
    """The per-iteration lines and the final line of a successful run."""
    assert out.returncode == 0, out.stdout + out.stderr[-5000:]
    assert f"{runners} EnvRunner(s) x {envs} env(s)" in out.stdout
    iters = re.findall(r"^iter +(\d+) +env steps +(\d+) +mean episode return +(\S+) +time +([\d.]+) s", out.stdout,
                       re.MULTILINE)
    assert [int(i) for i, *_ in iters] == list(range(1, iterations + 1)), out.stdout
    steps = [int(s) for _, s, _, _ in iters]
    assert steps[0] >= 64 and steps == sorted(set(steps)), steps
    # A break is one step, so every step ends an episode: a return exists, and is a few balls at most.
    assert all(math.isfinite(float(r)) and -2 <= float(r) <= 15 for _, _, r, _ in iters), iters
    final = out.stdout.strip().splitlines()[-1]
    assert final.startswith(f"done: {iterations} iterations, {steps[-1]} env steps in "), final
    assert "iterations/s" in final and "env steps/s" in final


def test_help_lists_the_options():
    out = run_example("--help", timeout=60)
    assert out.returncode == 0, out.stderr
    for flag in ("--iterations", "--num-env-runners", "--num-envs-per-env-runner", "--address", "--env-id"):
        assert flag in out.stdout


@pytest.mark.slow
def test_two_tiny_iterations_on_a_local_ray(ray_tmp):
    """Two iterations of 64 env steps, one EnvRunner (a Ray actor) stepping two envs."""
    env = ray_env(ray_tmp)
    del env["RAY_ENABLE_WINDOWS_OR_OSX_CLUSTER"]  # the example keeps a local Ray on 127.0.0.1 itself
    out = run_example("--iterations", "2", "--num-env-runners", "1", "--num-envs-per-env-runner", "2",
                      "--train-batch-size", "64", "--minibatch-size", "32", "--num-epochs", "1", env=env)
    check_output(out, iterations=2, runners=1, envs=2)
    assert "a local Ray instance" in out.stdout


@pytest.mark.slow
def test_joins_an_existing_cluster(ray_tmp):
    """--address: a head started with `ray start --head` (here on 127.0.0.1, ended by its pid); the
    EnvRunners step pool_env.PoolVectorEnvs (--vectorize vector_entry_point)."""
    env = ray_env(ray_tmp)
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    log = Path(ray_tmp) / "head.log"
    with open(log, "w") as f:
        head = subprocess.Popen([str(Path(sys.executable).with_name("ray")), "start", "--head", f"--port={port}",
                                 "--num-cpus=2", "--include-dashboard=false", "--disable-usage-stats", "--block"],
                                env=env, stdout=f, stderr=subprocess.STDOUT)
    try:
        deadline = time.monotonic() + 120
        while "Ray runtime started" not in log.read_text():
            assert head.poll() is None and time.monotonic() < deadline, log.read_text()[-5000:]
            time.sleep(0.5)
        out = run_example("--address", f"127.0.0.1:{port}", "--iterations", "1", "--num-env-runners", "2",
                          "--num-envs-per-env-runner", "2", "--vectorize", "vector_entry_point",
                          "--train-batch-size", "64", "--minibatch-size", "32", "--num-epochs", "1", env=env)
        check_output(out, iterations=1, runners=2, envs=2)
        assert "(vector_entry_point)" in out.stdout
        assert f"the Ray cluster at 127.0.0.1:{port} (2 CPUs)" in out.stdout
    finally:
        head.terminate()  # `ray start --block` drains and ends the processes it started
        try:
            head.wait(timeout=60)
        except subprocess.TimeoutExpired:
            head.kill()
            head.wait()
