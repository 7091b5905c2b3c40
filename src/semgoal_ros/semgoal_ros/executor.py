"""A single-threaded executor that keeps what it waits on between spins.

rclpy's ``SingleThreadedExecutor`` rebuilds, on every spin, the list of every entity of every node (each passed
through its callback group), enters each handle's context, builds a new wait set, and then looks every ready handle
up in lists. A node of the graph has about twenty entities (its parameter services, its publishers' and
subscriptions' QoS event handlers, its own services and subscriptions), so on the graph's hot path that work cost
more than taking and handling the messages (docs/measurements.md). :class:`SteadyExecutor` gathers them again only
when a node or an entity comes or goes (rclpy wakes its executor then), keeps their handles entered meanwhile (so
none is destroyed while it is waited on), reuses one wait set, finds ready handles in sets, is not woken by its own
callbacks, calls a subscription's plain callback without wrapping it in a task and two coroutines (:class:`_Call`),
and waits on the QoS event handlers once a second (:data:`EVENT_POLL_S`), not in every wait. What runs, in
what order and under which callback group's rule is rclpy's: tasks in progress first, then per node its waitables,
timers, subscriptions, guard conditions, clients and services. With :meth:`SteadyExecutor.route_in_process`, the
messages its nodes send each other without the middleware (:mod:`semgoal_ros.in_process`) run after the tasks in
progress, before the wait.
"""

from __future__ import annotations

import inspect
import threading
import time
from collections.abc import Callable, Generator, Iterable
from contextlib import ExitStack
from typing import Any

from rclpy.callback_groups import MutuallyExclusiveCallbackGroup, ReentrantCallbackGroup
from rclpy.event_handler import EventHandler
from rclpy.exceptions import InvalidHandle
from rclpy.executors import (
    ConditionReachedException,
    ExternalShutdownException,
    ShutdownException,
    SingleThreadedExecutor,
    TimeoutException,
    TimeoutObject,
)
from rclpy.impl.implementation_singleton import rclpy_implementation as _rclpy
from rclpy.subscription import Subscription
from rclpy.task import Task
from rclpy.timer import Timer
from rclpy.utilities import timeout_sec_to_nsec

from semgoal_ros.in_process import InProcessRoutes

KINDS = ("timer", "subscription", "guard_condition", "client", "service")
"""The wait set's kinds of plain entity, in the order rclpy hands a node's ready callbacks out."""
NODE_LISTS = ("timers", "subscriptions", "guards", "clients", "services")
"""The node's property listing each kind."""
EVENT_POLL_S = 1.0
"""How often the QoS event handlers (incompatible QoS or type, a publisher matched: two or three per publisher and
subscription, rclpy's defaults) are waited on. Added to every wait they were about two fifths of the executor's work
on the graph's hot path; an event's status waits in the middleware until it is taken, so one comes at most this late."""
ROUNDS_BEFORE_POLL = 8
"""How many spins in a row may run only messages sent in the process before the middleware is polled (a wait without
a timeout): so a chain of in-process messages cannot keep the others waiting."""


class _Waited:
    """Every entity of the executor's nodes, their handles entered, and one wait set with room for them all and a
    timeout timer."""

    def __init__(self, nodes: Iterable[Any], executor_guards: tuple, context: Any) -> None:
        self.stack = ExitStack()
        self.nodes: list[tuple[Any, dict[str, list], list]] = []
        self.without_events: list[list] = []
        """Per node, its waitables but the QoS event handlers: what a wait between two event polls adds."""
        room = dict.fromkeys(("subscription", "guard_condition", "timer", "client", "service", "event"), 0)
        for node in nodes:
            entities = {kind: self._entered(getattr(node, listed)) for kind, listed in zip(KINDS, NODE_LISTS, strict=True)}
            waitables = []
            for waitable in node.waitables:
                try:
                    self.stack.enter_context(waitable)
                except InvalidHandle:
                    continue
                waitables.append(waitable)
                number = waitable.get_num_entities()
                for kind in room:
                    room[kind] += getattr(number, f"num_{kind}s")
            for kind, entered in entities.items():
                room[kind] += len(entered)
            self.nodes.append((node, entities, waitables))
            self.without_events.append([waitable for waitable in waitables if not isinstance(waitable, EventHandler)])
        self.guards = self._entered(executor_guards)
        room["guard_condition"] += len(self.guards)
        self.groups = {entity.callback_group for _, entities, waitables in self.nodes
                       for entity in (*waitables, *(e for entered in entities.values() for e in entered))}
        self.plain = {subscription for _, entities, _ in self.nodes for subscription in entities["subscription"]
                      if not inspect.iscoroutinefunction(subscription.callback)}
        """The subscriptions whose callback is a plain function: run as a :class:`_Call`, not as a task."""
        self.pointers = {id(entity): entity.handle.pointer for _, entities, _ in self.nodes
                         for entered in entities.values() for entity in entered}
        self.wait_set = _rclpy.WaitSet(room["subscription"], room["guard_condition"], room["timer"] + 1, room["client"],
                                       room["service"], room["event"], context.handle)
        self.add = dict(zip(KINDS, (self.wait_set.add_timer, self.wait_set.add_subscription,
                                    self.wait_set.add_guard_condition, self.wait_set.add_client,
                                    self.wait_set.add_service), strict=True))

    def _entered(self, entities: Iterable[Any]) -> list[Any]:
        entered = []
        for entity in entities:
            try:
                self.stack.enter_context(entity.handle)
            except InvalidHandle:  # destroyed meanwhile
                continue
            entered.append(entity)
        return entered

    def close(self) -> None:
        self.wait_set.destroy_when_not_in_use()
        self.stack.close()


class SteadyExecutor(SingleThreadedExecutor):
    """rclpy's single-threaded executor, what it waits on kept between spins (module docstring).

    The spinning thread holds ``_waiting`` from gathering to the end of a wait. A wake (a node's entity came or
    went, from any thread) that finds it free lets the handles go at once, so a destroyed entity goes at once too;
    one that finds it held marks them stale, and the spinning thread gathers again before its next wait."""

    def __init__(self, *, context: Any = None) -> None:
        super().__init__(context=context)
        self._waited: _Waited | None = None
        self._stale = False
        self._events_due = 0.0
        self._waiting = threading.Lock()
        self._routes: InProcessRoutes | None = None
        self._in_process_rounds = 0

    def route_in_process(self) -> None:
        """Hand messages between this executor's nodes over as objects where no one else listens
        (:mod:`semgoal_ros.in_process`), from the next spin on."""
        self._routes = InProcessRoutes(self._guard.trigger)
        self._let_go()

    def wake(self) -> None:
        self._let_go()
        super().wake()

    def add_node(self, node: Any) -> bool:
        self._let_go()
        return super().add_node(node)

    def remove_node(self, node: Any) -> None:
        self._let_go()
        super().remove_node(node)

    def shutdown(self, timeout_sec: float | None = None) -> bool:
        done = super().shutdown(timeout_sec)
        self._let_go()
        return done

    def _make_handler(self, entity: Any, node: Any, take_from_wait_list: Callable) -> Task:
        """The task that takes ``entity``'s work and runs its callback, as rclpy's, without waking this executor twice
        per callback: rclpy's handler triggers the executor's guard condition once the work is taken and once it
        is done, so that other threads may wait on the entity again; this executor's one thread builds its next wait
        only after the handler returns, so each trigger was one more wait that found nothing but the trigger (two
        waits a message on the graph's hot path). A callback that awaits resumes as a task in progress (tasks come
        first in each wait) and a callback group it holds opens again before the next wait is built."""
        entity._executor_event = True  # out of the wait set until the work is taken

        async def handler() -> None:
            if self._is_shutdown or not entity.callback_group.beginning_execution(entity):
                entity._executor_event = False
                return
            with self._work_tracker:
                callback = take_from_wait_list(entity)
                entity._executor_event = False
                try:
                    if callback is not None:
                        await callback()
                finally:
                    entity.callback_group.ending_execution(entity)

        task = Task(handler, executor=self)
        with self._tasks_lock:
            self._tasks.append((task, entity, node))
        return task

    def _let_go(self) -> None:
        """Let the entities go now where no wait is using them; else mark them stale for the spinning thread."""
        if self._waiting.acquire(blocking=False):
            try:
                self._forget()
            finally:
                self._waiting.release()
        else:
            self._stale = True

    def _forget(self) -> None:
        waited, self._waited, self._stale = self._waited, None, False
        if waited is not None:
            waited.close()

    def _wait_for_ready_callbacks(self, timeout_sec: float | TimeoutObject | None = None, nodes: list | None = None,
                                  condition: Callable[[], bool] = lambda: False) -> Generator[tuple, None, None]:
        if nodes is not None:  # a spin over some of the nodes only: rclpy's own way
            yield from super()._wait_for_ready_callbacks(timeout_sec, nodes, condition)
            return
        timeout_nsec = timeout_sec_to_nsec(timeout_sec.timeout if isinstance(timeout_sec, TimeoutObject) else timeout_sec)
        timeout_timer = Timer(None, None, timeout_nsec, self._clock, context=self._context) if timeout_nsec > 0 else None
        yielded_work = False
        while not yielded_work and not self._is_shutdown and not condition():
            nodes_now = self.get_nodes()
            with self._tasks_lock:
                tasks = list(self._tasks)
            if tasks:  # tasks in progress (coroutines that awaited) go first, as in rclpy
                for task, entity, node in reversed(tasks):
                    if not task.executing() and not task.done() and (node is None or node in nodes_now):
                        yielded_work = True
                        yield task, entity, node
                with self._tasks_lock:
                    self._tasks = [t for t in self._tasks if not t[0].done() and not t[0].cancelled()]
            handed_over = False
            if self._routes is not None and self._routes.pending:
                for subscription, node, message in self._routes.take():
                    handed_over = yielded_work = True
                    yield _Call(self, subscription, message), subscription, node
            if handed_over:
                self._in_process_rounds += 1
                if self._in_process_rounds < ROUNDS_BEFORE_POLL:
                    continue
            self._in_process_rounds = 0
            with self._waiting:
                if self._waited is None or self._stale:
                    self._forget()
                    self._waited = _Waited(nodes_now, (self._guard, self._sigint_gc), self._context)
                    if self._routes is not None:
                        self._routes.refresh(nodes_now)
                waited = self._waited
                ready, waitables_ready = self._wait(waited, timeout_timer, 0 if handed_over else timeout_nsec)
            for node, _, waitables in waited.nodes:
                for waitable in waitables:
                    if waitable in waitables_ready and waitable.callback_group.can_execute(waitable):
                        yielded_work = True
                        yield self._make_handler(waitable, node, self._take_waitable), waitable, node
                        if self._waited is not waited or self._stale:  # a callback added or removed an entity
                            return
            for node, entities, _ in waited.nodes:
                for kind, take in zip(KINDS, (self._take_timer, self._take_subscription, self._take_guard_condition,
                                              self._take_client, self._take_service), strict=True):
                    for entity in entities[kind]:
                        if not _is_ready(entity, kind, waited, ready) or not entity.callback_group.can_execute(entity):
                            continue
                        yielded_work = True
                        plain = kind == "subscription" and entity in waited.plain
                        yield (_Call(self, entity) if plain else self._make_handler(entity, node, take)), entity, node
                        if self._waited is not waited or self._stale:
                            return
            if timeout_nsec == 0 or (timeout_timer is not None and timeout_timer.handle.pointer in ready["timer"]):
                raise TimeoutException()
        if self._is_shutdown:
            raise ShutdownException()
        if condition():
            raise ConditionReachedException()

    def _wait(self, waited: _Waited, timeout_timer: Timer | None, timeout_nsec: int) -> tuple[dict[str, set], set]:
        """One wait on the entities that may run now (``_waiting`` held); the ready handles' pointers by kind, and the
        ready waitables."""
        open_groups = {group for group in waited.groups if _group_open(group)}
        now = time.monotonic()
        with_events = now >= self._events_due
        if with_events:
            self._events_due = now + EVENT_POLL_S
            if self._routes is not None:  # late joiners outside, on the same rhythm as the QoS events
                self._routes.catch_up()
        else:  # back by the time the events are due
            until_events = int((self._events_due - now) * 1e9)
            timeout_nsec = until_events if timeout_nsec < 0 else min(timeout_nsec, until_events)
        wait_set, add = waited.wait_set, waited.add
        wait_set.clear_entities()
        added_waitables = []
        for (_, entities, waitables), without_events in zip(waited.nodes, waited.without_events, strict=True):
            for kind, entered in entities.items():
                for entity in entered:
                    if entity._executor_event or not _may_run(entity, open_groups):
                        continue
                    if kind == "guard_condition" and entity._executor_triggered:  # not handled yet: again
                        entity.trigger()
                    add[kind](entity.handle)
            for waitable in waitables if with_events else without_events:
                if not waitable._executor_event and _may_run(waitable, open_groups):
                    waitable.add_to_wait_set(wait_set)
                    added_waitables.append(waitable)
        for guard in waited.guards:
            wait_set.add_guard_condition(guard.handle)
        with ExitStack() as stack:
            if timeout_timer is not None:
                stack.enter_context(timeout_timer.handle)
                wait_set.add_timer(timeout_timer.handle)
            stack.enter_context(self._context.handle)
            wait_set.wait(timeout_nsec)
        if self._is_shutdown or not self._context.ok():
            self._forget()
            raise ShutdownException() if self._is_shutdown else ExternalShutdownException()
        ready = {kind: set(wait_set.get_ready_entities(kind)) for kind in KINDS}
        for _, entities, _ in waited.nodes:
            for guard in entities["guard_condition"]:
                if waited.pointers[id(guard)] in ready["guard_condition"]:
                    guard._executor_triggered = True
        return ready, {waitable for waitable in added_waitables if waitable.is_ready(wait_set)}


_TAKE = object()
"""A :class:`_Call`'s message still to be taken from the middleware."""


class _Call:
    """A subscription's message taken (or handed over in the process) and its plain callback run, as the task rclpy
    makes for it does (the callback group's turn, the work tracker, the exception kept for the spin to raise), without
    the task and the two coroutines that let a callback await: most of a message's cost in rclpy after taking it."""

    __slots__ = ("_exception", "_executor", "_message", "_subscription")

    def __init__(self, executor: SteadyExecutor, subscription: Any, message: Any = _TAKE) -> None:
        self._executor, self._subscription, self._exception, self._message = executor, subscription, None, message
        if message is _TAKE:
            subscription._executor_event = True  # out of the wait set until the message is taken

    def __call__(self) -> None:
        subscription, group = self._subscription, self._subscription.callback_group
        if self._executor._is_shutdown or not group.beginning_execution(subscription):
            if self._message is _TAKE:
                subscription._executor_event = False
            return
        try:
            with self._executor._work_tracker:
                taken = self._take() if self._message is _TAKE else self._handed_over()
                if taken is not None:
                    subscription.callback(*taken)
        except Exception as error:  # raised by the spin, as rclpy raises a task's
            self._exception = error
        finally:
            group.ending_execution(subscription)

    def _take(self) -> tuple | None:
        subscription, routes = self._subscription, self._executor._routes
        skip = routes is not None and routes.skipping(subscription)
        try:
            with subscription.handle:  # one this process handed over is only taken out of the way, not deserialised
                info = subscription.handle.take_message(subscription.msg_type, subscription.raw or skip)
        except InvalidHandle:  # destroyed since the wait
            return None
        finally:
            subscription._executor_event = False
        if info is None:
            return None
        if skip:
            routes.skipped(subscription)
            return None
        return (info[0],) if subscription._callback_type is Subscription.CallbackType.MessageOnly else info

    def _handed_over(self) -> tuple | None:
        try:
            with self._subscription.handle:
                return (self._message,)
        except InvalidHandle:  # destroyed since the message was queued
            return None

    def exception(self) -> Exception | None:
        return self._exception

    def result(self) -> None:
        if self._exception is not None:
            raise self._exception


def _is_ready(entity: Any, kind: str, waited: _Waited, ready: dict[str, set]) -> bool:
    if kind == "guard_condition":
        return entity._executor_triggered
    if waited.pointers[id(entity)] not in ready[kind]:
        return False
    try:
        return kind != "timer" or entity.handle.is_timer_ready()  # as rclpy: rcl reports cancelled timers ready
    except InvalidHandle:  # destroyed by a callback since the wait
        return False


def _group_open(group: Any) -> bool:
    """Whether a callback group lets its entities start now: rclpy's two kinds answer alike for each of their
    entities, so once per group; another kind is asked per entity (:func:`_may_run`)."""
    if isinstance(group, ReentrantCallbackGroup):
        return True
    return type(group) is MutuallyExclusiveCallbackGroup and group._active_entity is None


def _may_run(entity: Any, open_groups: set) -> bool:
    group = entity.callback_group
    if group in open_groups:
        return True
    return not isinstance(group, ReentrantCallbackGroup | MutuallyExclusiveCallbackGroup) and group.can_execute(entity)
