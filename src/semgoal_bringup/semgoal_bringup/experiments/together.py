"""`./semgoal eval together --task DC-4 --episodes 50 [--seed S] [--person-s 3] [--jobs J] [--json]`: the robot and a
scripted person on one plan, in turns and at once, from the same starts (in process, by the executive's at-rest rule).

The person claims whole turns of the plan from its end (:meth:`ScriptedPerson.claim`), takes a person-like
``--person-s`` seconds over each of their steps, then does it through the console's path: the console's place for
the step (:func:`~semgoal_bringup.tools.console_core.step_place`, ``place_position``) and the sim's ``move_block``,
and waits while the robot is at the bin. In turns, one step is active at a time in plan order; at once, the
executive runs each agent's first ready step (``concurrent``). Per mode: success at rest with its 95 % Wilson
interval and the median control steps; then the ratio of the medians, the median of each start's ratio, and the
control steps both worked at once. The last line is one JSON object of the same."""

from __future__ import annotations

import argparse
import json
import statistics
import sys
from dataclasses import dataclass

from semgoal_bringup.experiments.episodes import Outcome
from semgoal_bringup.experiments.evaluation import wilson_interval
from semgoal_bringup.experiments.executors import check_executor, run_jobs
from semgoal_bringup.tools.console_core import place_position, region_taken, step_place
from semgoal_core.arguments import count, natural
from semgoal_core.layout import CONTROL_DT
from semgoal_core.names import Assignee, StepStatus
from semgoal_core.tasks import get_task
from semgoal_planner.executive import Executive, turns_of
from semgoal_sim.sim_core import move_block
from semgoal_sim.world import FetchWorld

DEFAULT_SEED = 3_000_000
"""Task starts from here: the task evaluation's seeds, never used in training."""
ROBOT_TURN_STEPS = 30
"""About the control steps the desk actor takes for one turn (a pick and a put); the person's share of the turns is
sized by it."""


@dataclass
class ScriptedPerson:
    """A person beside the robot: claims turns of the plan and does each of their steps ``step_s`` seconds after it
    started, through the console's path."""

    name: str = Assignee.HUMAN
    step_s: float = 3.0

    @property
    def step_steps(self) -> int:
        return round(self.step_s / CONTROL_DT)

    def claim(self, executive: Executive) -> None:
        """Claim whole turns from the plan's end while their time (one step each: the person's pick is their own) is
        within the robot's for the turns left to it."""
        turns = len(set(turns_of(executive.steps)))
        firsts = [i for i, step in enumerate(executive.steps)
                  if step.subgoal.kind == "pick" and step.status == StepStatus.PENDING]
        for claimed, first in enumerate(reversed(firsts), start=1):
            if claimed * self.step_steps > (turns - claimed) * ROBOT_TURN_STEPS:
                break
            ok, message = executive.edit("claim", first, action=self.name)
            if not ok:
                raise RuntimeError(f"the scripted person's claim of step {first} was refused: {message}")

    def act(self, executive: Executive, world: FetchWorld) -> None:
        """Do the person's active step once its time is up and its place is free."""
        index = executive.working.get(self.name)
        if index is None:
            return
        step = executive.steps[index]
        if world.step_count - step.started < self.step_steps:
            return
        place, other = step_place(step.subgoal)
        if region_taken(place, [(str(s.subgoal), s.assignee, s.status) for s in executive.steps]):
            return
        positions = dict(zip(world.blocks, world.snapshot().block_positions, strict=True))
        try:
            target = place_position(place, step.subgoal.block, positions, world.scene.bin, other)
        except ValueError:  # no free spot now: the person tries again on the next step
            return
        move_block(world, step.subgoal.block, target)


def run_start(task: str, seed: int, step_s: float) -> tuple[Outcome, Outcome]:
    """One start, in turns and at once (one job)."""
    import torch

    from semgoal_bringup.experiments.episodes import make_agent

    torch.set_num_threads(1)
    spec = get_task(task)
    agent = make_agent("hierarchical", spec.scene)
    positions = spec.initial_state(seed)[0]
    return tuple(agent.run_goals(positions, (spec.name,), seed, label=spec.name, person=ScriptedPerson(step_s=step_s),
                                 concurrent=concurrent) for concurrent in (False, True))


def mode_summary(outcomes: list[Outcome]) -> dict:
    """Success at rest with its 95 % Wilson interval and the median control steps of the successes."""
    wins = sum(o.success for o in outcomes)
    return {"success": wins / len(outcomes), "interval": wilson_interval(wins, len(outcomes)),
            "median_steps": statistics.median(o.steps for o in outcomes if o.success) if wins else None}


def summary(pairs: list[tuple[Outcome, Outcome]], modes: tuple[str, str] = ("in_turns", "at_once")) -> dict:
    """Success, median steps per mode, the ratios (second mode over first) and the steps worked at once, over the
    starts."""
    first, second = mode_summary([p[0] for p in pairs]), mode_summary([p[1] for p in pairs])
    both = [(a.steps, b.steps, b.overlap) for a, b in pairs if a.success and b.success]
    misses = [{"seed": outcome.seed, "mode": name, "why": outcome.why}
              for pair in pairs for name, outcome in zip(modes, pair, strict=True) if not outcome.success]
    return {"episodes": len(pairs), modes[0]: first, modes[1]: second, "misses": misses,
            "ratio_of_medians": second["median_steps"] / first["median_steps"] if both else None,
            "median_ratio": statistics.median(b / a for a, b, _ in both) if both else None,
            "median_overlap_steps": statistics.median(o for *_, o in both) if both else None}


def print_summary(result: dict, modes: tuple[str, str]) -> None:
    """The summary's lines for people: each mode's success and median steps, then the ratios, then each miss."""
    for name in modes:
        row = result[name]
        low, high = row["interval"]
        print(f"{name:9s} success {row['success']:.1%} [{low:.1%}, {high:.1%}]  median steps {row['median_steps']}")
    if result["ratio_of_medians"] is not None:
        print(f"{modes[1]} / {modes[0]}: ratio of medians {result['ratio_of_medians']:.3f}, median ratio "
              f"{result['median_ratio']:.3f}; median steps both at work {result['median_overlap_steps']}")
    for miss in result["misses"]:
        print(f"missed: start {miss['seed']} ({miss['mode']}): {miss['why']}")


def paired_parser(prog: str, doc: str) -> argparse.ArgumentParser:
    """The options of two modes compared on the same starts: ``--task``, ``--episodes``, ``--seed``, ``--jobs``,
    ``--executor``, ``--json``."""
    parser = argparse.ArgumentParser(prog=prog, description=doc.split("\n\n")[0])
    parser.add_argument("--task", default="DC-4")
    parser.add_argument("--episodes", type=count, default=50)
    parser.add_argument("--seed", type=natural, default=DEFAULT_SEED, help="first task seed (start i: seed + i)")
    parser.add_argument("--jobs", type=count, default=1, help="starts run at once")
    parser.add_argument("--executor", default="local", help="local | dask | dask:ADDRESS")
    parser.add_argument("--json", action="store_true", help="only the JSON line")
    return parser


def check_paired(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """A parser error for an unknown task or executor, or no episodes."""
    try:
        get_task(args.task)
        check_executor(args.executor)
    except (KeyError, ValueError) as error:
        parser.error(str(error.args[0]))


def main(argv: list[str]) -> int:
    parser = paired_parser("semgoal eval together", __doc__)
    parser.add_argument("--person-s", type=float, default=3.0, help="seconds the person takes over each step")
    args = parser.parse_args(argv)
    check_paired(parser, args)
    if args.person_s <= 0:
        parser.error("--person-s must be positive")
    pairs = run_jobs(run_start, [(args.task, args.seed + i, args.person_s) for i in range(args.episodes)],
                     args.executor, args.jobs, what="start")
    result = {"task": args.task, "person_s": args.person_s, **summary(pairs)}
    if not args.json:
        print_summary(result, ("in_turns", "at_once"))
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
