"""World -> WorldState -> SemanticState, as the sim and predicates nodes convert them (no ROS graph)."""

import re

import pytest

from conftest import desk_with_a_fallen_block
from semgoal_ros import messages
from semgoal_sim import conversions


def test_semantic_state_matches_the_world_and_names_fallen_blocks() -> None:
    world = desk_with_a_fallen_block()
    snapshot = world.snapshot()
    msg = conversions.world_state(world, snapshot, "DC-3", episode=1)
    state = messages.semantic_state(msg, messages.semantic_vector(msg))
    assert state.objects == ["red", "green", "blue"]
    assert state.vector == world.semantic_vector(snapshot).tolist()
    assert state.fallen == ["green"] == world.fallen_blocks(snapshot)


def test_the_blocks_travel_as_flat_arrays_and_read_back_as_the_world_has_them() -> None:
    import numpy as np
    from rclpy.serialization import deserialize_message, serialize_message

    from semgoal_msgs.msg import WorldState

    world = desk_with_a_fallen_block()
    snapshot = world.snapshot()
    sent = conversions.world_state(world, snapshot, "DC-3", episode=1)
    msg = deserialize_message(serialize_message(sent), WorldState)  # as a subscriber takes it
    assert list(msg.block_names) == list(world.blocks)
    np.testing.assert_array_equal(messages.block_poses(msg)[:, :3], snapshot.block_positions)
    np.testing.assert_array_equal(messages.block_poses(msg)[:, 3:], snapshot.block_quaternions)
    np.testing.assert_array_equal(messages.block_velocities(msg), snapshot.block_velocities)
    assert list(messages.block_centres(msg)) == list(world.blocks)
    positions, present = messages.block_positions(msg)  # in the scene's slots
    np.testing.assert_array_equal(positions[present], snapshot.block_positions)


@pytest.mark.parametrize("field, values, names, refusal", [
    ("block_poses", [0.0] * 20, ["red", "green", "blue"], "block_poses has 20 values for 3 blocks (7 each)"),
    ("block_velocities", [], ["red", "green", "blue"], "block_velocities has 0 values for 3 blocks (6 each)"),
    ("block_poses", [0.0] * 21, ["red", "red", "blue"], "not distinct blocks of desk_cleanup"),
    ("block_poses", [0.0] * 21, ["red", "purple", "blue"], "not distinct blocks of desk_cleanup"),
])
def test_blocks_that_do_not_fit_their_names_are_refused_with_the_reason(field, values, names, refusal) -> None:
    world = desk_with_a_fallen_block()
    msg = conversions.world_state(world, world.snapshot(), "DC-3", episode=1)
    msg.block_names = names
    setattr(msg, field, values)
    with pytest.raises(ValueError, match=re.escape(refusal)):
        messages.semantic_state(msg, messages.semantic_vector(msg))


def test_markers_draw_the_bin_with_its_backboard_as_the_physics_has_it() -> None:
    world = desk_with_a_fallen_block()
    msg = conversions.world_state(world, world.snapshot(), "DC-3", episode=1)
    bin_parts = [m for m in conversions.markers(msg).markers if m.ns == "bin"]
    far_wall = world.model.geom("bin_wall_y_pos")
    assert len(bin_parts) == 2
    backboard = max(bin_parts, key=lambda m: m.scale.z)
    assert backboard.scale.z > bin_parts[0].scale.z  # taller than the rim
    assert abs(backboard.pose.position.y - world.data.geom(far_wall.id).xpos[1]) < 1e-6
    assert abs(2 * far_wall.size[2] - backboard.scale.z) < 1e-6


def test_markers_start_with_a_deleteall_and_draw_every_block_and_the_gripper() -> None:
    from visualization_msgs.msg import Marker

    world = desk_with_a_fallen_block()
    msg = conversions.world_state(world, world.snapshot(), "DC-3", episode=1)
    drawn = conversions.markers(msg).markers
    assert drawn[0].action == Marker.DELETEALL  # a reset to fewer blocks leaves none behind
    assert sorted(m.id for m in drawn if m.ns == "blocks") == list(range(len(msg.block_names)))
    gripper = [m for m in drawn if m.ns == "gripper"]
    assert len(gripper) == 1 and abs(gripper[0].pose.position.z - msg.gripper_position.z) < 1e-9


def test_a_second_arms_slice_carries_its_hand_the_others_and_the_contacts() -> None:
    from semgoal_core.tasks import TASKS
    from semgoal_ros.messages import semantic_vector
    from semgoal_sim.world import FetchWorld

    world = FetchWorld("desk_cleanup", 2, arms=2)
    world.reset(TASKS["DC-2"].initial_state(0)[0])
    world.place_in_gripper("red")  # in the first arm's hand
    first = conversions.world_state(world, world.snapshot(), "DC-2", episode=1)
    second = conversions.world_state(world, world.snapshot(1), "DC-2", episode=1, arm=1)
    assert second.gripper_position == first.other_grippers[0] and first.gripper_position == second.other_grippers[0]
    assert list(second.observation) == pytest.approx(world.observation(arm=1).tolist())
    assert first.arm_contacts == second.arm_contacts == world.arm_contacts
    for msg in (first, second):  # holding is in either hand, whichever slice the predicates read
        assert "red" in [lit.args[0] for lit in world.layout.true_literals(semantic_vector(msg)) if lit.name == "holding"]
    grippers = [m for m in conversions.markers(first).markers if m.ns == "gripper"]
    assert [m.id for m in grippers] == [0, 1] and grippers[1].pose.position.x > 1.3  # the second across the table


def test_the_plan_is_drawn_as_text_with_the_active_step_highlighted() -> None:
    from semgoal_core.names import Assignee, PlanStatus, StepStatus
    from semgoal_msgs.msg import Plan, SubGoal

    steps = [SubGoal(index=0, action="pick(red)", status=StepStatus.DONE, assignee=Assignee.ROBOT),
             SubGoal(index=1, action="put_in_bin(red)", status=StepStatus.ACTIVE, assignee=Assignee.ROBOT, after=[0]),
             SubGoal(index=2, action="pick(green)", status=StepStatus.PENDING, assignee=Assignee.HUMAN)]
    plan = Plan(goal="in_bin(red) & in_bin(green)", steps=steps, current=1, status=PlanStatus.EXECUTING, revision=3,
                message="step 0 pick(red) done")
    drawn = messages.plan_markers(plan).markers
    texts = [m.text for m in drawn[1:]]
    assert drawn[0].action == drawn[0].DELETEALL and len(texts) == 4
    assert texts[0].startswith("goal: in_bin(red) & in_bin(green) [executing, revision 3]")
    assert texts[2] == "> 1. put_in_bin(red) active robot after 0" and texts[3] == "2. pick(green) pending human"
    lines = messages.format_plan(plan).splitlines()  # the same in the plan text `plan show` prints, why it last changed
    assert lines[1] == "last: step 0 pick(red) done"
    assert lines[3].split() == [">", "1.", "put_in_bin(red)", "active", "robot", "after", "0"]
    assert lines[4].split() == ["2.", "pick(green)", "pending", "human"]
    plan.message = ""
    assert messages.format_plan(plan).splitlines()[1].split()[0] == "0."  # no line for no reason
    assert drawn[3].color.g == 1.0 and drawn[3].color.r < 1.0  # the active step in green
