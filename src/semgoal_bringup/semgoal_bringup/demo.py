"""`./semgoal demo [--task T] [--seed S] [--gif FILE]`: the whole node graph solving a task.

Starts sim (lockstep), predicates, planner and policy as separate processes in a fresh ROS domain,
resets the world to the task, sends the goal through the planner's ExecuteGoal action, and prints as
it happens the plan, each sub-goal starting and finishing, re-plans and the result. It writes a GIF
of the episode with the active sub-goal on every frame. The last line says ``success`` when the
task's goal holds.
"""

from __future__ import annotations

import argparse
import os
import random
import sys
import time
from pathlib import Path

READY_TIMEOUT_S = 60.0
EPISODE_TIMEOUT_S = 300.0


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="semgoal demo", description=__doc__.splitlines()[0])
    parser.add_argument("--task", default="DC-3")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--models", default="", help="folder of exported actors (SCENE/actor.pt); default: the shipped ones")
    parser.add_argument("--gif", type=Path, help="where to write the episode GIF (default results/demo-TASK.gif)")
    parser.add_argument("--no-gif", action="store_true")
    args = parser.parse_args(argv)
    os.environ["ROS_DOMAIN_ID"] = str(random.randint(1, 100))  # per-run domain: parallel demos never meet

    from semgoal_bringup.graph import start_graph, stop_graph
    from semgoal_sim.tasks import get_task

    try:
        task = get_task(args.task)
    except KeyError as error:
        parser.error(str(error.args[0]))
    gif = None if args.no_gif else args.gif or Path("results") / f"demo-{task.name}.gif"
    processes = start_graph(task.name, args.seed, models=args.models)
    try:
        return DemoClient(task.name, args.seed).run(gif)
    finally:
        stop_graph(processes)


class DemoClient:
    """The operator's side: reset, send the goal, print progress, record frames for the GIF."""

    def __init__(self, task_name: str, seed: int) -> None:
        import rclpy
        from rclpy.action import ActionClient
        from sensor_msgs.msg import JointState

        from semgoal_msgs.action import ExecuteGoal
        from semgoal_msgs.msg import SemanticState, SubGoal, WorldState
        from semgoal_msgs.srv import ResetWorld
        from semgoal_sim import ros_interfaces as topics
        from semgoal_sim.tasks import get_task

        self.rclpy, self.topics, self.task, self.seed = rclpy, topics, get_task(task_name), seed
        rclpy.init(domain_id=int(os.environ["ROS_DOMAIN_ID"]))
        self.node = node = rclpy.create_node("semgoal_demo")
        self.world: WorldState | None = None
        self.joints: JointState | None = None
        self.semantic: SemanticState | None = None
        self.caption = ""
        self.frames: list = []
        node.create_subscription(WorldState, topics.WORLD_STATE, self.world_callback, topics.STREAM)
        node.create_subscription(JointState, topics.JOINT_STATES, self.joints_callback, topics.STREAM)
        node.create_subscription(SemanticState, topics.SEMANTIC_STATE, self.semantic_callback, topics.LATCHED)
        node.create_subscription(SubGoal, topics.SUBGOAL, self.subgoal_callback, topics.LATCHED)
        self.reset_client = node.create_client(ResetWorld, topics.RESET_WORLD)
        self.action = ActionClient(node, ExecuteGoal, topics.EXECUTE_GOAL)
        self.ExecuteGoal, self.ResetWorld = ExecuteGoal, ResetWorld
        self.seen_steps: dict[int, str] = {}
        self.plan_revision = -1

    # -- subscriptions -------------------------------------------------------------------------------
    def world_callback(self, msg) -> None:
        self.world = msg
        if msg.step % 2 == 0 and self.joints is not None:
            from semgoal_bringup.episode_gif import Frame

            poses = {b.name: (b.pose.position.x, b.pose.position.y, b.pose.position.z, b.pose.orientation.w,
                              b.pose.orientation.x, b.pose.orientation.y, b.pose.orientation.z) for b in msg.blocks}
            self.frames.append(Frame(int(msg.step), dict(zip(self.joints.name, self.joints.position, strict=True)),
                                     poses, self.caption))

    def joints_callback(self, msg) -> None:
        self.joints = msg

    def semantic_callback(self, msg) -> None:
        self.semantic = msg

    def subgoal_callback(self, msg) -> None:
        self.caption = msg.action if msg.status == "active" else f"({msg.status})"

    # -- the episode ---------------------------------------------------------------------------------
    def spin_until(self, condition, timeout: float) -> bool:
        deadline = time.monotonic() + timeout
        while not condition():
            if time.monotonic() > deadline:
                return False
            self.rclpy.spin_once(self.node, timeout_sec=0.05)
        return True

    def log(self, text: str) -> None:
        step = self.world.step if self.world else 0
        print(f"[demo] step {step:4d}  {text}", flush=True)

    def feedback_callback(self, message) -> None:
        plan = message.feedback.plan
        if plan.revision != self.plan_revision and plan.steps and plan.status in ("executing", "awaiting_approval"):
            if self.plan_revision < 0 or plan.replans:
                what = "plan" if self.plan_revision < 0 else f"re-plan {plan.replans}"
                self.log(f"{what}: " + ", ".join(f"{s.index}. {s.action}" for s in plan.steps))
            self.plan_revision = plan.revision
        for step in plan.steps:
            if self.seen_steps.get(step.index) != f"{step.action}:{step.status}" and step.status in ("active", "done"):
                self.seen_steps[step.index] = f"{step.action}:{step.status}"
                verb = "started" if step.status == "active" else "done   "
                self.log(f"{verb} {step.index}. {step.action}")

    def run(self, gif: Path | None) -> int:
        topics = self.topics
        try:
            ready = lambda: (self.reset_client.service_is_ready() and self.action.server_is_ready()  # noqa: E731
                             and self.node.count_subscribers(topics.WORLD_STATE) >= 3
                             and self.node.count_subscribers(topics.SUBGOAL) >= 2)
            if not self.spin_until(ready, READY_TIMEOUT_S):
                print(f"the four nodes did not come up within {READY_TIMEOUT_S:.0f} s: failure", file=sys.stderr)
                return 1
            future = self.reset_client.call_async(self.ResetWorld.Request(task=self.task.name, seed=self.seed))
            self.spin_until(future.done, 30)
            reply = future.result()
            if not reply.success:
                print(f"reset failed: {reply.message}", file=sys.stderr)
                return 1
            self.spin_until(lambda: self.semantic is not None and self.semantic.step == 0, 10)
            self.spin_until(lambda: False, 0.5)  # the planner sees the same latched state
            print(f"[demo] {self.task.name} ({self.task.description}), seed {self.seed}, "
                  f"ROS domain {os.environ['ROS_DOMAIN_ID']}", flush=True)
            started = time.perf_counter()
            goal = self.ExecuteGoal.Goal()
            goal.goal.task = self.task.name
            sent = self.action.send_goal_async(goal, feedback_callback=self.feedback_callback)
            self.spin_until(sent.done, 10)
            result_future = sent.result().get_result_async()
            if not self.spin_until(result_future.done, EPISODE_TIMEOUT_S):
                print(f"no result within {EPISODE_TIMEOUT_S:.0f} s: failure", file=sys.stderr)
                return 1
            result = result_future.result().result
            elapsed = time.perf_counter() - started
            self.log(f"result: {result.message} ({result.replans} re-plans)")
            print(f"[demo] {result.control_steps} control steps ({result.sim_time:.1f} s sim time) in {elapsed:.1f} s "
                  f"wall: {result.control_steps / max(elapsed, 1e-9):.0f} steps/s through the graph", flush=True)
            if gif is not None and self.frames:
                from semgoal_bringup.episode_gif import write_gif

                write_gif(self.task.scene, self.task.n_blocks, self.frames, gif)
                print(f"[demo] episode GIF: {gif} ({len(self.frames)} frames)", flush=True)
            print(f"{self.task.name}: {'success' if result.success else 'failure'}")
            return 0 if result.success else 1
        finally:
            self.node.destroy_node()
            self.rclpy.try_shutdown()
