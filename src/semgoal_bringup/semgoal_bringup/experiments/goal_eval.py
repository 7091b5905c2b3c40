"""`./semgoal eval goals --scene S [--families F,G] --episodes N --seed S [--jobs J] [--via-ros] [--json]`: the
hierarchical agent on goal families beyond the benchmark (:mod:`semgoal_core.goal_families`), in process, by the
executive's at-rest rule: per family the success rate with its 95 % Wilson interval, mean steps and re-plans; the
last line is one JSON object ``{"<scene>/<family>": rate, ..., "overall": rate, "fell_off": {family: share},
"linger_holds": {family: share}}`` (``linger_holds`` with ``--linger N``: of the successes, the share whose goal
still held at rest N control steps later, the idle arm running).

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

from semgoal_bringup.experiments.episodes import Outcome
from semgoal_bringup.experiments.evaluation import wilson_interval
from semgoal_bringup.experiments.executors import check_executor, run_jobs
from semgoal_bringup.graph import TRUTH, Sight, add_sight_arguments, running_graph, sight_of
from semgoal_core import tasks
from semgoal_core.arguments import count, names, natural
from semgoal_core.goal_families import FAMILIES, GoalCase, goal_cases
from semgoal_core.vocabulary import SCENES

DEFAULT_SEED = 6_000_000
"""Goal seeds from here: never used in training (training draws below 1e6, task evaluation from 3e6)."""


def run_family(scene: str, family: str, episodes: int, seed: int, model_dir: Path | None = None, linger: int = 0
               ) -> list[Outcome]:
    """The outcome of each episode of one family (one job, ``task``: the goal as said); ``model_dir``: an exported
    actor instead of the shipped one; ``linger``: control steps after a success before the goal is checked again."""
    import torch

    from semgoal_bringup.experiments.episodes import make_agent

    torch.set_num_threads(1)
    agent = make_agent("hierarchical", scene, model_dir)
    outcomes = []
    for case in goal_cases(scene, family, episodes, seed):
        outcomes.append(agent.run_goals(case.positions, case.goals, case.seed, label=case.text, linger=linger))
    return outcomes


def run_via_ros(scene: str, cases: list[GoalCase], sight: Sight = TRUTH) -> list[bool]:
    """Success of each case through the node graph (seeing by ``sight``): reset to its start, then its goals one
    after the other."""
    def task_for(case: GoalCase) -> str:  # a task of the scene with the case's block count: the sim's world
        return next(name for name in tasks.scene_tasks(scene) if tasks.TASKS[name].n_blocks == len(case.positions))

    successes = []
    with running_graph(task_for(cases[0]), cases[0].seed, client_name="semgoal_eval_goals", watch=False,
                       sight=sight) as client:
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
    parser = argparse.ArgumentParser(prog="semgoal eval goals", description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", required=True, choices=list(SCENES))
    parser.add_argument("--families", type=names, help="comma-separated (default: all of the scene's): "
                        + "; ".join(f"{scene}: {', '.join(names)}" for scene, names in FAMILIES.items()))
    parser.add_argument("--episodes", type=count, default=50, help="episodes per family")
    parser.add_argument("--seed", type=natural, default=DEFAULT_SEED, help="first goal seed (episode i: seed + i)")
    parser.add_argument("--jobs", type=count, default=1, help="families evaluated at once")
    parser.add_argument("--executor", default="local", type=check_executor, help="local, dask or dask:ADDRESS")
    parser.add_argument("--model-dir", type=Path, help="an exported actor (default: the shipped one; in process only)")
    parser.add_argument("--via-ros", action="store_true", help="also run a sample of the cases through the node graph")
    parser.add_argument("--ros-episodes", type=count, default=50, help="with --via-ros: cases run through the graph")
    parser.add_argument("--linger", type=natural, default=0, help="after each success, this many control steps of the idle "
                        "arm, then whether the goal still holds at rest (in process)")
    parser.add_argument("--json", action="store_true", help="only the JSON line on stdout (the table on stderr)")
    add_sight_arguments(parser)
    args = parser.parse_args(argv)
    sight = sight_of(args, parser, tasks.scene_tasks(args.scene)[:1])
    if sight != TRUTH and not args.via_ros:
        parser.error("--perception / --policy-input camera run through the graph: add --via-ros")
    families = args.families or list(FAMILIES[args.scene])
    unknown = [f for f in families if f not in FAMILIES[args.scene]]
    if unknown:
        parser.error(f"families of {args.scene} are {', '.join(FAMILIES[args.scene])} (got {unknown})")
    if args.model_dir and args.via_ros:
        parser.error("--via-ros runs the shipped actor (the policy node's); leave out --model-dir")
    results = run_jobs(run_family, [(args.scene, f, args.episodes, args.seed, args.model_dir, args.linger)
                                    for f in families], args.executor, args.jobs, what="family")
    table = sys.stderr if args.json else sys.stdout
    rates, lingering, fell_off, wins_all, n_all = {}, {}, {}, 0, 0
    for family, outcomes in zip(families, results, strict=True):
        name, wins, n = f"{args.scene}/{family}", sum(o.success for o in outcomes), len(outcomes)
        low, high = wilson_interval(wins, n)
        checked = [o.linger_holds for o in outcomes if o.linger_holds is not None]
        fell_off[name] = round(sum(o.fell_off for o in outcomes) / n, 4)
        after = ""
        if checked:
            lingering[name] = round(sum(checked) / len(checked), 4)
            after = f"   holds {args.linger} steps on {100 * lingering[name]:5.1f} %"
        print(f"{name:28s} {100 * wins / n:5.1f} % [{100 * low:.0f}-{100 * high:.0f}] of {n}   "
              f"mean steps {statistics.fmean(o.steps for o in outcomes):6.1f}   re-plans "
              f"{statistics.fmean(o.replans for o in outcomes):.2f}{after}   fell off {100 * fell_off[name]:.1f} %",
              file=table)
        for o in outcomes:
            if not o.success or o.linger_holds is False:
                why = "failed" if not o.success else f"no longer held {args.linger} steps on"
                print(f"    {why}: {o.task} ({o.steps} steps{', a block fell off' if o.fell_off else ''})", file=table)
        rates[name] = round(wins / n, 4)
        wins_all, n_all = wins_all + wins, n_all + n
    if args.via_ros:
        by_family = {f: goal_cases(args.scene, f, args.episodes, args.seed) for f in families}
        in_process = {(f, case.seed): outcome.success for f, outcomes in zip(families, results, strict=True)
                      for case, outcome in zip(by_family[f], outcomes, strict=True)}
        sample = ros_sample(by_family, args.ros_episodes)
        graph = run_via_ros(args.scene, sample, sight)
        same = sum(in_process[(case.family, case.seed)] == success for case, success in zip(sample, graph, strict=True))
        for case, success in zip(sample, graph, strict=True):
            if in_process[(case.family, case.seed)] != success:
                print(f"    via ROS {'succeeded' if success else 'failed'}, in process not: {case.text}", file=sys.stderr)
        summary = {"episodes": len(sample), "success": round(sum(graph) / len(sample), 4), "same_as_in_process": same}
        print(f"via ROS: {sum(graph)} of {len(sample)} succeeded; {same} of {len(sample)} ended as in process",
              file=table)
        print(json.dumps({"via_ros": summary}), file=sys.stderr)
    print(json.dumps({**rates, "overall": round(wins_all / n_all, 4), "fell_off": fell_off,
                      **({"linger_holds": lingering} if args.linger else {})}))
    return 0
