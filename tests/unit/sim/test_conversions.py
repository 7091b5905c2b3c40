"""World -> WorldState -> SemanticState, as the sim and predicates nodes convert them (no ROS graph)."""

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
