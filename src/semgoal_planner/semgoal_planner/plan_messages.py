"""The planner node's messages, built without a node: a GoalRequest read into a typed goal, the plan and the
active sub-goal as the node publishes them, and operator requests as given (for the operator events)."""

from __future__ import annotations

from semgoal_core.names import Assignee, PlanStatus, StepStatus
from semgoal_msgs.msg import GoalRequest, Plan, SemanticState, SubGoal
from semgoal_msgs.srv import EditPlan
from semgoal_planner.executive import Executive
from semgoal_planner.goals import Goal, GoalError, read_goal, typed_goal
from semgoal_ros.messages import literal, predicate


def goal_as_given(msg: GoalRequest) -> str:
    """A GoalRequest as the operator gave it, malformed ones too (each part there is, joined by ' | ')."""
    predicates = " & ".join(str(literal(p)) for p in msg.predicates)
    return " | ".join(part for part in (msg.task.strip(), " & ".join(msg.literals), predicates, msg.text.strip()) if part)


def read_request(msg: GoalRequest, scene: str, objects: tuple[str, ...]) -> Goal:
    """The goal a request carries, read once: predicates are validated, a task, typed literals or a sentence
    are read (:func:`~semgoal_planner.goals.read_goal`). GoalError unless exactly one of the four is given."""
    given = [bool(msg.task.strip()), bool(msg.literals), bool(msg.predicates), bool(msg.text.strip())]
    if sum(given) != 1:
        raise GoalError("give exactly one of a task, literals (text or predicates) or a sentence (text)")
    if msg.predicates:
        return typed_goal([literal(p) for p in msg.predicates], scene, objects)
    return read_goal(msg.task.strip() or " & ".join(msg.literals) or msg.text.strip(), scene, objects)


def edit_text(request: EditPlan.Request) -> str:
    """An edit as the operator gave it: the op and each field set (``remove index=2``, ``assign index=1 action=human``)."""
    fields = {"index": request.index, "to_index": request.to_index, "action": request.action,
              "revision": request.revision}
    return " ".join([request.op, *(f"{name}={value}" for name, value in fields.items() if value)])


def sim_time(msg: SemanticState) -> float:
    return msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9


def plan_message(ex: Executive, stamp) -> Plan:
    """The plan as published (latched) and answered by GetPlan."""
    msg = Plan(goal=ex.goal_text, current=ex.current, status=ex.status, revision=ex.revision, replans=ex.replans,
               paused_because=ex.blind, message=ex.message)
    msg.header.stamp = stamp
    msg.steps = [step_message(i, step.subgoal, step.status, step.assignee, after)
                 for i, (step, after) in enumerate(zip(ex.steps, ex.orderings(), strict=True))]
    return msg


def step_message(index: int, subgoal, status: str, assignee: str, after: tuple[int, ...] = ()) -> SubGoal:
    return SubGoal(index=index, action=str(subgoal), status=status, assignee=assignee,
                   goal=[predicate(lit) for lit in subgoal.literals()], after=list(after))


def subgoal_message(ex: Executive, state: SemanticState | None, robot: str = Assignee.ROBOT) -> SubGoal:
    """``robot``'s active step; else an empty goal (no step for the policy) with the reason as status:
    ``settling`` (the goal holds, the world comes to rest), ``waiting_for_human`` (others work) or the plan's
    status."""
    active = ex.active_for(robot)
    if ex.settling:  # the goal's literals: the policy keeps what they ask to hold while the arm retreats
        msg = SubGoal(index=ex.current, status=StepStatus.SETTLING, goal=[predicate(lit) for lit in ex.goal])
    elif ex.status == PlanStatus.SUCCEEDED:
        msg = SubGoal(index=ex.current, status=ex.status, goal=[predicate(lit) for lit in ex.goal])
    elif active is None:
        waiting = ex.status == PlanStatus.EXECUTING  # executing without a step for this arm: it waits for others
        msg = SubGoal(index=ex.current, status=StepStatus.WAITING_FOR_HUMAN if waiting else ex.status,
                      assignee=Assignee.HUMAN if waiting else "")
    else:
        msg = step_message(ex.working[robot], active.subgoal, StepStatus.ACTIVE, robot)
    msg.step = state.step if state else 0  # the state this decision answers
    msg.episode = state.episode if state else 0
    return msg
