"""Frames of an episode seen over ROS (the console's live view, `replay --mp4`): both arms drawn where /joint_states
names a second, and joints the model lacks ignored rather than failing the frame."""

import numpy as np

from semgoal_bringup.tools.episode_video import Frame, FramePainter, arms_named
from semgoal_sim.world import FetchWorld

SHOULDER = "robot0:shoulder_pan_joint"


def _frame(joints: dict[str, float]) -> Frame:
    return Frame(0, joints, {}, "")


def test_the_second_arm_is_drawn_where_its_joints_put_it() -> None:
    world = FetchWorld("desk_cleanup", arms=2)
    joints = dict(zip(world.robot_joint_names, world.robot_joint_state()[0], strict=True))
    assert arms_named(joints) == 2 and arms_named([SHOULDER]) == 1
    painter = FramePainter("desk_cleanup", 4, arms_named(joints))
    try:
        home = painter.image(_frame(joints))
        turned = painter.image(_frame({**joints, f"robot2/{SHOULDER}": joints[f"robot2/{SHOULDER}"] + 0.8}))
    finally:
        painter.close()
    assert np.abs(home.astype(int) - turned).sum() > 0, "turning the second arm's shoulder changed nothing drawn"


def test_a_one_arm_painter_ignores_the_second_arms_joints() -> None:
    painter = FramePainter("desk_cleanup", 4)
    try:
        alone = painter.image(_frame({SHOULDER: 0.1}))
        with_other = painter.image(_frame({SHOULDER: 0.1, f"robot2/{SHOULDER}": 0.5, "no_such_joint": 1.0}))
    finally:
        painter.close()
    np.testing.assert_array_equal(alone, with_other)
