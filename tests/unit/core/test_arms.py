"""The second arm's names and frame: the reflection it sees the world through, and which arm takes which block."""

import numpy as np
import pytest

from semgoal_core import layout
from semgoal_core.arms import (
    MIRROR_X,
    ArmFrame,
    arm_namespace,
    arm_observation,
    arm_of,
    arms_for,
    robot_name,
    robot_names,
)
from semgoal_core.geometry import TABLE_TOP
from semgoal_core.names import agent
from semgoal_core.vocabulary import BLOCK_HALF_SIZE


def test_arm_names_namespaces_and_agents() -> None:
    assert robot_names(2) == ("robot", "robot:2")
    assert [arm_of(name) for name in robot_names(2)] == [0, 1]
    assert (arm_namespace(0), arm_namespace(1)) == ("", "robot2")
    assert agent(" Robot:2 ") == robot_name(1)
    for bad in ("robot:1", "robot:x", "robot:", "arm:2"):
        with pytest.raises(ValueError, match="robot:2"):
            agent(bad)
    with pytest.raises(ValueError, match="robot:2"):
        arm_of("robot:3")


def observation(rng: np.random.Generator, blocks: int = 3) -> np.ndarray:
    positions = rng.uniform([1.05, 0.4, 0.42], [1.55, 1.1, 0.6], (blocks, 3))
    grip = rng.uniform([1.0, 0.4, 0.45], [1.6, 1.1, 0.7])
    return layout.observation("desk_cleanup", grip, rng.normal(size=3), rng.uniform(0, 0.05, 2), rng.normal(size=2),
                              positions, rng.normal(size=(blocks, 6)))


def test_the_second_arm_sees_the_world_reflected_about_the_table_centre_line() -> None:
    rng = np.random.default_rng(0)
    world = observation(rng)
    seen = ArmFrame("desk_cleanup", 1).observation(world)
    again = ArmFrame("desk_cleanup", 1).observation(seen)
    np.testing.assert_allclose(again, world, atol=1e-6)  # a reflection is its own inverse
    arm, slots = layout.arm_state(seen), layout.block_slots("desk_cleanup", seen)
    assert arm["grip_position"][0] == pytest.approx(2 * MIRROR_X - world[0])
    assert arm["finger_positions"].tolist() == world[6:8][::-1].tolist()  # its right finger is the first's left
    # a block's offset from the grip is the reflected block minus the reflected grip; the absent slot stays zero
    np.testing.assert_allclose(slots["relative_position"][:3], slots["position"][:3] - arm["grip_position"], atol=1e-6)
    assert not slots["present"][3].any() and not slots["position"][3].any()
    np.testing.assert_array_equal(ArmFrame("desk_cleanup", 0).observation(world), world)


def test_a_command_in_the_second_arms_frame_moves_it_the_reflected_way() -> None:
    command = np.array([0.5, -0.2, 0.3, -1.0], dtype=np.float32)
    assert ArmFrame("desk_cleanup", 1).action(command).tolist() == pytest.approx([-0.5, -0.2, 0.3, -1.0])
    assert ArmFrame("desk_cleanup", 0).action(command) is command


def test_each_arm_takes_the_blocks_on_its_side_and_both_those_near_the_centre_line() -> None:
    assert arms_for(np.array([1.1, 0.7, 0.42]), 2) == (0,)
    assert arms_for(np.array([1.5, 0.7, 0.42]), 2) == (1,)
    assert arms_for(np.array([1.28, 0.7, 0.42]), 2) == (0, 1)
    assert arms_for(np.array([1.33, 0.7, 0.42]), 2) == (1, 0)
    assert arms_for(np.array([1.5, 0.7, 0.42]), 1) == (0,)


def test_a_step_on_a_block_in_a_hand_goes_to_that_hand() -> None:
    from semgoal_core.arms import holder_of, takers

    positions = np.array([[1.2, 0.6, 0.6], [1.45, 0.8, 0.425]])  # red in the first arm's hand, green on the table
    hands = [(positions[0] + [0.0, 0.0, 0.005], 0.05), (np.array([1.5, 0.75, 0.6]), 0.0)]
    assert holder_of(0, positions, hands) == 0 and holder_of(1, positions, hands) is None
    assert takers(0, positions, hands) == (0,)  # though red lies within reach of both
    assert takers(1, positions, hands) == (1,)


def test_a_block_in_the_other_arms_hand_is_shown_at_rest_on_the_table_under_it():
    grip, still, fingers = np.array([1.2, 0.6, 0.6]), np.zeros(3), np.array([0.03, 0.03])
    positions = np.array([[1.3, 0.9, 0.62], [1.1, 0.7, TABLE_TOP + BLOCK_HALF_SIZE]])
    velocities = np.array([[0.0, 0.1, 0.2], [0.0, 0.0, 0.0]])
    alone = arm_observation("two_blocks", grip, still, fingers, still[:2], positions, velocities)
    assert np.array_equal(alone, layout.observation("two_blocks", grip, still, fingers, still[:2], positions, velocities))
    other_hand = [(np.array([1.3, 0.9, 0.625]), 0.05)]  # closed on the first block
    shown = arm_observation("two_blocks", grip, still, fingers, still[:2], positions, velocities, other_hand)
    on_table = positions.copy()
    on_table[0, 2] = TABLE_TOP + BLOCK_HALF_SIZE
    assert np.array_equal(shown, layout.observation("two_blocks", grip, still, fingers, still[:2], on_table,
                                                    np.zeros_like(velocities)))
    assert positions[0, 2] == 0.62 and velocities[0, 2] == 0.2  # the caller's arrays untouched


def test_a_point_past_the_table_is_named_by_the_edge_it_went_over() -> None:
    from semgoal_core.geometry import table_edge

    assert table_edge(np.array([0.98, 0.63])) == "near"  # the robot's side: it faces +x
    assert table_edge(np.array([1.63, 1.02])) == "far"
    assert table_edge(np.array([1.20, 0.10])) == "right"
    assert table_edge(np.array([1.35, 1.20])) == "left"
    assert table_edge(np.array([1.06, 0.75])) == "near"  # on the table: the nearest edge
