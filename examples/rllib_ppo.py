"""Train PPO with Ray RLlib (its current API stack) on PoolBreak-v0, on this machine or on a Ray cluster.

The envs run unchanged: each RLlib EnvRunner builds its `num_envs_per_env_runner` envs with
`gymnasium.make_vec("pool_env:PoolBreak-v0", ...)`, the "pool_env:" prefix making every Ray
worker import pool_env (which registers the ids) first. `--vectorize sync` (the default) steps
them one after the other (Gymnasium's SyncVectorEnv); `--vectorize vector_entry_point` makes a
`pool_env.PoolVectorEnv`, which simulates all the shots of a step in one simulate_batch call.

    python examples/rllib_ppo.py                                  # local: a throwaway Ray on this machine
    python examples/rllib_ppo.py --iterations 40                   # 80,000 breaks: mean return -0.4 -> ~0.6
    python examples/rllib_ppo.py --address auto --num-env-runners 16   # an existing cluster (`ray start`)

ray[rllib] 2.60 pins gymnasium==1.2.2, so this runs in its own virtualenv (see docs/env.md,
"Scaling out"). It prints one line per training iteration and a final summary line.
"""

import argparse
import math
import os
import sys
import time

# Ray's usage statistics would be sent off this machine; a user who wants them can set it to 1.
os.environ.setdefault("RAY_USAGE_STATS_ENABLED", "0")


def parse_args(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("--iterations", type=int, default=5, help="training iterations (a demo by default)")
    p.add_argument("--num-env-runners", type=int, default=2,
                   help="RLlib EnvRunner actors sampling in parallel (0: sample in the driver process)")
    p.add_argument("--num-envs-per-env-runner", type=int, default=4,
                   help="envs stepped by each EnvRunner, its actions computed in one batch")
    p.add_argument("--address", default=None,
                   help="an existing Ray cluster: 'auto' (this machine runs a node of it) or HEAD_IP:6379; "
                        "None: start a private Ray instance on this machine only")
    p.add_argument("--vectorize", default="sync", choices=["sync", "vector_entry_point"],
                   help="how each EnvRunner steps its envs: Gymnasium's SyncVectorEnv of PoolBreakEnvs, or one "
                        "pool_env.PoolVectorEnv (one simulate_batch call per step)")
    p.add_argument("--env-id", default="PoolBreak-v0", choices=["PoolBreak-v0", "PoolBreakRun-v0"], help="the env")
    p.add_argument("--train-batch-size", type=int, default=2000, help="env steps collected per iteration")
    p.add_argument("--minibatch-size", type=int, default=250, help="env steps per gradient step")
    p.add_argument("--num-epochs", type=int, default=10, help="passes over each batch")
    p.add_argument("--lr", type=float, default=3e-4, help="learning rate")
    p.add_argument("--seed", type=int, default=0, help="seed of the networks and the envs")
    p.add_argument("--num-cpus", type=int, default=None,
                   help="local run only: CPUs Ray may schedule on (None: the machine's, at least one per "
                        "EnvRunner)")
    p.add_argument("--save", default=None, metavar="DIR", help="save the trained algorithm (a checkpoint) here")
    args = p.parse_args(argv)
    if args.iterations < 1 or args.num_env_runners < 0 or args.num_envs_per_env_runner < 1:
        p.error("need --iterations >= 1, --num-env-runners >= 0 and --num-envs-per-env-runner >= 1")
    if args.minibatch_size > args.train_batch_size:
        p.error("--minibatch-size must not exceed --train-batch-size")
    return args


def start_ray(args):
    if args.address is None:
        # A private single-node instance: Ray then takes 127.0.0.1 as this node's address (the
        # setting Ray uses on macOS and Windows), so its processes listen and talk on the loopback
        # only. Read when ray is imported, hence set before.
        os.environ.setdefault("RAY_ENABLE_WINDOWS_OR_OSX_CLUSTER", "0")
    import ray

    if args.address is None:
        # address="local": never join a cluster that happens to run here (or RAY_ADDRESS); no
        # dashboard. Oversubscribe rather than wait forever when more EnvRunners than cores are asked.
        num_cpus = args.num_cpus or max(os.cpu_count() or 1, args.num_env_runners)
        ray.init(address="local", num_cpus=num_cpus, include_dashboard=False)
        where = f"a local Ray instance ({num_cpus} CPUs)"
    else:
        # Every node must have pool_env and ray[rllib] installed in the same Python environment.
        try:
            ray.init(address=args.address)
        except ConnectionError:
            if args.address != "auto" and os.environ.get("RAY_AUTH_MODE") != "token":
                print("hint: if the cluster uses Ray's token authentication, an explicit --address needs "
                      "RAY_AUTH_MODE=token and the head's token (its ~/.ray/auth_token, or RAY_AUTH_TOKEN) here; "
                      "--address auto, on a node of the cluster that has the token file, needs neither",
                      file=sys.stderr)
            raise
        where = f"the Ray cluster at {args.address} ({ray.cluster_resources().get('CPU', 0):.0f} CPUs)"
    return ray, where


def build_config(args):
    from ray.rllib.algorithms.ppo import PPOConfig

    return (
        PPOConfig()  # the current API stack (RLModule, Learner, EnvRunner) is the default
        .environment(f"pool_env:{args.env_id}")
        .env_runners(num_env_runners=args.num_env_runners, num_envs_per_env_runner=args.num_envs_per_env_runner,
                     gym_env_vectorize_mode=args.vectorize, num_cpus_per_env_runner=1)
        .training(train_batch_size_per_learner=args.train_batch_size, minibatch_size=args.minibatch_size,
                  num_epochs=args.num_epochs, lr=args.lr)
        .debugging(seed=args.seed)
    )


def progress(result):
    """(env steps so far, mean episode return over the last episodes) from an RLlib result dict."""
    from ray.rllib.utils.metrics import ENV_RUNNER_RESULTS, EPISODE_RETURN_MEAN, NUM_ENV_STEPS_SAMPLED_LIFETIME

    runners = result.get(ENV_RUNNER_RESULTS, {})
    steps = result.get(NUM_ENV_STEPS_SAMPLED_LIFETIME, runners.get(NUM_ENV_STEPS_SAMPLED_LIFETIME, 0))
    ret = runners.get(EPISODE_RETURN_MEAN, math.nan)
    return int(steps), float(ret)


def main(argv=None):
    args = parse_args(argv)

    import pool_env  # noqa: F401  (registers the env ids in this process)
    from pool_env.physics import warm_up

    # Compile (or load) the physics once here, so that the EnvRunners load it from numba's cache.
    print(f"physics ready in {warm_up():.1f} s", flush=True)

    ray, where = start_ray(args)
    try:
        config = build_config(args)
        algo = config.build_algo()
        print(f"PPO on {args.env_id} on {where}: {args.num_env_runners} EnvRunner(s) x "
              f"{args.num_envs_per_env_runner} env(s) ({args.vectorize}), {args.train_batch_size} env steps per "
              "iteration",
              flush=True)
        start = time.perf_counter()
        steps, ret = 0, math.nan
        for i in range(1, args.iterations + 1):
            t0 = time.perf_counter()
            result = algo.train()
            steps, ret = progress(result)
            print(f"iter {i:3d}  env steps {steps:8d}  mean episode return {ret:7.3f}  "
                  f"time {time.perf_counter() - t0:6.1f} s (total {time.perf_counter() - start:6.1f} s)", flush=True)
        total = time.perf_counter() - start
        if args.save:
            path = algo.save_to_path(os.path.abspath(args.save))
            print(f"saved to {path}", flush=True)
        algo.stop()
        try:  # the empty folder RLlib makes under ~/ray_results for every run
            os.rmdir(algo.logdir)
        except OSError:
            pass
        print(f"done: {args.iterations} iterations, {steps} env steps in {total:.1f} s "
              f"({args.iterations / total:.3f} iterations/s, {steps / total:.0f} env steps/s), "
              f"final mean episode return {ret:.3f}", flush=True)
    finally:
        ray.shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
