"""Simulator subcommand of ./semgoal: `expert` (the scripted expert on a task)."""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time

from semgoal_core.arguments import count, natural
from semgoal_core.tasks import ALL_TASKS, TASKS, get_task


def expert_main(argv: list[str]) -> int:
    """`./semgoal expert --task T --episodes N --seed S [--json]`: success rate of the scripted expert."""
    parser = argparse.ArgumentParser(prog="semgoal expert", description=expert_main.__doc__)
    parser.add_argument("--task", required=True, help=f"one of {', '.join(ALL_TASKS)}, or 'all' (the paper's)")
    parser.add_argument("--episodes", type=count, default=100)
    parser.add_argument("--seed", type=natural, default=0, help="episode i uses seed S + i")
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
