"""The perceiver run again over a recording (`eval perception --recordings`): a small MCAP written as the recorder
writes one (the sim's world states, the camera's frames and its pose, CDR with ros2msg schemas), read back."""

import json
from pathlib import Path

import numpy as np
import pytest
from mcap.writer import Writer
from rclpy.serialization import serialize_message
from tf2_msgs.msg import TFMessage

from semgoal_bringup.experiments.perception_eval import main as eval_perception
from semgoal_bringup.experiments.perception_replay import FAR, recorded_frames, score_recording
from semgoal_core.vocabulary import LAYOUTS
from semgoal_perception.estimator import BlockEstimator
from semgoal_ros import interfaces as topics
from semgoal_ros.messages import block_poses, doubles
from semgoal_ros.package_data import share_path
from semgoal_ros.recording import message_definition
from semgoal_sim import conversions
from semgoal_sim.camera import SimCamera
from semgoal_sim.sim_core import SimCore

TASK, SEED, FRAMES = "MC-3", 3_000_000, 3


def write_recording(path: Path, shift: dict[str, np.ndarray] | None = None) -> None:
    """``FRAMES`` control steps of a still arm in ``TASK``'s start, each with its camera frame; ``shift``: blocks whose
    recorded true position is moved by that much (the frames are left as they are)."""
    core, camera = SimCore("three_blocks", TASK, SEED), SimCamera(160, 120)
    with path.open("wb") as stream:
        writer = Writer(stream)
        writer.start(profile="ros2", library="test")
        channels = {}
        for topic, type_name in ((topics.WORLD_STATE, "semgoal_msgs/msg/WorldState"),
                                 (topics.RGBD_COLOUR, "sensor_msgs/msg/Image"), (topics.RGBD_DEPTH, "sensor_msgs/msg/Image"),
                                 (topics.RGBD_INFO, "sensor_msgs/msg/CameraInfo"), (topics.TF_STATIC, "tf2_msgs/msg/TFMessage")):
            schema = writer.register_schema(type_name, "ros2msg", message_definition(type_name).encode())
            channels[topic] = writer.register_channel(topic, "cdr", schema)
        for i in range(FRAMES):
            core.step([0.0, 0.0, 0.0, 0.0])
            world = conversions.world_state(core.world, core.snapshot(), TASK, core.episode, SEED, core.clock_s)
            for block, offset in (shift or {}).items():
                index = list(world.block_names).index(block)
                world.block_poses[7 * index: 7 * index + 3] = doubles(block_poses(world)[index, :3] + offset)
            frame = camera.frame(core.world, core.episode, SEED)
            messages = [(topics.WORLD_STATE, world),
                        *zip((topics.RGBD_COLOUR, topics.RGBD_DEPTH, topics.RGBD_INFO),
                             conversions.rgbd(frame, core.clock_s), strict=True)]
            if i == 0:
                pose = conversions.transform(conversions.CAMERA_FRAME, frame.world_from_camera, core.clock_s)
                messages.insert(0, (topics.TF_STATIC, TFMessage(transforms=[pose])))
            for topic, msg in messages:
                writer.add_message(channels[topic], log_time=i, data=serialize_message(msg), publish_time=i)
        writer.finish()
    camera.close()


@pytest.fixture(scope="module")
def estimator() -> BlockEstimator:
    return BlockEstimator.load(share_path("semgoal_perception", "models", "block_voter"))


@pytest.fixture(scope="module")
def still(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("recordings") / "still.mcap"
    write_recording(path)
    return path


def test_a_still_scene_is_tracked_where_the_simulator_has_it(still, estimator) -> None:
    assert [frame.world.step for frame in recorded_frames(still)] == list(range(1, FRAMES + 1))
    score = score_recording(still, estimator)
    assert (score.frames, score.block_frames, score.far, score.wrong) == (FRAMES, 3 * FRAMES, 0, 0)
    assert score.literals == FRAMES * LAYOUTS["three_blocks"].size
    assert {key: counts[1] for key, counts in score.labelled.items()} == {f"{b} table": FRAMES for b in ("red", "green", "blue")}


def test_a_block_the_camera_places_elsewhere_than_the_simulator_counts_as_off(tmp_path, estimator) -> None:
    path = tmp_path / "shifted.mcap"
    write_recording(path, {"blue": np.array([2 * FAR, 0.0, 0.0])})
    score = score_recording(path, estimator)
    assert score.far == FRAMES and score.block_frames == 3 * FRAMES


def test_the_command_reads_recordings_and_refuses_what_is_none(still, tmp_path, capsys) -> None:
    again = tmp_path / "another run" / still.name  # two runs' recordings share their names
    again.parent.mkdir()
    again.write_bytes(still.read_bytes())
    assert eval_perception(["--recordings", str(still), str(again), "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert len(result["recordings"]) == 2 and result["all"]["frames"] == 2 * FRAMES and result["all"]["far"] == 0
    (tmp_path / "empty.mcap").write_bytes(b"not an mcap")
    with pytest.raises(SystemExit):
        eval_perception(["--recordings", str(tmp_path / "empty.mcap")])
    with pytest.raises(SystemExit):
        eval_perception(["--recordings", str(tmp_path / "absent.mcap")])
