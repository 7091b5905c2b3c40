"""Two robot arms through the graph: the nodes the launch file starts with ``robots:=2`` (a second policy node in
/robot2) bin DC-4 working at once, succeed at rest, never touch, and take the in-process episode's steps; so do they
with every node in one process (``composed``, the second arm's policy node in /robot2 there too), where their
messages to each other are handed over."""

import subprocess

import pytest

from conftest import ROOT, GraphProbe, NodeProcesses
from semgoal_bringup.experiments.episodes import make_agent
from semgoal_bringup.graph import graph_commands, graph_nodes
from semgoal_bringup.study.fluency import recorded_plans
from semgoal_core.names import StepStatus, is_person
from semgoal_core.tasks import TASK_STEP_BUDGET, get_task
from semgoal_ros import interfaces as topics
from semgoal_ros.client import GraphClient

TASK, SEED = "DC-4", 3_000_000


@pytest.mark.timeout(600)
@pytest.mark.parametrize("composed", [False, True], ids=["a process per node", "every node in one"])
def test_two_arms_bin_a_desk_at_once_through_the_graph(nodes: NodeProcesses, probe: GraphProbe, tmp_path,
                                                       composed: bool) -> None:
    expected = make_agent("hierarchical", get_task(TASK).scene, arms=2).run(TASK, SEED)
    assert expected.success and expected.arm_contacts == 0
    commands = graph_commands(graph_nodes(TASK, SEED, "lockstep", robots=2), composed)
    assert len(commands) == (1 if composed else 5)
    for name, command in commands.items():
        nodes.run(name.replace("/", "-"), command)
    client = GraphClient("semgoal_test_operator", watch=False)
    record = tmp_path / "two_arms.mcap"
    try:
        assert client.wait_ready(), nodes.logs()
        both = {("policy", "/"), ("policy", "/robot2")}
        probe.spin_until(lambda: both <= set(probe.node.get_node_names_and_namespaces()), 60, "both policy nodes")
        # the planner gives each arm its blocks by where the world state says they are: it must hear it
        probe.spin_until(lambda: probe.node.count_subscribers(topics.WORLD_STATE) >= 3, 60, "the world state's readers")
        ok, message = client.reset(TASK, SEED)
        assert ok, message
        with client.recording(record):
            result = client.execute(TASK, max_steps=TASK_STEP_BUDGET)
    finally:
        client.close()
    assert result.success, result.message
    assert (result.control_steps, result.replans) == (expected.steps, expected.replans), result.message
    plans = recorded_plans(record)
    at_once = [{step.assignee for step in plan.steps if step.status == StepStatus.ACTIVE} for plan in plans]
    assert {"robot", "robot:2"} in at_once  # both arms had a step under way at the same time
    assert not any(is_person(who) for working in at_once for who in working)
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    with record.open("rb") as stream:
        decoded = [(channel.topic, msg) for _, channel, _, msg in make_reader(
            stream, decoder_factories=[DecoderFactory()]).iter_decoded_messages()]
    contacts = [msg.arm_contacts for topic, msg in decoded if topic == topics.WORLD_STATE]
    assert contacts and max(contacts) == 0
    joints = next(msg.name for topic, msg in decoded if topic == topics.JOINT_STATES)
    assert "robot0:shoulder_pan_joint" in joints and "robot2/robot0:shoulder_pan_joint" in joints
    video = tmp_path / "two_arms.mp4"  # both arms drawn from the recording alone
    rendered = subprocess.run([str(ROOT / "semgoal"), "replay", str(record), "--mp4", str(video)], capture_output=True,
                              text=True, timeout=300, cwd=ROOT)
    assert rendered.returncode == 0 and video.stat().st_size > 0, rendered.stdout + rendered.stderr
