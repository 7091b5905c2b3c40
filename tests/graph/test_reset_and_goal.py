"""ResetWorld then ExecuteGoal at once, with no client-side wait (as `ros2 service call` then `ros2 action
send_goal` would): the goal names the reset's episode, so it is planned on the new world and never "succeeds"
on the state of the one before. Each MC-2 start has the blocks far apart, so success in 0 steps is false."""

from rclpy.action import ActionClient

from conftest import GraphProbe, NodeProcesses
from semgoal_bringup.graph import NODES, node_params
from semgoal_msgs.action import ExecuteGoal
from semgoal_msgs.msg import GoalRequest
from semgoal_msgs.srv import ResetWorld
from semgoal_ros import interfaces as topics

TASK, SEED, CYCLES = "MC-2", 3_000_000, 8


def test_reset_and_goal_compose_without_a_client_wait(nodes: NodeProcesses, probe: GraphProbe) -> None:
    params = node_params(TASK, SEED, "lockstep")
    for package, executable in NODES:
        nodes.start(package, executable, params=params[executable])
    reset = probe.node.create_client(ResetWorld, topics.RESET_WORLD)
    action = ActionClient(probe.node, ExecuteGoal, topics.EXECUTE_GOAL)
    probe.spin_until(lambda: reset.service_is_ready() and action.server_is_ready()
                     and probe.node.count_subscribers(topics.SUBGOAL) >= 1, 60, "the graph")
    outcomes = []
    for cycle in range(CYCLES):
        world = probe.spin_future(reset.call_async(ResetWorld.Request(task=TASK, seed=SEED + cycle)), 30, "reset").world
        handle = probe.send_goal(action, ExecuteGoal.Goal(goal=GoalRequest(task=TASK), max_steps=600, episode=world.episode))
        result = probe.spin_future(handle.get_result_async(), 120, "the goal's result").result
        assert result.episode == world.episode, (cycle, result.episode, world.episode)
        assert not (result.success and result.control_steps == 0), f"cycle {cycle}: success in 0 steps: {result.message}"
        outcomes.append(result.success)
    assert sum(outcomes) >= CYCLES - 1, outcomes
