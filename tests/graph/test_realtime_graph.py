"""The four node processes in realtime mode: the sim steps on its own 25 Hz clock and the policy acts at
its rate on the latest world state, so nothing waits for anyone. The operator resets the world and the
planner's GetPlan confirms it (the world goes on stepping meanwhile, the arm holding still), then MC-2
is solved within its step budget."""

from conftest import NodeProcesses
from semgoal_bringup.graph import NODES, node_params
from semgoal_core.layout import CONTROL_DT
from semgoal_core.tasks import TASK_STEP_BUDGET
from semgoal_ros.client import GraphClient

TASK, SEED = "MC-2", 3_000_000


def test_realtime_graph_resets_and_solves_mc2(nodes: NodeProcesses) -> None:
    params = node_params(TASK, SEED, "realtime")
    for package, exe in NODES:
        nodes.start(package, exe, params=params[exe])
    client = GraphClient("semgoal_test_operator", watch=False, lockstep=False)
    try:
        assert client.wait_ready(), "the four nodes did not come up"
        ok, message = client.reset(TASK, SEED)
        assert ok, message
        result = client.execute(TASK, max_steps=TASK_STEP_BUDGET, timeout=60)
    finally:
        client.close()
    assert result.success, result.message
    assert 0 < result.control_steps < TASK_STEP_BUDGET
    assert abs(result.sim_time - result.control_steps * CONTROL_DT) < 1e-6


def test_the_arm_stops_when_commands_stop_coming(nodes: NodeProcesses, probe) -> None:
    """A policy that dies mid-motion: the realtime sim applies its last command for a few periods, then holds."""
    from semgoal_msgs.msg import ArmCommand, WorldState
    from semgoal_ros import interfaces as topics
    from semgoal_sim.sim_node import WATCHDOG_PERIODS

    nodes.start("semgoal_sim", "sim_node", params={"scene": "two_blocks", "task": TASK, "seed": SEED, "mode": "realtime"})
    worlds: list[WorldState] = []
    probe.node.create_subscription(WorldState, topics.WORLD_STATE, worlds.append, topics.STREAM)
    commands = probe.node.create_publisher(ArmCommand, topics.ARM_COMMAND, topics.STREAM)
    probe.spin_until(lambda: worlds and commands.get_subscription_count() > 0, 30, "the realtime sim")
    start = worlds[-1].gripper_position.y
    command = ArmCommand(gripper=0.0)
    command.displacement.y = 0.2  # 1 cm per control step, sent once
    commands.publish(command)
    probe.spin_until(lambda: worlds[-1].gripper_position.y - start > 0.005, 5, "the arm to move")
    probe.spin_for(WATCHDOG_PERIODS * CONTROL_DT + 1.5)  # the watchdog's periods, then time to come to rest
    y = [w.gripper_position.y for w in worlds[-10:]]
    assert max(y) - min(y) < 0.002, y  # still: no longer driven by the stale command
    assert y[-1] - start < 0.01 * (WATCHDOG_PERIODS + 6), y[-1] - start  # it stopped within a few periods
