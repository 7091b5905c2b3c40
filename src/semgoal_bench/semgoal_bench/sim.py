"""`./semgoal bench sim [--json]`: env steps/s per scene, beside gymnasium-robotics' FetchPickAndPlace-v4
(the same random actions, one process each; the median of the repeats), and per scene what the env's own work
costs: the same actions through ``FetchWorld.step`` alone, and through ``mj_step`` with the world's substeps
alone (``env_over_world``, ``world_over_physics``: 1.0 is free)."""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np


def main(argv: list[str]) -> int:
    """`./semgoal bench-sim [--json]`: env steps/s per scene, beside gymnasium-robotics' FetchPickAndPlace-v4."""
    parser = argparse.ArgumentParser(prog="semgoal bench sim", description=main.__doc__)
    parser.add_argument("--steps", type=int, default=2000)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)
    import mujoco

    from semgoal_sim.env import SubgoalEnv
    from semgoal_sim.world import N_SUBSTEPS

    rng = np.random.default_rng(0)
    actions = rng.uniform(-1, 1, size=(args.steps, 4)).astype(np.float32)
    rows, world_rows, physics_rows = {}, {}, {}
    for label, scene, blocks in (("two_blocks", "two_blocks", None), ("three_blocks", "three_blocks", None),
                                 ("desk_cleanup_4", "desk_cleanup", 4)):
        env = SubgoalEnv(scene, n_blocks=blocks, max_steps=10**9)
        world = env.world
        reset = lambda env=env: env.reset(seed=1)  # noqa: E731
        rows[label] = _steps_per_second(lambda i, env=env: env.step(actions[i]), reset, args.steps, args.repeats)
        world_rows[label] = _steps_per_second(lambda i, world=world: world.step(actions[i]), reset, args.steps,
                                              args.repeats)
        physics_rows[label] = _steps_per_second(
            lambda i, world=world: mujoco.mj_step(world.model, world.data, nstep=N_SUBSTEPS), reset, args.steps,
            args.repeats)
    reference = _reference_rate(args.steps, args.repeats)
    if reference is not None:
        rows["reference:FetchPickAndPlace-v4"] = reference
    result = {"unit": "env steps/s (median of repeats, one process, random actions)",
              "steps_per_second": {k: round(v, 1) for k, v in rows.items()},
              "world_steps_per_second": {k: round(v, 1) for k, v in world_rows.items()},
              "physics_steps_per_second": {k: round(v, 1) for k, v in physics_rows.items()},
              "env_over_world": {k: round(rows[k] / world_rows[k], 3) for k in world_rows},
              "world_over_physics": {k: round(world_rows[k] / physics_rows[k], 3) for k in world_rows}}
    if reference is not None:
        result["ratio_to_reference"] = {k: round(v / reference, 2) for k, v in rows.items() if not k.startswith("ref")}
    out = sys.stderr if args.json else sys.stdout
    for name, rate in result["steps_per_second"].items():
        detail = (f"   (FetchWorld.step {world_rows[name]:7.1f}, mj_step x {N_SUBSTEPS} {physics_rows[name]:7.1f})"
                  if name in world_rows else "")
        print(f"{name:34s} {rate:8.1f} steps/s{detail}", file=out)
    if args.json:
        sys.stderr.flush()
        print(json.dumps(result))
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


def _reference_rate(steps: int, repeats: int) -> float | None:
    """gymnasium-robotics' FetchPickAndPlace-v4 (runners/fetch_reference.py), or None when it cannot run."""
    runner = Path(__file__).resolve().parent / "runners" / "fetch_reference.py"
    result = subprocess.run([sys.executable, "-O", str(runner), str(steps), str(repeats)], capture_output=True, text=True)
    if result.returncode != 0:
        print(f"reference env unavailable: {result.stderr.strip().splitlines()[-1:]}", file=sys.stderr)
        return None
    return float(result.stdout.strip().splitlines()[-1])
