"""`./semgoal eval-goals --scene S [--families F,G] --episodes N --seed S [--jobs J] [--json]`: the hierarchical
agent on goal families beyond the benchmark (:mod:`semgoal_core.goal_families`), in process, by the executive's
at-rest rule: per family the success rate with its 95 % Wilson interval, mean steps and re-plans; the last line
is one JSON object ``{"<scene>/<family>": rate, ..., "overall": rate}``."""

from __future__ import annotations

import argparse
import json
import statistics
import sys

from semgoal_bringup.evaluation import wilson_interval
from semgoal_bringup.executors import check_executor, run_jobs
from semgoal_core.goal_families import FAMILIES, goal_cases
from semgoal_core.vocabulary import SCENES

DEFAULT_SEED = 6_000_000
"""Goal seeds from here: never used in training (training draws below 1e6, task evaluation from 3e6)."""


def run_family(scene: str, family: str, episodes: int, seed: int) -> list[tuple[str, bool, int, int]]:
    """(goal, success, steps, re-plans) of each episode of one family (one job)."""
    import torch

    from semgoal_bringup.episodes import make_agent

    torch.set_num_threads(1)
    agent = make_agent("hierarchical", scene)
    outcomes = []
    for case in goal_cases(scene, family, episodes, seed):
        outcome = agent.run_goals(case.positions, case.goals, case.seed, label=family)
        outcomes.append((case.text, outcome.success, outcome.steps, outcome.replans))
    return outcomes


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="semgoal eval-goals", description=__doc__.splitlines()[0])
    parser.add_argument("--scene", required=True, choices=list(SCENES))
    parser.add_argument("--families", help=f"comma-separated (default: all of the scene's); {FAMILIES}")
    parser.add_argument("--episodes", type=int, default=50, help="episodes per family")
    parser.add_argument("--seed", type=int, default=DEFAULT_SEED, help="first goal seed (episode i: seed + i)")
    parser.add_argument("--jobs", type=int, default=1, help="families evaluated at once")
    parser.add_argument("--executor", default="local", type=check_executor, help="local, dask or dask:ADDRESS")
    parser.add_argument("--json", action="store_true", help="only the JSON line on stdout (the table on stderr)")
    args = parser.parse_args(argv)
    families = [f.strip() for f in (args.families or ",".join(FAMILIES[args.scene])).split(",") if f.strip()]
    unknown = [f for f in families if f not in FAMILIES[args.scene]]
    if unknown or args.episodes < 1:
        parser.error(f"families of {args.scene} are {', '.join(FAMILIES[args.scene])} (got {unknown}); episodes >= 1")
    results = run_jobs(run_family, [(args.scene, f, args.episodes, args.seed) for f in families], args.executor,
                       args.jobs, what="family")
    table = sys.stderr if args.json else sys.stdout
    rates, wins_all, n_all = {}, 0, 0
    for family, outcomes in zip(families, results, strict=True):
        wins, n = sum(o[1] for o in outcomes), len(outcomes)
        low, high = wilson_interval(wins, n)
        print(f"{args.scene}/{family:14s} {100 * wins / n:5.1f} % [{100 * low:.0f}-{100 * high:.0f}] of {n}   "
              f"mean steps {statistics.fmean(o[2] for o in outcomes):6.1f}   re-plans "
              f"{statistics.fmean(o[3] for o in outcomes):.2f}", file=table)
        for goal, success, steps, _ in outcomes:
            if not success:
                print(f"    failed: {goal} ({steps} steps)", file=table)
        rates[f"{args.scene}/{family}"] = round(wins / n, 4)
        wins_all, n_all = wins_all + wins, n_all + n
    print(json.dumps({**rates, "overall": round(wins_all / n_all, 4)}))
    return 0
