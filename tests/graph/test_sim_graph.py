"""sim_node and predicate_node as processes: the test drives the arm in lockstep with the expert's
commands over DDS and watches world and semantic state change; garbage commands do not stop the sim;
the predicates node names a block fallen off the table."""

import math

import numpy as np
import pytest
from sensor_msgs.msg import Image, JointState
from visualization_msgs.msg import MarkerArray

from conftest import GraphProbe, NodeProcesses, desk_with_a_fallen_block
from semgoal_core.expert import expert_action
from semgoal_core.vocabulary import SubGoal
from semgoal_msgs.msg import ArmCommand, SemanticState, WorldState
from semgoal_msgs.srv import MoveBlock, ResetWorld
from semgoal_ros import interfaces as topics
from semgoal_ros.messages import block_centres, block_positions
from semgoal_sim import conversions
from semgoal_sim.conversions import world_view


def command(step: int, values) -> ArmCommand:
    msg = ArmCommand(step=step, gripper=float(values[3]))
    msg.displacement.x, msg.displacement.y, msg.displacement.z = (float(v) for v in values[:3])
    return msg


class Graph:
    """The test's side of the graph: latest world and semantic state, a command publisher."""

    def __init__(self, probe: GraphProbe) -> None:
        self.probe = probe
        self.worlds: list[WorldState] = []
        self.semantic: list[SemanticState] = []
        self.joints: list[JointState] = []
        probe.node.create_subscription(WorldState, topics.WORLD_STATE, self.worlds.append, topics.STREAM)
        probe.node.create_subscription(SemanticState, topics.SEMANTIC_STATE, self.semantic.append, topics.LATCHED)
        probe.node.create_subscription(JointState, topics.JOINT_STATES, self.joints.append, topics.STREAM)
        self.commands = probe.node.create_publisher(ArmCommand, topics.ARM_COMMAND, topics.STREAM)

    def call(self, service_type, name, request):
        """The answer, the request sent again where none comes: Fast DDS drops a server's answer to a client it has not
        matched yet (ros2/ros2#1253), as the product's clients allow for (every request here is safe to repeat)."""
        from semgoal_ros.interfaces import send_until_answered

        client = self.probe.node.create_client(service_type, name)
        self.probe.spin_until(client.service_is_ready, 30, name)
        answer = send_until_answered(lambda: client.call_async(request), self.probe.poll, attempts=5, wait_s=6.0)
        if answer is None:
            pytest.fail(f"no answer from {name} to five requests")
        return answer

    def step(self, values) -> WorldState:
        """Send one command for the latest step and wait for the next step's world state (not a heartbeat,
        which repeats the latest step while the world waits)."""
        latest = self.worlds[-1]
        self.commands.publish(command(latest.step, values))
        self.probe.spin_until(lambda: self.worlds[-1].episode != latest.episode or self.worlds[-1].step > latest.step,
                              10, f"world state after step {latest.step}")
        return self.worlds[-1]

    def true_literals(self) -> set[str]:
        state = self.semantic[-1]
        return {f"{p.name}({','.join(p.args)})" for p in state.predicates if p.value}


def test_expert_drives_sim_in_lockstep(nodes: NodeProcesses, probe: GraphProbe) -> None:
    nodes.start("semgoal_sim", "sim_node", params={"scene": "two_blocks", "task": "MC-2", "seed": 3})
    nodes.start("semgoal_sim", "predicate_node")
    graph = Graph(probe)
    probe.spin_until(lambda: probe.node.count_subscribers(topics.WORLD_STATE) >= 2, 30, "predicate_node listening")
    reset = graph.call(ResetWorld, topics.RESET_WORLD, ResetWorld.Request(task="MC-2", seed=3))
    assert reset.success, reset.message
    probe.spin_until(lambda: graph.worlds and graph.worlds[-1].step == 0, 20, "world state of the reset")
    probe.spin_until(lambda: graph.semantic, 20, "semantic state")
    assert "close(red,green)" not in graph.true_literals()
    start = graph.worlds[-1]
    for subgoal in (SubGoal("pick", ("red",)), SubGoal("put_near", ("red", "green"))):
        for _ in range(60):
            world = graph.step(expert_action(subgoal, world_view(graph.worlds[-1])))
            probe.spin_until(lambda w=world: graph.semantic[-1].step >= w.step - 1, 5, "semantic state to follow")
            if subgoal.kind == "pick" and "holding(red)" in graph.true_literals():
                break
            if subgoal.kind == "put_near" and "close(red,green)" in graph.true_literals() and \
                    "holding(red)" not in graph.true_literals():
                break
    final = graph.worlds[-1]
    assert final.step > start.step
    probe.spin_until(lambda: graph.joints and graph.joints[-1].header.stamp == final.header.stamp, 5, "joint states of the last step")
    joints = graph.joints[-1]
    fingers = [joints.name.index("robot0:r_gripper_finger_joint"), joints.name.index("robot0:l_gripper_finger_joint")]
    assert len(joints.position) == len(joints.velocity) == len(joints.name) and np.isfinite(joints.position).all()
    np.testing.assert_allclose([joints.position[i] for i in fingers], final.finger_positions)
    assert "close(red,green)" in graph.true_literals()
    moved = np.linalg.norm(block_positions(final)[0][0] - block_positions(start)[0][0])
    assert moved > 0.05, "the red block moved"


def test_garbage_commands_do_not_stop_the_sim(nodes: NodeProcesses, probe: GraphProbe) -> None:
    process = nodes.start("semgoal_sim", "sim_node", params={"scene": "desk_cleanup", "task": "DC-2"})
    graph = Graph(probe)
    probe.spin_until(lambda: graph.commands.get_subscription_count() > 0, 20, "sim_node")
    graph.call(ResetWorld, topics.RESET_WORLD, ResetWorld.Request(task="DC-2", seed=1))
    probe.spin_until(lambda: graph.worlds and graph.worlds[-1].step == 0, 20, "reset world state")
    count = len(graph.worlds)
    for values in ([math.nan, 0, 0, 0], [0, math.inf, 0, 0]):  # dropped: no step
        graph.commands.publish(command(0, values))
    graph.commands.publish(command(99, [0, 0, 1, 0]))  # stale: dropped
    probe.spin_for(1.0)
    assert all(w.step == 0 for w in graph.worlds[count:]), "dropped commands must not step the world (heartbeats repeat step 0)"
    world = graph.step([5.0, -7.0, 0.0, 2.0])  # clamped and applied
    assert world.step == 1 and all(math.isfinite(v) for v in world.observation)
    refused = graph.call(ResetWorld, topics.RESET_WORLD, ResetWorld.Request(task="MC-2", seed=0))
    assert not refused.success and "two_blocks" in refused.message
    unknown = graph.call(MoveBlock, topics.MOVE_BLOCK, MoveBlock.Request(block="purple"))
    assert not unknown.success and "unknown block 'purple'" in unknown.message
    request = MoveBlock.Request(block="red")
    request.position.x, request.position.y = 1.25, 0.6
    moved = graph.call(MoveBlock, topics.MOVE_BLOCK, request)
    assert moved.success, moved.message
    assert abs(block_centres(moved.world)["red"][0] - 1.25) < 1e-6
    assert graph.step([0, 0, 0, 0]).step == 2  # still stepping
    assert process.poll() is None


def test_a_markers_viewer_that_joins_gets_the_latest_world_at_once(nodes: NodeProcesses, probe: GraphProbe) -> None:
    """The markers are built only while someone listens; a viewer joining between their periods (step 3 of every
    5th) gets the world of the latest step at once, not an old latched one."""
    nodes.start("semgoal_sim", "sim_node", params={"scene": "two_blocks", "task": "MC-2", "seed": 3,
                                                    "heartbeat_hz": 0.0})
    graph = Graph(probe)
    probe.spin_until(lambda: graph.commands.get_subscription_count() > 0, 20, "sim_node")
    graph.call(ResetWorld, topics.RESET_WORLD, ResetWorld.Request(task="MC-2", seed=3))
    probe.spin_until(lambda: graph.worlds and graph.worlds[-1].step == 0, 20, "reset world state")
    for _ in range(3):
        world = graph.step([0.0, 0.0, 1.0, 0.0])  # the hand rises 5 cm a step
    arrays: list[MarkerArray] = []
    probe.node.create_subscription(MarkerArray, topics.MARKERS, arrays.append, topics.LATCHED)
    probe.spin_until(lambda: arrays, 10, "markers")
    hand = next(m for m in arrays[-1].markers if m.ns == "gripper").pose.position
    np.testing.assert_allclose([hand.x, hand.y, hand.z], [world.gripper_position.x, world.gripper_position.y,
                                                          world.gripper_position.z], atol=1e-9)


def test_rendering_publishes_camera_frames(nodes: NodeProcesses, probe: GraphProbe) -> None:
    """render:=true: offscreen frames of the scene on /semgoal/camera/image_raw, not a blank image."""
    nodes.start("semgoal_sim", "sim_node", params={"scene": "desk_cleanup", "task": "DC-2", "seed": 1, "render": True,
                                                   "render_hz": 10.0, "render_width": 160, "render_height": 120})
    frames: list[Image] = []
    probe.node.create_subscription(Image, topics.CAMERA_IMAGE, frames.append, topics.CAMERA)
    probe.spin_until(lambda: len(frames) >= 2, 60, "two camera frames")
    frame = frames[-1]
    assert (frame.width, frame.height, frame.encoding) == (160, 120, "rgb8")
    pixels = np.frombuffer(bytes(frame.data), np.uint8).reshape(120, 160, 3)
    assert pixels.std() > 10, "the frame shows a scene, not a flat colour"


def test_predicates_name_and_log_a_block_fallen_off_the_table(nodes: NodeProcesses, probe: GraphProbe) -> None:
    nodes.start("semgoal_sim", "predicate_node")
    world = desk_with_a_fallen_block()
    semantic: list[SemanticState] = []
    probe.node.create_subscription(SemanticState, topics.SEMANTIC_STATE, semantic.append, topics.LATCHED)
    publisher = probe.node.create_publisher(WorldState, topics.WORLD_STATE, topics.STREAM)
    probe.spin_until(lambda: publisher.get_subscription_count() >= 1, 30, "predicate_node listening")
    publisher.publish(conversions.world_state(world, world.snapshot(), "DC-3", episode=1))
    probe.spin_until(lambda: semantic, 20, "semantic state")
    assert list(semantic[-1].fallen) == ["green"]
    probe.spin_until(lambda: "green fell off the table" in nodes.logs(), 10, "the fall logged")
