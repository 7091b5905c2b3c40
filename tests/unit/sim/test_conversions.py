"""World -> WorldState -> SemanticState, as the sim and predicates nodes convert them (no ROS graph)."""

from conftest import desk_with_a_fallen_block
from semgoal_sim import conversions


def test_semantic_state_matches_the_world_and_names_fallen_blocks() -> None:
    world = desk_with_a_fallen_block()
    snapshot = world.snapshot()
    msg = conversions.world_state(world, snapshot, "DC-3", episode=1)
    state = conversions.semantic_state(msg, conversions.semantic_vector(msg))
    assert state.objects == ["red", "green", "blue"]
    assert state.vector == world.semantic_vector(snapshot).tolist()
    assert state.fallen == ["green"] == world.fallen_blocks(snapshot)
