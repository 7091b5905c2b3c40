"""`./semgoal eval arms --task DC-4 --episodes 50 [--seed S] [--jobs J] [--executor E] [--json]`: one arm, then two arms
(a second Fetch across the table, :mod:`semgoal_core.arms`), on the same starts, in process, by the executive's
at-rest rule.

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
from semgoal_bringup.experiments.together import check_paired, paired_parser, print_summary, summary
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
    args = parser.parse_args(argv)
    check_paired(parser, args)
    pairs = run_jobs(run_start, [(args.task, args.seed + i, args.models) for i in range(args.episodes)], args.executor,
                     args.jobs, what="start")
    touched = [two.arm_contacts for _, two in pairs]
    result = {"task": args.task, "actor": args.models or "shipped", **summary(pairs, MODES),
              "starts_with_contact": sum(c > 0 for c in touched), "contact_substeps": sum(touched)}
    if not args.json:
        print_summary(result, MODES)
        print(f"arm-to-arm contact on {result['starts_with_contact']} of {len(pairs)} starts "
              f"({result['contact_substeps']} physics substeps)")
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
