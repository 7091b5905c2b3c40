"""`replay --summary`: on a recording from the camera, the spans of steps in which a block's estimate was far off the
simulator's pose, built from real message objects as the recorder's decoder gives them; and the plans of the recorded
episode alone."""

import numpy as np

from semgoal_bringup.experiments.perception_replay import FAR
from semgoal_bringup.tools.replay import Episode, OffSpan, off_spans, summary
from semgoal_msgs.msg import BlockEstimate, BlockEstimates, WorldState
from semgoal_perception.tracker import TrackStatus
from semgoal_ros.messages import set_blocks

TRUE = {"red": np.array([1.2, 0.6, 0.425]), "green": np.array([1.3, 0.7, 0.425])}


def world(step: int) -> WorldState:
    msg = WorldState(step=step, scene="two_blocks", task="MC-2", seed=7)
    set_blocks(msg, TRUE, np.array(list(TRUE.values())), np.tile([1.0, 0, 0, 0], (2, 1)), np.zeros((2, 6)))
    return msg


def estimates(step: int, red_off: float, red_status: int = TrackStatus.VISIBLE) -> BlockEstimates:
    msg = BlockEstimates(step=step)
    for name, centre in TRUE.items():
        red = name == "red"
        estimate = BlockEstimate(name=name, status=red_status if red else TrackStatus.VISIBLE)
        estimate.position.x, estimate.position.y, estimate.position.z = (float(v) for v in centre + np.array([red_off * red, 0, 0]))
        msg.blocks.append(estimate)
    return msg


def test_a_block_far_off_over_some_steps_is_one_span_with_its_worst_error_and_whether_it_was_seen_then() -> None:
    episode = Episode()
    offs = [0.0, 0.0, 0.04, 0.06, 0.0, 0.05]  # off at steps 2-3, back, off again from step 5 to the end
    for step, off in enumerate(offs):
        episode.worlds[step] = world(step)
        episode.estimates[step] = estimates(step, off, TrackStatus.OCCLUDED if step == 3 else TrackStatus.VISIBLE)
    spans = off_spans(episode)
    assert [(s.block, s.first, s.last, s.unseen) for s in spans] == [("red", 2, 3, True), ("red", 5, 5, False)]
    assert np.isclose(spans[0].worst, 0.06) and isinstance(spans[0], OffSpan)
    text = summary(episode)
    assert f"2 span(s) of a block more than {FAR * 100:.0f} cm off" in text
    assert "steps    2-   3: red off by up to 6.0 cm (unseen)" in text


def test_estimates_within_the_margin_read_as_such_and_a_run_without_the_camera_says_nothing() -> None:
    episode = Episode()
    for step in range(3):
        episode.worlds[step] = world(step)
    assert "camera:" not in summary(episode)
    episode.estimates = {step: estimates(step, FAR / 2) for step in range(3)}
    assert off_spans(episode) == [] and "every block within 3 cm of the sim's pose" in summary(episode)


def test_the_episode_befores_plan_latched_to_the_recorder_is_not_this_episodes(tmp_path) -> None:
    """The planner's last plan is latched: a recorder started for the next episode gets it first, before the reset."""
    from mcap.writer import Writer
    from rclpy.serialization import serialize_message

    from semgoal_bringup.tools.replay import read
    from semgoal_msgs.msg import Plan, SubGoal
    from semgoal_ros import interfaces as topics
    from semgoal_ros.recording import message_definition

    path = tmp_path / "episode.mcap"
    with path.open("wb") as stream:
        writer = Writer(stream)
        writer.start(profile="ros2", library="test")
        channels = {}
        for topic, type_name in ((topics.WORLD_STATE, "semgoal_msgs/msg/WorldState"), (topics.PLAN, "semgoal_msgs/msg/Plan")):
            schema = writer.register_schema(type_name, "ros2msg", message_definition(type_name).encode())
            channels[topic] = writer.register_channel(topic, "cdr", schema)
        before = Plan(goal="old", replans=3, status="failed", steps=[SubGoal(action="pick(red)")])
        now = Plan(goal="new", status="executing", steps=[SubGoal(action="pick(green)")])
        for time, (topic, msg) in enumerate(((topics.PLAN, before), (topics.WORLD_STATE, world(0)),
                                             (topics.PLAN, now), (topics.WORLD_STATE, world(1)))):
            writer.add_message(channels[topic], log_time=time, data=serialize_message(msg), publish_time=time)
        writer.finish()
    episode = read(path)
    assert [plan.goal for plan in episode.plans] == ["new"]
    assert "re-plan 3" not in summary(episode) and "plan for new: 0. pick(green)" in summary(episode)
