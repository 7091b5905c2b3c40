"""Simulator subcommands of ./semgoal: `expert` (scripted expert on a task) and `bench-sim`."""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time

import numpy as np

from semgoal_core.tasks import TASKS, get_task


def expert_main(argv: list[str]) -> int:
    """`./semgoal expert --task T --episodes N --seed S [--json]`: success rate of the scripted expert."""
    parser = argparse.ArgumentParser(prog="semgoal expert", description=expert_main.__doc__)
    parser.add_argument("--task", required=True, help=f"one of {', '.join(TASKS)}, or 'all'")
    parser.add_argument("--episodes", type=int, default=100)
    parser.add_argument("--seed", type=int, default=0, help="episode i uses seed S + i")
    parser.add_argument("--json", action="store_true", help="last line: one JSON object")
    args = parser.parse_args(argv)
    from semgoal_sim.rollout import run_task

    names = list(TASKS) if args.task == "all" else [args.task]
    try:
        names = [get_task(name).name for name in names]
    except KeyError as error:
        parser.error(str(error.args[0]))
    results = {}
    for name in names:
        start = time.perf_counter()
        episodes = [run_task(name, args.seed + i) for i in range(args.episodes)]
        results[name] = {
            "task": name,
            "episodes": args.episodes,
            "seed": args.seed,
            "success_rate": sum(e.success for e in episodes) / args.episodes,
            "mean_steps": statistics.fmean(e.steps for e in episodes),
            "mean_subgoals": statistics.fmean(e.subgoals for e in episodes),
            "failed_seeds": [args.seed + i for i, e in enumerate(episodes) if not e.success],
            "wall_s": round(time.perf_counter() - start, 2),
        }
        if not args.json or len(names) > 1:
            r = results[name]
            print(f"{name:7s} success {r['success_rate']:6.1%}  mean steps {r['mean_steps']:6.1f}  "
                  f"sub-goals {r['mean_subgoals']:4.1f}  ({r['wall_s']} s)", file=sys.stderr if args.json else sys.stdout)
    if args.json:
        print(json.dumps(results[names[0]] if len(names) == 1 else results))
    return 0


def _steps_per_second(step, reset, steps: int, repeats: int) -> float:
    rates = []
    for _ in range(repeats):
        reset()
        start = time.perf_counter()
        for i in range(steps):
            step(i)
        rates.append(steps / (time.perf_counter() - start))
    return statistics.median(rates)


def bench_sim_main(argv: list[str]) -> int:
    """`./semgoal bench-sim [--json]`: env steps/s per scene, beside gymnasium-robotics' FetchPickAndPlace-v4."""
    parser = argparse.ArgumentParser(prog="semgoal bench-sim", description=bench_sim_main.__doc__)
    parser.add_argument("--steps", type=int, default=2000)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)
    from semgoal_sim.env import SubgoalEnv

    rng = np.random.default_rng(0)
    actions = rng.uniform(-1, 1, size=(args.steps, 4)).astype(np.float32)
    rows = {}
    for label, scene, blocks in (("two_blocks", "two_blocks", None), ("three_blocks", "three_blocks", None),
                                 ("desk_cleanup_4", "desk_cleanup", 4)):
        env = SubgoalEnv(scene, n_blocks=blocks, max_steps=10**9)
        rows[label] = _steps_per_second(lambda i, env=env: env.step(actions[i]), lambda env=env: env.reset(seed=1),
                                        args.steps, args.repeats)
    reference = _reference_rate(actions, args.steps, args.repeats)
    if reference is not None:
        rows["reference:FetchPickAndPlace-v4"] = reference
    result = {"unit": "env steps/s (median of repeats, one process, random actions)",
              "steps_per_second": {k: round(v, 1) for k, v in rows.items()}}
    if reference is not None:
        result["ratio_to_reference"] = {k: round(v / reference, 2) for k, v in rows.items() if not k.startswith("ref")}
    for name, rate in result["steps_per_second"].items():
        print(f"{name:34s} {rate:8.1f} steps/s", file=sys.stderr if args.json else sys.stdout)
    if args.json:
        sys.stderr.flush()
        print(json.dumps(result))
    return 0


def _reference_rate(actions: np.ndarray, steps: int, repeats: int) -> float | None:
    """gymnasium-robotics' FetchPickAndPlace-v4, in a child `python -O` (its asserts fail on mujoco >= 3.12)."""
    import subprocess

    code = f"""
import time, statistics, numpy as np, gymnasium as gym, gymnasium_robotics
gym.register_envs(gymnasium_robotics)
env = gym.make("FetchPickAndPlace-v4", max_episode_steps=10**9)
actions = np.random.default_rng(0).uniform(-1, 1, size=({steps}, 4)).astype(np.float32)
rates = []
for _ in range({repeats}):
    env.reset(seed=1)
    t = time.perf_counter()
    for a in actions:
        env.step(a)
    rates.append({steps} / (time.perf_counter() - t))
print(statistics.median(rates))
"""
    result = subprocess.run([sys.executable, "-O", "-c", code], capture_output=True, text=True)
    if result.returncode != 0:
        print(f"reference env unavailable: {result.stderr.strip().splitlines()[-1:]}", file=sys.stderr)
        return None
    return float(result.stdout.strip().splitlines()[-1])
