"""`./semgoal bench sim [--json]`: env steps/s per scene, beside gymnasium-robotics' FetchPickAndPlace-v4
(the same random actions, one process each; the median of the repeats)."""

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
    from semgoal_sim.env import SubgoalEnv

    rng = np.random.default_rng(0)
    actions = rng.uniform(-1, 1, size=(args.steps, 4)).astype(np.float32)
    rows = {}
    for label, scene, blocks in (("two_blocks", "two_blocks", None), ("three_blocks", "three_blocks", None),
                                 ("desk_cleanup_4", "desk_cleanup", 4)):
        env = SubgoalEnv(scene, n_blocks=blocks, max_steps=10**9)
        rows[label] = _steps_per_second(lambda i, env=env: env.step(actions[i]), lambda env=env: env.reset(seed=1),
                                        args.steps, args.repeats)
    reference = _reference_rate(args.steps, args.repeats)
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
