"""Each node's health on /diagnostics (diagnostic_msgs), once a second on a steady clock: what
``ros2 topic echo /diagnostics``, rqt_robot_monitor or a diagnostic aggregator read. A node counts its events
in a :class:`Counters` and times its work with a :class:`Latencies`; :class:`Diagnostics` reports them."""

from __future__ import annotations

import time
from collections import Counter, deque
from collections.abc import Callable

import numpy as np
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from rclpy.clock import Clock, ClockType

TOPIC = "/diagnostics"
PERIOD_S = 1.0

OK, WARN = DiagnosticStatus.OK, DiagnosticStatus.WARN
Report = tuple[bytes, str, dict[str, object]]
"""(a DiagnosticStatus level, OK or WARN, a one-line message, the values to show)."""


class Latencies:
    """The last ``size`` durations of a piece of work, timed with :meth:`time` (a context manager)."""

    def __init__(self, size: int = 1000) -> None:
        self.seconds: deque[float] = deque(maxlen=size)

    def time(self) -> _Timing:
        return _Timing(self.seconds)

    def summary(self, name: str) -> dict[str, object]:
        """``name`` p50 / p99 / max in ms over the window, and how many were timed."""
        if not self.seconds:
            return {f"{name} timed": 0}
        ms = np.array(self.seconds) * 1e3
        return {f"{name} p50 ms": round(float(np.percentile(ms, 50)), 3), f"{name} p99 ms": round(float(np.percentile(ms, 99)), 3),
                f"{name} max ms": round(float(ms.max()), 3), f"{name} timed": len(ms)}


class _Timing:
    def __init__(self, into: deque[float]) -> None:
        self.into = into

    def __enter__(self) -> None:
        self.start = time.perf_counter()

    def __exit__(self, *_) -> None:
        self.into.append(time.perf_counter() - self.start)


class Counters(Counter):
    """Events since the node started (dropped commands, re-plans, ...), by name."""


class Diagnostics:
    """Publishes ``report()`` as the node's DiagnosticStatus every :data:`PERIOD_S` (steady time, so a node on
    ``use_sim_time`` reports while the sim clock stands still)."""

    def __init__(self, node, report: Callable[[], Report]) -> None:
        self.node, self.report = node, report
        self.publisher = node.create_publisher(DiagnosticArray, TOPIC, 10)
        node.create_timer(PERIOD_S, self.publish, clock=Clock(clock_type=ClockType.STEADY_TIME))

    def publish(self) -> None:
        level, message, values = self.report()
        status = DiagnosticStatus(level=level, name=f"semgoal/{self.node.get_name()}", message=message,
                                  hardware_id="semgoal", values=[KeyValue(key=k, value=str(v)) for k, v in values.items()])
        array = DiagnosticArray(status=[status])
        array.header.stamp = self.node.get_clock().now().to_msg()
        self.publisher.publish(array)


