"""World -> WorldState -> SemanticState, as the sim and predicates nodes convert them (no ROS graph)."""

import numpy as np

from semgoal_sim import conversions
from semgoal_sim.scene import TABLE_HEIGHT
from semgoal_sim.tasks import TASKS
from semgoal_sim.world import FetchWorld


def test_semantic_state_matches_the_world_and_names_fallen_blocks() -> None:
    world = FetchWorld("desk_cleanup", 3)
    world.reset(TASKS["DC-3"].initial_state(0)[0])
    world.set_block_pose("green", np.array([0.9, 0.3, TABLE_HEIGHT + 0.1]))  # off the desk's edge
    for _ in range(25):
        world.step(np.zeros(4))
    snapshot = world.snapshot()
    msg = conversions.world_state(world, snapshot, "DC-3", episode=1)
    state = conversions.semantic_state(msg, conversions.semantic_vector(msg))
    assert state.objects == ["red", "green", "blue"]
    assert state.vector == world.semantic_vector(snapshot).tolist()
    assert state.fallen == ["green"] == world.fallen_blocks(snapshot)
