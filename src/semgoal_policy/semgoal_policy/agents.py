"""The agents that can be trained: what goals each learns, what it groups success by, where it is shipped.

``hierarchical`` is the paper's low level: one policy over the scene's sub-goal types, driven by the
planner. The paper's two flat baselines ("Baselines") learn whole tasks with one policy and no planner:
``flat-semantic`` on the task's semantic goal (sparse reward), ``flat-continuous`` on block positions of
a goal configuration (dense distance reward). All three get the same budget and the same expert
supervision (demonstrations and behaviour cloning from the scripted expert), so the comparison isolates
the hierarchy and the goal representation. Which simulated env each trains in is the simulator's business
(``semgoal_bringup.experiments.training.make_env``): this package imports no simulator.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from semgoal_core import layout
from semgoal_core.settling import MotionReward
from semgoal_core.tasks import scene_tasks
from semgoal_core.vocabulary import LAYOUTS, SCENES, TAKE_OUT
from semgoal_policy.replay import RewardFn


@dataclass(frozen=True)
class AgentSpec:
    subgoals: bool
    """Whether it learns the planner's sub-goals (the hierarchy's low level) or whole tasks (a flat baseline)."""
    kinds: Callable[[str], tuple[str, ...]]
    """scene -> the goal kinds the curriculum draws (sub-goal types or tasks); evaluation reports them and more
    (:meth:`evaluated_kinds`)."""
    reward_fn: Callable[[str], RewardFn]
    """scene -> (achieved, desired, motion) -> reward, vectorised: the function HER relabels with."""
    goal: str = "semantic"
    """The goal layout (:data:`semgoal_core.layout.GOAL_KINDS`), stored with the exported actor."""
    suffix: str = ""
    """Appended to the scene for the export folder under ``models/``."""

    def model_name(self, scene: str) -> str:
        return scene + self.suffix

    def evaluated_kinds(self, scene: str) -> tuple[str, ...]:
        """What evaluation reports: the curriculum's kinds and, for sub-goals in a scene with a bin, take-outs apart
        (:data:`~semgoal_core.vocabulary.TAKE_OUT`), which training meets only in starts with blocks in the bin."""
        kinds = self.kinds(scene)
        return (*kinds, TAKE_OUT) if self.subgoals and SCENES[scene].bin is not None else kinds


def semantic_reward(scene: str) -> RewardFn:
    """The sparse semantic reward at rest (:class:`semgoal_core.settling.MotionReward`)."""
    return MotionReward(LAYOUTS[scene])


def position_reward(scene: str) -> RewardFn:
    """The flat-continuous baseline's dense distance reward; it has no goal literals to judge at rest."""
    return lambda achieved, desired, motion: layout.position_reward(achieved, desired)


AGENTS: dict[str, AgentSpec] = {
    "hierarchical": AgentSpec(
        subgoals=True,
        kinds=lambda scene: SCENES[scene].subgoal_types,
        reward_fn=semantic_reward,
    ),
    "flat-semantic": AgentSpec(
        subgoals=False,
        kinds=scene_tasks,
        reward_fn=semantic_reward,
        suffix="-flat-semantic",
    ),
    "flat-continuous": AgentSpec(
        subgoals=False,
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
