"""sim_node, predicate_node and policy_node as processes: the test sets the sub-goal pick(red) and the
shipped actor achieves it in lockstep within the step budget; without an active sub-goal the lockstep
world waits (the arm holds still)."""

import numpy as np

from conftest import GraphProbe, NodeProcesses
from semgoal_msgs.msg import Predicate, SemanticState, SubGoal, WorldState
from semgoal_msgs.srv import ResetWorld
from semgoal_sim import ros_interfaces as topics

STEP_BUDGET = 50


def test_policy_picks_red_in_lockstep(nodes: NodeProcesses, probe: GraphProbe) -> None:
    nodes.start("semgoal_sim", "sim_node", params={"scene": "two_blocks", "task": "MC-2", "seed": 11})
    nodes.start("semgoal_sim", "predicate_node")
    nodes.start("semgoal_policy", "policy_node", params={"scene": "two_blocks"})
    worlds: list[WorldState] = []
    semantic: list[SemanticState] = []
    probe.node.create_subscription(WorldState, topics.WORLD_STATE, worlds.append, topics.STREAM)
    probe.node.create_subscription(SemanticState, topics.SEMANTIC_STATE, semantic.append, topics.LATCHED)
    subgoals = probe.node.create_publisher(SubGoal, topics.SUBGOAL, topics.LATCHED)
    probe.spin_until(lambda: probe.node.count_subscribers(topics.WORLD_STATE) >= 3, 40, "predicates and policy listening")
    probe.spin_until(lambda: subgoals.get_subscription_count() >= 1, 20, "policy subscribed to sub-goals")

    subgoals.publish(SubGoal(status="empty"))  # nothing active: the arm holds still
    reset = probe.node.create_client(ResetWorld, topics.RESET_WORLD)
    probe.spin_until(reset.service_is_ready, 20, "reset service")
    assert probe.spin_future(reset.call_async(ResetWorld.Request(task="MC-2", seed=11)), 20, "reset").success
    probe.spin_until(lambda: worlds and worlds[-1].step == 0, 20, "reset world state")
    probe.spin_for(1.5)  # heartbeats repeat step 0: no command came for it
    assert all(w.step == 0 for w in worlds)
    grip = [np.array([w.gripper_position.x, w.gripper_position.y, w.gripper_position.z]) for w in worlds]
    assert max(np.linalg.norm(g - grip[0]) for g in grip) < 0.005

    start = worlds[-1].step
    subgoals.publish(SubGoal(index=0, action="pick(red)", status="active", assignee="robot",
                             goal=[Predicate(name="holding", args=["red"], value=True)]))

    def holding_red() -> bool:
        return bool(semantic) and any(p.name == "holding" and p.args == ["red"] and p.value for p in semantic[-1].predicates)

    probe.spin_until(lambda: holding_red() or worlds[-1].step - start > STEP_BUDGET, 60, "pick(red) or budget")
    assert holding_red(), f"not holding red after {worlds[-1].step - start} steps"
    assert semantic[-1].step - start <= STEP_BUDGET
