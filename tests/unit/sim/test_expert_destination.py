"""Where the scripted expert puts a carried block. It places it where it is when the put will hold once
the block rests there (put_near, put_away, put_in_bin: lowered to PLACE_HEIGHT, then let go; the labels
teach the actor to let go, as the reward does, not to carry on to one exact spot); otherwise a put_near heads for the most compact spot, a
put_in_bin for a free slot (dropped anywhere over the floor, blocks crowd the bin for the next ones)."""

import itertools

import numpy as np

from semgoal_core.expert import PLACE_HEIGHT, RELEASE, WorldView, destination, expert_action
from semgoal_core.tasks import TABLE_TOP
from semgoal_core.vocabulary import BLOCK_HALF_SIZE, SCENES, SubGoal

BIN = SCENES["desk_cleanup"].bin
REST_Z = TABLE_TOP + BLOCK_HALF_SIZE
RIM_Z = TABLE_TOP + BIN.floor_thickness + BIN.wall_height


def carried(block: np.ndarray, others: dict[str, np.ndarray], with_bin: bool = False) -> WorldView:
    """A view in which ``red`` is held at ``block`` (fingers closed on it)."""
    return WorldView({"red": block, **others}, grip=block + np.array([0.0, 0.0, 0.005]), opening=0.048,
                     bin=BIN if with_bin else None)


def assert_lets_go(action: np.ndarray, where: object = None) -> None:
    """The arm stays put and the fingers open fully (a label of +0.015, just past the few mm
    that drop a held block, was cloned as 0 and actors hovered holding the block)."""
    np.testing.assert_allclose(action[:3], 0.0, err_msg=str(where))
    assert action[3] == RELEASE, where


def test_put_near_places_wherever_every_reference_is_within_reach() -> None:
    """Beside green, with every reference within reach: the label opens the fingers where the block is,
    once it is at most PLACE_HEIGHT over what it lands on, and lowers it (fingers shut) while higher. An expert
    that carried it on to its exact spot froze the cloned actor there; one that let go at carry height
    dropped the block for 6 to 8 steps."""
    green = np.array([1.30, 0.75, REST_Z])
    for offset in ([0.08, 0.0, 0.015], [0.0, 0.07, 0.01], [0.06, 0.05, PLACE_HEIGHT - 0.002]):
        assert_lets_go(expert_action(SubGoal("put_near", ("red", "green")), carried(green + np.array(offset), {"green": green})), offset)
    for offset in ([0.0, 0.07, 0.10], [0.06, 0.05, 0.06]):
        action = expert_action(SubGoal("put_near", ("red", "green")), carried(green + np.array(offset), {"green": green}))
        assert action[3] < 0 and action[2] < 0, offset  # shut, going down


def test_a_block_over_another_is_placed_on_its_top() -> None:
    """Over green, the block lands on green's top: low enough 2 cm above it, not 2 cm above the table."""
    green = np.array([1.30, 0.75, REST_Z])
    assert_lets_go(expert_action(SubGoal("put_near", ("red", "green")), carried(green + np.array([0.03, 0.0, 0.065]), {"green": green})))
    assert expert_action(SubGoal("put_near", ("red", "green")), carried(green + np.array([0.03, 0.0, 0.09]), {"green": green}))[3] < 0


def test_put_near_carries_the_block_on_while_a_reference_is_out_of_reach() -> None:
    green, blue = np.array([1.30, 0.75, REST_Z]), np.array([1.45, 0.75, REST_Z])
    subgoal = SubGoal("put_near", ("red", "green", "blue"))
    action = expert_action(subgoal, carried(green + np.array([-0.06, 0.0, 0.10]), {"green": green, "blue": blue}))
    assert action[3] < 0 and action[0] > 0  # shut, towards blue


def test_put_away_lets_go_low_over_a_spot_far_from_its_references_only() -> None:
    """Three_blocks actors hovered, holding the block where letting go would have done (more
    than 10 cm from the others), the expert's label carrying it on with the fingers shut."""
    green, blue = np.array([1.20, 0.60, REST_Z]), np.array([1.40, 0.80, REST_Z])
    subgoal, others = SubGoal("put_away", ("red", "green")), {"green": green, "blue": blue}
    for xy, height in itertools.product(([1.40, 0.55], [1.33, 0.60]), (0.005, 0.015)):  # 13 cm from green
        assert_lets_go(expert_action(subgoal, carried(np.array([*xy, REST_Z + height]), others)), (xy, height))
    for height in (0.06, 0.11):  # far enough, but high: lowered first
        lowered = expert_action(subgoal, carried(np.array([1.40, 0.55, REST_Z + height]), others))
        assert lowered[3] < 0 and lowered[2] < 0
    far_from_both = np.array([1.40, 0.55])
    too_high = expert_action(subgoal, carried(np.array([*far_from_both, REST_Z + 0.15]), others))
    near_green = expert_action(subgoal, carried(np.array([1.28, 0.60, REST_Z + 0.06]), others))
    near_blue = expert_action(subgoal, carried(np.array([1.40, 0.70, REST_Z + 0.06]), others))  # close to blue
    assert too_high[3] < 0 and near_green[3] < 0 and near_blue[3] < 0


def test_put_in_bin_lets_go_over_the_bin_near_a_free_slot_only() -> None:
    slot = BIN.slots()[2]
    over = lambda dx, dz: carried(np.array([slot[0] + dx, slot[1], RIM_Z + dz]), {}, with_bin=True)  # noqa: E731
    assert_lets_go(expert_action(SubGoal("put_in_bin", ("red",)), over(0.015, 0.0)))
    assert expert_action(SubGoal("put_in_bin", ("red",)), over(0.04, 0.03))[3] < 0  # would crowd the next slot


def test_put_near_carries_on_when_the_fingers_would_hit_the_reference() -> None:
    green = np.array([1.30, 0.75, REST_Z])
    here = green + np.array([0.0, 0.07, 0.03])  # 7 cm away along y: opening fingers would push green
    spot = destination(SubGoal("put_near", ("red", "green")), carried(here, {"green": green}))
    assert not np.allclose(spot[:2], here[:2])
    assert 0.055 <= np.linalg.norm(spot[:2] - green[:2]) <= 0.10


def test_put_in_bin_goes_to_a_free_slot() -> None:
    here = np.array([BIN.center[0], BIN.center[1] - 0.05, RIM_Z + 0.03])  # footprint over the wall in y
    spot = destination(SubGoal("put_in_bin", ("red",)), carried(here, {}, with_bin=True))
    assert any(np.allclose(spot[:2], slot) for slot in BIN.slots())


def test_put_in_bin_does_not_let_go_onto_a_binned_block() -> None:
    binned = np.array([*BIN.slots()[1], TABLE_TOP + BIN.floor_thickness + BLOCK_HALF_SIZE])
    here = binned + np.array([0.0, 0.0, 0.06])
    spot = destination(SubGoal("put_in_bin", ("red",)), carried(here, {"blue": binned}, with_bin=True))
    assert np.linalg.norm(spot[:2] - binned[:2]) >= 0.058


def test_put_in_bin_finds_the_gap_an_untidy_bin_leaves() -> None:
    """Three blocks let go around the middle leave no slot free, but a gap at the end still fits one."""
    floor_z = TABLE_TOP + BIN.floor_thickness + BLOCK_HALF_SIZE
    binned = {name: np.array([BIN.center[0] + dx, BIN.center[1], floor_z])
              for name, dx in (("green", -0.075), ("blue", -0.01), ("yellow", 0.055))}
    here = np.array([BIN.center[0], BIN.center[1] - 0.15, RIM_Z + 0.05])
    spot = destination(SubGoal("put_in_bin", ("red",)), carried(here, binned, with_bin=True))
    assert spot is not None
    assert spot[0] - BIN.center[0] > 0.055 + 0.058
    assert BIN.contains(spot[None], TABLE_TOP)[0]


def test_put_in_bin_keeps_hold_over_a_neighbour_even_near_its_slot() -> None:
    """Within the slot tolerance but too near a binned block to fall clear of it: carry on, fingers shut."""
    slot = BIN.slots()[2]
    floor_z = TABLE_TOP + BIN.floor_thickness + BLOCK_HALF_SIZE
    neighbour = {"blue": np.array([slot[0] - 0.065, slot[1], floor_z])}
    over = carried(np.array([slot[0] - 0.015, slot[1], RIM_Z]), neighbour, with_bin=True)
    assert expert_action(SubGoal("put_in_bin", ("red",)), over)[3] < 0
