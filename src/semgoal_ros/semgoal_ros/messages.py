"""Between semgoal_msgs and the semantic core: what the predicate, planner and policy nodes read from a
world state, and the plan as the operator reads it. No MuJoCo (the sim's own messages are built in ``semgoal_sim.conversions``)."""

from __future__ import annotations

from array import array as array_type

import numpy as np

from semgoal_core.geometry import TABLE_TOP
from semgoal_core.names import PlanStatus, StepStatus
from semgoal_core.settling import moving_blocks
from semgoal_core.vocabulary import LAYOUTS, SCENES, Literal, evaluate, fallen_blocks
from semgoal_msgs.msg import BlockEstimates, Plan, Predicate, SemanticState, WorldState


def literal(predicate: Predicate) -> Literal:
    """A ``semgoal_msgs/Predicate`` as the core's literal."""
    return Literal(predicate.name, tuple(predicate.args), bool(predicate.value))


def predicate(lit: Literal) -> Predicate:
    """A core literal as a ``semgoal_msgs/Predicate``."""
    return Predicate(name=lit.name, args=list(lit.args), value=bool(lit.value))


POSE_SIZE = 7
"""Values per block in ``WorldState.block_poses``: centre x y z, orientation qw qx qy qz (MuJoCo's order)."""
VELOCITY_SIZE = 6
"""Values per block in ``WorldState.block_velocities``: linear x y z, angular x y z."""


def _per_block(msg: WorldState, values, size: int, field: str) -> np.ndarray:
    """A flat per-block field as a (blocks, size) array, refused (ValueError) where it does not fit the names."""
    array = np.asarray(values, dtype=np.float64)  # rclpy's array.array('d') without a copy; a recording's list too
    if array.size != size * len(msg.block_names):
        raise ValueError(f"{field} has {array.size} values for {len(msg.block_names)} blocks ({size} each)")
    return array.reshape(len(msg.block_names), size)


def block_poses(msg: WorldState) -> np.ndarray:
    """(blocks, 7) poses in ``block_names``' order: centre x y z, orientation qw qx qy qz."""
    return _per_block(msg, msg.block_poses, POSE_SIZE, "block_poses")


def block_velocities(msg: WorldState) -> np.ndarray:
    """(blocks, 6) velocities in ``block_names``' order: linear x y z, angular x y z."""
    return _per_block(msg, msg.block_velocities, VELOCITY_SIZE, "block_velocities")


def block_centres(msg: WorldState) -> dict[str, np.ndarray]:
    """Each block's centre (m) by name."""
    return dict(zip(msg.block_names, block_poses(msg)[:, :3], strict=True))


def estimated_blocks(msg: BlockEstimates) -> list[tuple[str, np.ndarray, int]]:
    """Each block the camera estimated: name, centre (m; NaN before it is first seen), status."""
    return [(b.name, np.array([b.position.x, b.position.y, b.position.z]), b.status) for b in msg.blocks]


def doubles(values) -> array_type:
    """A ``float64[]`` field's value from any array of numbers: one copy, no Python float per value."""
    return array_type("d", np.ascontiguousarray(values, dtype=np.float64).tobytes())


def set_blocks(msg: WorldState, names, positions, quaternions, velocities) -> None:
    """Fill a world state's blocks: ``names`` with (n, 3) centres, (n, 4) orientations (w x y z), (n, 6) velocities."""
    msg.block_names = list(names)
    msg.block_poses = doubles(np.hstack([np.reshape(positions, (-1, 3)), np.reshape(quaternions, (-1, 4))]))
    msg.block_velocities = doubles(velocities)


def block_positions(msg: WorldState) -> tuple[np.ndarray, np.ndarray]:
    """(max_blocks, 3) centres in the scene's slot order and the (max_blocks,) presence mask."""
    objects = SCENES[msg.scene].objects
    positions = np.zeros((len(objects), 3))
    present = np.zeros(len(objects), dtype=bool)
    try:
        slots = [objects.index(name) for name in msg.block_names]
    except ValueError:
        slots = []
    if len(set(slots)) != len(msg.block_names):
        raise ValueError(f"block names {list(msg.block_names)} are not distinct blocks of {msg.scene} ({', '.join(objects)})")
    positions[slots], present[slots] = block_poses(msg)[:, :3], True
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
    return moving_blocks(list(msg.block_names), block_velocities(msg)[:, :3])


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
