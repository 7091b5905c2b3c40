"""An empty hand picking a block beside a stack comes down off the block's centre, so that the gripper's palm passes
the stack (``palm_clear_of_stacks``): the rule's shift, its commands, and the tower standing in the physics."""

import numpy as np
import pytest

from semgoal_core.expert import move_to
from semgoal_core.layout import MAX_DISPLACEMENT
from semgoal_core.tasks import TABLETOP_TASKS
from semgoal_core.vocabulary import BLOCK_HALF_SIZE
from semgoal_policy.controller import (
    PALM_BOTTOM,
    PALM_CLEARANCE,
    PALM_FOOTPRINT,
    PICK_SHIFT,
    SubgoalController,
    _palm_shift,
    palm_clear_of_stacks,
)
from semgoal_sim.world import FetchWorld

TOWER = ("red", "green", "blue", "yellow")
BESIDE = 0.08
"""How far (m, along y) the block to pick stands from the tower: its palm-side face 3 cm from the tower's."""


def test_the_shift_is_the_least_move_along_one_axis_that_clears_every_block() -> None:
    assert _palm_shift(np.array([[0.0, 0.2]])) is None  # nothing under the palm: no shift
    np.testing.assert_allclose(_palm_shift(np.array([[0.01, BESIDE]])), [0.0, BESIDE - PALM_FOOTPRINT[1]])
    np.testing.assert_allclose(_palm_shift(np.array([[-0.075, 0.0]])), [PALM_FOOTPRINT[0] - 0.075, 0.0])
    two = np.array([[0.01, BESIDE], [0.01, BESIDE + 0.01]])  # a leaning tower: the nearest block sets the move
    np.testing.assert_allclose(_palm_shift(two), [0.0, BESIDE - PALM_FOOTPRINT[1]])
    assert _palm_shift(np.array([[0.0, PALM_FOOTPRINT[1] - PICK_SHIFT[1] - 0.005]])) is None  # too near to pass
    assert _palm_shift(np.array([[0.0, BESIDE], [0.0, -BESIDE]])) is None  # a tower on either side


def _hand_over_a_block_beside_a_tower(height: float) -> FetchWorld:
    """The tabletop with a tower of four and orange on the table :data:`BESIDE` from it along y, the empty hand wide
    open ``height`` (m) over orange's centre."""
    world = FetchWorld("tabletop", 5)
    world.reset(TABLETOP_TASKS["Tower-5"].initial_state(3_000_000)[0])
    red = world.snapshot().block_positions[world.blocks.index("red")]
    for level, block in enumerate(TOWER[1:], start=1):
        world.set_block_pose(block, red + np.array([0.0, 0.0, 2 * BLOCK_HALF_SIZE * level]))
    orange = red + np.array([0.0, BESIDE, 0.0])
    world.set_block_pose("orange", orange)
    world.open_fingers(0.1)
    for _ in range(60):
        world.step(move_to(world.snapshot().grip_position, orange + np.array([0.0, 0.0, height]), 0.0))
    return world


def _tower(world: FetchWorld) -> np.ndarray:
    return world.snapshot().block_positions[[world.blocks.index(b) for b in TOWER]].copy()


def test_the_hand_goes_off_centre_before_its_palm_comes_down_past_the_tower() -> None:
    """With the palm 1 cm over the tower's top, a command straight down over the block is turned into a move away from
    the tower, at that height; once there, the hand goes down as the actor asks. High over the tower, or picking the
    tower's top block (``grasped_in_place``'s case), the actor's command is kept."""
    top = 4 * 2 * BLOCK_HALF_SIZE  # the tower's top over the table
    world = _hand_over_a_block_beside_a_tower(top - BLOCK_HALF_SIZE + PALM_CLEARANCE + 0.01 - PALM_BOTTOM)
    down = np.array([0.0, 0.0, -1.0, 0.0], dtype=np.float32)
    action = palm_clear_of_stacks("tabletop", world.observation(), down.copy(), "orange")
    assert action[1] > 0.0 and action[2] * MAX_DISPLACEMENT >= -0.011, action  # away in y; not past the top
    observation = world.observation()
    orange = world.snapshot().block_positions[world.blocks.index("orange")]
    shift = _palm_shift(_tower(world)[:, :2] - orange[:2])
    assert shift[0] == 0.0 and 0.0 < shift[1] <= PICK_SHIFT[1]
    observation[:2] = orange[:2] + shift  # at the shifted pick point
    kept = palm_clear_of_stacks("tabletop", observation, down.copy(), "orange")
    assert kept[2] == -1.0 and np.abs(kept[:2]).max() < 0.01
    high = world.observation()
    high[2] += top
    assert palm_clear_of_stacks("tabletop", high, down.copy(), "orange").tolist() == down.tolist()
    assert palm_clear_of_stacks("tabletop", world.observation(), down.copy(), "yellow").tolist() == down.tolist()


@pytest.mark.parametrize("ruled", [True, False], ids=["with the rule", "without it"])
def test_a_hand_brought_straight_down_on_a_block_beside_a_tower_picks_it_and_the_tower_stands(ruled: bool) -> None:
    """Brought straight down on orange, 8 cm from a tower of four, the palm struck the tower's top blocks and pushed
    them off it; under the rule the hand picks orange off centre and the tower stays where it stood."""
    world = _hand_over_a_block_beside_a_tower(0.3)
    tower = _tower(world)
    controller = SubgoalController("tabletop")
    controller.set_subgoal([])
    for step in range(70):
        snapshot = world.snapshot()
        orange = snapshot.block_positions[world.blocks.index("orange")]
        command = move_to(snapshot.grip_position, orange, 0.0 if step < 60 else -1.0).astype(np.float32)
        if ruled:
            command = palm_clear_of_stacks("tabletop", world.observation(), command, "orange")
        world.step(command)
    moved = np.abs(_tower(world) - tower).max()
    if ruled:
        assert moved < 0.005 and "holding(orange)" in world.layout.readable(world.semantic_vector())
    else:
        assert moved > 0.02
