"""`./semgoal eval arms --task DC-4 --episodes 50 [--seed S] [--jobs J] [--executor E] [--json]`: one arm, then two arms
(a second Fetch across the table, :mod:`semgoal_core.arms`), on the same starts, in process, by the executive's
at-rest rule. `--via-ros [--ros-episodes N] [--perception camera] [--policy-input camera]`: then the first N starts
with two arms through the node graph in lockstep (``robots`` 2), seeing by the simulator's poses (each start that
does not end as in process is named) or by the camera.

With two arms each robot step goes to the free arm on its block's side of the table (the other one takes it only near
the centre line), each arm works its own steps at once, and the sim's separation guard keeps the arms apart. Per mode:
success at rest with its 95 % Wilson interval and the median control steps; then the ratio of the medians, the median
of each start's ratio and the control steps both arms worked at once; then the starts on which the two arms touched
and the physics substeps they touched for (a touch is a failure of the guard). The last line is one JSON object of
the same."""

from __future__ import annotations

import json
import sys
from pathlib import Path

from semgoal_bringup.experiments.episodes import Outcome
from semgoal_bringup.experiments.executors import run_jobs
from semgoal_bringup.experiments.together import check_paired, mode_summary, paired_parser, print_summary, summary
from semgoal_bringup.graph import TRUTH, Sight, add_sight_arguments, sight_of
from semgoal_core.arguments import count
from semgoal_core.tasks import get_task
from semgoal_policy.expert_actor import EXPERT

MODES = ("one_arm", "two_arms")


def run_start(task: str, seed: int, models: str = "") -> tuple[Outcome, Outcome]:
    """One start with one arm and with two (one job); ``models``: ``expert`` for the scripted expert as the actor."""
    import torch

    from semgoal_bringup.experiments.episodes import make_agent

    torch.set_num_threads(1)
    spec = get_task(task)
    positions = spec.initial_state(seed)[0]
    actor = Path(models) if models else None
    return tuple(make_agent("hierarchical", spec.scene, actor, arms=arms).run_goals(positions, (spec.name,), seed,
                                                                                   label=spec.name)
                 for arms in (1, 2))


def main(argv: list[str]) -> int:
    parser = paired_parser("semgoal eval arms", __doc__)
    parser.add_argument("--models", default="", choices=("", EXPERT),
                        help="expert: the scripted expert, the actors' teacher, drives both arms")
    parser.add_argument("--via-ros", action="store_true", help="also run starts with two arms through the node graph")
    parser.add_argument("--ros-episodes", type=count, help="with --via-ros: the first N starts (default: --episodes)")
    add_sight_arguments(parser)
    args = parser.parse_args(argv)
    check_paired(parser, args)
    sight = sight_of(args, parser, [args.task])
    if (sight != TRUTH or args.ros_episodes) and not args.via_ros:
        parser.error("--ros-episodes, --perception and --policy-input run through the graph: add --via-ros")
    pairs = run_jobs(run_start, [(args.task, args.seed + i, args.models) for i in range(args.episodes)], args.executor,
                     args.jobs, what="start")
    touched = [two.arm_contacts for _, two in pairs]
    result = {"task": args.task, "actor": args.models or "shipped", **summary(pairs, MODES),
              "starts_with_contact": sum(c > 0 for c in touched), "contact_substeps": sum(touched)}
    if args.via_ros:
        result["two_arms_via_ros"] = via_ros(args, sight, [two for _, two in pairs])
    if not args.json:
        print_summary(result, MODES)
        print(f"arm-to-arm contact on {result['starts_with_contact']} of {len(pairs)} starts "
              f"({result['contact_substeps']} physics substeps)")
        if args.via_ros:
            graph = result["two_arms_via_ros"]
            print(f"two arms via ROS ({graph['sees_by']}): success {graph['success']:.1%} {graph['interval']}, median "
                  f"steps {graph['median_steps']}, re-plans {graph['replans']}")
    print(json.dumps(result))
    return 0


def via_ros(args, sight: Sight, in_process: list[Outcome]) -> dict:
    """The first ``--ros-episodes`` starts with two arms through the graph; seeing by the simulator's poses, the
    starts that do not end as in process (success, steps and re-plans), each named on stderr."""
    from semgoal_bringup.experiments.graph_eval import run_via_ros

    episodes = min(args.ros_episodes or args.episodes, args.episodes)
    outcomes = list(run_via_ros([args.task], episodes, args.seed, args.models, sight=sight, robots=2))
    row = {"sees_by": f"planner {sight.perception}, policy {sight.policy_input}", "episodes": len(outcomes),
           **mode_summary(outcomes), "replans": sum(o.replans for o in outcomes),
           "missed": [o.seed for o in outcomes if not o.success]}
    for outcome in outcomes:
        if not outcome.success:
            print(f"start {outcome.seed}: missed through the graph, after {outcome.steps} steps", file=sys.stderr)
    if sight == TRUTH:
        differ = [(o, p) for o, p in zip(outcomes, in_process, strict=False)
                  if (o.success, o.steps, o.replans) != (p.success, p.steps, p.replans)]
        for graph, process in differ:
            print(f"start {graph.seed}: through the graph {graph.success} in {graph.steps} steps ({graph.replans} "
                  f"re-plans), in process {process.success} in {process.steps} ({process.replans})", file=sys.stderr)
        row["as_in_process"] = len(outcomes) - len(differ)
    return row


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
