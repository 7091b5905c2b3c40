"""policy_node: world state and the active sub-goal in, arm commands out.

Lockstep: one ArmCommand per world state. The planner's decision on step k (the sub-goal message carries
the episode and step it decided on) is what the policy follows at step k + 1: one control step of
decision latency, as the nodes have in realtime, and the in-process episode keeps the same rule, so
the graph takes exactly its steps. The actor then runs as soon as a world state comes, while the
predicates and the planner work on the same state, instead of after them. At an episode's first step,
or when the decision on the step before names no sub-goal, the policy waits for the decision on the
current step; without an active sub-goal no command goes out and the world waits, except while the
goal settles (status ``settling``): then the arm retreats clear of the blocks, so the world steps on and comes
to rest.
Realtime: a command at ``rate_hz`` with the latest sub-goal; once that is achieved (its literals held at
rest for ``SETTLE_STEPS`` steps, the planner's rule) the arm holds still until the planner names the
next. It never publishes NaN or values outside [-1, 1].
"""

from __future__ import annotations

import contextlib
import time
from typing import Any

import numpy as np
import torch
from rclpy.node import Node

from semgoal_core.arms import MAX_ARMS
from semgoal_core.layout import CONTROL_DT
from semgoal_core.lockstep import followed_decision
from semgoal_core.names import Mode, PlanStatus, StepStatus
from semgoal_core.settling import held_blocks_asked
from semgoal_core.vocabulary import SCENES, Literal
from semgoal_msgs.msg import ArmCommand, SubGoal, WorldState
from semgoal_policy.actor import LayoutMismatchError
from semgoal_policy.controller import ACTION_MODES, HOLD, Idle, SubgoalController, VocabularyError
from semgoal_policy.expert_actor import EXPERT
from semgoal_ros import interfaces as topics
from semgoal_ros import messages
from semgoal_ros.diagnostics import OK, WARN, Counters, Diagnostics, Latencies
from semgoal_ros.parameters import Param, ParameterValueError, apply_changes, declare

PARAMS = (
    Param("scene", "desk_cleanup", "the scene the actor was trained for", choices=tuple(SCENES)),
    Param("model_dir", "", "an exported actor's folder (empty: the shipped one for the scene; 'expert': the scripted "
          "expert, the actors' teacher)"),
    Param("mode", Mode.LOCKSTEP.value, "must match the sim's: lockstep | realtime", choices=tuple(Mode)),
    Param("rate_hz", 25.0, "realtime mode: commands per second", low=0.1, high=1000.0, runtime=True),
    Param("world_topic", topics.WORLD_STATE, "the world state the actor reads: the sim's, or the camera's "
          f"perception ({topics.PERCEIVED_WORLD})", choices=(topics.WORLD_STATE, topics.PERCEIVED_WORLD)),
    Param("arm", 1, "the arm this node drives: 1, or 2 for the second Fetch across the table (its topics under "
          "/semgoal/robot2/)", low=1, high=MAX_ARMS),
    Param("arms", 1, "robot arms at the table: with 2, while a plan is under way an arm without a step of its own "
          "answers each step holding still (an empty hand draws back to its side), so the other's steps go on",
          low=1, high=MAX_ARMS),
    Param("action_mode", "sample", "sample: SAC's Gaussian, seeded per task and step | mean: the deterministic actor",
          choices=ACTION_MODES, runtime=True),
    Param("threads", 1, "torch threads for the actor: a batch of one is fastest on one, and a second thread's OpenMP "
          "worker spins on a core between commands, a core the graph's other nodes want", low=1, high=64),
)
IDLING = {StepStatus.SETTLING: Idle.RETREAT, PlanStatus.SUCCEEDED: Idle.RETREAT, StepStatus.WAITING_FOR_HUMAN: Idle.MAKE_ROOM}
"""What the arm does on a sub-goal status without a step for it: it retreats clear of the blocks once the goal holds,
keeping what the goal asks it to hold, and makes room while others work; on any other (paused, failed) it holds
still."""
DECISIONS_KEPT = 8
"""Decisions remembered: the step before the world's and its own are the ones used, a few more cover a
reordering between the two topics."""


class PolicyNode(Node):
    def __init__(self, **options: Any) -> None:
        """``options``: rclpy ``Node``'s (a namespace, parameter overrides: ``graph_node`` composes nodes so)."""
        super().__init__("policy", **options)
        values = declare(self, PARAMS)
        torch.set_num_threads(values["threads"])
        self.mode, scene = values["mode"], values["scene"]
        arm, self.arms = values["arm"] - 1, values["arms"]
        if arm >= self.arms:
            raise ParameterValueError(f"policy: arm {arm + 1} needs arms >= {arm + 1}")
        try:
            self.controller = SubgoalController(scene, values["model_dir"] or None, values["action_mode"], arm,
                                                shared=self.arms > 1)
        except (FileNotFoundError, ValueError, LayoutMismatchError) as error:  # no actor, or one of another layout
            raise ParameterValueError(f"policy: {error}") from None
        self.get_logger().info(f"{scene}: the scripted expert drives the arm (model_dir: expert)"
                               if self.controller.meta.get("actor") == EXPERT else
                               f"actor for {scene} from {self.controller.model_dir}: "
                               f"{self.controller.meta.get('env_steps')} training steps, "
                               f"eval {self.controller.meta.get('final_eval', {}).get('per_kind')}")
        self.publisher = self.create_publisher(ArmCommand, topics.arm_topic(topics.ARM_COMMAND, arm), topics.RECORDING)
        self.create_subscription(WorldState, topics.arm_topic(values["world_topic"], arm), self.world_callback,
                                 topics.STREAM)
        self.create_subscription(SubGoal, topics.arm_topic(topics.SUBGOAL, arm), self.subgoal_callback, topics.PER_STEP)
        self.latest: WorldState | None = None
        self.decisions: dict[tuple[int, int], SubGoal] = {}
        """The planner's latest answer per (episode, control step), the last ``DECISIONS_KEPT``."""
        self.answered: tuple[int, int] | None = None
        self.answered_at = 0.0
        # realtime: act at rate_hz. lockstep: the world waits for each command, so the timer only resends
        # one that may have been lost
        self.timer = self.create_timer(1.0 / values["rate_hz"] if self.mode == Mode.REALTIME else 1.0,
                                       self.timer_callback)
        self.subgoal_key: tuple | None = None
        self.counters, self.acting = Counters(), Latencies()
        self.diagnostics = Diagnostics(self, self.health)
        apply_changes(self, PARAMS, self.apply_parameter)

    def health(self):
        """Commands sent, invalid sub-goals, and the actor's latency per command (p99 against the 40 ms step)."""
        latency = self.acting.summary("actor")
        slow = latency.get("actor p99 ms", 0.0) > 1000 * CONTROL_DT
        message = f"{self.counters['commands']} commands, actor p99 {latency.get('actor p99 ms', '-')} ms"
        return (WARN if slow else OK), message, {"mode": self.mode, "sub-goal": self.subgoal_key[1] if self.subgoal_key else "",
                                                 **self.counters, **latency}

    def apply_parameter(self, name: str, value) -> None:
        """A change made while running: the realtime command rate, or mean / sampled actions."""
        if name == "rate_hz" and self.mode == Mode.REALTIME:
            self.timer.timer_period_ns = int(1e9 / value)
        elif name == "action_mode":
            self.controller.mode = value

    def subgoal_callback(self, msg: SubGoal) -> None:
        if self.mode == Mode.REALTIME:
            self.follow(msg)
            return
        self.decisions[(msg.episode, msg.step)] = msg
        if len(self.decisions) > DECISIONS_KEPT:
            del self.decisions[next(iter(self.decisions))]
        self.answer_lockstep()

    def follow(self, msg: SubGoal) -> None:
        """Condition the actor on a sub-goal message's goal (most messages repeat the last one)."""
        key = (msg.status, msg.action, tuple((p.name, tuple(p.args), p.value) for p in msg.goal))
        if key == self.subgoal_key:
            return
        self.subgoal_key = key
        literals = [messages.literal(p) for p in msg.goal]
        try:
            if msg.status == StepStatus.ACTIVE:
                self.controller.set_subgoal(literals)
            else:  # the plan's goal, when it holds: the blocks it asks to be held stay in the hand
                self.controller.set_subgoal([], IDLING.get(msg.status, Idle.HOLD), keep=self.asked_held(literals))
        except VocabularyError as error:
            self.controller.set_subgoal([])
            self.get_logger().warn(f"holding still: sub-goal {msg.action!r} is not valid here: {error}")
            self.counters["invalid sub-goals"] += 1
            return
        text = msg.action if msg.status == StepStatus.ACTIVE else f"(none: {msg.status or 'no plan'})"
        self.get_logger().info(f"sub-goal {text}")

    def asked_held(self, literals: list[Literal]) -> set[str]:
        """The blocks a goal's literals ask to be held; literals that do not fit the scene are left out."""
        fitting = []
        for literal in literals:
            with contextlib.suppress(VocabularyError):
                fitting.append(self.controller.layout.validate(literal))
        return held_blocks_asked(fitting)

    def world_callback(self, msg: WorldState) -> None:
        self.latest = msg
        if self.mode == Mode.LOCKSTEP:
            self.answer_lockstep()

    def timer_callback(self) -> None:
        if self.latest is None:
            return
        if self.mode == Mode.REALTIME:
            with self.acting.time():
                action = self.decide_realtime(self.latest)
            self.publish_command(self.latest, action)
        elif time.monotonic() - self.answered_at > 1.0:
            self.answered = None  # lockstep: the command for this step may have been lost; send it again
            self.answer_lockstep()

    def decide_realtime(self, msg: WorldState) -> np.ndarray:
        """The command for a world state; hold still once the sub-goal is confirmed (the planner names the next)."""
        try:
            confirmed = self.controller.goal is not None and self.controller.confirmed(
                msg.step, messages.semantic_vector(msg), messages.moving(msg))
        except (KeyError, ValueError) as error:  # a world state of another scene, or malformed: hold still
            self.get_logger().warn(f"holding still on a world state that does not fit: {error}", throttle_duration_sec=5.0)
            return HOLD.copy()
        if confirmed:
            return self.controller.hold(np.asarray(msg.observation, dtype=np.float32))
        return self.controller.act(msg.observation, (msg.seed, msg.step))

    def answer_lockstep(self) -> None:
        """Act once on the latest world state, on the sub-goal :func:`followed_decision` picks from the
        planner's decisions on that step and the one before; wait while it picks none."""
        msg = self.latest
        if msg is None or (msg.episode, msg.step) == self.answered:
            return
        decision = followed_decision(self.decisions, msg.episode, msg.step)
        if decision is None and not self.others_work(msg):
            return
        with self.acting.time():
            if decision is None:  # the plan names no step for this arm now: it holds while the other works
                action = self.controller.hold(np.asarray(msg.observation, dtype=np.float32))
            else:
                self.follow(decision)  # a settling decision: no goal, the controller's command is to retreat
                action = self.controller.act(msg.observation, (msg.seed, msg.step))
        self.publish_command(msg, action)

    def others_work(self, msg: WorldState) -> bool:
        """With two arms: the planner's answer on this state is a plan under way with no step for this arm (another
        agent works), so the world must not wait for this arm's command."""
        decision = self.decisions.get((msg.episode, msg.step))
        return self.arms > 1 and decision is not None and decision.status == StepStatus.WAITING_FOR_HUMAN

    def publish_command(self, msg: WorldState, action: np.ndarray) -> None:
        command = ArmCommand(step=msg.step, gripper=float(action[3]))
        command.header.stamp = self.get_clock().now().to_msg()
        command.displacement.x, command.displacement.y, command.displacement.z = (float(v) for v in action[:3])
        self.publisher.publish(command)
        self.counters["commands"] += 1
        self.answered, self.answered_at = (msg.episode, msg.step), time.monotonic()


def main(args: list[str] | None = None) -> None:
    topics.run_node(PolicyNode, args)
