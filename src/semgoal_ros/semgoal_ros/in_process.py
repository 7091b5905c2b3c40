"""Messages between the nodes of one process handed over as Python objects, not through the middleware.

With the graph's nodes in one process (``graph_node``), every control step's world state, semantic state, sub-goal and
arm command went out through Fast DDS and came back into the same process: serialised once, deserialised into new
Python objects for each subscriber, and each one waited for by the executor. Where every subscription matched to a
publisher is one of this process's, :class:`InProcessRoutes` puts the message object itself in each one's queue (as
deep as its QoS history) and :class:`~semgoal_ros.executor.SteadyExecutor` calls their callbacks before it waits:
rclcpp's intra-process communication, for rclpy. Where anyone else listens (a recorder, ``ros2 topic echo``, a node
of another process) the publisher matches more subscriptions than this process has, and the message goes through the
middleware to all of them, as without routes.

A transient-local publisher's late joiner still gets the last message handed over: it is sent through when the
executor next polls its QoS events (within a second) or before the next message, whichever comes first, and this
process's own subscriptions, having had it, skip it. The subscribers share the one object, so their callbacks must
only read it (the graph's do, as rclcpp's shared intra-process messages are const). When the last outside listener
leaves, a message sent through and not yet taken may reach a subscription after the next one handed over.
"""

from __future__ import annotations

import inspect
import threading
from collections import deque
from collections.abc import Callable, Iterable, Iterator
from typing import Any

from rclpy.exceptions import InvalidHandle
from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSCompatibility, qos_check_compatible
from rclpy.subscription import Subscription


class _Route:
    """A publisher's ``publish``: to its process's subscriptions' queues where they are all it matches, else through
    the middleware (``publish_through``)."""

    __slots__ = ("_last", "_publish_through", "_publisher", "_routes", "queues", "subscriptions")

    def __init__(self, routes: InProcessRoutes, publisher: Any, publish_through: Callable[[Any], None]) -> None:
        self._routes, self._publisher, self._publish_through = routes, publisher, publish_through
        self.queues: list[deque] = []
        self.subscriptions: list[Subscription] = []
        self._last: Any = None
        """A transient-local publisher's last message handed over, while the middleware's history lacks it."""

    def __call__(self, msg: Any) -> None:
        publisher = self._publisher
        if not isinstance(msg, publisher.msg_type):
            self._publish_through(msg)  # raw bytes, or a wrong type (rclpy raises)
            return
        if self.catch_up():  # a listener outside this process
            self._publish_through(msg)
            return
        if publisher.qos_profile.durability == DurabilityPolicy.TRANSIENT_LOCAL:
            self._last = msg
        for queue in self.queues:
            queue.append(msg)
        self._routes.delivered()

    def catch_up(self) -> bool:
        """Whether a listener outside this process is matched; if one is, the last message handed over goes through
        first, as the history a transient-local writer gives a late joiner (this process's own have had it)."""
        if self._publisher.get_subscription_count() <= len(self.queues):
            return False
        if self._last is not None:
            self._publish_through(self._last)
            self._routes.skip_one(self.subscriptions)
            self._last = None
        return True


class InProcessRoutes:
    """The routes between the publishers and the subscriptions of an executor's nodes (module docstring).

    :meth:`refresh` (re)wires them from the nodes' entities; :meth:`take` hands the executor the messages waiting,
    one per subscription; ``wake`` is called when a message is queued from a thread other than the one spinning."""

    def __init__(self, wake: Callable[[], None]) -> None:
        self._wake = wake
        self._queues: dict[Subscription, deque] = {}
        self._nodes: dict[Subscription, Any] = {}
        self._routes: dict[Any, _Route] = {}
        self._skips: dict[Subscription, int] = {}
        """Per subscription, how many of its next messages through the middleware it has had handed over."""
        self._spinning = threading.get_ident()
        self.pending = False
        """Whether a message may be waiting: the executor's cheap test before it asks :meth:`take`."""

    def refresh(self, nodes: Iterable[Any]) -> None:
        """Route every publisher of ``nodes`` to the subscriptions of ``nodes`` on its topic that can take a message
        object from it (:func:`_takes_objects`); messages already queued stay."""
        nodes = list(nodes)
        subscriptions = [(subscription, node) for node in nodes for subscription in node.subscriptions
                         if _takes_objects(subscription)]
        self._nodes = {subscription: node for subscription, node in subscriptions}
        self._queues = {subscription: self._queues.get(subscription) or _queue(subscription)
                        for subscription, _ in subscriptions}
        routes = {}
        for node in nodes:
            for publisher in node.publishers:
                local = [subscription for subscription, _ in subscriptions if _matches(publisher, subscription)]
                route = self._routes.get(publisher)
                if route is None and local:
                    route = publisher.publish = _Route(self, publisher, type(publisher).publish.__get__(publisher))
                if route is not None:  # a publisher whose subscriptions went publishes through: nothing in its queues
                    route.subscriptions, route.queues = local, [self._queues[subscription] for subscription in local]
                    routes[publisher] = route
        for publisher in self._routes.keys() - routes.keys():  # its node left the executor: rclpy's publish again
            del publisher.publish
        self._routes = routes

    def catch_up(self) -> None:
        """Give the listeners outside that joined since the last message of each transient-local route (its
        :meth:`_Route.catch_up`): called now and then by the executor, so a late joiner has it soon even while
        nothing is published."""
        for route in list(self._routes.values()):
            try:
                route.catch_up()
            except InvalidHandle:  # its publisher destroyed meanwhile
                continue

    def skip_one(self, subscriptions: Iterable[Subscription]) -> None:
        for subscription in subscriptions:
            self._skips[subscription] = self._skips.get(subscription, 0) + 1

    def skipping(self, subscription: Subscription) -> bool:
        """Whether ``subscription``'s next message through the middleware is one it had handed over."""
        return self._skips.get(subscription, 0) > 0

    def skipped(self, subscription: Subscription) -> None:
        self._skips[subscription] -= 1

    def delivered(self) -> None:
        self.pending = True
        if threading.get_ident() != self._spinning:
            self._wake()

    def take(self) -> Iterator[tuple[Subscription, Any, Any]]:
        """(subscription, its node, the message) for the oldest message of each subscription with one, whose callback
        group lets it run now; called by the spinning thread."""
        self._spinning = threading.get_ident()
        self.pending = False
        for subscription, queue in self._queues.items():
            if not queue:
                continue
            if not subscription.callback_group.can_execute(subscription):
                self.pending = True  # its turn comes when the group opens
                continue
            message = queue.popleft()
            self.pending = self.pending or bool(queue)
            yield subscription, self._nodes[subscription], message


def _takes_objects(subscription: Subscription) -> bool:
    """A subscription that takes a deserialised message alone into a plain function: one a message object can be
    handed to as the middleware would hand it."""
    return (not subscription.raw and subscription._callback_type is Subscription.CallbackType.MessageOnly
            and not inspect.iscoroutinefunction(subscription.callback))


def _matches(publisher: Any, subscription: Subscription) -> bool:
    """Whether the middleware would carry ``publisher``'s messages to ``subscription``: same topic, type, and QoS that
    match."""
    try:
        same_topic = publisher.topic_name == subscription.topic_name
    except InvalidHandle:  # destroyed meanwhile
        return False
    return (same_topic and publisher.msg_type is subscription.msg_type
            and qos_check_compatible(publisher.qos_profile, subscription.qos_profile)[0] != QoSCompatibility.ERROR)


def _queue(subscription: Subscription) -> deque:
    qos = subscription.qos_profile
    return deque(maxlen=None if qos.history == HistoryPolicy.KEEP_ALL else max(1, qos.depth))
