"""planner_node: goals and semantic states in; the plan and the active sub-goal out (latched).

Wires the pure :class:`~semgoal_planner.executive.Executive` to ROS: the goal topic, GetPlan and
EditPlan services, the ExecuteGoal action. The semantic state (one per world state, stamped with its
control step) is also the clock: each one is a tick and an observation, in that order, as in the
in-process episode, and each one gets an answer on the sub-goal topic stamped with its step, so the
policy in lockstep follows the decision on each step at the next (one step of decision latency).
"""

from __future__ import annotations

import time

from action_msgs.msg import GoalInfo, GoalStatus, GoalStatusArray
from rclpy.action import ActionServer, CancelResponse, GoalResponse
from rclpy.action.server import ServerGoalHandle
from rclpy.clock import Clock, ClockType
from rclpy.node import Node
from rclpy.qos import qos_profile_action_status_default
from rclpy.task import Future
from visualization_msgs.msg import MarkerArray

from semgoal_core.layout import CONTROL_DT
from semgoal_core.names import UNDER_WAY, Assignee, PlanStatus, StepStatus
from semgoal_core.vocabulary import LAYOUTS, SCENES, Literal, VocabularyError
from semgoal_msgs.action import ExecuteGoal
from semgoal_msgs.msg import GoalRequest, OperatorEvent, Plan, Predicate, SemanticState, SubGoal
from semgoal_msgs.srv import EditPlan, GetPlan
from semgoal_planner.doubt import Doubt, unsure_literals
from semgoal_planner.executive import Executive, Observation
from semgoal_planner.goals import Goal, GoalError, read_goal, typed_goal
from semgoal_planner.journal import PlanJournal, Record, Verdict, World, resume
from semgoal_planner.semantic import SemanticPlanner
from semgoal_ros import interfaces as topics
from semgoal_ros import messages
from semgoal_ros.diagnostics import OK, Counters, Diagnostics, Latencies
from semgoal_ros.messages import format_plan
from semgoal_ros.parameters import Param, apply_changes, declare
from strips_planner.search import SEARCHES

FINAL = (PlanStatus.SUCCEEDED, PlanStatus.FAILED)
SILENCE_CHECK_S = 0.25


def goal_as_given(msg: GoalRequest) -> str:
    """A GoalRequest as the operator gave it, malformed ones too (each part there is, joined by ' | ')."""
    predicates = " & ".join(str(literal_of(p)) for p in msg.predicates)
    return " | ".join(part for part in (msg.task.strip(), " & ".join(msg.literals), predicates, msg.text.strip()) if part)


def literal_of(predicate) -> Literal:
    return Literal(predicate.name, tuple(predicate.args), bool(predicate.value))


def read_request(msg: GoalRequest, scene: str, objects: tuple[str, ...]) -> Goal:
    """The goal a request carries, read once: predicates are validated, a task, typed literals or a sentence
    are read (:func:`~semgoal_planner.goals.read_goal`). GoalError unless exactly one of the four is given."""
    given = [bool(msg.task.strip()), bool(msg.literals), bool(msg.predicates), bool(msg.text.strip())]
    if sum(given) != 1:
        raise GoalError("give exactly one of a task, literals (text or predicates) or a sentence (text)")
    if msg.predicates:
        return typed_goal([literal_of(p) for p in msg.predicates], scene, objects)
    return read_goal(msg.task.strip() or " & ".join(msg.literals) or msg.text.strip(), scene, objects)


def edit_text(request: EditPlan.Request) -> str:
    """An edit as the operator gave it: the op and each field set (``remove index=2``, ``assign index=1 action=human``)."""
    fields = {"index": request.index, "to_index": request.to_index, "action": request.action,
              "revision": request.revision}
    return " ".join([request.op, *(f"{name}={value}" for name, value in fields.items() if value)])


PARAMS = (
    Param("scene", "desk_cleanup", "the scene whose vocabulary and domain the planner uses", choices=tuple(SCENES)),
    Param("search", "bfs", "bfs (shortest plans) | astar | gbfs", choices=SEARCHES),
    Param("stall_steps", 150, "control steps a robot step may take without holding before a re-plan",
          low=1, high=1_000_000, runtime=True),
    Param("human_steps", 3000, "control steps a person's step may take before the goal fails (2 min at 25 Hz)",
          low=1, high=10_000_000, runtime=True),
    Param("contradiction_steps", 10, "control steps the observed state may contradict the plan before a re-plan",
          low=1, high=100_000, runtime=True),
    Param("max_replans", 10, "re-plans before the goal fails with a reason", low=0, high=10_000, runtime=True),
    Param("require_approval", False, "a new plan waits for the operator's approve", runtime=True),
    Param("state_wait_s", 5.0, "ExecuteGoal before any semantic state: wait this long for one",
          low=0.0, high=3600.0, runtime=True),
    Param("world_silence_s", 3.0, "a goal under way fails once no semantic state has come for this long (the sim "
          "or the predicates gone; the lockstep sim's heartbeat keeps a still world talking); 0: wait for ever",
          low=0.0, high=3600.0, runtime=True),
    Param("state_dir", "", "a folder for the planner's journal (SQLite): goal, plan, edits and revision survive a "
          "restart on the same world; empty: nothing survives"),
    Param("min_confidence", 0.9, "a literal the plan relies on that the source (the camera) is less sure of than this "
          "holds the planner's decisions", low=0.0, high=1.0, runtime=True),
    Param("unsure_wait_steps", 25, "control steps the planner holds its decisions for unsure literals before it takes "
          "the state as it is", low=0, high=100_000, runtime=True),
)
EXECUTIVE_PARAMS = ("stall_steps", "human_steps", "contradiction_steps", "max_replans", "require_approval")
"""Parameters that are the executive's settings of the same name."""


def sim_time(msg: SemanticState) -> float:
    return msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9


class PlannerNode(Node):
    def __init__(self) -> None:
        super().__init__("planner")
        values = declare(self, PARAMS)
        self.executive = Executive(SemanticPlanner(values["scene"], values["search"]),
                                   **{name: values[name] for name in EXECUTIVE_PARAMS})
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
        self.subgoal_publisher = self.create_publisher(SubGoal, topics.SUBGOAL, topics.PER_STEP)
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
        reset's) rather than being refused for want of one or judged on the world before. The wait is a task of
        its own: awaited here, it would hold the callback group the states come in on."""
        goal = self.read(msg, self.reset_episode)
        if isinstance(goal, Goal) and not self.has_state(self.reset_episode):
            self.executor.create_task(self.start_goal_on_state(msg, goal, self.reset_episode))
        else:
            self.min_episode = 0
            self.start_goal(msg, goal)

    async def start_goal_on_state(self, msg: GoalRequest, goal: Goal, episode: int) -> None:
        await self.state_of(episode, self.state_wait_s)
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

    def semantic_callback(self, msg: SemanticState) -> None:
        if msg.scene != self.executive.planner.scene:
            self.get_logger().warn(f"ignored a semantic state of scene {msg.scene!r}", throttle_duration_sec=5.0)
            return
        if self.last_state is not None and sim_time(msg) < sim_time(self.last_state):  # one sim's clock never goes back
            self.world_restarted(msg)
        if msg.episode < self.min_episode:  # a state of the world before the reset the goal was sent for
            self.get_logger().warn(f"ignored a semantic state of episode {msg.episode} (the goal is for "
                                   f"episode {self.min_episode})", throttle_duration_sec=5.0)
            return
        literals = [Literal(p.name, tuple(p.args), bool(p.value)) for p in msg.predicates]
        try:
            LAYOUTS[msg.scene].check_state(tuple(msg.objects), literals, (*msg.fallen, *msg.moving))
        except VocabularyError as error:
            self.get_logger().warn(f"ignored a semantic state: {error}", throttle_duration_sec=5.0)
            return
        try:
            unsure = unsure_literals(literals, list(msg.confidence), self.relied_on(), self.doubt.threshold)
        except ValueError as error:
            self.get_logger().warn(f"ignored a semantic state: {error}", throttle_duration_sec=5.0)
            return
        if self.journaled is not None:
            self.take_up_journal(msg)
        self.last_state, self.heard_at = msg, time.monotonic()
        for waiter in self.state_waiters:
            if not waiter.done():
                waiter.set_result(True)
        self.state_waiters.clear()
        replans = self.executive.replans
        with self.deciding.time():
            self.executive.tick(int(msg.step))
            if msg.stale:  # the source says this state is not to be acted on: hold the plan until one is
                self.executive.pause_blind(msg.stale)
            elif self.doubt.holds(unsure, int(msg.step), int(msg.episode)):
                self.executive.resume_sighted()
                self.counters["states held in doubt"] += 1
                self.get_logger().info("deciding nothing on " + ", ".join(f"{lit} ({sure:.0%} sure)" for lit, sure in unsure),
                                       throttle_duration_sec=1.0)
            else:
                self.executive.resume_sighted()
                self.executive.observe(Observation(tuple(msg.objects), literals, int(msg.step), tuple(msg.fallen),
                                                   tuple(msg.moving)))
        self.counters["re-plans"] += max(0, self.executive.replans - replans)
        self.publish(decided=True)

    def relied_on(self) -> list[Literal]:
        """The literals the plan's decisions rest on now: the goal's and the active step's."""
        active = self.executive.active
        return [*self.executive.goal, *(active.subgoal.literals() if active else ())]

    # -- the journal ---------------------------------------------------------------------------------
    def take_up_journal(self, msg: SemanticState) -> None:
        """Carry on with the plan of the planner before this one when the world is the one it was for;
        else discard it, numbering plans on from its revision. An action goal it had in flight is ended for
        its client, with the reason, either way: its handle died with that planner."""
        record = self.journaled
        verdict, why = resume(record, World(msg.scene, tuple(msg.objects), int(msg.episode), sim_time(msg)))
        if verdict == Verdict.WAIT:
            return
        self.journaled, ok = None, verdict == Verdict.RESUME
        revision = int(record.executive.get("revision", 0))
        if ok:
            try:
                self.executive.restore(record.executive, f"planner restarted: resumed the plan at revision {revision}, "
                                                         f"step {record.executive.get('current', 0)} ({why})")
            except ValueError as error:
                ok, why = False, str(error)
        if not ok:
            self.executive.continue_revisions(revision)
            self.get_logger().warn(f"the planner's journal ({self.journal.path}) was discarded: {why}")
        outcome = (f"the plan resumed at revision {revision}" if ok
                   else f"the journal was discarded ({why}): send the goal again")
        self.operator_event(OperatorEvent.KIND_GOAL, record.executive.get("goal_text", ""), ok,
                            f"planner_node stopped and started again; {outcome}")
        if record.action_goal:
            self.end_journaled_action_goal(record, f"the ExecuteGoal was interrupted: planner_node stopped and "
                                                   f"started again; {outcome}")

    def end_journaled_action_goal(self, record: Record, reason: str) -> None:
        """Mark the old planner's action goal aborted on the action's status topic (a client's goal handle reads
        it) and say why on the operator events, under the goal's id."""
        status = GoalStatus(status=GoalStatus.STATUS_ABORTED,
                            goal_info=GoalInfo(stamp=self.get_clock().now().to_msg()))
        status.goal_info.goal_id.uuid = list(bytes.fromhex(record.action_goal))
        self.action_status_pub.publish(GoalStatusArray(status_list=[status]))
        self.operator_event(OperatorEvent.KIND_GOAL, record.executive.get("goal_text", ""), False, reason,
                            request_id=record.action_goal)
        self.get_logger().warn(f"action goal {record.action_goal}: {reason}")

    def save_journal(self) -> None:
        """Write the plan to the journal when it changed (a new revision, status or step, another action goal)."""
        if self.journal is None or self.last_state is None or self.journaled is not None:
            return
        action_goal = bytes(self.action_goal[0].goal_id.uuid).hex() if self.action_goal else ""
        ex, state = self.executive, self.last_state
        key = (ex.revision, ex.status, ex.current, action_goal, state.episode)
        if key == self.last_saved:
            return
        self.last_saved = key
        world = World(state.scene, tuple(state.objects), int(state.episode), sim_time(state))
        self.journal.save(Record(ex.snapshot(), world, action_goal))

    def check_silence(self) -> None:
        silent = time.monotonic() - self.heard_at
        if self.world_silence_s <= 0 or self.executive.status not in UNDER_WAY or silent <= self.world_silence_s:
            return
        reason = (f"no semantic state for {silent:.1f} s (are sim_node and predicate_node running?): the goal cannot "
                  "be followed; send it again once the world is back")
        self.get_logger().warn(reason)
        self.executive.cancel(reason)
        self.publish()

    def world_restarted(self, msg: SemanticState) -> None:
        """A world whose clock went back (a sim started again: its clock and episodes count from the start): the
        goal under way was for the world before, so it fails with the reason rather than waiting for ever."""
        reason = (f"the world started again (sim time {sim_time(msg):.2f} s after {sim_time(self.last_state):.2f} s: "
                  "was sim_node restarted?); the goal was for the world before: send it again")
        self.get_logger().warn(reason)
        self.min_episode = self.reset_episode = 0
        self.executive.cancel(reason)
        self.publish()

    def get_plan_callback(self, request: GetPlan.Request, response: GetPlan.Response) -> GetPlan.Response:
        response.plan = self.plan_message()
        if self.last_state is not None:
            response.state = self.last_state
        response.success = self.executive.status != PlanStatus.EMPTY
        response.message = format_plan(response.plan)
        return response

    def edit_plan_callback(self, request: EditPlan.Request, response: EditPlan.Response) -> EditPlan.Response:
        asked = (request.op, request.index, request.to_index, request.action, request.revision)
        try:
            answered = self.edit_answers.get(request.request_id, asked)
        except topics.ReusedRequestIdError as error:  # refused, the plan as it is
            response.success, response.message, response.plan = False, str(error), self.plan_message()
            self.operator_event(OperatorEvent.KIND_EDIT, edit_text(request), False, response.message, request.request_id)
            return response
        if answered is not None:  # sent again because our answer was lost: it was applied once already
            response.success, response.message, response.plan = answered
            return response
        response.success, response.message = self.executive.edit(
            request.op, int(request.index), int(request.to_index), request.action, int(request.revision))
        self.report(response.success, f"edit {request.op} {request.index} {request.action!r}: {response.message}")
        self.publish()
        response.plan = self.plan_message()
        self.operator_event(OperatorEvent.KIND_EDIT, edit_text(request), response.success, response.message,
                            request.request_id)
        self.edit_answers.remember(request.request_id, (response.success, response.message, response.plan), asked)
        return response

    async def execute_callback(self, handle: ServerGoalHandle) -> ExecuteGoal.Result:
        """Start the goal, then wait (without a thread: the callbacks go on) until it ends; feedback
        goes out with every change of the plan (:meth:`publish`)."""
        result = ExecuteGoal.Result()
        episode = int(handle.request.episode)
        goal = self.read(handle.request.goal, episode)
        if isinstance(goal, Goal) and not self.has_state(episode):
            await self.state_of(episode, self.state_wait_s)
        if episode and not self.has_state(episode):
            ok, message = False, (f"no semantic state of world episode {episode} within {self.state_wait_s:g} s "
                                  f"(the latest is of episode {self.last_state.episode if self.last_state else '-'})")
            self.report(False, f"goal refused: {message}")
            self.operator_event(OperatorEvent.KIND_GOAL, goal_as_given(handle.request.goal), False, message)
        else:
            self.min_episode = episode
            ok, message = self.start_goal(handle.request.goal, goal, int(handle.request.max_steps))
        result.episode = self.last_state.episode if self.last_state else 0
        # a refused goal ran no steps: its result must not carry the previous goal's figures
        steps = self.executive.goal_steps if ok else 0
        if ok and self.executive.status not in FINAL:
            ended = Future(executor=self.executor)
            self.action_goal = (handle, ended)
            self.publish_feedback()
            # ``ended`` carries the goal's step count when it ended: a new goal may come before this resumes
            message, steps = await ended
        self.min_episode = 0  # only while this goal runs: a sim restarted later counts episodes from 1 again
        if handle.is_cancel_requested:
            handle.canceled()
            result.message = "cancelled"
            return self._fill(result, ok, steps)
        result.success = ok and self.executive.status == PlanStatus.SUCCEEDED
        result.message = message
        (handle.succeed if result.success else handle.abort)()
        return self._fill(result, ok, steps)

    def has_state(self, episode: int) -> bool:
        """Whether a semantic state has come (of world ``episode`` or a later one, when it is not 0)."""
        return self.last_state is not None and self.last_state.episode >= episode

    async def state_of(self, episode: int, timeout_s: float) -> None:
        """Wait up to ``timeout_s`` for a semantic state (of ``episode`` or later, when not 0), so that a goal
        sent right after the nodes start, or right after a reset, is planned on that world rather than refused
        or decided on the one before; after that the executive says what is missing."""
        if timeout_s <= 0:
            return
        self.get_logger().info(f"goal waits up to {timeout_s:g} s for a semantic state"
                               + (f" of world episode {episode}" if episode else ""))
        deadline = time.monotonic() + timeout_s  # states of older episodes come meanwhile: the wait is one
        while not self.has_state(episode) and (left := deadline - time.monotonic()) > 0:
            seen = Future(executor=self.executor)
            self.state_waiters.append(seen)
            timer = self.create_timer(left, lambda seen=seen: seen.done() or seen.set_result(False))
            await seen
            self.destroy_timer(timer)

    def cancel_callback(self, handle: ServerGoalHandle) -> CancelResponse:
        if self.action_goal is not None and self.action_goal[0] is handle:
            self.executive.cancel()
            self.publish()
        return CancelResponse.ACCEPT

    def end_action_goal(self, reason: str, steps: int | None = None) -> None:
        """Resolve the action goal with ``reason`` and its step count (default: the goal's now)."""
        if self.action_goal is not None:
            _, ended = self.action_goal
            self.action_goal = None
            ended.set_result((reason, self.executive.goal_steps if steps is None else steps))

    def publish_feedback(self) -> None:
        handle, _ = self.action_goal
        feedback = ExecuteGoal.Feedback(plan=self.plan_message(), control_steps=self.executive.goal_steps)
        if self.last_state is not None:
            feedback.state = self.last_state
        handle.publish_feedback(feedback)

    def _fill(self, result: ExecuteGoal.Result, started: bool, steps: int) -> ExecuteGoal.Result:
        result.replans = self.executive.replans if started else 0
        result.control_steps = steps
        result.sim_time = result.control_steps * CONTROL_DT
        return result

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

    def plan_message(self) -> Plan:
        ex = self.executive
        msg = Plan(goal=ex.goal_text, current=ex.current, status=ex.status, revision=ex.revision, replans=ex.replans,
                   paused_because=ex.blind)
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.steps = [self.step_message(i, step.subgoal, step.status, step.assignee) for i, step in enumerate(ex.steps)]
        return msg

    @staticmethod
    def step_message(index: int, subgoal, status: str, assignee: str) -> SubGoal:
        return SubGoal(index=index, action=str(subgoal), status=status, assignee=assignee,
                       goal=[Predicate(name=lit.name, args=list(lit.args), value=lit.value) for lit in subgoal.literals()])

    def publish(self, decided: bool = False) -> None:
        """Publish the plan when it changed and the active sub-goal when it changed or ``decided`` (a new
        semantic state was observed: the policy waits for this answer); log the executive's events."""
        ex = self.executive
        for line in ex.drain_events():
            self.get_logger().info(line)
        key = (ex.revision, ex.status, ex.current)
        changed = key != self.last_published
        if changed:
            self.last_published = key
            plan = self.plan_message()
            self.plan_publisher.publish(plan)
            self.plan_marker_publisher.publish(messages.plan_markers(plan))
            if self.action_goal is not None:
                if ex.status in FINAL:
                    self.end_action_goal(ex.message)
                else:
                    self.publish_feedback()
        if changed or decided:
            self.subgoal_publisher.publish(self.subgoal_message())
        self.save_journal()

    def subgoal_message(self) -> SubGoal:
        """The active robot step; else an empty goal (the policy holds still) with the reason as status:
        ``settling`` (the goal holds, the world comes to rest), ``waiting_for_human`` or the plan's status."""
        ex = self.executive
        active = ex.active
        goal = [Predicate(name=lit.name, args=list(lit.args), value=lit.value) for lit in ex.goal]
        if ex.settling:  # the goal's literals: the policy keeps what they ask to hold while the arm retreats
            msg = SubGoal(index=ex.current, status=StepStatus.SETTLING, goal=goal)
        elif ex.status == PlanStatus.SUCCEEDED:
            msg = SubGoal(index=ex.current, status=ex.status, goal=goal)
        elif active is None:
            waiting = ex.status == PlanStatus.EXECUTING  # executing without an active robot step: a human's turn
            msg = SubGoal(index=ex.current, status=StepStatus.WAITING_FOR_HUMAN if waiting else ex.status,
                          assignee=Assignee.HUMAN if waiting else "")
        else:
            msg = self.step_message(ex.current, active.subgoal, StepStatus.ACTIVE, Assignee.ROBOT)
        msg.step = self.last_state.step if self.last_state else 0  # the state this decision answers
        msg.episode = self.last_state.episode if self.last_state else 0
        return msg



def main(args: list[str] | None = None) -> None:
    topics.run_node(PlannerNode, args)
