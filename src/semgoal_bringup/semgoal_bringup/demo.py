"""`./semgoal demo [--task T] [--seed S] [--max-steps N] [--gif FILE] [--record FILE]`: the whole node graph
solving a task.

Starts sim (lockstep), predicates, planner and policy as separate processes in a fresh ROS domain,
resets the world to the task, sends the goal through the planner's ExecuteGoal action, and prints as
it happens the plan, each sub-goal starting and finishing, re-plans and the result. The episode is
recorded as MCAP (``results/demo-TASK.mcap``, ``./semgoal replay``), and its GIF, with the active sub-goal
on every frame, is rendered from that record. The last line says ``success`` when the task's goal holds.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from semgoal_core.arguments import natural
from semgoal_core.names import PlanStatus, StepStatus
from semgoal_core.tasks import TASK_STEP_BUDGET

DEFAULT_TASK = "DC-3"
DEFAULT_SEED = 6
"""A DC-3 start the shipped actors solve through the graph (124 control steps to success at rest, no re-plan)."""
TO_DO = (StepStatus.PENDING, StepStatus.ACTIVE)
"""Plan steps a printed plan lists: a re-plan keeps the steps already done ahead of the new ones."""


def main(argv: list[str]) -> int:
    from semgoal_bringup.graph import add_sight_arguments, sight_of, start_graph, stop_graph

    parser = argparse.ArgumentParser(prog="semgoal demo", description=__doc__.split("\n\n")[0])
    parser.add_argument("--task", default=DEFAULT_TASK)
    parser.add_argument("--seed", type=natural, default=DEFAULT_SEED, help="the task start (default %(default)s)")
    parser.add_argument("--max-steps", type=int, default=TASK_STEP_BUDGET,
                        help="control steps the goal may take before it fails, as in the evaluation (0: no limit)")
    parser.add_argument("--models", default="", help="folder of exported actors (SCENE/actor.pt); default: the shipped "
                        "ones (expert: the scripted expert, the actors' teacher)")
    parser.add_argument("--gif", type=Path, help="where to write the episode GIF (default results/demo-TASK.gif)")
    parser.add_argument("--no-gif", action="store_true")
    parser.add_argument("--record", type=Path, help="where to record the episode as MCAP (default results/demo-TASK.mcap)")
    parser.add_argument("--no-record", action="store_true")
    add_sight_arguments(parser)
    args = parser.parse_args(argv)
    if args.max_steps < 0:
        parser.error("--max-steps must be 0 (no limit) or a number of control steps")
    from semgoal_core.tasks import get_task
    from semgoal_ros.domains import domain_for_this_process

    try:
        task = get_task(args.task)
    except KeyError as error:
        parser.error(str(error.args[0]))
    sight = sight_of(args, parser, [task.name])
    gif = None if args.no_gif else args.gif or Path("results") / f"demo-{task.name}.gif"
    record = None if args.no_record else args.record or Path("results") / f"demo-{task.name}.mcap"  # None: a scratch file
    with domain_for_this_process():  # a domain of its own: parallel demos never meet
        processes = start_graph(task.name, args.seed, models=args.models, sight=sight)
        try:
            return Demo(task.name, args.seed).run(gif, args.max_steps, record)
        finally:
            stop_graph(processes)


class Demo:
    """One episode through the graph, narrated: plan, steps started and done, re-plans, result, GIF."""

    def __init__(self, task_name: str, seed: int) -> None:
        from semgoal_core.tasks import get_task
        from semgoal_ros.client import GraphClient

        self.task, self.seed = get_task(task_name), seed
        self.client = GraphClient("semgoal_demo")
        self.seen_steps: dict[int, str] = {}
        self.replans_shown = -1
        """Re-plans of the plan last printed (-1: none printed yet); a step done changes the plan too."""

    def log(self, text: str) -> None:
        step = self.client.world.step if self.client.world else 0
        print(f"[demo] step {step:4d}  {text}", flush=True)

    def feedback(self, message) -> None:
        plan = message.feedback.plan
        if plan.replans != self.replans_shown and plan.steps and plan.status in (PlanStatus.EXECUTING, PlanStatus.AWAITING_APPROVAL):
            what = "plan" if self.replans_shown < 0 else f"re-plan {plan.replans}"
            self.log(f"{what}: " + ", ".join(f"{s.index}. {s.action}" for s in plan.steps if s.status in TO_DO))
            self.replans_shown = plan.replans
        for step in plan.steps:
            if self.seen_steps.get(step.index) != f"{step.action}:{step.status}" and step.status in (StepStatus.ACTIVE, StepStatus.DONE):
                self.seen_steps[step.index] = f"{step.action}:{step.status}"
                verb = "started" if step.status == StepStatus.ACTIVE else "done   "
                self.log(f"{verb} {step.index}. {step.action}")

    def run(self, gif: Path | None, max_steps: int = TASK_STEP_BUDGET, record: Path | None = None) -> int:
        """The episode, recorded to ``record`` (a temporary file when None); the GIF is rendered from the record."""
        import tempfile

        client = self.client
        with tempfile.TemporaryDirectory() as scratch:
            path = record or Path(scratch) / "episode.mcap"
            try:
                if not client.wait_ready():
                    print("the four nodes did not come up in time: failure", file=sys.stderr)
                    return 1
                with client.recording(path) as recorder:
                    result = self.episode(max_steps)
                counts = recorder.counts
            finally:
                client.close()
            if result is None:
                return 1
            if record is not None:
                print(f"[demo] recorded {sum(counts.values())} messages on {sum(map(bool, counts.values()))} topics: "
                      f"{record} (./semgoal replay {record} --summary)", flush=True)
            if gif is not None:
                self.write_gif(path, gif)
        print(f"{self.task.name}: {'success' if result.success else 'failure'}")
        return 0 if result.success else 1

    def episode(self, max_steps: int):
        """Reset, execute with the plan narrated; the result, or None when the reset failed."""
        ok, message = self.client.reset(self.task.name, self.seed)
        if not ok:
            print(f"reset failed: {message}", file=sys.stderr)
            return None
        print(f"[demo] {self.task.name} ({self.task.description}), seed {self.seed}, "
              f"ROS domain {os.environ['ROS_DOMAIN_ID']}", flush=True)
        result = self.client.execute(self.task.name, self.feedback, max_steps=max_steps)
        self.log(f"result: {result.message} ({result.replans} re-plans)")
        print(f"[demo] {result.control_steps} control steps ({result.sim_time:.1f} s sim time) in "
              f"{result.wall_s:.1f} s wall: {result.control_steps / max(result.wall_s, 1e-9):.0f} steps/s "
              "through the graph", flush=True)
        return result

    def write_gif(self, record: Path, gif: Path) -> None:
        """The episode GIF, rendered from the recorded world and joint states (``./semgoal replay --gif``)."""
        from semgoal_bringup.tools.episode_video import write_video
        from semgoal_bringup.tools.replay import episode_frames, read

        frames = episode_frames(read(record))
        write_video(self.task.scene, self.task.n_blocks, frames, gif)
        print(f"[demo] episode GIF: {gif} ({len(frames)} frames)", flush=True)
