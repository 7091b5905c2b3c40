"""`./semgoal eval-goals --scene S [--families F,G] --episodes N --seed S [--jobs J] [--via-ros] [--json]`: the
hierarchical agent on goal families beyond the benchmark (:mod:`semgoal_core.goal_families`), in process, by the
executive's at-rest rule: per family the success rate with its 95 % Wilson interval, mean steps and re-plans; the
last line is one JSON object ``{"<scene>/<family>": rate, ..., "overall": rate}``.

``--via-ros`` also runs a sample of the same cases (``--ros-episodes`` per scene, spread over the families: the
first cases of each) through the node graph, each from its very start (``ResetWorld`` with the positions), and
says how many episodes end as they did in process (on stderr, and as a JSON object there)."""

from __future__ import annotations

import argparse
import itertools
import json
import statistics
import sys
from pathlib import Path

from semgoal_bringup.evaluation import wilson_interval
from semgoal_bringup.executors import check_executor, run_jobs
from semgoal_core import tasks
from semgoal_core.goal_families import FAMILIES, GoalCase, goal_cases
from semgoal_core.vocabulary import SCENES

DEFAULT_SEED = 6_000_000
"""Goal seeds from here: never used in training (training draws below 1e6, task evaluation from 3e6)."""


def run_family(scene: str, family: str, episodes: int, seed: int, model_dir: Path | None = None
               ) -> list[tuple[str, bool, int, int]]:
    """(goal, success, steps, re-plans) of each episode of one family (one job); ``model_dir``: an exported
    actor instead of the shipped one."""
    import torch

    from semgoal_bringup.episodes import make_agent

    torch.set_num_threads(1)
    agent = make_agent("hierarchical", scene, model_dir)
    outcomes = []
    for case in goal_cases(scene, family, episodes, seed):
        outcome = agent.run_goals(case.positions, case.goals, case.seed, label=family)
        outcomes.append((case.text, outcome.success, outcome.steps, outcome.replans))
    return outcomes


def run_via_ros(scene: str, cases: list[GoalCase]) -> list[bool]:
    """Success of each case through the node graph: reset to its start, then its goals one after the other."""
    from semgoal_bringup.graph import running_graph

    def task_for(case: GoalCase) -> str:  # a task of the scene with the case's block count: the sim's world
        return next(name for name in tasks.scene_tasks(scene) if tasks.TASKS[name].n_blocks == len(case.positions))

    successes = []
    with running_graph(task_for(cases[0]), cases[0].seed, client_name="semgoal_eval_goals", watch=False) as client:
        for case in cases:
            client.must_reset(task_for(case), case.seed, positions=case.positions.ravel())
            success = True
            for goal in case.goals:
                success = success and client.execute(goal, max_steps=tasks.TASK_STEP_BUDGET).success
            successes.append(success)
    return successes


def ros_sample(cases: dict[str, list[GoalCase]], episodes: int) -> list[GoalCase]:
    """The first ``episodes`` cases taken in turns from each family (a family's first cases first)."""
    turns = itertools.zip_longest(*cases.values())
    return [case for case in itertools.chain.from_iterable(turns) if case is not None][:episodes]


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="semgoal eval-goals", description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", required=True, choices=list(SCENES))
    parser.add_argument("--families", help="comma-separated (default: all of the scene's): "
                        + "; ".join(f"{scene}: {', '.join(names)}" for scene, names in FAMILIES.items()))
    parser.add_argument("--episodes", type=int, default=50, help="episodes per family")
    parser.add_argument("--seed", type=int, default=DEFAULT_SEED, help="first goal seed (episode i: seed + i)")
    parser.add_argument("--jobs", type=int, default=1, help="families evaluated at once")
    parser.add_argument("--executor", default="local", type=check_executor, help="local, dask or dask:ADDRESS")
    parser.add_argument("--model-dir", type=Path, help="an exported actor (default: the shipped one; in process only)")
    parser.add_argument("--via-ros", action="store_true", help="also run a sample of the cases through the node graph")
    parser.add_argument("--ros-episodes", type=int, default=50, help="with --via-ros: cases run through the graph")
    parser.add_argument("--json", action="store_true", help="only the JSON line on stdout (the table on stderr)")
    args = parser.parse_args(argv)
    families = [f.strip() for f in (args.families or ",".join(FAMILIES[args.scene])).split(",") if f.strip()]
    unknown = [f for f in families if f not in FAMILIES[args.scene]]
    if unknown or args.episodes < 1 or args.ros_episodes < 1:
        parser.error(f"families of {args.scene} are {', '.join(FAMILIES[args.scene])} (got {unknown}); episodes and ros-episodes >= 1")
    if args.model_dir and args.via_ros:
        parser.error("--via-ros runs the shipped actor (the policy node's); leave out --model-dir")
    results = run_jobs(run_family, [(args.scene, f, args.episodes, args.seed, args.model_dir) for f in families], args.executor,
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
    if args.via_ros:
        by_family = {f: goal_cases(args.scene, f, args.episodes, args.seed) for f in families}
        in_process = {(f, case.seed): outcome[1] for f, outcomes in zip(families, results, strict=True)
                      for case, outcome in zip(by_family[f], outcomes, strict=True)}
        sample = ros_sample(by_family, args.ros_episodes)
        graph = run_via_ros(args.scene, sample)
        same = sum(in_process[(case.family, case.seed)] == success for case, success in zip(sample, graph, strict=True))
        for case, success in zip(sample, graph, strict=True):
            if in_process[(case.family, case.seed)] != success:
                print(f"    via ROS {'succeeded' if success else 'failed'}, in process not: {case.text}", file=sys.stderr)
        summary = {"episodes": len(sample), "success": round(sum(graph) / len(sample), 4), "same_as_in_process": same}
        print(f"via ROS: {sum(graph)} of {len(sample)} succeeded; {same} of {len(sample)} ended as in process",
              file=table)
        print(json.dumps({"via_ros": summary}), file=sys.stderr)
    print(json.dumps({**rates, "overall": round(wins_all / n_all, 4)}))
    return 0
