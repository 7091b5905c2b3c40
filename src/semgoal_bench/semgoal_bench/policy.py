"""`./semgoal bench policy [--json]`: training throughput and actor latency beside Stable-Baselines3.

Training: env steps per second with the gradient steps included, once the replay buffer holds its first
episodes, on one torch thread:
- ours (`Trainer.cycle`) on `two_blocks` sub-goals, with one gradient step per env step (the reference's
  setting), the same with the update's matrix products in bfloat16 (``SacConfig.precision``; only where the CPU
  multiplies bfloat16 in hardware: elsewhere it is a dozen times slower than fp32, so it is listed under
  ``not_measured`` with the reason), the same without the expert's cloning loss (``no-cloning``: the reference's
  work per update, one batch through SAC's losses, where ours also clones the expert on a second batch through
  the critic's Q-filter), and with the shipped setting (``TrainConfig.updates_per_step``);
- SB3 SAC + HerReplayBuffer (batch 256, nets [256, 256], one gradient step per env step) on the same env,
  and on gymnasium-robotics' FetchPickAndPlace-v4: the reference the policy issue measured (~47 steps/s).
Each configuration runs in its own child process (``python -O``: gymnasium-robotics' asserts fail on
mujoco >= 3.12), one after the other, ``--repeats`` times; the medians and the ratios to the reference
are printed.

Learning (``--learning STEPS``, instead of the timings): whether the faster configuration learns as well as SB3's,
step for step (:mod:`semgoal_bench.learning`).

Inference: latency of one action for one observation (what the policy node does per control step):
``Actor.act`` on two_blocks, ``SubgoalController.act`` (sampled noise, clipping, derived features) with
each scene's shipped actor, and SB3's ``policy.predict`` for a network of the same size as two_blocks';
p50 and p99 over ``--calls`` calls.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from semgoal_core.arguments import count, natural

if TYPE_CHECKING:
    from semgoal_policy.trainer import TrainConfig

TRAIN_CONFIGS = ("ours:1", "ours:1:bf16", "ours:1:bf16:no-cloning", "ours:shipped", "sb3:two_blocks",
                 "sb3:FetchPickAndPlace-v4")
"""``ours:UPDATES[:PRECISION[:no-cloning]]`` (UPDATES ``1`` or ``shipped``) or ``sb3:ENV``."""
REFERENCE = "sb3:FetchPickAndPlace-v4"
WARMUP_STEPS = 1_000
NOT_NATIVE = "this CPU has no bfloat16 in hardware (AVX512-BF16 or AMX), where bf16 updates are emulated"


def train_configs(bf16_native: bool) -> tuple[tuple[str, ...], dict[str, str]]:
    """The configurations worth timing on this CPU, and those left out with the reason."""
    if bf16_native:
        return TRAIN_CONFIGS, {}
    left_out = {config: NOT_NATIVE for config in TRAIN_CONFIGS if ":bf16" in config}
    return tuple(config for config in TRAIN_CONFIGS if config not in left_out), left_out


def sb3_model(env, keep_infos: bool, warmup: int = WARMUP_STEPS):
    """SB3's SAC + HER as the reference runs it; ``keep_infos`` for envs whose reward reads the step's info."""
    import torch
    from stable_baselines3 import SAC, HerReplayBuffer
    from stable_baselines3.common.logger import Logger

    from semgoal_core.settling import HER_REPLAY_KWARGS

    torch.set_num_threads(1)
    her = {"n_sampled_goal": 4, "goal_selection_strategy": "future", **(HER_REPLAY_KWARGS if keep_infos else {})}
    model = SAC("MultiInputPolicy", env, replay_buffer_class=HerReplayBuffer, replay_buffer_kwargs=her,
                batch_size=256, policy_kwargs={"net_arch": [256, 256]}, train_freq=1, gradient_steps=1,
                learning_starts=warmup, buffer_size=100_000, seed=0, verbose=0)
    model.set_logger(Logger(None, []))  # SB3's default logger leaves an empty folder in the temp dir per run
    return model


def _sb3_env(name: str):
    if name == "two_blocks":
        from semgoal_sim.env import SubgoalEnv

        return SubgoalEnv("two_blocks")
    import gymnasium as gym
    import gymnasium_robotics

    gym.register_envs(gymnasium_robotics)
    return gym.make(name)


def our_config(arg: str, warmup: int) -> TrainConfig:
    """The :class:`TrainConfig` that ``ours:ARG`` names (see :data:`TRAIN_CONFIGS`), on two_blocks from seed 0."""
    from semgoal_policy.sac import SacConfig
    from semgoal_policy.trainer import TrainConfig

    updates, precision, losses, *rest = [*arg.split(":"), "", ""]
    if updates not in ("1", "shipped") or losses not in ("", "no-cloning") or any(rest):
        raise ValueError(f"not a configuration of ours: {arg!r}; valid: UPDATES[:PRECISION[:no-cloning]], UPDATES 1 or "
                         "shipped")
    defaults = TrainConfig(scene="two_blocks")
    sac = SacConfig(precision=precision or "fp32", bc_weight=0.0 if losses else defaults.sac.bc_weight)
    return TrainConfig(scene="two_blocks", seed=0, learning_starts=warmup, run_dir=None, sac=sac,
                       updates_per_step=1.0 if updates == "1" else defaults.updates_per_step)


def train_rate(config: str, steps: int, warmup: int = WARMUP_STEPS) -> float:
    """Env steps/s of one training configuration over ``steps`` env steps after ``warmup`` steps without updates."""
    kind, _, arg = config.partition(":")
    if kind == "ours":
        from semgoal_bringup.experiments.training import trainer_for

        trainer = trainer_for(our_config(arg, warmup))
        while trainer.replay.transitions < warmup:
            trainer.cycle()
        start, done = time.perf_counter(), 0
        while done < steps:
            done += trainer.cycle()
        return done / (time.perf_counter() - start)
    from stable_baselines3.common.callbacks import BaseCallback

    class Clock(BaseCallback):
        """Time from the first gradient step on."""

        def _on_step(self) -> bool:
            if self.num_timesteps == warmup:
                self.locals["self"].bench_start = time.perf_counter()
            return True

    model = sb3_model(_sb3_env(arg), keep_infos=arg == "two_blocks", warmup=warmup)
    model.learn(total_timesteps=warmup + steps, callback=Clock())
    return steps / (time.perf_counter() - model.bench_start)


def _percentiles(fn, calls: int) -> dict[str, float]:
    times = []
    for _ in range(calls):
        start = time.perf_counter()
        fn()
        times.append((time.perf_counter() - start) * 1e3)
    return {"p50_ms": round(float(np.percentile(times, 50)), 4), "p99_ms": round(float(np.percentile(times, 99)), 4)}


def inference(calls: int) -> dict[str, dict[str, float]]:
    """Latency of one action for one observation, ours and SB3's, on one thread."""
    import torch

    from semgoal_core.vocabulary import PAPER_SCENES
    from semgoal_policy.controller import SubgoalController
    from semgoal_sim.env import SubgoalEnv

    torch.set_num_threads(1)
    envs, observations, controllers = {}, {}, {}
    for scene in PAPER_SCENES:  # every shipped actor, as the policy node runs it (derived features included)
        envs[scene] = SubgoalEnv(scene)
        observations[scene] = envs[scene].reset(seed=0, options={"subgoal": "pick(red)"})[0]
        controllers[scene] = SubgoalController(scene)
        controllers[scene].set_subgoal(envs[scene].subgoal.literals())
    obs, actor = observations["two_blocks"], controllers["two_blocks"].actor
    sb3 = sb3_model(envs["two_blocks"], keep_infos=True)
    return {
        "ours:Actor.act": _percentiles(lambda: actor.act(obs["observation"], obs["desired_goal"]), calls),
        **{f"ours:SubgoalController.act[{scene}]":
           _percentiles(lambda c=controller, o=observations[scene]: c.act(o["observation"], (0, 1)), calls)
           for scene, controller in controllers.items()},
        "sb3:policy.predict": _percentiles(lambda: sb3.predict(obs, deterministic=True), calls),
    }


def _child(args: list[str]) -> str:
    result = subprocess.run([sys.executable, "-O", "-m", "semgoal_bench.policy", *args], capture_output=True, text=True)
    if result.returncode != 0:
        raise RuntimeError(f"bench worker {args} failed:\n{result.stderr[-2000:]}")
    return result.stdout.strip().splitlines()[-1]


def _work(args: argparse.Namespace) -> object:
    """A child's one measurement: ``inference``, ``learning:CONFIG`` or a training ``CONFIG``'s rate."""
    if args.worker == "inference":
        return inference(args.calls)
    if args.worker.startswith("learning:"):
        from semgoal_bench.learning import curve

        return curve(args.worker.removeprefix("learning:"), args.learning or args.steps, args.eval_every,
                     args.eval_episodes, args.warmup)
    return train_rate(args.worker, args.steps, args.warmup)


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="semgoal bench policy", description=__doc__.split("\n\n")[0])
    parser.add_argument("--steps", type=count, default=2_000, help="env steps timed per training run")
    parser.add_argument("--warmup", type=natural, default=WARMUP_STEPS, help="env steps before the first update")
    parser.add_argument("--repeats", type=count, default=3)
    parser.add_argument("--calls", type=count, default=5_000, help="single-observation actions timed")
    parser.add_argument("--learning", type=count, metavar="STEPS",
                        help="instead of the timings: train ours and SB3 for STEPS env steps each and compare their "
                             "success at rest as they learn (semgoal_bench.learning)")
    parser.add_argument("--eval-every", type=count, default=10_000, help="with --learning: env steps between evaluations")
    parser.add_argument("--eval-episodes", type=count, default=50, help="with --learning: episodes per sub-goal type")
    parser.add_argument("--figure", type=Path, help="with --learning: a PNG of both learning curves")
    parser.add_argument("--json", action="store_true")
    parser.add_argument("--worker", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.worker:  # a child: one measurement, printed as its last line
        print(json.dumps(_work(args)))
        return 0
    out = sys.stderr if args.json else sys.stdout
    if args.learning:
        from semgoal_bench.learning import compare

        result = compare(args.learning, args.eval_every, args.eval_episodes, args.warmup, args.figure, out)
        if args.json:
            out.flush()
            print(json.dumps({"learning": result}))
        return 0
    from semgoal_policy.sac import bf16_is_native

    configs, not_measured = train_configs(bf16_is_native())
    for config, reason in not_measured.items():
        print(f"{config}: not measured: {reason}", file=out, flush=True)
    rates: dict[str, list[float]] = {config: [] for config in configs}
    for repeat in range(args.repeats):
        for config in configs:
            worker = ["--worker", config, "--steps", str(args.steps), "--warmup", str(args.warmup)]
            rates[config].append(float(_child(worker)))
            print(f"[repeat {repeat + 1}/{args.repeats}] {config:28s} {rates[config][-1]:7.1f} steps/s", file=out, flush=True)
    medians = {config: round(statistics.median(values), 1) for config, values in rates.items()}
    latency = json.loads(_child(["--worker", "inference", "--calls", str(args.calls)]))
    result = {"training": {"unit": "env steps/s with gradient steps, median of repeats, one torch thread",
                           "bf16_native": not not_measured, "steps_per_second": medians, "not_measured": not_measured,
                           "ratio_to_reference": {c: round(v / medians[REFERENCE], 2) for c, v in medians.items()},
                           "reference": REFERENCE},
              "inference": latency}
    for config, rate in medians.items():
        print(f"{config:28s} {rate:7.1f} steps/s  x{result['training']['ratio_to_reference'][config]:.2f}", file=out)
    for name, figures in latency.items():
        print(f"{name:28s} p50 {figures['p50_ms']:.3f} ms  p99 {figures['p99_ms']:.3f} ms", file=out)
    if args.json:
        out.flush()
        print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
