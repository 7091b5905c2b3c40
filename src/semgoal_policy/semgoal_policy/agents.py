"""The agents that can be trained: what env each uses, what it groups success by, where it is shipped.

``hierarchical`` is the paper's low level: one policy over the scene's sub-goal types, driven by the
planner. The paper's two flat baselines ("Baselines") learn whole tasks with one policy and no planner:
``flat-semantic`` on the task's semantic goal (sparse reward), ``flat-continuous`` on block positions of
a goal configuration (dense distance reward). All three get the same budget and the same expert
supervision (demonstrations and behaviour cloning from the scripted expert), so the comparison isolates
the hierarchy and the goal representation.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from semgoal_core import layout
from semgoal_core.settling import MotionReward
from semgoal_core.vocabulary import LAYOUTS, SCENES
from semgoal_policy.replay import RewardFn
from semgoal_sim.env import SubgoalEnv
from semgoal_sim.task_env import TaskEnv, scene_tasks


@dataclass(frozen=True)
class AgentSpec:
    make_env: Callable[..., object]
    """(scene, derived=(), spawn_margin=0.0) -> a goal-conditioned env with ``max_steps``, ``kind``, ``expert_action()`` and an
    ``is_success`` info entry; ``reset(options={"kind": k})`` fixes the kind."""
    kinds: Callable[[str], tuple[str, ...]]
    """scene -> the goal kinds the curriculum draws and evaluation reports (sub-goal types or tasks)."""
    reward_fn: Callable[[str], RewardFn]
    """scene -> (achieved, desired, motion) -> reward, vectorised: the function HER relabels with."""
    goal: str = "semantic"
    """The goal layout (:data:`semgoal_core.layout.GOAL_KINDS`), stored with the exported actor."""
    suffix: str = ""
    """Appended to the scene for the export folder under ``models/``."""

    def model_name(self, scene: str) -> str:
        return scene + self.suffix


def semantic_reward(scene: str) -> RewardFn:
    """The sparse semantic reward at rest (:class:`semgoal_core.settling.MotionReward`)."""
    return MotionReward(LAYOUTS[scene])


def position_reward(scene: str) -> RewardFn:
    """The flat-continuous baseline's dense distance reward; it has no goal literals to judge at rest."""
    return lambda achieved, desired, motion: layout.position_reward(achieved, desired)


def _task_env(goal: str) -> Callable[..., TaskEnv]:
    def make(scene: str, derived: tuple[str, ...] = (), spawn_margin: float = 0.0) -> TaskEnv:
        if derived:
            raise ValueError(f"derived features ({', '.join(derived)}) are for the hierarchical agent only")
        if spawn_margin:
            raise ValueError("a spawn margin is for the hierarchical agent only (task starts are the paper's)")
        return TaskEnv(scene, goal)
    return make


AGENTS: dict[str, AgentSpec] = {
    "hierarchical": AgentSpec(
        make_env=lambda scene, derived=(), spawn_margin=0.0: SubgoalEnv(scene, derived=derived, spawn_margin=spawn_margin),
        kinds=lambda scene: SCENES[scene].subgoal_types,
        reward_fn=semantic_reward,
    ),
    "flat-semantic": AgentSpec(
        make_env=_task_env("semantic"),
        kinds=scene_tasks,
        reward_fn=semantic_reward,
        suffix="-flat-semantic",
    ),
    "flat-continuous": AgentSpec(
        make_env=_task_env("positions"),
        kinds=scene_tasks,
        reward_fn=position_reward,
        goal="positions",
        suffix="-flat-continuous",
    ),
}


def get_agent(name: str) -> AgentSpec:
    if name not in AGENTS:
        raise KeyError(f"unknown agent {name!r}; valid: {', '.join(AGENTS)}")
    return AGENTS[name]
