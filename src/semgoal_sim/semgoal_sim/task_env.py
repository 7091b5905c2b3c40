"""A whole-task goal-conditioned environment: what the paper's two flat baselines train on.

An episode is one of the scene's tasks (MC-2, DC-3, ...) from its seeded start, with one horizon for the
whole task and no planner. The goal is either

- ``semantic`` (flat semantic baseline): the task's goal literals as ``concat(target, mask)`` over the
  predicate vector, sparse reward 1 when they all hold, exactly the sub-goal env's encoding; or
- ``positions`` (flat continuous baseline): the block centres of one goal configuration that satisfies
  the task (a cluster, a far-apart scatter, the swapped stack, the bin slots), with the dense reward
  minus the summed distance (:func:`semgoal_core.layout.position_reward`).

Success is the same for both and for the hierarchical agent: the task's goal literals hold.
``reset(options={"kind": "MC-2", "start_seed": s})`` fixes the task and its start (evaluation uses the
seeds the hierarchical evaluation uses); without them both are drawn from the env's generator.
The expert label is the closed-loop scripted expert: next sub-goal toward the task goal, then its action.
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np

from semgoal_core import layout, tasks
from semgoal_core.expert import expert_action
from semgoal_core.settling import MotionReward, info_motion
from semgoal_core.vocabulary import SCENES, Literal, SubGoal
from semgoal_sim.render import RgbArrayRendering
from semgoal_sim.rollout import SUBGOAL_STEPS, expert_next_steps, satisfied
from semgoal_sim.world import FetchWorld

TASK_EPISODE_STEPS = {"two_blocks": 120, "three_blocks": 150, "desk_cleanup": 250}
"""Whole-task horizons: about twice the scripted expert's mean steps on the scene's longest task
(Swap-2 58, MC-3 65, DC-4 165; ``./semgoal expert --task T --json``)."""


def goal_configuration(task: tasks.Task, start: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """Block centres (n, 3) of one configuration that satisfies ``task``'s goal from ``start``."""
    count = task.n_blocks
    if task.name.startswith("MC"):
        return tasks.cluster(rng, count)
    if task.name.startswith("MA"):
        return tasks.scatter(rng, count, tasks.FAR_APART)
    if task.name.startswith("Swap"):
        bottom = int(np.argmin(start[:, 2]))
        swapped = start.copy()
        swapped[[bottom, 1 - bottom]] = start[[1 - bottom, bottom]]
        return swapped
    bin_ = SCENES[task.scene].bin
    slots = bin_.slots(count)
    return np.column_stack([slots, np.full(count, tasks.TABLE_TOP + bin_.floor_thickness + tasks.BLOCK_HALF_SIZE)])


class TaskEnv(RgbArrayRendering, gym.Env):
    """Dict observation (observation / achieved_goal / desired_goal), 4-D action in [-1, 1]."""

    def __init__(self, scene: str, goal: str = "semantic", max_steps: int | None = None,
                 render_mode: str | None = None) -> None:
        self._set_render_mode(render_mode)
        self.scene = SCENES[scene]
        self.goal_kind = goal
        self.task_names = tasks.scene_tasks(scene)
        self.worlds = {n: FetchWorld(scene, n) for n in sorted({tasks.get_task(t).n_blocks for t in self.task_names})}
        self.world = next(iter(self.worlds.values()))
        self.layout = self.world.layout
        self.motion_reward = MotionReward(self.layout)
        self.max_steps = max_steps or TASK_EPISODE_STEPS[scene]
        obs_size = layout.observation_size(scene)
        achieved_size = layout.goal_size(scene, goal)
        self.observation_space = gym.spaces.Dict({
            "observation": gym.spaces.Box(-np.inf, np.inf, (obs_size,), np.float32),
            "achieved_goal": gym.spaces.Box(-np.inf, np.inf, (achieved_size,), np.float32),
            "desired_goal": gym.spaces.Box(-np.inf, np.inf, (achieved_size,), np.float32),
        })
        self.action_space = gym.spaces.Box(-1.0, 1.0, (4,), np.float32)
        self.task: tasks.Task | None = None
        self.goal_literals: list[Literal] = []
        self._desired = np.zeros(achieved_size, np.float32)
        self._mask = np.zeros(self.layout.size, np.float32)
        self._steps = 0
        self._expert_subgoal: SubGoal | None = None
        self._expert_since = 0

    @property
    def kind(self) -> str:
        """The current task's name: what training and evaluation group success by."""
        return self.task.name if self.task else ""

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        options = options or {}
        name = options.get("kind") or str(self.np_random.choice(self.task_names))
        self.task = tasks.get_task(name)
        if self.task.scene != self.scene.name:
            raise ValueError(f"task {self.task.name} is set in {self.task.scene}, not {self.scene.name}")
        start_seed = options.get("start_seed", int(self.np_random.integers(2**31)))
        start, self.goal_literals = self.task.initial_state(start_seed)
        self.world = self.worlds[self.task.n_blocks]
        self.world.reset(start)
        if self.goal_kind == "semantic":
            target, self._mask = self.layout.encode(self.goal_literals)
            self._desired = np.concatenate([target, self._mask])
        else:
            settled = self.world.snapshot().block_positions
            self._desired = self._padded(goal_configuration(self.task, settled, self.np_random))
        self._steps = 0
        self._expert_subgoal = None
        return self._read()

    def step(self, action: np.ndarray):
        self.world.step(action)
        self._steps += 1
        obs, info = self._read()
        reward = float(self.compute_reward(obs["achieved_goal"], obs["desired_goal"], info))
        return obs, reward, False, self._steps >= self.max_steps, info

    def compute_reward(self, achieved_goal: np.ndarray, desired_goal: np.ndarray, info: Any) -> np.ndarray:
        """Semantic goals: the sparse reward at rest (``info``: a step's info dict, or one per row), as the
        sub-goal env has it. Positions: the dense distance reward."""
        if self.goal_kind != "semantic":
            return layout.position_reward(achieved_goal, desired_goal)
        return self.motion_reward(achieved_goal, desired_goal, info_motion(info))

    def expert_action(self) -> np.ndarray:
        """The scripted expert's action toward the task goal (zeros once it holds), as :func:`run_task`
        runs it: each of its sub-goals is kept until its literals hold or its step budget ran out."""
        view, vector = self.world.view(), self.world.semantic_vector()
        current = self._expert_subgoal
        if (current is None or satisfied(self.layout, vector, current.literals())
                or self._steps - self._expert_since >= SUBGOAL_STEPS):
            steps = expert_next_steps(self.goal_literals, self.layout, vector, view)
            self._expert_subgoal, self._expert_since = (steps[0] if steps else None), self._steps
        return expert_action(self._expert_subgoal, view) if self._expert_subgoal else np.zeros(4, np.float32)

    def _padded(self, positions: np.ndarray) -> np.ndarray:
        padded = np.zeros((self.scene.max_blocks, 3), np.float32)
        padded[: len(positions)] = positions
        return padded.ravel()

    def _read(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        """Observation and info from one snapshot and one evaluation of the predicates."""
        snapshot = self.world.snapshot()
        vector = self.world.semantic_vector(snapshot)
        achieved = (layout.achieved_goal(vector, self._mask) if self.goal_kind == "semantic"
                    else self._padded(snapshot.block_positions))
        obs = {"observation": self.world.observation(snapshot), "achieved_goal": achieved,
               "desired_goal": self._desired.copy()}
        motion = self.world.motion(snapshot, vector)
        settled = self.motion_reward.settled(np.concatenate(self.layout.encode(self.goal_literals)), motion)
        holds = satisfied(self.layout, vector, self.goal_literals)
        return obs, {"task": self.kind, "is_success": holds and bool(settled), "goal_holds": holds, "motion": motion}
