"""SteadyExecutor runs what rclpy's single-threaded executor runs: messages, services, timers, guard conditions,
coroutines, entities that come and go while it spins, and a clean shutdown (real DDS, in this process)."""

import threading
import time

import pytest
import rclpy
from rclpy.callback_groups import MutuallyExclusiveCallbackGroup, ReentrantCallbackGroup
from rclpy.event_handler import EventHandler, SubscriptionEventCallbacks
from rclpy.executors import SingleThreadedExecutor
from rclpy.qos import QoSProfile, ReliabilityPolicy
from std_msgs.msg import Int64

from conftest import executor_nodes, spin_executor_until
from semgoal_msgs.srv import GetPlan
from semgoal_ros.executor import EVENT_POLL_S, SteadyExecutor

pytestmark = pytest.mark.slow


@pytest.fixture(params=[SteadyExecutor, SingleThreadedExecutor])
def ros(ros_domain, request):
    """Each test with ours and with rclpy's own, the reference."""
    context = rclpy.Context()
    rclpy.init(context=context, domain_id=ros_domain)
    executor = request.param(context=context)
    with executor_nodes(executor, context) as node:
        yield executor, node
    rclpy.shutdown(context=context)


def _matched(executor, publisher) -> None:
    spin_executor_until(executor, lambda: publisher.get_subscription_count() > 0)


def test_messages_go_back_and_forth_in_order(ros) -> None:
    executor, node = ros
    a, b = node("ping"), node("pong")
    got: list[int] = []
    to_b = a.create_publisher(Int64, "to_b", 10)
    to_a = b.create_publisher(Int64, "to_a", 10)
    b.create_subscription(Int64, "to_b", lambda msg: to_a.publish(Int64(data=msg.data + 1)), 10)
    a.create_subscription(Int64, "to_a", lambda msg: (got.append(msg.data), to_b.publish(Int64(data=msg.data + 1))), 10)
    _matched(executor, to_b)
    _matched(executor, to_a)
    to_b.publish(Int64(data=0))
    spin_executor_until(executor, lambda: len(got) >= 200)
    assert got[:200] == list(range(1, 400, 2))


def test_each_message_costs_one_wait(ros_domain) -> None:
    """rclpy's handler triggers the executor's guard condition twice per callback, so each message that came alone
    cost a second wait that found only the trigger; ours builds its next wait after the callback and needs no wake.
    The messages come from another context, one every 5 ms, as from another node's process."""
    contexts = [rclpy.Context(), rclpy.Context()]
    for context in contexts:
        rclpy.init(context=context, domain_id=ros_domain)
    executor = SteadyExecutor(context=contexts[0])
    waits = [0]
    wait = executor._wait

    def counted(*args):
        waits[0] += 1
        return wait(*args)

    executor._wait = counted
    listener, talker = (rclpy.create_node(name, context=context) for name, context in zip(("listener", "talker"), contexts, strict=True))
    executor.add_node(listener)
    got: list[int] = []
    listener.create_subscription(Int64, "beat", lambda msg: got.append(msg.data), 100)
    publisher = talker.create_publisher(Int64, "beat", 100)
    try:
        _matched(executor, publisher)
        before = waits[0]

        def beat() -> None:
            for count in range(100):
                publisher.publish(Int64(data=count))
                time.sleep(0.005)

        thread = threading.Thread(target=beat)
        thread.start()
        spin_executor_until(executor, lambda: len(got) >= 100)
        thread.join()
        assert got == list(range(100)) and waits[0] - before <= 120  # rclpy's way: about 200
    finally:
        executor.shutdown()
        for made in (listener, talker):
            made.destroy_node()
        for context in contexts:
            rclpy.shutdown(context=context)


def test_qos_events_come_within_a_poll_and_are_not_waited_on_every_message(ros_domain, monkeypatch) -> None:
    """The QoS event handlers go into a wait at most once per EVENT_POLL_S, yet an event (a subscriber whose QoS the
    publisher cannot serve) still reaches its callback, while nothing else wakes the executor."""
    added = [0]
    add = EventHandler.add_to_wait_set

    def counted(self, wait_set) -> None:
        added[0] += 1
        add(self, wait_set)

    monkeypatch.setattr(EventHandler, "add_to_wait_set", counted)
    context = rclpy.Context()
    rclpy.init(context=context, domain_id=ros_domain)
    executor = SteadyExecutor(context=context)
    node = rclpy.create_node("events", context=context)
    executor.add_node(node)
    incompatible: list[str] = []
    try:
        beat = node.create_publisher(Int64, "beat", 10)
        got: list[int] = []
        node.create_subscription(Int64, "beat", lambda msg: (got.append(msg.data), got[-1] < 300 and beat.publish(
            Int64(data=msg.data + 1))), 10)
        _matched(executor, beat)
        before = added[0]
        beat.publish(Int64(data=0))
        spin_executor_until(executor, lambda: len(got) > 300)
        handlers = sum(isinstance(w, EventHandler) for w in node.waitables)
        assert added[0] - before <= handlers * 10  # 300 messages; each wait adding them: 300 times each
        best_effort = QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_EFFORT)
        node.create_publisher(Int64, "strict", best_effort)
        node.create_subscription(Int64, "strict", lambda msg: None, QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE),
                                 event_callbacks=SubscriptionEventCallbacks(
                                     incompatible_qos=lambda event: incompatible.append(event.last_policy_kind)))
        spin_executor_until(executor, lambda: incompatible, timeout=3 * EVENT_POLL_S + 2)
    finally:
        executor.shutdown()
        node.destroy_node()
        rclpy.shutdown(context=context)


def test_a_plain_callback_runs_without_a_task_and_a_coroutine_with_one(ros_domain, monkeypatch) -> None:
    """A subscription's plain callback (with or without the message's info) is called straight after its message is
    taken; one that is a coroutine still runs as rclpy's task, so it may await."""
    context = rclpy.Context()
    rclpy.init(context=context, domain_id=ros_domain)
    executor, node = SteadyExecutor(context=context), rclpy.create_node("listener", context=context)
    executor.add_node(node)
    tasks = []
    make_handler = executor._make_handler
    monkeypatch.setattr(executor, "_make_handler", lambda entity, *rest: (tasks.append(entity), make_handler(entity, *rest))[1])
    heard: dict[str, list] = {"plain": [], "with info": [], "coroutine": []}

    async def awaiting(msg: Int64) -> None:
        heard["coroutine"].append(msg.data)

    try:
        publisher = node.create_publisher(Int64, "numbers", 10)
        node.create_subscription(Int64, "numbers", lambda msg: heard["plain"].append(msg.data), 10)
        node.create_subscription(Int64, "numbers", lambda msg, info: heard["with info"].append(
            (msg.data, info["publication_sequence_number"] > 0)), 10)
        coroutine = node.create_subscription(Int64, "numbers", awaiting, 10)
        spin_executor_until(executor, lambda: publisher.get_subscription_count() == 3)
        for number in range(5):
            publisher.publish(Int64(data=number))
        spin_executor_until(executor, lambda: all(len(got) == 5 for got in heard.values()))
        assert heard == {"plain": list(range(5)), "with info": [(n, True) for n in range(5)], "coroutine": list(range(5))}
        assert [entity for entity in tasks if entity in node.subscriptions] == [coroutine] * 5
    finally:
        executor.shutdown()
        node.destroy_node()
        rclpy.shutdown(context=context)


def test_an_exception_in_a_callback_is_raised_by_the_spin(ros) -> None:
    executor, node = ros
    talker = node("talker")
    publisher = talker.create_publisher(Int64, "numbers", 10)

    def fails(msg: Int64) -> None:
        raise ValueError(f"bad {msg.data}")

    talker.create_subscription(Int64, "numbers", fails, 10)
    _matched(executor, publisher)
    publisher.publish(Int64(data=3))
    with pytest.raises(ValueError, match="bad 3"):
        spin_executor_until(executor, lambda: False, timeout=5.0)


def test_a_coroutine_awaits_a_service_of_another_node(ros) -> None:
    executor, node = ros
    server, caller = node("server"), node("caller")

    def answer(request, response):
        response.message = "answered"
        return response

    server.create_service(GetPlan, "get", answer)
    client = caller.create_client(GetPlan, "get", callback_group=ReentrantCallbackGroup())  # free while ask() waits
    answers: list[str] = []

    async def ask() -> None:
        timer.cancel()
        response = await client.call_async(GetPlan.Request())
        answers.append(response.message)

    spin_executor_until(executor, client.service_is_ready)
    timer = caller.create_timer(0.01, ask)
    spin_executor_until(executor, lambda: answers)
    assert answers == ["answered"]


def test_entities_made_and_destroyed_while_spinning_are_waited_on_and_let_go(ros) -> None:
    executor, node = ros
    talker, listener = node("talker"), node("listener")
    publisher = talker.create_publisher(Int64, "numbers", 10)
    heard: list[int] = []
    made: list = []
    timer = listener.create_timer(0.01, lambda: (timer.cancel(), made.append(
        listener.create_subscription(Int64, "numbers", lambda msg: heard.append(msg.data), 10))))
    spin_executor_until(executor, lambda: made)
    _matched(executor, publisher)
    publisher.publish(Int64(data=7))
    spin_executor_until(executor, lambda: heard)
    assert heard == [7]

    assert listener.destroy_subscription(made[0])
    spin_executor_until(executor, lambda: publisher.get_subscription_count() == 0)  # destroyed, not held by the executor
    publisher.publish(Int64(data=8))
    executor.spin_once(timeout_sec=0.2)
    assert heard == [7]


def test_a_guard_condition_triggered_from_another_thread_runs_its_callback(ros) -> None:
    executor, node = ros
    woken: list[str] = []
    guard = node("guarded").create_guard_condition(lambda: woken.append(threading.current_thread().name))
    threading.Timer(0.05, guard.trigger).start()
    spin_executor_until(executor, lambda: woken)
    assert woken == [threading.current_thread().name]


def test_spin_until_future_complete_and_timeouts_behave_as_rclpy(ros) -> None:
    executor, node = ros
    ticks: list[float] = []
    node("ticker").create_timer(0.02, lambda: ticks.append(time.monotonic()))
    future = rclpy.task.Future()
    threading.Timer(0.3, lambda: future.set_result("done")).start()
    executor.spin_until_future_complete(future, timeout_sec=5.0)
    assert future.result() == "done"
    assert len(ticks) >= 5
    started = time.monotonic()
    executor.spin_once(timeout_sec=0.0)  # nothing to wait for: back at once
    assert time.monotonic() - started < 0.1


def test_it_is_faster_than_rclpys_own_on_the_same_ping_pong(ros_domain) -> None:
    """The reason it exists: messages back and forth between two nodes that have the entities every rclpy node has,
    each executor three times in turn, the best of each."""
    rates: dict[str, list[float]] = {}
    for kind in (SingleThreadedExecutor, SteadyExecutor) * 3:
        rates.setdefault(kind.__name__, []).append(_ping_pong_rate(kind, ros_domain))
    assert max(rates["SteadyExecutor"]) > 1.1 * max(rates["SingleThreadedExecutor"]), rates


def _ping_pong_rate(kind: type, domain: int, messages: int = 1000) -> float:
    context = rclpy.Context()
    rclpy.init(context=context, domain_id=domain)
    executor = kind(context=context)
    a, b = (rclpy.create_node(name, context=context) for name in ("a", "b"))
    for made in (a, b):
        executor.add_node(made)
    count = [0]
    to_b, to_a = a.create_publisher(Int64, "ab", 10), b.create_publisher(Int64, "ba", 10)

    def back(msg: Int64) -> None:
        count[0] += 1
        to_b.publish(msg)

    b.create_subscription(Int64, "ab", to_a.publish, 10)
    a.create_subscription(Int64, "ba", back, 10)
    try:
        _matched(executor, to_b)
        _matched(executor, to_a)
        to_b.publish(Int64(data=0))
        spin_executor_until(executor, lambda: count[0] >= 50)
        started, first = time.perf_counter(), count[0]
        spin_executor_until(executor, lambda: count[0] >= first + messages, timeout=60)
        return (count[0] - first) / (time.perf_counter() - started)
    finally:
        executor.shutdown()
        a.destroy_node()
        b.destroy_node()
        rclpy.shutdown(context=context)


def test_a_busy_exclusive_group_keeps_its_messages_waiting_without_spinning(ros) -> None:
    """While a coroutine of a mutually exclusive group awaits, the group's other callbacks wait (not taken, and not
    spun on at full speed), and run once it is done."""
    executor, node = ros
    talker, worker = node("talker"), node("worker")
    publisher = talker.create_publisher(Int64, "work", 10)
    group = MutuallyExclusiveCallbackGroup()
    events: list[str] = []
    later = rclpy.task.Future()

    async def slow() -> None:
        timer.cancel()
        events.append("awaiting")
        await later
        events.append("done")

    worker.create_subscription(Int64, "work", lambda msg: events.append(f"message {msg.data}"), 10, callback_group=group)
    _matched(executor, publisher)
    timer = worker.create_timer(0.01, slow, callback_group=group)
    spin_executor_until(executor, lambda: events == ["awaiting"])
    publisher.publish(Int64(data=1))
    cpu, end = time.process_time(), time.monotonic() + 0.5
    while time.monotonic() < end:
        executor.spin_once(timeout_sec=0.05)
    assert events == ["awaiting"]
    assert time.process_time() - cpu < 0.25  # waiting, not spinning on the ready message
    later.set_result(None)
    spin_executor_until(executor, lambda: events[-1:] == ["message 1"])
    assert events == ["awaiting", "done", "message 1"]
