"""Between semgoal_msgs and the semantic core: what the predicate, planner and policy nodes read from a
world state, and the plan as the operator reads it. No MuJoCo (the sim's own messages are built in ``semgoal_sim.conversions``)."""

from __future__ import annotations

import numpy as np

from semgoal_core.geometry import TABLE_TOP
from semgoal_core.names import PlanStatus, StepStatus
from semgoal_core.settling import moving_blocks
from semgoal_core.vocabulary import LAYOUTS, SCENES, Literal, evaluate, fallen_blocks
from semgoal_msgs.msg import Plan, Predicate, SemanticState, WorldState


def literal(predicate: Predicate) -> Literal:
    """A ``semgoal_msgs/Predicate`` as the core's literal."""
    return Literal(predicate.name, tuple(predicate.args), bool(predicate.value))


def predicate(lit: Literal) -> Predicate:
    """A core literal as a ``semgoal_msgs/Predicate``."""
    return Predicate(name=lit.name, args=list(lit.args), value=bool(lit.value))


def block_positions(msg: WorldState) -> tuple[np.ndarray, np.ndarray]:
    """(max_blocks, 3) centres in the scene's slot order and the (max_blocks,) presence mask."""
    objects = SCENES[msg.scene].objects
    positions = np.zeros((len(objects), 3))
    present = np.zeros(len(objects), dtype=bool)
    for block in msg.blocks:
        i = objects.index(block.name)
        p = block.pose.position
        positions[i], present[i] = (p.x, p.y, p.z), True
    return positions, present


def hands(msg: WorldState) -> list[tuple[np.ndarray, float]]:
    """Each arm's grip position and finger opening in a world state: the message's own arm first, then the others."""
    g = msg.gripper_position
    return [(np.array([g.x, g.y, g.z]), float(sum(msg.finger_positions))),
            *((np.array([p.x, p.y, p.z]), float(opening))
              for p, opening in zip(msg.other_grippers, msg.other_finger_openings, strict=False))]


def semantic_vector(msg: WorldState) -> np.ndarray:
    """Evaluate the scene's predicates on a world state message (``holding`` in any arm's hand)."""
    positions, present = block_positions(msg)
    (grip, opening), *others = hands(msg)
    return evaluate(LAYOUTS[msg.scene], positions, grip, opening, TABLE_TOP, present, other_hands=others)


def moving(msg: WorldState) -> tuple[str, ...]:
    """The blocks of a world state message that are not at rest (:func:`semgoal_core.settling.moving_blocks`)."""
    velocities = np.array([[b.twist.linear.x, b.twist.linear.y, b.twist.linear.z] for b in msg.blocks]).reshape(-1, 3)
    return moving_blocks([b.name for b in msg.blocks], velocities)


def semantic_state(msg: WorldState, vector: np.ndarray) -> SemanticState:
    layout = LAYOUTS[msg.scene]
    positions, present = block_positions(msg)
    objects = [name for name, here in zip(layout.objects, present, strict=True) if here]
    return semantic_message(msg, objects, vector, fallen_blocks(objects, positions[present], TABLE_TOP), moving(msg))


def semantic_message(world: WorldState, objects, vector, fallen, moving_now, confidence=()) -> SemanticState:
    """The SemanticState of a world state's scene, step, episode and stamp, from its evaluated ``vector``
    (whoever evaluated it: the simulator's predicates or the camera's perception)."""
    state = SemanticState(scene=world.scene, step=world.step, episode=world.episode, objects=list(objects),
                          vector=[bool(v) for v in vector], confidence=[float(c) for c in confidence],
                          fallen=list(fallen), moving=list(moving_now))
    state.header = world.header
    state.predicates = [Predicate(name=name, args=list(args), value=bool(v))
                        for (name, args), v in zip(LAYOUTS[world.scene].atoms, vector, strict=True)]
    return state


PLAN_TEXT_ORIGIN = (0.6, 1.0, 1.2)
"""Where RViz shows the plan (m, world frame): beside the table, above it."""
PLAN_LINE_SPACING = 0.05


def plan_markers(plan: Plan):
    """The plan as RViz text, a line per step (action, status, assignee; the active one larger and green,
    done ones grey) under a line with the goal and status, after a DELETEALL so a shorter plan leaves none."""
    from visualization_msgs.msg import Marker, MarkerArray

    lines = [(f"goal: {plan.goal or '(none)'} [{plan.status}, revision {plan.revision}]", (1.0, 1.0, 1.0), 0.04)]
    for step in plan.steps:
        active = step.status == StepStatus.ACTIVE and plan.status == PlanStatus.EXECUTING
        colour = (0.2, 1.0, 0.2) if active else (0.6, 0.6, 0.6) if step.status == StepStatus.DONE else (1.0, 1.0, 1.0)
        lines.append((f"{'> ' if active else ''}{step.index}. {step.action} {step.status} {step.assignee} "
                      f"{after_text(step)}".rstrip(), colour, 0.04 if active else 0.03))
    items = [Marker(action=Marker.DELETEALL)]
    for i, (text, colour, height) in enumerate(lines):
        marker = Marker(ns="plan", id=i, type=Marker.TEXT_VIEW_FACING, action=Marker.ADD, text=text)
        marker.header.frame_id = "world"
        marker.pose.position.x, marker.pose.position.y = PLAN_TEXT_ORIGIN[:2]
        marker.pose.position.z = PLAN_TEXT_ORIGIN[2] - i * PLAN_LINE_SPACING
        marker.pose.orientation.w = 1.0
        marker.scale.z = height
        marker.color.r, marker.color.g, marker.color.b, marker.color.a = (*colour, 1.0)
        items.append(marker)
    return MarkerArray(markers=items)


def format_plan(plan: Plan) -> str:
    """A plan as the operator reads it: goal, status and revision, why it last changed, then a line per step (> marks
    each agent's active one; "after 1, 2": the steps it must follow)."""
    status = f"{plan.status} ({plan.paused_because})" if plan.paused_because else plan.status
    lines = [f"goal: {plan.goal or '(none)'}   status: {status}   revision {plan.revision}   replans {plan.replans}",
             *([f"last: {plan.message}"] if plan.message else [])]
    for step in plan.steps:
        marker = ">" if step.status == StepStatus.ACTIVE and plan.status == PlanStatus.EXECUTING else " "
        lines.append(f"{marker} {step.index:2d}. {step.action:28s} {step.status:8s} {step.assignee:6s} {after_text(step)}"
                     .rstrip())
    return "\n".join(lines)


def after_text(step) -> str:
    """The steps a plan step must follow, as the plan shows them: ``after 0, 2``; "" for none."""
    return f"after {', '.join(map(str, step.after))}" if len(step.after) else ""
