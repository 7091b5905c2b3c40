"""The sim's /clock (0.04 s per control step, never backwards across a reset), nodes on use_sim_time
stamping with it, and every node's health on /diagnostics."""

from diagnostic_msgs.msg import DiagnosticArray
from rosgraph_msgs.msg import Clock
from test_sim_graph import Graph

from conftest import GraphProbe, NodeProcesses
from semgoal_core.layout import CONTROL_DT
from semgoal_msgs.msg import GoalRequest, Plan
from semgoal_msgs.srv import ResetWorld
from semgoal_ros import interfaces as topics
from semgoal_ros.diagnostics import TOPIC


def seconds(stamp) -> float:
    return stamp.sec + stamp.nanosec * 1e-9


def test_the_sim_clock_drives_use_sim_time_and_every_node_reports_its_health(nodes: NodeProcesses, probe: GraphProbe) -> None:
    nodes.start("semgoal_sim", "sim_node", params={"scene": "desk_cleanup", "task": "DC-2", "seed": 1})
    nodes.start("semgoal_sim", "predicate_node")
    nodes.start("semgoal_planner", "planner_node", params={"scene": "desk_cleanup", "use_sim_time": True})
    nodes.start("semgoal_policy", "policy_node", params={"scene": "desk_cleanup"})
    graph, ticks, health, plans = Graph(probe), [], {}, []
    probe.node.create_subscription(Clock, topics.CLOCK, lambda m: ticks.append(seconds(m.clock)), 10)
    probe.node.create_subscription(DiagnosticArray, TOPIC, lambda m: health.update({s.name: s for s in m.status}), 10)
    probe.node.create_subscription(Plan, topics.PLAN, plans.append, topics.LATCHED)
    probe.spin_until(lambda: probe.node.count_subscribers(topics.WORLD_STATE) >= 3, 60, "the nodes")

    reset = graph.call(ResetWorld, topics.RESET_WORLD, ResetWorld.Request(task="DC-2", seed=1))
    probe.spin_until(lambda: graph.worlds and graph.worlds[-1].episode == reset.world.episode, 20, "the reset world")
    before = seconds(graph.worlds[-1].header.stamp)
    for _ in range(3):
        world = graph.step([0.0, 0.0, 0.0, 0.0])
    assert abs(seconds(world.header.stamp) - before - 3 * CONTROL_DT) < 1e-6
    probe.spin_until(lambda: ticks and abs(ticks[-1] - seconds(world.header.stamp)) < 1e-9, 5, "/clock at the last step")
    graph.call(ResetWorld, topics.RESET_WORLD, ResetWorld.Request(task="DC-2", seed=2))
    probe.spin_until(lambda: ticks[-1] > seconds(world.header.stamp), 5, "the clock to go on across a reset")
    assert ticks == sorted(ticks)

    goals = probe.node.create_publisher(GoalRequest, topics.GOAL, 10)
    probe.spin_until(lambda: goals.get_subscription_count() > 0, 30, "the planner's goal topic")
    goals.publish(GoalRequest(task="DC-2"))
    probe.spin_until(lambda: plans and plans[-1].steps, 30, "a plan")
    assert seconds(plans[-1].header.stamp) <= ticks[-1] + 1e-9  # stamped on the sim clock, not the wall clock

    def values() -> dict[str, dict[str, str]]:
        return {name: {kv.key: kv.value for kv in status.values} for name, status in health.items()}

    probe.spin_until(lambda: {"semgoal/sim", "semgoal/planner", "semgoal/policy"} <= set(health)
                     and "goals planned" in values()["semgoal/planner"], 10, "/diagnostics after the goal")
    values = values()
    assert "steps per second" in values["semgoal/sim"] and "sim time s" in values["semgoal/sim"]
    assert "goal planning p99 ms" in values["semgoal/planner"] and values["semgoal/planner"]["goals planned"] == "1"
    assert "mode" in values["semgoal/policy"]
