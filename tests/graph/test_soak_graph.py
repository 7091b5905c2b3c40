"""A soak through the four node processes: 100 reset-and-goal cycles, none a false success, and no
node's memory growing.

Each cycle first makes the goal hold in the old world (a person moves red next to green), then resets to a new
MC-2 start (blocks far apart) and at once sends MC-2 for the new episode with a budget of a few control steps,
too few to bring the blocks together. A goal decided on the old world's state would "succeed"; every result
must be a failure for the budget, in the new episode, after exactly the budget's control steps of the world."""

import math
import os
from pathlib import Path

import pytest
from rclpy.action import ActionClient

from conftest import GraphProbe, NodeProcesses
from semgoal_bringup.graph import NODES, node_params
from semgoal_core.vocabulary import THRESHOLDS
from semgoal_msgs.action import ExecuteGoal
from semgoal_msgs.msg import GoalRequest
from semgoal_msgs.srv import MoveBlock, ResetWorld
from semgoal_ros import interfaces as topics
from semgoal_ros.messages import block_centres

TASK, SEED = "MC-2", 4_000_000
CYCLES = int(os.environ.get("SEMGOAL_SOAK_CYCLES", "100"))
BUDGET = 8
SIDES = ((0.07, 0.0), (-0.07, 0.0), (0.0, 0.07), (0.0, -0.07))
"""Offsets (m) from green where red is put: close (centres within 0.10 m), not touching."""
WARM_UP = 10
"""Cycles before the first memory reading: imports, caches and DDS buffers fill in the first ones."""
GROWTH_LIMIT_MB = 8.0
"""Most a node's resident memory may grow from the warm-up to the last cycle (a leak of one plan, state or
episode per cycle would pass this by far over the cycles)."""


def resident_mb(pid: int) -> float:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    raise AssertionError(f"no VmRSS for {pid}")


@pytest.mark.timeout(900)
def test_a_hundred_reset_and_goal_cycles_give_no_false_success_and_keep_memory_flat(nodes: NodeProcesses,
                                                                                      probe: GraphProbe) -> None:
    params = node_params(TASK, SEED, "lockstep")
    for package, executable in NODES:
        nodes.start(package, executable, params=params[executable])
    reset = probe.node.create_client(ResetWorld, topics.RESET_WORLD)
    move = probe.node.create_client(MoveBlock, topics.MOVE_BLOCK)
    action = ActionClient(probe.node, ExecuteGoal, topics.EXECUTE_GOAL)
    probe.spin_until(lambda: reset.service_is_ready() and move.service_is_ready() and action.server_is_ready()
                     and probe.node.count_subscribers(topics.SUBGOAL) >= 1, 60, "the graph")

    memory: dict[str, list[float]] = {name: [] for name, _ in nodes.processes}
    world = None
    for cycle in range(CYCLES):
        if world is not None:  # the goal holds in the old world: red beside green, on whichever side is free
            green, answers = block_centres(world)["green"], []
            for dx, dy in SIDES:
                request = MoveBlock.Request(block="red")
                request.position.x, request.position.y, request.position.z = green[0] + dx, green[1] + dy, green[2]
                answers.append(probe.spin_future(move.call_async(request), 30, "the move"))
                if answers[-1].success:
                    break
            assert answers[-1].success, f"cycle {cycle}: {[answer.message for answer in answers]}"
            now = block_centres(answers[-1].world)
            assert math.dist(now["red"][:2], now["green"][:2]) < THRESHOLDS.close_distance
        world = probe.spin_future(reset.call_async(ResetWorld.Request(task=TASK, seed=SEED + cycle)), 30, "the reset").world
        handle = probe.send_goal(action, ExecuteGoal.Goal(goal=GoalRequest(task=TASK), max_steps=BUDGET, episode=world.episode))
        result = probe.spin_future(handle.get_result_async(), 60, "the goal's result").result
        assert not result.success, f"cycle {cycle}: a false success ({result.message}, {result.control_steps} steps)"
        assert result.episode == world.episode and "budget" in result.message, (cycle, result)
        assert result.control_steps == BUDGET, (cycle, result.control_steps)  # the new world's steps, all of them
        if cycle in (WARM_UP, CYCLES - 1):
            for name, process in nodes.processes:
                memory[name].append(resident_mb(process.pid))
    grown = {name: round(readings[-1] - readings[0], 1) for name, readings in memory.items()}
    print(f"\n{CYCLES} cycles, resident memory (MB) after cycle {WARM_UP} and {CYCLES - 1}: {memory}; grown {grown}")
    assert all(growth <= GROWTH_LIMIT_MB for growth in grown.values()), grown
