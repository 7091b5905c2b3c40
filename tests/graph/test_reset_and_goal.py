"""ResetWorld then ExecuteGoal at once, with no client-side wait (as `ros2 service call` then `ros2 action
send_goal` would): the goal names the reset's episode, so it is planned on the new world and never "succeeds"
on the state of the one before. Each MC-2 start has the blocks far apart, so success in 0 steps is false."""

from rclpy.action import ActionClient

from conftest import GraphProbe, NodeProcesses
from semgoal_bringup.graph import NODES, node_params
from semgoal_msgs.action import ExecuteGoal
from semgoal_msgs.msg import GoalRequest, OperatorEvent
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


def test_a_topic_goal_sent_right_after_a_reset_is_judged_on_the_new_world(nodes: NodeProcesses,
                                                                          probe: GraphProbe) -> None:
    """ResetWorld to a desk of another size, then at once the task's goal on the topic (as `ros2 service call`
    then `ros2 topic pub` would), or the goal first: every goal is planned on the new world, none refused against
    the old one's blocks; a refused topic goal is announced with its reason."""
    params = node_params("DC-2", 0, "lockstep")
    for package, executable in NODES[:3]:  # no policy: the plans need only be made
        nodes.start(package, executable, params=params[executable])
    reset = probe.node.create_client(ResetWorld, topics.RESET_WORLD)
    goals = probe.node.create_publisher(GoalRequest, topics.GOAL, 10)
    answers: list[OperatorEvent] = []
    probe.node.create_subscription(OperatorEvent, topics.OPERATOR_EVENTS,
                                   lambda e: e.kind == OperatorEvent.KIND_GOAL and answers.append(e), topics.EVENTS_LIVE)
    probe.spin_until(lambda: reset.service_is_ready() and goals.get_subscription_count() >= 1
                     and probe.node.count_publishers(topics.OPERATOR_EVENTS) >= 2, 60, "the graph")
    probe.spin_for(1.0)  # the planner's events reader matched the sim's writer
    tasks = ["DC-4", "DC-2", "DC-3", "DC-4", "DC-2", "DC-4"]
    for cycle, task in enumerate(tasks):
        assert probe.spin_future(reset.call_async(ResetWorld.Request(task=task, seed=cycle)), 30, "reset").success
        goals.publish(GoalRequest(task=task))
        probe.spin_until(lambda n=cycle + 1: len(answers) >= n, 30, f"the answer to goal {cycle}")
    assert [a.accepted for a in answers] == [True] * len(tasks), [a.answer for a in answers if not a.accepted]
    # the goal even before the reset's call (its answer, and the sim's event, can come after the goal): it fits the
    # scene, not the world of four blocks, so it waits for the next world
    goals.publish(GoalRequest(task="DC-2"))
    assert probe.spin_future(reset.call_async(ResetWorld.Request(task="DC-2", seed=9)), 30, "reset").success
    probe.spin_until(lambda: len(answers) > len(tasks), 30, "the answer to the goal sent before its reset")
    assert answers[-1].accepted, answers[-1].answer
    tasks.append("DC-2")
    goals.publish(GoalRequest(literals=["holding(red)", "holding(green)"]))
    probe.spin_until(lambda: len(answers) > len(tasks), 30, "the refusal")
    assert not answers[-1].accepted and "one hand holds one block at a time" in answers[-1].answer
