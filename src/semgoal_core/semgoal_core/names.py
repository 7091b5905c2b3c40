"""The names the graph's messages carry as strings, defined once: plan and step statuses, assignees, the
sub-goal topic's extra statuses and the control modes. ``semgoal_msgs`` repeats them as message constants
for ROS users (``Plan.STATUS_EXECUTING``, ...); a test keeps the two equal."""

from enum import StrEnum


class PlanStatus(StrEnum):
    EMPTY = "empty"
    AWAITING_APPROVAL = "awaiting_approval"
    EXECUTING = "executing"
    PAUSED = "paused"
    SUCCEEDED = "succeeded"
    FAILED = "failed"


FINISHED = (PlanStatus.EMPTY, PlanStatus.SUCCEEDED, PlanStatus.FAILED)
"""No plan under way: nothing to edit, nothing to execute."""
UNDER_WAY = (PlanStatus.EXECUTING, PlanStatus.PAUSED, PlanStatus.AWAITING_APPROVAL)


class StepStatus(StrEnum):
    """A step's status in a plan; on the sub-goal topic also ``settling`` and ``waiting_for_human``."""

    PENDING = "pending"
    ACTIVE = "active"
    DONE = "done"
    FAILED = "failed"
    SKIPPED = "skipped"
    SETTLING = "settling"
    WAITING_FOR_HUMAN = "waiting_for_human"


class Assignee(StrEnum):
    """Who does a step: the robot (a second arm: ``robot:2``), or a person (``human``, or one named: ``human:alice``,
    :func:`agent`)."""

    ROBOT = "robot"
    HUMAN = "human"


PERSON_PREFIX = f"{Assignee.HUMAN}:"
ARM_PREFIX = f"{Assignee.ROBOT}:"


def agent(text: str) -> str:
    """``text`` as an agent's name (``robot``, a second arm ``robot:2``, ``human``, ``human:alice``: letters, digits,
    ``_`` and ``-`` after the colon), lower case; ValueError naming the valid forms."""
    name = text.strip().lower()
    person, arm = name.removeprefix(PERSON_PREFIX), name.removeprefix(ARM_PREFIX)
    if name in (Assignee.ROBOT, Assignee.HUMAN) or (
            name.startswith(PERSON_PREFIX) and person and all(c.isalnum() or c in "_-" for c in person)) or (
            name.startswith(ARM_PREFIX) and arm.isdigit() and int(arm) >= 2):
        return name
    raise ValueError(f"an agent is 'robot', a second arm 'robot:2', 'human' or a named person 'human:NAME', got {text!r}")


def is_person(assignee: str) -> bool:
    return assignee == Assignee.HUMAN or assignee.startswith(PERSON_PREFIX)


class Mode(StrEnum):
    """lockstep: the sim steps once per arm command; realtime: on its own clock."""

    LOCKSTEP = "lockstep"
    REALTIME = "realtime"
