"""Messages between the nodes of one SteadyExecutor handed over as objects (semgoal_ros.in_process): only where no one
else listens, in order, none twice, none lost when a listener comes and goes, the transient-local history kept for
late joiners (real DDS, in this process; a node outside the executor is a listener of another process to it)."""

import threading
import time

import pytest
import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy
from std_msgs.msg import Int64, String

from conftest import executor_nodes, spin_executor_until
from semgoal_ros.executor import EVENT_POLL_S, SteadyExecutor

pytestmark = pytest.mark.slow

VOLATILE = QoSProfile(depth=10, history=HistoryPolicy.KEEP_LAST, reliability=ReliabilityPolicy.RELIABLE,
                      durability=DurabilityPolicy.VOLATILE)
LATCHED = QoSProfile(depth=1, history=HistoryPolicy.KEEP_LAST, reliability=ReliabilityPolicy.RELIABLE,
                     durability=DurabilityPolicy.TRANSIENT_LOCAL)


@pytest.fixture
def context(ros_domain):
    context = rclpy.Context()
    rclpy.init(context=context, domain_id=ros_domain)
    yield context
    rclpy.shutdown(context=context)


@pytest.fixture
def routed(context):
    """A SteadyExecutor routing in the process, and a maker of its nodes."""
    executor = SteadyExecutor(context=context)
    executor.route_in_process()
    with executor_nodes(executor, context) as node:
        yield executor, node


def _started(executor) -> None:
    """One spin, so the executor has wired its routes (it does so when it first waits)."""
    executor.spin_once(timeout_sec=0.01)


@pytest.mark.parametrize("qos", [VOLATILE, LATCHED], ids=["volatile", "transient-local"])
def test_a_message_between_nodes_of_the_executor_is_handed_over_itself(routed, qos) -> None:
    executor, node = routed
    publisher = node("talker").create_publisher(Int64, "numbers", qos)
    got = []
    node("listener").create_subscription(Int64, "numbers", got.append, qos)
    _started(executor)
    sent = [Int64(data=i) for i in range(5)]
    for i, message in enumerate(sent):  # each taken before the next (LATCHED keeps one)
        publisher.publish(message)
        spin_executor_until(executor, lambda i=i: len(got) == i + 1)
    assert all(received is message for received, message in zip(got, sent, strict=True))


def test_with_a_listener_outside_every_message_goes_through_to_both_in_order_once(routed, context) -> None:
    executor, node = routed
    publisher = node("talker").create_publisher(Int64, "numbers", VOLATILE)
    inside, outside = [], []
    node("listener").create_subscription(Int64, "numbers", lambda m: inside.append(m.data), VOLATILE)
    _started(executor)
    publisher.publish(Int64(data=0))  # handed over
    spin_executor_until(executor, lambda: inside == [0])
    stranger = rclpy.create_node("stranger", context=context)  # not the executor's: as another process's node
    watcher = SingleThreadedExecutor(context=context)
    watcher.add_node(stranger)
    try:
        stranger.create_subscription(Int64, "numbers", lambda m: outside.append(m.data), VOLATILE)
        spin_executor_until(executor, lambda: publisher.get_subscription_count() == 2)
        for i in range(1, 4):
            publisher.publish(Int64(data=i))
        spin_executor_until(executor, lambda: len(inside) == 4)
        spin_executor_until(watcher, lambda: len(outside) == 3)
        assert inside == [0, 1, 2, 3] and outside == [1, 2, 3]
    finally:
        watcher.shutdown()
        stranger.destroy_node()
    spin_executor_until(executor, lambda: publisher.get_subscription_count() == 1)
    message = Int64(data=4)
    publisher.publish(message)  # handed over again
    spin_executor_until(executor, lambda: len(inside) == 5)
    executor.spin_once(timeout_sec=0.2)
    assert inside == [0, 1, 2, 3, 4]


def test_a_late_joiner_outside_gets_the_last_message_handed_over_and_the_nodes_inside_get_it_once(routed, context):
    executor, node = routed
    publisher = node("talker").create_publisher(Int64, "state", LATCHED)
    inside, outside = [], []
    node("listener").create_subscription(Int64, "state", lambda m: inside.append(m.data), LATCHED)
    _started(executor)
    for i in range(3):
        publisher.publish(Int64(data=i))
        spin_executor_until(executor, lambda i=i: len(inside) == i + 1)
    stranger = rclpy.create_node("late", context=context)
    watcher = SingleThreadedExecutor(context=context)
    watcher.add_node(stranger)
    try:
        stranger.create_subscription(Int64, "state", lambda m: outside.append(m.data), LATCHED)
        joined = time.monotonic()
        while not outside:  # nothing more is published: the executor's next event poll sends the last one through
            assert time.monotonic() - joined < EVENT_POLL_S + 5, "the late joiner never got the last message"
            executor.spin_once(timeout_sec=0.05)
            watcher.spin_once(timeout_sec=0.05)
        publisher.publish(Int64(data=3))
        spin_executor_until(watcher, lambda: len(outside) == 2)
        spin_executor_until(executor, lambda: len(inside) == 4)
        executor.spin_once(timeout_sec=0.2)
        assert outside == [2, 3]  # the last one before it joined, as a transient-local writer keeps it
        assert inside == [0, 1, 2, 3]
    finally:
        watcher.shutdown()
        stranger.destroy_node()


def test_a_message_published_from_another_thread_wakes_the_executor(routed) -> None:
    executor, node = routed
    publisher = node("talker").create_publisher(String, "words", VOLATILE)
    got = []
    node("listener").create_subscription(String, "words", got.append, VOLATILE)
    _started(executor)
    timer = threading.Timer(0.2, lambda: publisher.publish(String(data="hello")))
    timer.start()
    started = time.monotonic()
    while not got and time.monotonic() - started < 5:
        executor.spin_once(timeout_sec=5.0)
    timer.join()
    assert [m.data for m in got] == ["hello"] and time.monotonic() - started < 2.0


def test_a_wrong_type_is_still_refused(routed) -> None:
    executor, node = routed
    publisher = node("talker").create_publisher(Int64, "numbers", VOLATILE)
    node("listener").create_subscription(Int64, "numbers", lambda m: None, VOLATILE)
    _started(executor)
    with pytest.raises(TypeError):
        publisher.publish(String(data="not a number"))


def test_a_chain_of_handed_over_messages_does_not_keep_the_middleware_waiting(routed, context) -> None:
    """Two nodes ping-ponging in the process for ever; a message from outside still comes within a few spins."""
    executor, node = routed
    a, b = node("ping"), node("pong")
    to_b = a.create_publisher(Int64, "to_b", VOLATILE)
    to_a = b.create_publisher(Int64, "to_a", VOLATILE)
    b.create_subscription(Int64, "to_b", lambda m: to_a.publish(Int64(data=m.data + 1)), VOLATILE)
    a.create_subscription(Int64, "to_a", lambda m: to_b.publish(Int64(data=m.data + 1)), VOLATILE)
    heard = []
    a.create_subscription(String, "news", heard.append, VOLATILE)
    outsider = rclpy.create_node("outsider", context=context)
    try:
        news = outsider.create_publisher(String, "news", VOLATILE)
        spin_executor_until(executor, lambda: news.get_subscription_count() == 1)
        to_b.publish(Int64(data=0))
        news.publish(String(data="from outside"))
        spin_executor_until(executor, lambda: bool(heard), timeout=5.0)
    finally:
        outsider.destroy_node()


def test_a_node_that_leaves_the_executor_publishes_through_the_middleware_again(routed) -> None:
    executor, node = routed
    talker = node("talker")
    publisher = talker.create_publisher(Int64, "numbers", VOLATILE)
    got = []
    node("listener").create_subscription(Int64, "numbers", lambda m: got.append(m.data), VOLATILE)
    _started(executor)
    publisher.publish(Int64(data=0))
    spin_executor_until(executor, lambda: got == [0])
    executor.remove_node(talker)
    _started(executor)  # the routes wired again without it
    publisher.publish(Int64(data=1))
    spin_executor_until(executor, lambda: got == [0, 1])
