"""Task episodes through the real node graph (``./semgoal eval --via-ros``): the hierarchical agent as
deployed. One graph per scene (sim in lockstep, predicates, planner, policy: four processes on a fresh
ROS domain) serves every episode of that scene's tasks: reset to the task's seeded start, send the task
through ExecuteGoal, read the result; the planner fails an episode that spends its step budget. With
``record``, each episode is also written to ``record/<task>-<seed>.mcap`` (``./semgoal replay``).
"""

from __future__ import annotations

import os
import sys
from collections.abc import Iterator
from pathlib import Path

from semgoal_bringup.experiments.episodes import Outcome
from semgoal_bringup.graph import TRUTH, Sight, running_graph
from semgoal_core.tasks import TASK_STEP_BUDGET, get_task


def run_via_ros(task_names: list[str], episodes: int, seed: int, models: str = "",
                record: Path | None = None, sight: Sight = TRUTH, composed: bool = False,
                robots: int = 1) -> Iterator[Outcome]:
    """Yield one :class:`Outcome` per episode, task by task, starting each scene's graph once; ``sight``: what the
    planner and the policy see by (the simulator's poses, or the camera's); ``composed``: the graph's nodes in one
    process; ``robots``: the arms at the table."""
    by_scene: dict[str, list[str]] = {}
    for name in task_names:
        by_scene.setdefault(get_task(name).scene, []).append(name)
    for scene_tasks in by_scene.values():
        with running_graph(scene_tasks[0], seed, client_name="semgoal_eval", models=models,
                           watch=False, sight=sight, composed=composed, robots=robots) as client:
            print(f"eval via ROS: the {get_task(scene_tasks[0]).scene} graph on ROS domain {os.environ['ROS_DOMAIN_ID']}",
                  file=sys.stderr, flush=True)
            for task_name in scene_tasks:
                for i in range(episodes):
                    with client.recording(record / f"{task_name}-{seed + i}.mcap" if record else None):
                        client.must_reset(task_name, seed + i)
                        result = client.execute(task_name, max_steps=TASK_STEP_BUDGET)
                    yield Outcome(task_name, seed + i, result.success, result.control_steps, result.replans)
