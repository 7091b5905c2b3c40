"""What the perception node takes from the wire: images of the declared encoding and a whole size, poses
from /tf_static; anything else is refused with the reason (the node counts it and carries on)."""

import numpy as np
import pytest
from geometry_msgs.msg import Transform
from sensor_msgs.msg import Image

from semgoal_perception.perception_node import image_array, pose_matrix


def image(encoding: str, width: int, height: int, step: int, size: int) -> Image:
    return Image(encoding=encoding, width=width, height=height, step=step, data=bytes(size))


def test_a_whole_rgb8_and_32fc1_image_is_read() -> None:
    colour = image_array(image("rgb8", 4, 3, 12, 36), "rgb8", 3, np.uint8)
    depth = np.arange(12, dtype=np.float32).reshape(3, 4)
    msg = Image(encoding="32FC1", width=4, height=3, step=16, data=depth.tobytes())
    assert colour.shape == (3, 4, 3) and np.array_equal(image_array(msg, "32FC1", 1, np.float32), depth)


@pytest.mark.parametrize(("msg", "reason"), [
    (image("bgr8", 4, 3, 12, 36), "encoding 'bgr8'"),
    (image("rgb8", 4, 3, 12, 35), "not a whole rgb8 image"),
    (image("rgb8", 4, 3, 10, 30), "not a whole rgb8 image"),
    (image("rgb8", 0, 0, 0, 0), "not a whole rgb8 image"),
])
def test_a_wrong_image_is_refused_with_the_reason(msg: Image, reason: str) -> None:
    with pytest.raises(ValueError, match=reason):
        image_array(msg, "rgb8", 3, np.uint8)


def test_a_transform_becomes_its_rotation_and_translation() -> None:
    transform = Transform()
    transform.translation.x, transform.translation.y, transform.translation.z = 1.0, 2.0, 3.0
    transform.rotation.w, transform.rotation.z = np.cos(np.pi / 4), np.sin(np.pi / 4)  # 90 degrees about z
    pose = pose_matrix(transform)
    assert np.allclose(pose[:3, :3], [[0, -1, 0], [1, 0, 0], [0, 0, 1]]) and np.allclose(pose[:3, 3], [1, 2, 3])


def test_blocks_of_colours_the_voter_was_not_trained_on_are_refused_by_name() -> None:
    from semgoal_perception.estimator import BlockEstimator
    from semgoal_perception.network import BlockVoter, VoterConfig

    paper = BlockEstimator(BlockVoter(VoterConfig(classes=5)))
    assert paper.colours == ("red", "green", "blue", "yellow")
    paper.check_blocks(("red", "yellow"))
    with pytest.raises(ValueError, match="knows red, green, blue, yellow, not orange, pink: train one"):
        paper.check_blocks(("red", "orange", "pink"))
    BlockEstimator(BlockVoter()).check_blocks(("orange", "pink", "cyan", "purple"))
