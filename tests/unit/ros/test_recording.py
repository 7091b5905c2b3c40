"""Recording schemas: a type's ros2msg text names every type it uses once, and an independent decoder
(mcap-ros2-support) reads rclpy's serialisation of a message back with it."""

from types import SimpleNamespace

from rclpy.serialization import serialize_message

from semgoal_msgs.msg import Plan, SubGoal
from semgoal_ros.recording import message_definition, recorded_topics


def test_a_definition_carries_every_type_it_uses_once() -> None:
    text = message_definition("semgoal_msgs/msg/Plan")
    used = [line.removeprefix("MSG: ") for line in text.splitlines() if line.startswith("MSG: ")]
    assert sorted(used) == sorted(set(used))
    assert {"semgoal_msgs/SubGoal", "semgoal_msgs/Predicate", "std_msgs/Header", "builtin_interfaces/Time"} <= set(used)
    assert 'string STATUS_EXECUTING="executing"' in text  # constants stay, and bring in no type


def test_an_independent_decoder_reads_rclpy_serialisation_with_it() -> None:
    from mcap_ros2.decoder import DecoderFactory

    plan = Plan(goal="in_bin(red)", status=Plan.STATUS_EXECUTING, revision=4,
                steps=[SubGoal(index=0, action="pick(red)", status=SubGoal.STATUS_ACTIVE, assignee=SubGoal.ASSIGNEE_ROBOT)])
    schema = SimpleNamespace(id=1, name="semgoal_msgs/msg/Plan", encoding="ros2msg",
                             data=message_definition("semgoal_msgs/msg/Plan").encode())
    decode = DecoderFactory().decoder_for("cdr", schema)
    decoded = decode(serialize_message(plan))
    assert (decoded.goal, decoded.status, decoded.revision) == ("in_bin(red)", "executing", 4)
    assert decoded.steps[0].action == "pick(red)" and decoded.steps[0].assignee == "robot"


def test_every_recorded_type_has_a_definition() -> None:
    for _, type_name, _ in recorded_topics():
        assert message_definition(type_name)


def test_camera_frames_are_kept_at_their_recording_instants_only() -> None:
    from sensor_msgs.msg import Image

    from semgoal_ros import interfaces as topics
    from semgoal_ros.recording import kept, stamp_of

    def frame(step: int) -> bytes:
        image = Image(encoding="rgb8", width=1, height=1, step=3, data=bytes(3))
        nanoseconds = step * 40_000_000  # 25 Hz control steps
        image.header.stamp.sec, image.header.stamp.nanosec = divmod(nanoseconds, 1_000_000_000)
        return serialize_message(image)

    assert stamp_of(frame(123)) == 4.92
    assert [step for step in range(12) if kept(topics.RGBD_COLOUR, frame(step))] == [0, 5, 10]
    assert all(kept(topics.WORLD_STATE, frame(step)) for step in range(12))
