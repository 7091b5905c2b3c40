"""`./semgoal bench eval [--episodes N] [--json]`: in-process evaluation episodes per second on the local pool
and on a Dask LocalCluster, with 1 and 2 workers, on the same jobs (the hierarchical agent on MA-2 and DC-2,
chunks of 2 episodes): what Dask costs on one host. Each configuration starts its own workers (the spawn and
the actors' loading count, as they do in a real evaluation)."""

from __future__ import annotations

import argparse
import json
import time

from semgoal_bringup.experiments.evaluation import evaluate_in_process
from semgoal_core.arguments import count
from semgoal_policy.actor import models_dir

TASKS, SEED, CHUNK = ["MA-2", "DC-2"], 3_000_000, 2


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="semgoal bench eval", description=__doc__.split("\n\n")[0])
    parser.add_argument("--episodes", type=count, default=8, help="episodes per task")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)
    results = []
    for executor in ("local", "dask"):
        for workers in (1, 2):
            started = time.perf_counter()
            rows = evaluate_in_process(["hierarchical"], TASKS, args.episodes, SEED, 1, models_dir(), workers, executor, CHUNK)
            wall = time.perf_counter() - started
            episodes = sum(row.episodes(task) for row in rows for task in TASKS)
            results.append({"executor": executor, "workers": workers, "episodes": episodes, "wall_s": round(wall, 2),
                            "episodes_per_s": round(episodes / wall, 2)})
            print(f"{executor:6s} {workers} worker(s): {episodes} episodes in {wall:6.1f} s = {episodes / wall:5.2f} /s",
                  flush=True)
    if args.json:
        print(json.dumps(results))
    return 0
