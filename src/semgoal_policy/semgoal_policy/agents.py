"""The agents that can be trained: what env each uses, what it groups success by, where it is shipped."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from semgoal_sim import layout
from semgoal_sim.env import SubgoalEnv
from semgoal_sim.vocabulary import SCENES


@dataclass(frozen=True)
class AgentSpec:
    make_env: Callable[[str], object]
    """scene -> a goal-conditioned env with ``max_steps``, ``subgoal_kind`` and ``expert_action()``."""
    kinds: Callable[[str], tuple[str, ...]]
    """scene -> the goal kinds the curriculum draws and evaluation reports (``subgoal_type`` option)."""
    reward_fn: Callable
    """(achieved, desired) -> reward, vectorised: the function HER relabels with."""
    model_name: Callable[[str], str]
    """scene -> folder under ``models/`` for the exported actor."""


AGENTS: dict[str, AgentSpec] = {
    "hierarchical": AgentSpec(
        make_env=SubgoalEnv,
        kinds=lambda scene: SCENES[scene].subgoal_types,
        reward_fn=layout.goal_reward,
        model_name=lambda scene: scene,
    ),
}


def get_agent(name: str) -> AgentSpec:
    if name not in AGENTS:
        raise KeyError(f"unknown agent {name!r}; valid: {', '.join(AGENTS)}")
    return AGENTS[name]
