"""The one client of a running semgoal graph: reset the world, move a block, send a goal and follow it, read
and edit the plan. The operator CLI, the demo, ``./semgoal eval --via-ros``, the graph benchmark and the
graph tests all go through :class:`GraphClient`.

Every request goes out again while no answer comes (:func:`~semgoal_ros.interfaces.send_until_answered`):
reads, resets and block moves are safe to repeat, plan edits carry a request id, and the planner runs one
goal at a time.

Only callers that look at the per-step streams (world state, semantic state, sub-goal: the demo, the
tests) subscribe to them (``watch``). In lockstep every reader of those topics is one more process woken
on each step, on the path from one step to the next: without them the graph steps about 1.2 times as
fast (``./semgoal bench-graph``). A reset is confirmed through the planner's GetPlan instead, which
reports the episode and step of the semantic state it last decided on.
"""

from __future__ import annotations

import os
import time
import uuid
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

from semgoal_core.layout import CONTROL_DT
from semgoal_ros import interfaces as topics

READY_TIMEOUT_S = 60.0
EPISODE_TIMEOUT_S = 300.0
RESET_TIMEOUT_S = 5.0
SERVICE_WAIT_S = 10.0
POLL_S = 0.005
RECORDER_MATCH_S = 10.0
RECORDER_SETTLE_S = 0.5
PLANNER_SILENCE_S = 3.0
"""A planner that leaves GetPlan unanswered this long while a goal runs is taken for gone (killed, hung): the
goal is reported failed with that reason instead of being waited on (a restarted planner has lost it)."""
RESULT_GRACE_S = 1.0
"""How long a goal marked aborted may wait for its result before it counts as ended without one."""
PLANNER_ASK_S = 0.5
"""How often a running goal's client asks the planner whether it is still there."""


class GraphUnavailableError(TimeoutError):
    """A service or action of the graph that is not there or does not answer; the message names it."""


@dataclass(frozen=True)
class GoalResult:
    success: bool
    message: str
    replans: int
    control_steps: int
    """The world's control steps of the goal, as the planner counts them; for a goal whose result was lost (the
    planner died), its last count in the feedback."""
    sim_time: float
    wall_s: float


def goal_request(text: str):
    """The GoalRequest for a goal as typed: a task name, literals joined by '&' (read here, sent as predicates),
    or a sentence (the planner reads it against the world's blocks). Literals that do not read go as typed, so
    that the planner's refusal names what is wrong."""
    from semgoal_core.tasks import goal_form, split_literals
    from semgoal_core.vocabulary import VocabularyError, parse_literal
    from semgoal_msgs.msg import GoalRequest
    from semgoal_ros.messages import predicate

    form = goal_form(text)
    if form == "task":
        return GoalRequest(task=text.strip())
    if form == "text":
        return GoalRequest(text=text)
    try:
        literals = [parse_literal(part) for part in split_literals(text)]
    except (ValueError, VocabularyError):
        return GoalRequest(literals=[text])
    return GoalRequest(predicates=[predicate(lit) for lit in literals])


class PlannerWatch:
    """Asks the planner GetPlan every :data:`PLANNER_ASK_S` while a goal runs; :meth:`gone` once a question has
    gone unanswered for :data:`PLANNER_SILENCE_S` (an action result never comes from a planner that died)."""

    def __init__(self, client, request) -> None:
        self.client, self.request = client, request
        self.asked_at, self.answer = 0.0, None

    def gone(self) -> bool:
        now = time.monotonic()
        if self.answer is None or (self.answer.done() and now - self.asked_at >= PLANNER_ASK_S):
            self.asked_at, self.answer = now, self.client.call_async(self.request)
        return not self.answer.done() and now - self.asked_at > PLANNER_SILENCE_S


class InterruptionWatch:
    """A goal marked aborted on the action's status topic whose result does not follow within
    :data:`RESULT_GRACE_S`: how a planner started again ends the goals of the one before (their results died with it)."""

    def __init__(self, handle, result_future) -> None:
        from action_msgs.msg import GoalStatus

        self.handle, self.result, self.aborted = handle, result_future, GoalStatus.STATUS_ABORTED
        self.since: float | None = None

    def ended(self) -> bool:
        if self.handle.status != self.aborted or self.result.done():
            return False
        self.since = self.since or time.monotonic()
        return time.monotonic() - self.since > RESULT_GRACE_S


def interrupted(error: BaseException | None) -> bool:
    """Whether ``error`` is Ctrl-C: one that lands inside an rclpy call (taking feedback, a message's fields built in
    C++) comes out as the error pybind11 makes of it, a TypeError caused by the KeyboardInterrupt."""
    while error is not None:
        if isinstance(error, KeyboardInterrupt):
            return True
        error = error.__cause__ or error.__context__
    return False


class GraphClient:
    """An rclpy node holding the sim's reset and move services, the planner's services and ExecuteGoal, and
    (``watch``) the state streams. It initialises rclpy on the current ROS_DOMAIN_ID when the caller's
    process has not; ``handle_signals=False`` leaves Ctrl-C to the caller as a KeyboardInterrupt, with the
    context still valid, so a command can cancel its goal before it exits."""

    def __init__(self, name: str = "semgoal_operator", watch: bool = True, lockstep: bool = True,
                 handle_signals: bool = True) -> None:
        import rclpy
        from rclpy.action import ActionClient
        from rclpy.experimental import EventsExecutor
        from rclpy.signals import SignalHandlerOptions

        from semgoal_msgs.action import ExecuteGoal
        from semgoal_msgs.msg import GoalRequest, OperatorEvent, SemanticState, SubGoal, WorldState
        from semgoal_msgs.srv import EditPlan, GetPlan, MoveBlock, ResetWorld

        if not rclpy.ok():
            rclpy.init(domain_id=int(os.environ.get("ROS_DOMAIN_ID", "0")),
                       signal_handler_options=None if handle_signals else SignalHandlerOptions.NO)
        self.rclpy = rclpy
        self.node = node = rclpy.create_node(name)
        self.executor = EventsExecutor()
        """rclpy's events executor (C++ dispatch): per message read it costs the client about a third of the CPU
        of rclpy.spin_once(node), which adds and removes the node and rebuilds its wait set on every call
        (5.5 → 1.8 ms per control step with a recorder on every topic, /tmp measurement in docs/measurements)."""
        self.executor.add_node(node)
        self.world: WorldState | None = None
        self.semantic: SemanticState | None = None
        self.subgoal: SubGoal | None = None
        self.world_listeners: list[Callable] = []
        self.watch, self.lockstep = watch, lockstep
        self.episode = 0
        """The world episode of this client's last reset: its goals are planned on that world, never an older one."""
        self.answers: dict[str, str] = {}
        """The planner's latest answers on the operator events, by request id (an action goal's id in hex among
        them), as many as the topic keeps."""
        node.create_subscription(OperatorEvent, topics.OPERATOR_EVENTS, self._on_event, topics.EVENTS)
        if watch:
            node.create_subscription(WorldState, topics.WORLD_STATE, self._on_world, topics.STREAM)
            node.create_subscription(SemanticState, topics.SEMANTIC_STATE, self._on_semantic, topics.LATCHED)
            node.create_subscription(SubGoal, topics.SUBGOAL, self._on_subgoal, topics.LATCHED)
        self.reset_client = node.create_client(ResetWorld, topics.RESET_WORLD)
        self.move_client = node.create_client(MoveBlock, topics.MOVE_BLOCK)
        self.plan_client = node.create_client(GetPlan, topics.GET_PLAN)
        self.edit_client = node.create_client(EditPlan, topics.EDIT_PLAN)
        self.action = ActionClient(node, ExecuteGoal, topics.EXECUTE_GOAL)
        self.goal_publisher = node.create_publisher(GoalRequest, topics.GOAL, 10)
        self.ExecuteGoal, self.ResetWorld, self.MoveBlock = ExecuteGoal, ResetWorld, MoveBlock
        self.GetPlan, self.EditPlan = GetPlan, EditPlan

    # -- streams -------------------------------------------------------------------------------------
    def _on_world(self, msg) -> None:
        self.world = msg
        for listener in self.world_listeners:
            listener(msg)

    def _on_event(self, event) -> None:
        if event.request_id:
            self.answers[event.request_id] = event.answer
            if len(self.answers) > topics.EVENTS.depth:  # a long-lived client keeps no more than the topic does
                del self.answers[next(iter(self.answers))]

    def _on_semantic(self, msg) -> None:
        self.semantic = msg

    def _on_subgoal(self, msg) -> None:
        self.subgoal = msg

    def spin_until(self, condition: Callable[[], bool], timeout: float) -> bool:
        return topics.spin_executor_until(self.executor, condition, timeout)

    # -- calls ---------------------------------------------------------------------------------------
    def wait_ready(self, timeout: float = READY_TIMEOUT_S, policy: bool = True, arms: int = 1) -> bool:
        """Sim services, the planner's services and action, the predicates and (with ``policy``) the policy
        are up: world state is read by the predicates (or the perception) and the policy (the sim's, or the
        perceived one), the semantic state by the planner, the sub-goal by the policy (each arm's by its own of
        ``arms``), and each of them by this client too when it watches."""
        own = int(self.watch)
        world_readers, subgoal_readers = (2 + own, 1 + own) if policy else (1 + own, own)
        return self.spin_until(lambda: (self.reset_client.service_is_ready() and self.plan_client.service_is_ready()
                                        and self.action.server_is_ready()
                                        and self.world_readers() >= world_readers
                                        and self.node.count_subscribers(topics.SEMANTIC_STATE) >= 1 + own
                                        and self.node.count_subscribers(topics.SUBGOAL) >= subgoal_readers
                                        and all(self.node.count_subscribers(topics.arm_topic(topics.SUBGOAL, arm))
                                                >= int(policy) for arm in range(1, arms))),
                               timeout)

    def world_readers(self) -> int:
        """Readers of the sim's world state and of the camera's perceived one (the policy reads either)."""
        return self.node.count_subscribers(topics.WORLD_STATE) + self.node.count_subscribers(topics.PERCEIVED_WORLD)

    def call(self, client, request, wait_s: float = SERVICE_WAIT_S):
        """Call a service (waiting up to ``wait_s`` for it to appear), sending the request again while no
        answer comes; raises :class:`GraphUnavailableError` naming the service."""
        if not client.wait_for_service(timeout_sec=wait_s):
            raise GraphUnavailableError(f"no {client.srv_name} service: is its node running (same ROS_DOMAIN_ID)?")
        reply = topics.send_until_answered(lambda: client.call_async(request), self.spin_until)
        if reply is None:
            raise GraphUnavailableError(f"{client.srv_name} did not answer after {topics.SEND_ATTEMPTS} tries")
        return reply

    def get_plan(self):
        """The planner's GetPlan answer: the plan, and the semantic state it last decided on."""
        return self.call(self.plan_client, self.GetPlan.Request())

    def reset(self, task: str, seed: int, attempts: int = 2, positions: Sequence[float] = ()) -> tuple[bool, str]:
        """Reset the world to a task's start (``positions``: the blocks' x, y, z instead of the seeded start);
        returns once the planner has decided on the new world's first state, so a goal sent next is planned from it.

        In lockstep, should the new world have stepped first (a goal still under way when it was reset),
        the reset is made again; in realtime the world steps on the sim's clock from the start (the arm
        holding still without a goal), and any state of the new world will do."""
        message = "reset_world did not answer"
        for _ in range(attempts):
            try:
                reply = self.call(self.reset_client, self.ResetWorld.Request(
                    task=task, seed=seed, positions=[float(v) for v in positions]))
            except GraphUnavailableError as error:
                return False, str(error)
            if not reply.success:
                return False, reply.message
            self.episode = int(reply.world.episode)
            state = self.planner_state(reply.world.episode)
            if state is None:
                message = f"the planner saw no state of episode {reply.world.episode} ({reply.message})"
            elif state.step == 0 or not self.lockstep:
                return True, reply.message
            else:
                message = f"the world was at step {state.step} before a goal was sent ({reply.message})"
        return False, f"{message}; tried {attempts} resets"

    def must_reset(self, task: str, seed: int, positions: Sequence[float] = ()) -> None:
        """:meth:`reset`, raising RuntimeError with the reason when it fails (for unattended runs)."""
        ok, message = self.reset(task, seed, positions=positions)
        if not ok:
            raise RuntimeError(f"reset to {task} seed {seed} failed: {message}")

    def planner_state(self, episode: int, timeout: float = RESET_TIMEOUT_S):
        """The semantic state the planner last decided on, once it is of world ``episode``; None if it
        does not come within ``timeout``."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            try:
                state = self.get_plan().state
            except GraphUnavailableError:
                return None
            if state.scene and state.episode == episode:
                return state
            time.sleep(POLL_S)
        return None

    def move_block(self, block: str, x: float, y: float, z: float) -> tuple[bool, str]:
        request = self.MoveBlock.Request(block=block)
        request.position.x, request.position.y, request.position.z = float(x), float(y), float(z)
        try:
            reply = self.call(self.move_client, request)
        except GraphUnavailableError as error:
            return False, str(error)
        return reply.success, reply.message

    def edit(self, op: str, index: int = 0, action: str = "", to_index: int = 0, revision: int = 0):
        """An operator's plan edit: the planner's EditPlan answer (``success``, ``message``, ``plan``). The
        request id makes a repeat safe (the planner answers it without applying it twice); ``revision``
        (not 0) refuses the edit unless the plan is still at that revision."""
        request = self.EditPlan.Request(op=op, index=index, to_index=to_index, action=action, revision=revision,
                                        request_id=uuid.uuid4().hex)
        return self.call(self.edit_client, request)

    def publish_goal(self, text: str, wait_s: float = SERVICE_WAIT_S) -> bool:
        """Publish a goal on the goal topic (no answer comes: the plan topic shows what the planner made of
        it); False when nobody subscribes within ``wait_s``."""
        if not self.spin_until(lambda: self.goal_publisher.get_subscription_count() > 0, wait_s):
            return False
        self.goal_publisher.publish(goal_request(text))
        return True

    def send(self, text: str, max_steps: int = 0, feedback: Callable | None = None, sent: list | None = None):
        """Send a goal through ExecuteGoal; its goal handle (None when never answered). Every goal sent, the
        resends included, is appended to ``sent`` so a caller can cancel all of them."""
        goal = self.ExecuteGoal.Goal(goal=goal_request(text), max_steps=max_steps, episode=self.episode)
        if not self.action.wait_for_server(timeout_sec=SERVICE_WAIT_S):
            raise GraphUnavailableError(f"no {topics.EXECUTE_GOAL} action: is planner_node running?")
        sent = [] if sent is None else sent

        def send_once():
            sent.append(self.action.send_goal_async(goal, feedback_callback=feedback))
            return sent[-1]

        return topics.send_until_answered(send_once, self.spin_until)

    def execute(self, text: str, feedback: Callable | None = None, timeout: float = EPISODE_TIMEOUT_S,
                max_steps: int = 0, while_running: Callable[[], None] | None = None) -> GoalResult:
        """Send a goal (a task, literals or a sentence) through ExecuteGoal and wait for its result; the
        planner fails it once ``max_steps`` control steps are spent (0: no limit). A goal that outlasts
        ``timeout`` is cancelled, and so is one interrupted by Ctrl-C (the KeyboardInterrupt goes on up):
        the goal is the caller's to stop, not to leave running.

        ``while_running`` is called between spins (not inside a callback, so it may call services): the
        robustness tests intervene there."""
        started, sent, counted = time.perf_counter(), [], [0]

        def on_feedback(message) -> None:  # the planner's step count so far: all a lost goal's result can say
            counted[0] = int(message.feedback.control_steps)
            if feedback is not None:
                feedback(message)

        try:
            handle = self.send(text, max_steps, on_feedback, sent)
            if handle is None or not handle.accepted:
                return GoalResult(False, "the planner did not accept the goal", 0, 0, 0.0, 0.0)
            result_future = handle.get_result_async()
            planner = PlannerWatch(self.plan_client, self.GetPlan.Request())
            interruption = InterruptionWatch(handle, result_future)

            def done() -> bool:
                if while_running is not None:
                    while_running()
                return result_future.done() or interruption.ended() or planner.gone()

            if not self.spin_until(done, timeout):
                self.cancel(sent)
                return GoalResult(False, f"no result within {timeout:.0f} s; cancelled", 0, 0, 0.0,
                                  time.perf_counter() - started)
            if interruption.ended():
                reason = self.answers.get(bytes(handle.goal_id.uuid).hex(), "the planner ended the goal without a result")
                return GoalResult(False, reason, 0, counted[0], counted[0] * CONTROL_DT, time.perf_counter() - started)
            if not result_future.done():
                return GoalResult(False, f"planner_node left GetPlan unanswered for {PLANNER_SILENCE_S:.0f} s (killed or "
                                  "hung?): this goal's result is lost with it; a planner started again on the same world "
                                  "carries on with its plan (./semgoal plan show)", 0, counted[0],
                                  counted[0] * CONTROL_DT, time.perf_counter() - started)
        except GraphUnavailableError as error:
            return GoalResult(False, str(error), 0, 0, 0.0, 0.0)
        except KeyboardInterrupt:
            self.cancel(sent)
            raise
        except Exception as error:
            if not interrupted(error):
                raise
            self.cancel(sent)
            raise KeyboardInterrupt from error
        result = result_future.result().result
        return GoalResult(bool(result.success), result.message, int(result.replans), int(result.control_steps),
                          float(result.sim_time), time.perf_counter() - started)

    def cancel(self, sent: list) -> None:
        """Cancel every goal sent that the planner accepted (waiting briefly for answers still on their way)."""
        for future in sent:
            self.spin_until(future.done, SERVICE_WAIT_S)
            handle = future.result() if future.done() else None
            if handle is not None and handle.accepted:
                self.spin_until(handle.cancel_goal_async().done, SERVICE_WAIT_S)

    @contextmanager
    def recording(self, path: Path | str | None) -> Iterator:
        """Record the graph into ``path`` (MCAP, :class:`~semgoal_ros.recording.Recorder`) while the block runs:
        from once every publisher has matched the recorder until the last messages have come in. Yields the
        recorder (its ``counts`` per topic are final after the block), or None when ``path`` is None."""
        from semgoal_ros.recording import Recorder

        if path is None:
            yield None
            return
        recorder = Recorder(self.node, path)
        if not self.spin_until(recorder.matched, RECORDER_MATCH_S):
            self.node.get_logger().warn(f"the recorder did not match every publisher in {RECORDER_MATCH_S:.0f} s: "
                                        "the record may miss the start")
        try:
            yield recorder
            self.spin_until(lambda: False, RECORDER_SETTLE_S)  # the last states, still on their way
        finally:
            recorder.close()

    def close(self) -> None:
        self.executor.shutdown()
        self.node.destroy_node()
        self.rclpy.try_shutdown()
