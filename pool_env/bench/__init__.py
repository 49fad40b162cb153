"""Benchmarks: `python -m pool_env.bench {speed,env,accuracy,stability}` (figures, never test assertions)."""
