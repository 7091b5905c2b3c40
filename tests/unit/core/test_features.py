"""Derived actor inputs: the bin target points where the expert would put the block between the fingers,
the subject offset at the block(s) the sub-goal names."""

import numpy as np
import pytest

from semgoal_core import features, layout
from semgoal_core.layout import observation_size
from semgoal_core.tasks import TABLE_TOP
from semgoal_core.vocabulary import BLOCK_HALF_SIZE, LAYOUTS, SCENES, Literal
from semgoal_sim.env import SubgoalEnv

SCENE = "desk_cleanup"
BIN = SCENES[SCENE].bin
FLOOR_Z = TABLE_TOP + BIN.floor_thickness + BLOCK_HALF_SIZE
GRIP = np.array([1.05, 0.70, 0.55])


def observe(blocks: list[np.ndarray], grip: np.ndarray = GRIP) -> np.ndarray:
    positions = np.array(blocks, dtype=np.float64)
    return layout.observation(SCENE, grip, np.zeros(3), np.full(2, 0.02), np.zeros(2), positions, np.zeros_like(positions))


def binned(slot: int) -> np.ndarray:
    return np.array([*BIN.slots()[slot], FLOOR_Z])


def test_the_bin_target_is_the_free_end_slot_when_three_are_taken() -> None:
    held = GRIP - np.array([0.0, 0.0, 0.01])
    obs = observe([binned(0), binned(1), binned(2), held])
    assert np.allclose(features.bin_target(SCENE, obs), BIN.slots()[3] - GRIP[:2], atol=1e-6)


def test_the_block_between_the_fingers_is_no_obstacle_even_over_its_own_slot() -> None:
    grip = np.array([*BIN.slots()[3], FLOOR_Z + 0.06]) - np.array([0.01, 0.0, 0.0])
    obs = observe([binned(0), binned(1), binned(2), grip - np.array([0.0, 0.0, 0.01])], grip)
    assert np.allclose(features.bin_target(SCENE, obs), [0.01, 0.0], atol=1e-6)


def test_an_untidy_bin_leaves_the_widest_gap_as_target_and_a_full_one_none() -> None:
    untidy = [np.array([x, BIN.center[1], FLOOR_Z]) for x in (1.19, 1.25, 1.32)]  # no slot free, a gap at +x
    target = features.bin_target(SCENE, observe([*untidy, GRIP]))
    spot = target + GRIP[:2]
    assert spot[0] > 1.36 and abs(spot[1] - BIN.center[1]) < BIN.inner_half_size[1]
    full = [binned(slot) for slot in range(4)]
    assert np.array_equal(features.bin_target(SCENE, observe(full)), np.zeros(2))


def test_augment_appends_the_named_features_and_check_refuses_bad_names() -> None:
    obs = observe([binned(0), GRIP])
    assert features.augment(SCENE, obs, ()) is obs
    augmented = features.augment(SCENE, obs, ("bin_target",))
    assert augmented.dtype == np.float32 and augmented.shape == (obs.size + features.width(("bin_target",)),)
    assert np.array_equal(augmented[obs.size:], features.bin_target(SCENE, obs))
    with pytest.raises(ValueError, match="unknown derived feature 'colour'"):
        features.check(("colour",))

def test_bin_target_is_zero_in_a_scene_without_a_bin() -> None:
    obs = np.ones(observation_size("two_blocks"), np.float32)
    assert np.array_equal(features.augment("two_blocks", obs, ("bin_target",))[obs.size:], np.zeros(2))


def test_an_actor_trained_with_a_bin_is_shown_its_training_scenes_bin_where_there_is_none() -> None:
    """The scene's own bin where it has one; else the training scene's, which ``bin_target`` reads as the scene's."""
    tabletop_bin = SCENES["tabletop"].bin
    assert features.shown_bin("two_blocks", "tabletop") is tabletop_bin
    assert features.shown_bin(SCENE, "tabletop") is BIN
    assert features.shown_bin("two_blocks", "two_blocks") is None
    grip = np.array([1.30, 0.70, 0.55])
    positions = np.array([[1.25, 0.65, 0.425], [1.40, 0.80, 0.425]])
    obs = layout.observation("two_blocks", grip, np.zeros(3), np.full(2, 0.02), np.zeros(2), positions,
                             np.zeros_like(positions))
    shown = features.augment("two_blocks", obs, ("bin_target",), None, tabletop_bin)[obs.size:]
    assert np.allclose(shown, features.bin_target("tabletop", _tabletop_observation(grip, positions)), atol=1e-6)
    assert np.linalg.norm(shown) > 0.1


def _tabletop_observation(grip: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """The tabletop's observation of the same grip and blocks (the rest of its slots empty)."""
    return layout.observation("tabletop", grip, np.zeros(3), np.full(2, 0.02), np.zeros(2), positions,
                              np.zeros_like(positions))


def test_the_env_appends_derived_features_to_its_observations() -> None:
    env = SubgoalEnv(SCENE, derived=("bin_target",))
    obs, _ = env.reset(seed=3, options={"kind": "put_in_bin"})
    base = env.world.observation()
    assert env.observation_space["observation"].shape == (base.size + 2,)
    assert np.array_equal(obs["observation"], features.augment(SCENE, base, ("bin_target",)))


def goal_of(scene: str, *literals: Literal) -> np.ndarray:
    return np.concatenate(LAYOUTS[scene].encode(list(literals)))


def test_the_subject_offset_points_at_the_block_the_subgoal_names() -> None:
    blocks = [np.array([1.2, 0.6, 0.43]), np.array([1.3, 0.7, 0.43]), np.array([1.4, 0.8, 0.43]), binned(0)]
    obs = observe(blocks)
    for colour, block in zip(SCENES[SCENE].objects, blocks, strict=True):
        for literal in (Literal("holding", (colour,)), Literal("in_bin", (colour,))):
            offset = features.subject_offset(SCENE, obs, goal_of(SCENE, literal))
            assert np.allclose(offset, block - GRIP, atol=1e-6), literal
    assert np.array_equal(features.subject_offset(SCENE, obs, None), np.zeros(3))
    assert np.array_equal(features.subject_offset(SCENE, obs, np.zeros(2 * LAYOUTS[SCENE].size)), np.zeros(3))


def test_a_relation_names_both_its_blocks_and_absent_blocks_count_for_nothing() -> None:
    scene = "three_blocks"
    positions = np.array([[1.2, 0.6, 0.43], [1.3, 0.7, 0.43], [1.4, 0.8, 0.43]])
    obs = layout.observation(scene, GRIP, np.zeros(3), np.full(2, 0.02), np.zeros(2), positions, np.zeros_like(positions))
    red, green = SCENES[scene].objects[:2]
    offset = features.subject_offset(scene, obs, goal_of(scene, Literal("close", (red, green))))
    assert np.allclose(offset, positions[:2].mean(0) - GRIP, atol=1e-6)
    desk_two = observe([np.array([1.2, 0.6, 0.43]), np.array([1.3, 0.7, 0.43])])  # blue and yellow absent
    assert np.array_equal(features.subject_offset(SCENE, desk_two, goal_of(SCENE, Literal("in_bin", ("blue",)))),
                          np.zeros(3))


def test_the_env_computes_the_subject_offset_for_its_episode_goal() -> None:
    env = SubgoalEnv(SCENE, derived=("bin_target", "subject_offset"))
    obs, _ = env.reset(seed=4, options={"subgoal": "pick(green)"})
    green = env.world.observation()[layout.ARM_SIZE:].reshape(-1, layout.BLOCK_SIZE)[SCENES[SCENE].objects.index("green")]
    assert env.observation_space["observation"].shape == (obs["observation"].size,)
    assert np.allclose(obs["observation"][-3:], green[layout.BLOCK_SLICE["relative_position"]])


def test_feature_values_are_pinned_to_their_versions() -> None:
    """Golden values: a change to what a derived feature computes (here or in geometry.bin_spot) fails this
    until FEATURE_VERSIONS is bumped, and a bumped version makes every actor trained on the old one refuse
    to load, rather than silently see other inputs."""
    assert features.FEATURE_VERSIONS == {"bin_target": 1, "subject_offset": 1}
    scene = "desk_cleanup"
    blocks = np.array([[1.20, 0.60, 0.425], [1.34, 1.00, 0.436], [1.40, 0.70, 0.425], [1.26, 1.00, 0.436]])
    obs = layout.observation(scene, np.array([1.30, 0.65, 0.50]), np.zeros(3), np.array([0.04, 0.04]), np.zeros(2),
                             blocks, np.zeros((4, 3)))
    target, mask = LAYOUTS[scene].encode([Literal("in_bin", ("red",)), Literal("holding", ("red",), False)])
    goal = np.concatenate([target, mask])
    np.testing.assert_allclose(features.bin_target(scene, obs, goal), [-0.12, 0.35], atol=1e-6)
    np.testing.assert_allclose(features.subject_offset(scene, obs, goal), [-0.10, -0.05, -0.075], atol=1e-6)
