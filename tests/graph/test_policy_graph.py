"""sim_node, predicate_node and policy_node as processes: the test plays the planner (it answers every
semantic state with the sub-goal, stamped with the state's episode and step) and sets pick(red); the shipped actor
achieves it in lockstep within the step budget. Without an active sub-goal, or without the planner's
answer for the current step or the one before, the lockstep world waits (the arm holds still)."""

import numpy as np

from conftest import GraphProbe, NodeProcesses
from semgoal_msgs.msg import Predicate, SemanticState, SubGoal, WorldState
from semgoal_msgs.srv import ResetWorld
from semgoal_ros import interfaces as topics

STEP_BUDGET = 50


def test_policy_picks_red_in_lockstep(nodes: NodeProcesses, probe: GraphProbe) -> None:
    nodes.start("semgoal_sim", "sim_node", params={"scene": "two_blocks", "task": "MC-2", "seed": 11})
    nodes.start("semgoal_sim", "predicate_node")
    nodes.start("semgoal_policy", "policy_node", params={"scene": "two_blocks"})
    worlds: list[WorldState] = []
    semantic: list[SemanticState] = []
    subgoals = probe.node.create_publisher(SubGoal, topics.SUBGOAL, topics.PER_STEP)
    planner = {"answers": True, "subgoal": SubGoal(status="empty")}  # nothing active: the arm holds still

    def answer(state: SemanticState) -> None:
        semantic.append(state)
        if planner["answers"]:
            planner["subgoal"].step, planner["subgoal"].episode = state.step, state.episode
            subgoals.publish(planner["subgoal"])

    probe.node.create_subscription(WorldState, topics.WORLD_STATE, worlds.append, topics.STREAM)
    probe.node.create_subscription(SemanticState, topics.SEMANTIC_STATE, answer, topics.LATCHED)
    probe.spin_until(lambda: probe.node.count_subscribers(topics.WORLD_STATE) >= 3, 40, "predicates and policy listening")
    probe.spin_until(lambda: subgoals.get_subscription_count() >= 1, 20, "policy subscribed to sub-goals")

    reset = probe.node.create_client(ResetWorld, topics.RESET_WORLD)
    probe.spin_until(reset.service_is_ready, 20, "reset service")
    assert probe.spin_future(reset.call_async(ResetWorld.Request(task="MC-2", seed=11)), 20, "reset").success
    probe.spin_until(lambda: worlds and worlds[-1].step == 0, 20, "reset world state")
    probe.spin_for(1.5)  # heartbeats repeat step 0: no command came for it
    assert all(w.step == 0 for w in worlds)
    grip = [np.array([w.gripper_position.x, w.gripper_position.y, w.gripper_position.z]) for w in worlds]
    assert max(np.linalg.norm(g - grip[0]) for g in grip) < 0.005

    start, episode = worlds[-1].step, worlds[-1].episode
    pick_red = SubGoal(index=0, action="pick(red)", status="active", assignee="robot", step=start + 5, episode=episode,
                       goal=[Predicate(name="holding", args=["red"], value=True)])
    planner["answers"] = False
    subgoals.publish(pick_red)  # decided for a step the world has not reached: the policy waits
    probe.spin_for(1.5)
    assert worlds[-1].step == start
    pick_red.step, pick_red.episode = start, episode + 1
    subgoals.publish(pick_red)  # decided for this step of another episode (a reset world): it waits too
    probe.spin_for(1.5)
    assert worlds[-1].step == start
    pick_red.episode = episode
    subgoals.publish(pick_red)  # decided for this step: the policy acts on it, and on the next step too
    probe.spin_for(1.5)  # (one step of decision latency), then waits for a decision on that next step
    assert worlds[-1].step == start + 2
    pick_red.step = start + 2
    planner.update(answers=True, subgoal=pick_red)
    subgoals.publish(pick_red)

    def holding_red() -> bool:
        return bool(semantic) and any(p.name == "holding" and p.args == ["red"] and p.value for p in semantic[-1].predicates)

    probe.spin_until(lambda: holding_red() or worlds[-1].step - start > STEP_BUDGET, 60, "pick(red) or budget")
    assert holding_red(), f"not holding red after {worlds[-1].step - start} steps"
    assert semantic[-1].step - start <= STEP_BUDGET
