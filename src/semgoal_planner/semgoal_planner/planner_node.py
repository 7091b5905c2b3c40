"""planner_node: goals and semantic states in; the plan and the active sub-goal out (latched).

Wires the pure :class:`~semgoal_planner.executive.Executive` to ROS: the goal topic, GetPlan and
EditPlan services, the ExecuteGoal action (:mod:`~semgoal_planner.goal_action`), the journal
(:mod:`~semgoal_planner.journal_keeping`). The semantic state (one per world state, stamped with its
control step) is also the clock: each one is a tick and an observation, in that order, as in the
in-process episode, and each one gets an answer on the sub-goal topic stamped with its step, so the
policy in lockstep follows the decision on each step at the next (one step of decision latency).
"""

from __future__ import annotations

import time
from typing import Any

from action_msgs.msg import GoalStatusArray
from rclpy.action import ActionServer, GoalResponse
from rclpy.action.server import ServerGoalHandle
from rclpy.clock import Clock, ClockType
from rclpy.node import Node
from rclpy.qos import qos_profile_action_status_default
from rclpy.task import Future
from visualization_msgs.msg import MarkerArray

from semgoal_core.arms import robot_name, robot_names, takers
from semgoal_core.tasks import get_task
from semgoal_core.vocabulary import LAYOUTS
from semgoal_msgs.action import ExecuteGoal
from semgoal_msgs.msg import GoalRequest, OperatorEvent, Plan, SemanticState, SubGoal, WorldState
from semgoal_msgs.srv import EditPlan, GetPlan
from semgoal_planner.arm_worlds import ArmWorlds
from semgoal_planner.doubt import Doubt
from semgoal_planner.executive import Executive
from semgoal_planner.goal_action import FINAL, GoalAction
from semgoal_planner.goals import Goal, GoalError
from semgoal_planner.journal import PlanJournal
from semgoal_planner.journal_keeping import JournalKeeping
from semgoal_planner.plan_messages import goal_as_given, plan_message, read_request, subgoal_message
from semgoal_planner.plan_services import PlanServices
from semgoal_planner.planner_params import EXECUTIVE_PARAMS, PARAMS
from semgoal_planner.semantic import SemanticPlanner
from semgoal_planner.world_watch import WorldWatch
from semgoal_ros import interfaces as topics
from semgoal_ros import messages
from semgoal_ros.diagnostics import OK, Counters, Diagnostics, Latencies
from semgoal_ros.parameters import apply_changes, declare

SILENCE_CHECK_S = 0.25
NEXT_WORLD_WAIT_S = 1.0
"""How long a topic goal that fits the scene but not the world seen waits for the next world: a goal sent on a
reset's answer can come before the sim's event that announces the reset (another writer, another topic)."""


class PlannerNode(WorldWatch, PlanServices, GoalAction, JournalKeeping, Node):
    def __init__(self, **options: Any) -> None:
        """``options``: rclpy ``Node``'s (a namespace, parameter overrides: ``graph_node`` composes nodes so)."""
        super().__init__("planner", **options)
        values = declare(self, PARAMS)
        robots = robot_names(values["arms"])
        self.executive = Executive(SemanticPlanner(values["scene"], values["search"]), robots=robots,
                                   reach=self.reach if len(robots) > 1 else None,
                                   **{name: values[name] for name in EXECUTIVE_PARAMS})
        self.worlds: ArmWorlds[WorldState, SemanticState] | None = ArmWorlds() if len(robots) > 1 else None
        """With two arms: the latest world states (where each block and hand is), for :meth:`reach`."""
        self.state_wait_s = float(values["state_wait_s"])
        self.world_silence_s = float(values["world_silence_s"])
        self.doubt = Doubt(values["min_confidence"], values["unsure_wait_steps"])
        apply_changes(self, PARAMS, self.apply_parameter)
        self.state_waiters: list[Future] = []
        """ExecuteGoal requests that arrived before any semantic state: resolved by the first one."""
        self.min_episode = 0
        """The world episode the current ExecuteGoal asked for: older semantic states are ignored."""
        self.heard_at = time.monotonic()
        """When the last semantic state came (or the goal started): the world's silence is counted from it."""
        self.create_timer(SILENCE_CHECK_S, self.check_silence, clock=Clock(clock_type=ClockType.STEADY_TIME))
        self.plan_publisher = self.create_publisher(Plan, topics.PLAN, topics.LATCHED)
        self.plan_marker_publisher = self.create_publisher(MarkerArray, topics.PLAN_MARKERS, topics.LATCHED)
        self.subgoal_publishers = {robot: self.create_publisher(SubGoal, topics.arm_topic(topics.SUBGOAL, arm),
                                                                topics.PER_STEP) for arm, robot in enumerate(robots)}
        if len(robots) > 1:
            self.create_subscription(WorldState, values["world_topic"], self.world_callback, topics.STREAM)
        self.events_pub = self.create_publisher(OperatorEvent, topics.OPERATOR_EVENTS, topics.EVENTS)
        self.action_status_pub = self.create_publisher(GoalStatusArray, topics.action_status(topics.EXECUTE_GOAL),
                                                       qos_profile_action_status_default)
        """Beside the action server's own: tells a client of the planner before a restart that its goal ended."""
        self.journal = PlanJournal(values["state_dir"]) if values["state_dir"] else None
        self.journaled = self.journal.load() if self.journal else None
        """The journal's record, taken up (or discarded) on the first semantic state: only then is the world known."""
        self.last_saved: tuple | None = None
        if self.journal is not None:
            self.get_logger().info(f"journal {self.journal.path}" + (
                f": revision {self.journaled.executive.get('revision')} is taken up if the world is the same"
                if self.journaled else ""))
        # the sim's reset answers first: the executor takes what is ready in the order it was subscribed to, and a
        # goal sent on the reset's answer often comes in the same wait as the reset's event
        self.create_subscription(OperatorEvent, topics.OPERATOR_EVENTS, self.operator_event_callback, topics.EVENTS_LIVE)
        self.create_subscription(GoalRequest, topics.GOAL, self.goal_callback, 10)
        self.reset_episode = 0
        """The least world episode a topic goal is planned on: one past the latest state's, once the sim
        announces a reset (the goal's sender has the reset's answer; the new world's state may still be on its way)."""
        self.create_subscription(SemanticState, topics.SEMANTIC_STATE, self.semantic_callback, topics.PER_STEP)
        self.create_service(GetPlan, topics.GET_PLAN, self.get_plan_callback)
        self.create_service(EditPlan, topics.EDIT_PLAN, self.edit_plan_callback)
        self.action_server = ActionServer(
            self, ExecuteGoal, topics.EXECUTE_GOAL, self.execute_callback,
            goal_callback=lambda _: GoalResponse.ACCEPT, cancel_callback=self.cancel_callback)
        self.edit_answers = topics.RecentAnswers()
        self.last_published: tuple | None = None
        self.last_state: SemanticState | None = None
        self.action_goal: tuple[ServerGoalHandle, Future] | None = None
        """The ExecuteGoal being executed and the future its coroutine awaits: resolved with the reason
        when the goal ends (succeeded, failed, cancelled or superseded by another goal)."""
        self.counters, self.planning, self.deciding = Counters(), Latencies(), Latencies()
        """Goals and re-plans; the time to plan a goal and to decide on a semantic state (re-plans included)."""
        self.diagnostics = Diagnostics(self, self.health)
        self.publish()

    def health(self):
        ex = self.executive
        values = {"plan status": ex.status, "revision": ex.revision, "re-plans of this goal": ex.replans,
                  **self.counters, **self.planning.summary("goal planning"), **self.deciding.summary("decision")}
        return OK, f"plan {ex.status}, {self.counters['re-plans']} re-plans so far", values

    def apply_parameter(self, name: str, value) -> None:
        """A change made while running: the executive's settings hold from the next control step on."""
        if name in EXECUTIVE_PARAMS:
            setattr(self.executive, name, value)
        elif name == "state_wait_s":
            self.state_wait_s = float(value)
        elif name == "min_confidence":
            self.doubt.threshold = value
        elif name == "unsure_wait_steps":
            self.doubt.wait_steps = value
        elif name == "world_silence_s":
            self.world_silence_s = float(value)

    # -- inputs --------------------------------------------------------------------------------------
    def goal_callback(self, msg: GoalRequest) -> None:
        """A goal on the topic (``ros2 topic pub``), perhaps sent as the nodes start or right after a reset: like
        an action goal, it waits up to ``state_wait_s`` for a state of the current world (the first one, or the
        reset's) rather than being refused for want of one or judged on the world before; one that fits the scene
        but not the world seen waits a little for the next world. The wait is a task of its own: awaited here, it
        would hold the callback group the states come in on."""
        goal = self.read(msg, self.reset_episode)
        if isinstance(goal, Goal) and not self.has_state(self.reset_episode):
            self.executor.create_task(self.start_goal_on_state(msg, goal, self.reset_episode, self.state_wait_s))
        elif self.for_another_world(msg, goal):
            wait_s = min(self.state_wait_s, NEXT_WORLD_WAIT_S)
            self.executor.create_task(self.start_goal_on_state(msg, goal, self.last_state.episode + 1, wait_s))
        else:
            self.min_episode = 0
            self.start_goal(msg, goal)

    def for_another_world(self, msg: GoalRequest, goal: Goal | GoalError) -> bool:
        """Whether ``goal`` fits the scene but not the world seen: a task of other blocks, or literals naming a
        block this world lacks."""
        if self.last_state is None:
            return False
        if isinstance(goal, Goal):
            return bool(goal.task) and get_task(goal.task).blocks != tuple(self.last_state.objects)
        return isinstance(self.read(msg, self.last_state.episode + 1), Goal)  # read against every block of the scene

    async def start_goal_on_state(self, msg: GoalRequest, goal: Goal | GoalError, episode: int, wait_s: float) -> None:
        """``goal`` once a state of world ``episode`` has come, or ``wait_s`` has passed; one that did not fit the
        world before is read again against the new one (else refused as it was)."""
        await self.state_of(episode, wait_s)
        if isinstance(goal, GoalError) and self.has_state(episode):
            goal = self.read(msg, episode)
        self.min_episode = 0
        self.start_goal(msg, goal)

    def read(self, msg: GoalRequest, episode: int) -> Goal | GoalError:
        """The request's goal, read once where it enters, or why it cannot be: against the blocks of the world
        seen, or, while the goal waits for world ``episode``, against every block of the scene (the world it is
        planned on checks its blocks)."""
        scene = self.executive.planner.scene
        objects = tuple(self.last_state.objects) if self.has_state(episode) else LAYOUTS[scene].objects
        try:
            return read_request(msg, scene, objects)
        except GoalError as error:
            return error

    def operator_event_callback(self, event: OperatorEvent) -> None:
        """The sim's answer to a reset: a topic goal sent from here on waits for the new world's state."""
        if event.kind == OperatorEvent.KIND_RESET and event.accepted:
            self.reset_episode = max(self.reset_episode, (self.last_state.episode if self.last_state else 0) + 1)

    def start_goal(self, msg: GoalRequest, goal: Goal | GoalError, max_steps: int = 0) -> tuple[bool, str]:
        steps_before = self.executive.goal_steps  # what a goal this one supersedes reports
        if isinstance(goal, GoalError):
            ok, message = False, str(goal)
        else:
            with self.planning.time():
                ok, message = self.executive.set_goal(goal, step_budget=max_steps)
        self.counters["goals planned" if ok else "goals refused"] += 1
        self.report(ok, f"goal task={msg.task!r} literals={list(msg.literals)} text={msg.text!r}: {message}")
        if ok:
            self.heard_at = time.monotonic()  # a goal planned on a state from long ago gets its own time to hear one
            self.end_action_goal("superseded by a new goal", steps_before)
        self.publish()
        self.operator_event(OperatorEvent.KIND_GOAL, goal_as_given(msg), ok, message)
        return ok, message

    def report(self, ok: bool, text: str) -> None:
        # rclpy refuses one call site switching severity, so each severity has its own call
        if ok:
            self.get_logger().info(text)
        else:
            self.get_logger().warn(text)

    # -- outputs -------------------------------------------------------------------------------------
    def operator_event(self, kind: str, request: str, accepted: bool, answer: str, request_id: str = "") -> None:
        event = OperatorEvent(kind=kind, request=request, request_id=request_id, accepted=accepted, answer=answer,
                              revision=self.executive.revision)
        event.header.stamp = self.get_clock().now().to_msg()
        self.events_pub.publish(event)

    def world_callback(self, msg: WorldState) -> None:
        held = self.worlds.add(msg)
        if held is not None:
            self.semantic_callback(held)

    def reach(self, block: str) -> tuple[str, ...]:
        """The arms that may take a step on ``block`` in the world state of the semantic state being decided on (in
        lockstep the world runs a step or two ahead), else the latest, the nearer first
        (:func:`semgoal_core.arms.takers`); every arm before one came."""
        world = self.worlds.world_of(self.last_state) if self.worlds is not None else None
        names = list(world.block_names) if world is not None else []
        if block not in names:
            return self.executive.robots
        return tuple(robot_name(arm) for arm in takers(names.index(block), messages.block_poses(world)[:, :3],
                                                       messages.hands(world)))

    def plan_now(self) -> Plan:
        return plan_message(self.executive, self.get_clock().now().to_msg())

    def publish(self, decided: bool = False) -> None:
        """Publish the plan when it changed and the active sub-goal when it changed or ``decided`` (a new
        semantic state was observed: the policy waits for this answer); log the executive's events."""
        ex = self.executive
        for line in ex.drain_events():
            self.get_logger().info(line)
        key = (ex.revision, ex.status, ex.current, tuple(ex.working.items()))  # a step started changes the plan
        changed = key != self.last_published
        if changed:
            self.last_published = key
            plan = self.plan_now()
            self.plan_publisher.publish(plan)
            self.plan_marker_publisher.publish(messages.plan_markers(plan))
            if self.action_goal is not None:
                if ex.status in FINAL:
                    self.end_action_goal(ex.message)
                else:
                    self.publish_feedback()
        if changed or decided:
            for robot, publisher in self.subgoal_publishers.items():
                publisher.publish(subgoal_message(self.executive, self.last_state, robot))
        self.save_journal()


def main(args: list[str] | None = None) -> None:
    topics.run_node(PlannerNode, args)
