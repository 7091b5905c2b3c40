"""`./semgoal bench policy --learning STEPS`: does our faster update learn as SB3's SAC+HER does, step for step?

Ours at the configuration the throughput table sets beside SB3 (one bf16 update per env step, no cloning loss:
the reference's work per update) and SB3 SAC + HerReplayBuffer (as the throughput bench builds it) train on
``two_blocks`` sub-goals from seed 0, each in its own process, side by side. Every ``every`` env steps both are
evaluated the same way: the deterministic actor, the trainer's evaluation (``success_by_kind``: success held at
rest over ``SETTLE_STEPS``, the executive's rule), the same starts from ``EVAL_SEED_BASE`` (never a training
seed), ``episodes`` per sub-goal type. The rates carry Wilson intervals; a figure draws both curves.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np

from semgoal_sim.env import SubgoalEnv

LEARNERS = ("ours:1:bf16:no-cloning", "sb3:two_blocks")
SCENE = "two_blocks"
EVAL_ENVS = 8


def _kinds() -> tuple[str, ...]:
    from semgoal_policy.agents import AGENTS

    return AGENTS["hierarchical"].evaluated_kinds(SCENE)


def learning_point(env_steps: int, rates: dict[str, float], episodes: int) -> dict:
    """One evaluation: the rates per type, pooled with a Wilson interval (every type has ``episodes``)."""
    from semgoal_bringup.experiments.evaluation import wilson_interval

    wins = round(sum(rates.values()) * episodes)
    total = episodes * len(rates)
    low, high = wilson_interval(wins, total)
    return {"env_steps": env_steps, "success": rates, "overall": wins / total, "wilson_95": [round(low, 4), round(high, 4)]}


def ours_curve(arg: str, steps: int, every: int, episodes: int, warmup: int) -> list[dict]:
    """Our trainer at ``ours:ARG`` (:func:`semgoal_bench.policy.our_config`), evaluated every ``every`` env steps."""
    from semgoal_bench.policy import our_config
    from semgoal_bringup.experiments.training import trainer_for

    trainer = trainer_for(our_config(arg, warmup))
    points, next_eval = [], every
    while trainer.env_steps < steps:
        trainer.cycle()
        if trainer.env_steps >= next_eval:
            points.append(learning_point(trainer.env_steps, trainer.evaluate(episodes), episodes))
            next_eval += every
    return points


class _Remembered(SubgoalEnv):
    """The env keeping its last observation: SB3's policy reads the achieved goal too, the trainer's rollouts hand an
    actor only the observation and the desired goal."""

    def reset(self, **kwargs):
        self.last, info = super().reset(**kwargs)
        return self.last, info

    def step(self, action):
        result = super().step(action)
        self.last = result[0]
        return result


def sb3_curve(env_name: str, steps: int, every: int, episodes: int, warmup: int) -> list[dict]:
    """SB3's SAC + HER on our ``env_name`` scene, evaluated as :func:`ours_curve` evaluates ours."""
    from semgoal_bench.policy import sb3_model
    from semgoal_policy.evaluate import EVAL_SEED_BASE, success_by_kind

    model = sb3_model(SubgoalEnv(env_name), keep_infos=True, warmup=warmup)
    envs = [_Remembered(env_name) for _ in range(EVAL_ENVS)]

    def act(obs: np.ndarray, goal: np.ndarray) -> np.ndarray:
        achieved = np.stack([env.last["achieved_goal"] for env in envs[:len(obs)]])
        return model.predict({"observation": obs, "achieved_goal": achieved, "desired_goal": goal}, deterministic=True)[0]

    points = []
    while model.num_timesteps < steps:
        model.learn(total_timesteps=min(every, steps - model.num_timesteps), reset_num_timesteps=False)
        points.append(learning_point(model.num_timesteps, success_by_kind(envs, act, _kinds(), episodes, EVAL_SEED_BASE),
                             episodes))
    return points


def curve(config: str, steps: int, every: int, episodes: int, warmup: int) -> list[dict]:
    kind, _, arg = config.partition(":")
    learn = ours_curve if kind == "ours" else sb3_curve
    return learn(arg, steps, every, episodes, warmup)


def compare(steps: int, every: int, episodes: int, warmup: int, figure: Path | None, out) -> dict:
    """Both learners at once, each in its own ``python -O`` process on one torch thread; their curves side by side."""
    workers = {config: subprocess.Popen(
        [sys.executable, "-O", "-m", "semgoal_bench.policy", "--worker", f"learning:{config}", "--steps", str(steps),
         "--warmup", str(warmup), "--eval-every", str(every), "--eval-episodes", str(episodes)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for config in LEARNERS}
    curves = {}
    for config, worker in workers.items():
        stdout, stderr = worker.communicate()
        if worker.returncode != 0:
            raise RuntimeError(f"learning worker {config} failed:\n{stderr[-2000:]}")
        curves[config] = json.loads(stdout.strip().splitlines()[-1])
    for config, points in curves.items():
        for point in points:
            low, high = point["wilson_95"]
            rates = " ".join(f"{kind} {rate:.2f}" for kind, rate in point["success"].items())
            print(f"{config:24s} {point['env_steps']:7d} steps: {point['overall']:.3f} [{low:.3f}, {high:.3f}]  {rates}",
                  file=out)
    if figure is not None:
        _plot(curves, figure)
    return {"scene": SCENE, "episodes_per_kind": episodes, "seed": 0, "curves": curves}


def _plot(curves: dict[str, list[dict]], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 3.6))
    for config, points in curves.items():
        x = [p["env_steps"] for p in points]
        ax.plot(x, [p["overall"] for p in points], marker="o", label=config)
        ax.fill_between(x, [p["wilson_95"][0] for p in points], [p["wilson_95"][1] for p in points], alpha=0.2)
    ax.set(xlabel="env steps", ylabel="success at rest (all sub-goal types)", ylim=(0, 1),
           title=f"{SCENE}: one update per env step, seed 0")
    ax.legend(loc="lower right")
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=120)
    plt.close(fig)
