"""What runs while train.py trains: the learning curve's evaluations, PPO's exploration schedule, a progress line."""

from __future__ import annotations

import logging
import time

from .evaluate import evaluate
from .report import progress_line
from .run_eval import play_games, trained_agent
from .sb3 import SB3Agent

log = logging.getLogger("train")  # train.py's logger: its console and the run folder's train.log

# `args` below is train.py's options (`Args`), `run` what its phases share (`Run`).


def make_callbacks(args, run):
    """What runs during training: deterministic evaluations on fixed seeds (the learning curve and
    the best checkpoint), PPO's exploration schedule, and a progress line every few seconds."""
    from stable_baselines3.common.callbacks import BaseCallback, CallbackList


    class CurveCallback(BaseCallback):
        def __init__(self, every: int):
            super().__init__()
            self.every, self.next_at, self.points, self.failed_shots = every, 0, [], 0
            self.best, self.trained_steps = None, 0

        @property
        def kept_untrained(self) -> bool:  # the first evaluation comes before any policy update
            return bool(args.keep_best and self.points and self.best is self.points[0])

        def _on_step(self) -> bool:
            self.failed_shots += sum(bool(info.get("error")) for info in self.locals["infos"])
            if self.every and self.num_timesteps >= self.next_at:
                self.next_at += self.every
                self.measure()
            return True

        def _on_training_end(self) -> None:
            self.trained_steps = int(self.num_timesteps)

        def measure(self):
            if run.game:  # games against the opponent: the reward is +1 a win, -1 a loss
                result = play_games(trained_agent(args, run, self.model), args, run, run.curve_seeds)
                point = {"timesteps": int(self.num_timesteps), "reward": result["reward"],
                         "win_rate": result["win_rate"]["mean"]}
            else:
                result = evaluate(SB3Agent(self.model), args.env_id, run.curve_seeds, run.env_kwargs)
                point = {"timesteps": int(self.num_timesteps), "reward": result["reward"],
                         "pocketed_per_shot": result["pocketed_per_shot"]["mean"],
                         "scratch_rate": result["scratch_rate"]["mean"]}
            self.points.append(point)
            if self.best is None or point["reward"]["mean"] > self.best["reward"]["mean"]:
                self.best = point
                self.model.save(run.dir / "best_model.zip")
            self.logger.record("eval/mean_reward", point["reward"]["mean"])
            for key in ("scratch_rate", "win_rate"):
                if key in point:
                    self.logger.record(f"eval/{key}", point[key])
            self.logger.dump(self.num_timesteps)

    # No more often than the policy changes (PPO updates once per rollout of n_steps * n_envs).
    every = max(args.timesteps // max(args.curve_points, 1), args.n_steps * args.n_envs if args.algo == "ppo" else 1)
    curve = CurveCallback(every if args.curve_points else 0)
    anneal = [anneal_std(args)] if args.algo == "ppo" and args.anneal_std else []
    callbacks = [curve, progress_callback(args), *anneal]
    return curve, CallbackList(callbacks)


def anneal_std(args):
    """PPO's exploration schedule as a callback: the policy's log std from --log-std-init to --log-std-final."""
    from stable_baselines3.common.callbacks import BaseCallback

    class AnnealStd(BaseCallback):
        """Exploration from coarse to fine: the reward is a rugged function of the aim (a fifth of a
        ball radius can halve it), so the Gaussian policy's spread follows a fixed schedule,
        wide at first and narrow at the end, instead of being learned."""

        def _on_training_start(self) -> None:
            self.model.policy.log_std.requires_grad_(False)

        def _on_rollout_start(self) -> None:
            progress = min(self.num_timesteps / args.timesteps, 1.0)
            value = args.log_std_init + progress * (args.log_std_final - args.log_std_init)
            self.model.policy.log_std.data.fill_(value)
            self.logger.record("train/log_std", value)

        def _on_step(self) -> bool:
            return True

    return AnnealStd()


def progress_callback(args):
    """A callback that logs a progress line (agents.report.progress_line) every --progress-every seconds."""
    from stable_baselines3.common.callbacks import BaseCallback

    class Progress(BaseCallback):
        """A progress line every --progress-every seconds, to train.log and (unless the progress bar
        draws on a terminal) stdout: for runs redirected to a file or under CI. Cheap: it reads the
        clock only every 64th step."""

        def _on_training_start(self) -> None:
            self.start = self.last = time.perf_counter()

        def _on_step(self) -> bool:
            if args.progress_every > 0 and self.n_calls % 64 == 0:
                now = time.perf_counter()
                if now - self.last >= args.progress_every:
                    self.last = now
                    rewards = [episode["r"] for episode in self.model.ep_info_buffer]  # SB3 keeps the last 100
                    log.info(progress_line(self.num_timesteps, args.timesteps, now - self.start, rewards),
                             extra={"progress": True})
            return True

    return Progress()
