"""Scenes compile with what the code looks up; control and resets behave as the Fetch benchmark's."""

import mujoco
import numpy as np
import pytest

from semgoal_core.expert import move_to
from semgoal_core.geometry import GRASP_OPENING, TABLE_TOP
from semgoal_core.tasks import TASKS
from semgoal_core.vocabulary import Literal, SubGoal
from semgoal_sim.rollout import run_subgoal
from semgoal_sim.scene import build_model
from semgoal_sim.sim_core import SimCore, check_command
from semgoal_sim.world import FetchWorld


@pytest.mark.parametrize("scene, blocks", [("two_blocks", None), ("three_blocks", None), ("desk_cleanup", 2),
                                           ("desk_cleanup", 4)])
def test_scene_compiles_with_named_parts(scene: str, blocks: int | None) -> None:
    model = build_model(scene, blocks)
    for name in ("robot0:mocap", "robot0:gripper_link", "block_red", "table0"):
        assert mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, name) >= 0, name
    assert model.actuator("robot0:l_gripper_finger_joint") is not None
    assert (mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "bin") >= 0) == (scene == "desk_cleanup")
    assert mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "object0") == -1


def test_reset_is_deterministic_and_blocks_rest_on_the_table() -> None:
    world = FetchWorld("two_blocks")
    positions, _ = TASKS["MC-2"].initial_state(4)
    first = world.reset(positions)
    second = world.reset(positions)
    np.testing.assert_allclose(first.block_positions, second.block_positions, atol=1e-9)
    assert np.allclose(first.block_positions[:, 2], TABLE_TOP + 0.025, atol=0.002)
    np.testing.assert_allclose(first.grip_position, world.home_grip_position, atol=0.01)


def test_action_moves_the_gripper_like_fetch() -> None:
    world = FetchWorld("two_blocks")
    world.reset(TASKS["MC-2"].initial_state(0)[0])
    start = world.snapshot().grip_position
    for _ in range(5):
        world.step(np.array([1.0, 0.0, 0.0, 0.0]))
    moved = world.snapshot().grip_position - start
    assert 0.15 < moved[0] < 0.26 and abs(moved[1]) < 0.01  # up to 0.05 m per step
    world.step(np.array([np.nan, np.inf, 0.0, 0.0]))  # non-finite entries count as zero
    assert np.all(np.isfinite(world.snapshot().grip_position))


def test_stacked_start_settles_into_above() -> None:
    world = FetchWorld("two_blocks")
    positions, _ = TASKS["Swap-2"].initial_state(2)
    world.reset(positions)
    top = int(np.argmax(positions[:, 2]))
    assert f"above({world.blocks[top]},{world.blocks[1 - top]})" in world.layout.readable(world.semantic_vector())


def test_commands_are_checked() -> None:
    assert check_command([0.1, 0, 0, -1]).warning == ""
    assert check_command([np.nan, 0, 0, 0]).action is None
    clamped = check_command([3, -2, 0, 0.5])
    assert clamped.action.tolist() == [1, -1, 0, 0.5] and "clamped" in clamped.warning
    assert check_command([1, 2]).action is None


def test_sim_core_refuses_bad_requests_and_keeps_state() -> None:
    core = SimCore("desk_cleanup", "DC-3", seed=5)
    before = core.snapshot().block_positions
    assert core.reset("MC-2", 0) == (False, "task MC-2 runs in scene two_blocks, this sim is desk_cleanup "
                                            "(tasks here: DC-2, DC-3, DC-4)")
    assert not core.move_block("red", np.array([3.0, 0.0, 0.0]))[0]
    assert not core.move_block("purple", np.array([1.3, 0.7, 0.0]))[0]
    np.testing.assert_array_equal(core.snapshot().block_positions, before)
    ok, message = core.reset("DC-4", -1)
    assert ok and "seed 6" in message and len(core.world.blocks) == 4


def test_only_the_hand_end_of_the_arm_collides_and_the_floor_catches_blocks() -> None:
    """Collision filtering (scene.TOUCHING_LINKS) leaves the hand in contact and keeps the floor real."""
    world = FetchWorld("two_blocks")
    world.reset(TASKS["MC-2"].initial_state(0)[0])
    model = world.model
    assert model.geom_contype[model.geom("robot0:head_pan_link").id] == 0
    assert model.geom_conaffinity[model.geom("robot0:r_gripper_finger_link").id] == 1
    world.set_block_pose("red", np.array([0.9, 0.3, TABLE_TOP + 0.1]))  # off the desk's edge, in the air
    for _ in range(25):
        world.step(np.zeros(4))
    red = world.snapshot().block_positions[0]
    assert red[2] == pytest.approx(0.025, abs=0.003), "a block off the desk rests on the floor"
    assert world.fallen_blocks() == ["red"]
    base = world.data.xpos[model.body("robot0:base_link").id]
    assert abs(base[2]) < 1e-4, "the base stays where its slide joints hold it without floor contacts"


def test_robot_joint_state_names_every_robot_joint_and_reads_them_now() -> None:
    world = FetchWorld("two_blocks")
    world.reset(TASKS["MC-2"].initial_state(1)[0])
    names = world.robot_joint_names
    assert len(names) == len(set(names)) > 2 and all(name.startswith("robot0:") for name in names)
    fingers = [names.index("robot0:r_gripper_finger_joint"), names.index("robot0:l_gripper_finger_joint")]
    for _ in range(3):
        world.step(np.array([0.0, 0.0, 0.0, -1.0]))
        snapshot = world.snapshot()
        positions, velocities = world.robot_joint_state()
        assert positions.shape == velocities.shape == (len(names),)
        np.testing.assert_array_equal(positions[fingers], snapshot.finger_positions)
        np.testing.assert_array_equal(velocities[fingers], snapshot.finger_velocities)


def test_with_two_arms_the_joint_state_names_both_arms_joints() -> None:
    world = FetchWorld("desk_cleanup", arms=2)
    names = world.robot_joint_names
    first = [name for name in names if name.startswith("robot0:")]
    second = [name for name in names if name.startswith("robot2/robot0:")]
    assert len(first) == len(second) > 2 and len(names) == len(set(names)) == 2 * len(first)
    assert [name.removeprefix("robot2/") for name in second] == first
    world.step(np.array([[0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.0, -1.0]]))
    positions, _ = world.robot_joint_state()
    finger = names.index("robot0:r_gripper_finger_joint"), names.index("robot2/robot0:r_gripper_finger_joint")
    assert positions[finger[0]] > positions[finger[1]]  # each arm's own fingers: one opening, one closing


def test_a_grasp_low_on_a_stack_lifts_both_blocks_and_the_expert_picks_the_top_one_alone() -> None:
    world = FetchWorld("two_blocks")
    world.reset(np.array([[1.3, 0.7, TABLE_TOP + 0.025], [1.3, 0.7, TABLE_TOP + 0.075]]))
    above, low, lifted = (world.view().positions["green"] + np.array([0, 0, dz]) for dz in (0.08, -0.013, 0.05))
    for target, fingers, steps in ((above, 1.0, 15), (low, 1.0, 15), (low, -1.0, 8), (lifted, -1.0, 10)):
        for _ in range(steps):
            world.step(move_to(world.view().grip, target, fingers))
    assert world.view().positions["red"][2] > TABLE_TOP + 0.04, "the low grasp should lift the bottom block too"
    assert not any(lit.name == "holding" for lit in world.layout.true_literals(world.semantic_vector()))
    picked, _ = run_subgoal(world, SubGoal("pick", ("green",)), max_steps=80, confirm_steps=3)
    assert picked and world.view().positions["red"][2] < TABLE_TOP + 0.03  # red back on the table


@pytest.mark.parametrize("speed", [0.5, 1.0])
def test_a_block_flung_over_the_bin_stays_on_the_desk(speed: float) -> None:
    """The bin's far wall is a backboard: a block let go moving away from the robot over the bin lands in
    it. With the low far wall it flew off the desk's far edge, 3.5 cm behind the bin, out of the arm's
    reach: once most lost DC-4 episodes."""
    world = FetchWorld("desk_cleanup", 2)
    bin_ = world.scene.bin
    rest = TABLE_TOP + 0.025
    world.reset(np.array([[1.20, 0.60, rest], [1.40, 0.60, rest]]))
    world.set_block_pose("red", np.array([bin_.center[0], bin_.center[1], TABLE_TOP + 0.12]))
    dof = world.model.joint("block_red:joint").dofadr[0]
    world.data.qvel[dof + 1] = speed  # +y, away from the robot
    for _ in range(25):
        world.step(np.zeros(4))
    assert world.fallen_blocks() == []
    assert world.semantic_vector()[world.layout.index(Literal("in_bin", ("red",)))] == 1.0


def test_the_seed_stream_wraps_within_int64() -> None:
    """A reset to seed 2**63 - 1, then to the next seed (-1), overflowed WorldState.seed."""
    core = SimCore("two_blocks", "MC-2", seed=0)
    assert core.reset("MC-2", 2**63 - 1)[0]
    assert core.reset("MC-2", -1) == (True, "reset to MC-2 with seed 0")


def test_move_block_sets_a_block_in_the_bin_and_refuses_the_walls() -> None:
    """A MoveBlock into the bin's wall reported success and the block was thrown off the desk."""
    core = SimCore("desk_cleanup", "DC-2", seed=0)
    bin_ = core.world.scene.bin
    ok, message = core.move_block("red", np.array(bin_.center))
    assert ok and message.endswith("in the bin")
    wall = np.array([bin_.center[0], bin_.center[1] + bin_.inner_half_size[1] + bin_.wall_thickness / 2])
    ok, message = core.move_block("green", wall)
    assert not ok and "overlaps the bin's walls" in message
    for _ in range(25):
        core.world.step(np.zeros(4))
    assert "in_bin(red)" in core.world.layout.readable(core.world.semantic_vector())
    assert not core.world.fallen_blocks()


def test_a_person_puts_a_block_on_a_tower_and_it_stands() -> None:
    """The console's "on green" put the block on the table under green's tower (refused: "taken by red"); centred on
    a tower it goes on top and stays at rest, half over a block it is refused, and a block with another on it
    stays put (the top one would fall)."""
    core = SimCore("tabletop", "Tower-4", seed=3_000_000)
    world = core.world
    red = core.snapshot().block_positions[world.blocks.index("red")]
    assert core.move_block("green", red)[1].endswith(" on red")
    ok, message = core.move_block("blue", red)
    assert ok and message.endswith(" on green"), message
    for _ in range(50):
        world.step(np.zeros(4))
    assert {"above(green,red)", "above(blue,green)"} <= set(world.layout.readable(world.semantic_vector()).split(" & "))
    np.testing.assert_allclose(core.snapshot().block_positions[world.blocks.index("blue"), :2], red[:2], atol=0.005)
    ok, message = core.move_block("yellow", red + np.array([0.03, 0.0, 0.0]))
    assert not ok and "taken by" in message and "centre" in message
    ok, message = core.move_block("green", np.array([1.2, 0.55, 0.0]))
    assert not ok and message == "blue rests on green: move blue first"
    assert not world.fallen_blocks()


def test_a_reset_to_given_positions_starts_there_and_refuses_what_no_world_can_hold() -> None:
    """The goal families' starts through ResetWorld.positions: checked, the world unchanged on refusal."""
    core = SimCore("three_blocks", "MC-3", seed=0)
    start = np.array([[1.25, 0.70, TABLE_TOP + 0.025], [1.35, 0.70, TABLE_TOP + 0.025], [1.35, 0.70, TABLE_TOP + 0.076]])
    ok, message = core.reset("MC-3", 7, start.ravel())
    assert ok and message == "reset to MC-3 with seed 7 from the positions given"
    np.testing.assert_allclose(core.snapshot().block_positions, start, atol=0.003)  # settled
    for bad, why in [(start[:2].ravel(), "9 numbers"), (np.where(start == start[0, 0], np.nan, start).ravel(), "finite"),
                     (start.ravel() + np.array([3.0, 0, 0] * 3), "off the table"),
                     (start.ravel() - np.array([0, 0, 0.1] * 3), "not between the table top")]:
        ok, message = core.reset("MC-3", 8, bad)
        assert not ok and why in message, message
        np.testing.assert_allclose(core.snapshot().block_positions, start, atol=0.003)  # settled


def test_moving_a_held_block_out_of_the_hand_lets_it_go() -> None:
    """The fingers open as the block leaves them, so the idle arm cannot close on it (or on a block put back
    under it) and the next state says the hand is empty."""
    core = SimCore("desk_cleanup", "DC-2", seed=0)
    world = core.world
    world.place_in_gripper("red")
    assert world.layout.readable(world.semantic_vector()) == "holding(red)"
    ok, message = core.move_block("red", np.array([1.35, 0.55, 0.0]))
    assert ok and message.endswith("out of the robot's hand (the fingers opened)")
    for _ in range(10):
        world.step(np.zeros(4))
        assert world.snapshot().finger_opening == pytest.approx(GRASP_OPENING, abs=0.005)
        assert "holding(red)" not in world.layout.readable(world.semantic_vector())
    ok, message = core.move_block("green", np.array([1.25, 0.65, 0.0]))
    assert ok and "hand" not in message  # a block that was not held: the fingers stay as they are


@pytest.mark.parametrize(("scene", "blocks"), [("two_blocks", None), ("desk_cleanup", 3)])
def test_motion_from_the_semantic_vector_is_the_motion_from_the_geometry(scene: str, blocks: int | None) -> None:
    """The env reads what is held off the step's semantic vector instead of working the holding geometry out again:
    the same bits on every step of the expert picking a block up and carrying it (held, then not)."""
    from semgoal_core.expert import expert_action

    world = FetchWorld(scene, blocks)
    world.reset(np.array([[1.3, 0.7, 0.425], [1.2, 0.9, 0.425], [1.45, 0.55, 0.425]])[: len(world.blocks)])
    held = 0
    for subgoal in (SubGoal("pick", (world.blocks[0],)), SubGoal("put_on_table", (world.blocks[0],))):
        for _ in range(60):
            world.step(expert_action(subgoal, world.view()))
            snapshot = world.snapshot()
            with_vector = world.motion(snapshot, world.semantic_vector(snapshot))
            assert np.array_equal(with_vector, world.motion(snapshot)), world.step_count
            held += bool(with_vector[world.scene.max_blocks:].any())
    assert 0 < held < 120


def test_a_block_is_not_put_into_a_hand_near_the_table_but_may_be_set_down_from_the_hand_holding_it() -> None:
    """A person's MoveBlock onto the block a lowered hand holds put the new block into the fingers."""
    core = SimCore("desk_cleanup", "DC-2", seed=0)
    world = core.world
    world.place_in_gripper("red")
    for _ in range(40):
        world.step(np.array([0.0, 0.0, -1.0, -1.0]))
    grip = world.snapshot().grip_position
    assert world.holder("red") == 0 and grip[2] - TABLE_TOP < 0.1
    before = core.snapshot().block_positions
    ok, message = core.move_block("green", grip)
    assert not ok and message.startswith("robot's hand is at") and "once it has risen" in message
    np.testing.assert_array_equal(core.snapshot().block_positions, before)
    assert core.move_block("green", grip + np.array([0.12, 0.0, 0.0]))[0]
    ok, message = core.move_block("red", grip)  # out of the hand that holds it, straight down
    assert ok and "out of the robot's hand" in message


def test_blocks_at_rest_sleep_unless_kept_awake_and_wake_when_moved_touched_or_reset() -> None:
    """Resting blocks leave the physics (the arm's tree never sleeps); a block teleported into the
    air wakes and falls, the expert still picks a sleeping block, and a reset after a history of sleeping gives the
    episode a new world gives (over whole episodes: ``test_tabletop_hierarchy.py``)."""
    world = FetchWorld("desk_cleanup", 4)
    positions, _ = TASKS["DC-4"].initial_state(5)
    first = world.reset(positions)
    for _ in range(20):
        world.step(np.zeros(4))
    assert world.data.ntree_awake == 1  # the arm alone
    lifted = first.block_positions[1] + np.array([0.0, 0.0, 0.1])
    world.set_block_pose(world.blocks[1], lifted)
    for _ in range(15):
        world.step(np.zeros(4))
    assert abs(world.snapshot().block_positions[1][2] - first.block_positions[1][2]) < 0.005  # it fell back
    assert run_subgoal(world, SubGoal("pick", (world.blocks[0],)), max_steps=60)[0]
    fresh = FetchWorld("desk_cleanup", 4)
    for each in (world, fresh):  # the same episode after a history of sleeping and waking, and on a new world
        each.reset(positions)
        run_subgoal(each, SubGoal("pick", (each.blocks[2],)), max_steps=40)
    np.testing.assert_array_equal(world.snapshot().block_positions, fresh.snapshot().block_positions)
    assert not FetchWorld("desk_cleanup", 4, sleep=False).model.opt.enableflags & int(mujoco.mjtEnableBit.mjENBL_SLEEP)
