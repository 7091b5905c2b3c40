"""Which of the planner's decisions the policy follows at a lockstep control step (no ROS, no torch):
the policy node, the in-process episode and the demo's captions share this one rule."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Protocol, TypeVar

from semgoal_core.names import StepStatus

Decision = TypeVar("Decision")


def lockstep_subgoal(decided_before: Decision | None, decided_now: Decision | None) -> Decision | None:
    """The planner's decision the policy follows at a lockstep control step, given the active sub-goals
    decided on the step before and on this one (None where a decision names none or has not come; an
    empty decision, the goal settling, is followed by the arm's retreat).

    The decision on the step before, when it names a sub-goal: one control step of decision latency, as
    in realtime, lets the actor run while the predicates and the planner work on the same world state,
    instead of after them. At an episode's first step, or when the step before named none (no plan yet, a
    human's turn), the decision on this step; None: the world waits. The policy node and the in-process
    episode both follow this rule, so they take the same steps.
    """
    return decided_before if decided_before is not None else decided_now


FOLLOWED = (StepStatus.ACTIVE, StepStatus.SETTLING)
"""Sub-goal statuses the policy answers with a command: act on the step, or retreat clear of the blocks while the
goal's world settles (in lockstep the world waits for a command, so the retreat must be one)."""


class PlannerDecision(Protocol):
    status: str


Message = TypeVar("Message", bound=PlannerDecision)


def followed_decision(decisions: Mapping[tuple[int, int], Message], episode: int, step: int) -> Message | None:
    """:func:`lockstep_subgoal` over the planner's sub-goal messages keyed by (episode, step): the one the
    policy follows at that step of that episode, or None (the world waits)."""

    def active(decided_step: int) -> Message | None:
        decision = decisions.get((episode, decided_step))
        return decision if decision is not None and decision.status in FOLLOWED else None

    return lockstep_subgoal(active(step - 1), active(step))
