"""`./semgoal bench sim [--json]`: env steps/s per scene, beside gymnasium-robotics' FetchPickAndPlace-v4
(the same random actions, one process each; the median of the repeats; the reference run before each scene and after
the last, its median kept), and per scene what the env's own work
costs: the same actions through ``FetchWorld.step`` alone, and through ``mj_step`` with the world's substeps
alone (``env_over_world``, ``world_over_physics``: 1.0 is free), and the env with every body awake (as the shipped
actors were trained: MuJoCo's sleeping islands off). Last, the desk's worlds stepped in a batch
(:class:`~semgoal_sim.batch.WorldBatch`) on one thread and on a thread per core: ``batch_over_one_core``."""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from semgoal_core.arguments import count

BATCH_WORLDS = 8
CHUNK = 50
"""Steps each way of stepping takes before the next has its turn."""


def main(argv: list[str]) -> int:
    """`./semgoal bench-sim [--json]`: env steps/s per scene, beside gymnasium-robotics' FetchPickAndPlace-v4."""
    parser = argparse.ArgumentParser(prog="semgoal bench sim", description=main.__doc__)
    parser.add_argument("--steps", type=count, default=2000)
    parser.add_argument("--repeats", type=count, default=5)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)
    import mujoco

    from semgoal_sim.env import SubgoalEnv
    from semgoal_sim.world import N_SUBSTEPS

    rng = np.random.default_rng(0)
    actions = rng.uniform(-1, 1, size=(args.steps, 4)).astype(np.float32)
    rows, world_rows, physics_rows, awake_rows = {}, {}, {}, {}
    references = [_reference_rate(args.steps, args.repeats)]  # one before each scene and one after: the machine's
    # speed drifts, so the reference is measured across the same minutes as ours
    for label, scene, blocks in (("two_blocks", "two_blocks", None), ("three_blocks", "three_blocks", None),
                                 ("desk_cleanup_4", "desk_cleanup", 4)):
        env = SubgoalEnv(scene, n_blocks=blocks, max_steps=10**9)
        awake = SubgoalEnv(scene, n_blocks=blocks, max_steps=10**9, sleep=False)
        world = env.world
        reset = lambda env=env, awake=awake: (env.reset(seed=1), awake.reset(seed=1))  # noqa: E731
        rows[label], world_rows[label], physics_rows[label], awake_rows[label] = _interleaved(
            [lambda i, env=env: env.step(actions[i]), lambda i, world=world: world.step(actions[i]),
             lambda i, world=world: mujoco.mj_step(world.model, world.data, nstep=N_SUBSTEPS),
             lambda i, env=awake: env.step(actions[i])],
            reset, args.steps, args.repeats)
        references.append(_reference_rate(args.steps, args.repeats))
    batched = _batch_rates(actions, args.repeats)
    measured = [rate for rate in references if rate is not None]
    reference = statistics.median(measured) if measured else None
    if reference is not None:
        rows["reference:FetchPickAndPlace-v4"] = reference
    result = {"unit": "env steps/s (over the repeats, each way of stepping taking turns every 50 steps; one process, "
                      "random actions)",
              "steps_per_second": {k: round(v, 1) for k, v in rows.items()},
              "world_steps_per_second": {k: round(v, 1) for k, v in world_rows.items()},
              "physics_steps_per_second": {k: round(v, 1) for k, v in physics_rows.items()},
              "awake_steps_per_second": {k: round(v, 1) for k, v in awake_rows.items()},
              "env_over_world": {k: round(rows[k] / world_rows[k], 3) for k in world_rows},
              "world_over_physics": {k: round(world_rows[k] / physics_rows[k], 3) for k in world_rows},
              "batch_steps_per_second": {str(threads): round(rate, 1) for threads, rate in batched.items()},
              "batch_over_one_core": round(batched[max(batched)] / batched[1], 3),
              "reference_runs": [None if rate is None else round(rate, 1) for rate in references]}
    if reference is not None:
        result["ratio_to_reference"] = {k: round(v / reference, 2) for k, v in rows.items() if not k.startswith("ref")}
        # what an env with no work of its own beside the physics would reach: the scene's physics is the bound
        result["physics_ratio_to_reference"] = {k: round(v / reference, 2) for k, v in physics_rows.items()}
        # the env with every body awake, as the shipped actors were trained
        result["awake_ratio_to_reference"] = {k: round(v / reference, 2) for k, v in awake_rows.items()}
    out = sys.stderr if args.json else sys.stdout
    for name, rate in result["steps_per_second"].items():
        detail = (f"   (FetchWorld.step {world_rows[name]:7.1f}, mj_step x {N_SUBSTEPS} {physics_rows[name]:7.1f})"
                  if name in world_rows else "")
        print(f"{name:34s} {rate:8.1f} steps/s{detail}", file=out)
    if reference is not None:
        print("ratio to the reference, the env's / its physics alone's: " + ", ".join(
            f"{k} {result['ratio_to_reference'][k]} / {result['physics_ratio_to_reference'][k]}" for k in physics_rows),
            file=out)
        print("with every body awake (SubgoalEnv(sleep=False)): " + ", ".join(
            f"{k} {rate:.1f} steps/s ({result['awake_ratio_to_reference'][k]}x)" for k, rate in awake_rows.items()),
            file=out)
    print(f"desk_cleanup_4 x {BATCH_WORLDS} worlds in a batch: " + ", ".join(
        f"{threads} thread(s) {rate:7.1f} world steps/s" for threads, rate in batched.items())
        + f"  ({result['batch_over_one_core']}x one core)", file=out)
    if args.json:
        sys.stderr.flush()
        print(json.dumps(result))
    return 0


def _batch_rates(actions: np.ndarray, repeats: int) -> dict[int, float]:
    """World steps/s of :data:`BATCH_WORLDS` desk worlds stepped together, on one thread and on one per core."""
    import os

    from semgoal_core.tasks import get_task
    from semgoal_sim.batch import WorldBatch
    from semgoal_sim.world import FetchWorld

    worlds = [FetchWorld("desk_cleanup", 4) for _ in range(BATCH_WORLDS)]
    starts = [get_task("DC-4").initial_state(seed)[0] for seed in range(BATCH_WORLDS)]
    steps = max(1, len(actions) // BATCH_WORLDS)
    batch_actions = actions[: steps * BATCH_WORLDS].reshape(steps, BATCH_WORLDS, 4)
    def reset() -> None:
        for world, start in zip(worlds, starts, strict=True):
            world.reset(start)

    batches = [WorldBatch(worlds, threads) for threads in sorted({1, os.cpu_count() or 1})]
    try:
        rates = _interleaved([lambda i, b=batch: b.step(batch_actions[i]) for batch in batches], reset, steps, repeats)
    finally:
        for batch in batches:
            batch.close()
    return {batch.threads: BATCH_WORLDS * rate for batch, rate in zip(batches, rates, strict=True)}


def _interleaved(steppers: list, reset, steps: int, repeats: int) -> list[float]:
    """Steps/s of each of ``steppers`` (each called with the step's number) over ``repeats`` runs of ``steps``: they
    take turns every :data:`CHUNK` steps, so that a machine whose speed drifts (this one's does, within seconds)
    weighs on each alike."""
    spent = [0.0] * len(steppers)
    for _ in range(repeats):
        reset()
        for first in range(0, steps, CHUNK):
            for k, step in enumerate(steppers):
                start = time.perf_counter()
                for i in range(first, min(first + CHUNK, steps)):
                    step(i)
                spent[k] += time.perf_counter() - start
    return [steps * repeats / seconds for seconds in spent]


def _reference_rate(steps: int, repeats: int) -> float | None:
    """gymnasium-robotics' FetchPickAndPlace-v4 (runners/fetch_reference.py), or None when it cannot run."""
    runner = Path(__file__).resolve().parent / "runners" / "fetch_reference.py"
    result = subprocess.run([sys.executable, "-O", str(runner), str(steps), str(repeats)], capture_output=True, text=True)
    if result.returncode != 0:
        print(f"reference env unavailable: {result.stderr.strip().splitlines()[-1:]}", file=sys.stderr)
        return None
    return float(result.stdout.strip().splitlines()[-1])
