"""The realtime figures of `./semgoal bench-graph`: a stall counts once; a slow timer shows in the rate."""

import pytest

from semgoal_bench.graph import arrival_timing

PERIOD = 0.04


def test_a_steady_timer_is_on_time() -> None:
    timing = arrival_timing([(step, step * PERIOD) for step in range(100)], 25.0)
    assert timing["late_fraction"] == 0.0 and timing["rate_hz"] == pytest.approx(25.0)


def test_one_stall_counts_once_and_repeated_steps_keep_their_last_arrival() -> None:
    arrivals = [(step, step * PERIOD + (0.05 if step >= 10 else 0.0)) for step in range(101)]
    arrivals.append((3, 3 * PERIOD + 0.001))  # a heartbeat repeating step 3
    timing = arrival_timing(arrivals, 25.0)
    assert timing["late_fraction"] == pytest.approx(1 / 100)
    assert timing["max_gap_ms"] == pytest.approx(90.0)


def test_a_slow_timer_shows_in_the_rate() -> None:
    timing = arrival_timing([(step, step * 0.05) for step in range(100)], 25.0)
    assert timing["rate_hz"] == pytest.approx(20.0) and timing["late_fraction"] == 0.0
