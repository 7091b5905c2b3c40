"""`./semgoal demo [--task T] [--seed S]`: the node graph solving a task, printed as it happens.

Starts ``sim_node`` (lockstep) and ``predicate_node`` as separate processes in a fresh ROS domain,
resets the world to the task, and closes the loop over DDS: every world state is answered with an arm
command. Until the planner and the trained policy take their places, the scripted expert chooses the
sub-goals and the commands (clearly a stand-in: the semantic state it is judged on comes from the
predicates node). The last line says ``success`` when the task's goal holds.
"""

from __future__ import annotations

import argparse
import os
import random
import subprocess
import sys
import time
from pathlib import Path

STEP_BUDGET = 1500
"""Control steps allowed per episode (60 s of sim time)."""


def start_nodes(root: Path, scene: str, task: str, seed: int) -> list[subprocess.Popen]:
    run = [str(root / "semgoal"), "run"]
    return [
        subprocess.Popen([*run, "semgoal_sim", "sim_node", "--ros-args", "-p", f"scene:={scene}", "-p",
                          f"task:={task}", "-p", f"seed:={seed}", "-p", "mode:=lockstep", "--log-level", "warn"]),
        subprocess.Popen([*run, "semgoal_sim", "predicate_node", "--ros-args", "--log-level", "warn"]),
    ]


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="semgoal demo", description=__doc__.splitlines()[0])
    parser.add_argument("--task", default="DC-3")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    os.environ["ROS_DOMAIN_ID"] = str(random.randint(1, 100))  # per-run domain: parallel demos never meet

    from semgoal_sim.tasks import get_task

    try:
        task = get_task(args.task)
    except KeyError as error:
        parser.error(str(error.args[0]))
    processes = start_nodes(Path(os.environ["SEMGOAL_ROOT"]), task.scene, task.name, args.seed)
    try:
        return run_episode(task.name, args.seed)
    finally:
        for process in processes:
            process.terminate()
        for process in processes:
            process.wait()


def run_episode(task_name: str, seed: int) -> int:
    import numpy as np
    import rclpy

    from semgoal_msgs.msg import ArmCommand, SemanticState, WorldState
    from semgoal_msgs.srv import ResetWorld
    from semgoal_sim import ros_interfaces as topics
    from semgoal_sim.conversions import world_view
    from semgoal_sim.expert import expert_action
    from semgoal_sim.rollout import expert_next_steps, satisfied
    from semgoal_sim.tasks import get_task
    from semgoal_sim.vocabulary import LAYOUTS

    task = get_task(task_name)
    layout = LAYOUTS[task.scene]
    rclpy.init(domain_id=int(os.environ["ROS_DOMAIN_ID"]))
    node = rclpy.create_node("semgoal_demo")
    worlds: list[WorldState] = []
    semantic: list[SemanticState] = []
    node.create_subscription(WorldState, topics.WORLD_STATE, worlds.append, topics.STREAM)
    node.create_subscription(SemanticState, topics.SEMANTIC_STATE, semantic.append, topics.LATCHED)
    commands = node.create_publisher(ArmCommand, topics.ARM_COMMAND, topics.STREAM)
    reset_client = node.create_client(ResetWorld, topics.RESET_WORLD)

    def spin_until(condition, timeout: float) -> bool:
        deadline = time.monotonic() + timeout
        while not condition():
            if time.monotonic() > deadline:
                return False
            rclpy.spin_once(node, timeout_sec=0.05)
        return True

    try:
        # The reset's world state is published once (volatile stream): the predicates node must be
        # listening before it, or no semantic state would come until the first command.
        ready = lambda: reset_client.service_is_ready() and node.count_subscribers(topics.WORLD_STATE) >= 2  # noqa: E731
        if not spin_until(ready, 30):
            print("sim_node and predicate_node did not come up within 30 s: failure", file=sys.stderr)
            return 1
        future = reset_client.call_async(ResetWorld.Request(task=task.name, seed=seed))
        spin_until(future.done, 30)
        reply = future.result()
        spin_until(lambda: worlds and worlds[-1].step == 0 and worlds[-1].episode == reply.world.episode, 10)
        if not spin_until(lambda: semantic, 10):
            print("no semantic state from predicate_node within 10 s: failure", file=sys.stderr)
            return 1
        goal = task.initial_state(seed)[1]
        print(f"[demo] {task.name} ({task.description}), seed {seed}, ROS domain {os.environ['ROS_DOMAIN_ID']}")
        print(f"[demo] goal: {' & '.join(map(str, goal))}")
        started = time.perf_counter()
        queue: list = []
        while worlds[-1].step < STEP_BUDGET:
            vector = np.array(semantic[-1].vector, dtype=bool)
            if not queue:
                queue = expert_next_steps(goal, layout, vector, world_view(worlds[-1]))
                if not queue:
                    break
                print(f"[demo] step {worlds[-1].step:4d}  next: {', '.join(map(str, queue))}")
            subgoal = queue[0]
            if satisfied(layout, vector, subgoal.literals()):
                print(f"[demo] step {worlds[-1].step:4d}  done: {subgoal}   state: {layout.readable(vector)}")
                queue.pop(0)
                continue
            action = expert_action(subgoal, world_view(worlds[-1]))
            command = ArmCommand(step=worlds[-1].step, gripper=float(action[3]))
            command.displacement.x, command.displacement.y, command.displacement.z = (float(a) for a in action[:3])
            count = len(worlds)
            commands.publish(command)
            # The semantic state comes on change only: one step late at worst, which the closed loop absorbs.
            if not spin_until(lambda count=count: len(worlds) > count, 10):
                print(f"[demo] no world state after step {command.step}: failure", file=sys.stderr)
                return 1
        elapsed = time.perf_counter() - started
        spin_until(lambda: False, 0.6)  # the predicates node republishes at 2 Hz: take the settled state
        vector = np.array(semantic[-1].vector, dtype=bool)
        steps = worlds[-1].step
        print(f"[demo] final state: {layout.readable(vector)}")
        print(f"[demo] {steps} control steps ({steps * 0.04:.1f} s sim time) in {elapsed:.1f} s wall, "
              f"{steps / max(elapsed, 1e-9):.0f} steps/s through the graph")
        if satisfied(layout, vector, goal):
            print(f"{task.name}: success")
            return 0
        print(f"{task.name}: failure (goal not reached within {STEP_BUDGET} steps)")
        return 1
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
