"""Hoffman's objective fluency measures (Hoffman, "Evaluating Fluency in Human-Robot Collaboration", IEEE THMS
2019) from an episode's plan as the planner published it: who had an active step when.

Over the task's working time (the plan executing with steps left; approval, pauses and the final settling left
out), as shares of it:
- robot idle: no robot step active;
- human idle: no person's step active;
- concurrent activity: a robot step and a person's step active at once;
- functional delay: neither active, each waiting on the other (or on the world) between one's step and the next.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable
from dataclasses import asdict, dataclass
from pathlib import Path

from semgoal_core.names import PlanStatus, StepStatus, is_person

MEASURES = ("robot_idle", "human_idle", "concurrent_activity", "functional_delay")


@dataclass(frozen=True)
class PlanSample:
    """What one plan message says, from its stamp until the next."""

    time: float
    robot: bool
    person: bool
    working: bool


@dataclass(frozen=True)
class Fluency:
    task_time: float
    """Seconds of working time."""
    robot_idle: float
    human_idle: float
    concurrent_activity: float
    functional_delay: float

    def as_dict(self) -> dict[str, float]:
        return asdict(self)


def sample(plan) -> PlanSample:
    """A Plan message as a :class:`PlanSample` (its header stamp is the sim time it was decided at)."""
    active = [step.assignee for step in plan.steps if step.status == StepStatus.ACTIVE]
    left = any(step.status in (StepStatus.PENDING, StepStatus.ACTIVE) for step in plan.steps)
    return PlanSample(plan.header.stamp.sec + plan.header.stamp.nanosec * 1e-9,
                      any(not is_person(who) for who in active), any(is_person(who) for who in active),
                      plan.status == PlanStatus.EXECUTING and left)


def fluency(samples: Iterable[PlanSample]) -> Fluency:
    """The measures over ``samples`` (in time order; each holds until the next); all 0 without working time."""
    ordered = sorted(samples, key=lambda s: s.time)
    totals = dict.fromkeys(("task", *MEASURES), 0.0)
    for now, after in itertools.pairwise(ordered):
        if not now.working:
            continue
        span = after.time - now.time
        totals["task"] += span
        totals["robot_idle"] += span * (not now.robot)
        totals["human_idle"] += span * (not now.person)
        totals["concurrent_activity"] += span * (now.robot and now.person)
        totals["functional_delay"] += span * (not now.robot and not now.person)
    task = totals["task"]
    return Fluency(task, *(totals[m] / task if task else 0.0 for m in MEASURES))


def recorded_plans(path: Path) -> list:
    """The plan messages of an MCAP recording, decoded (the ``mcap`` reader and ``mcap-ros2-support``)."""
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    with Path(path).open("rb") as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        return [decoded for _, channel, _, decoded in reader.iter_decoded_messages() if channel.topic.endswith("/plan")]


def recording_fluency(path: Path) -> Fluency:
    return fluency(sample(plan) for plan in recorded_plans(path))
