"""The realtime figures of `./semgoal bench-graph`: a stall counts once; a slow timer shows in the rate. The CPU
figure counts what the graph's processes (children and theirs) spend."""

import os
import signal
import subprocess
import sys
import time

import psutil
import pytest

from semgoal_bench.graph import Run, arrival_timing, cpu_ms_per_step, descendants_cpu_s

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


@pytest.mark.slow
def test_cpu_counts_grandchildren_and_not_idle_ones() -> None:
    burn = "import time\nend = time.process_time() + 0.4\nwhile time.process_time() < end: pass\ntime.sleep(30)"
    others = {process.pid for process in psutil.Process().children(recursive=True)}  # an earlier test's, ending
    before = descendants_cpu_s(others)
    started = [subprocess.Popen([sys.executable, "-c", "import time; time.sleep(30)"], start_new_session=True),
               subprocess.Popen(["sh", "-c", f"{sys.executable} -c '{burn}'; true"],  # a grandchild, as `./semgoal run`
                                start_new_session=True)]
    try:
        deadline = time.monotonic() + 10
        while descendants_cpu_s(others) - before < 0.4:
            assert time.monotonic() < deadline, "the grandchild's CPU was not counted"
            time.sleep(0.05)
        time.sleep(0.3)  # the burner sleeps now, and the idle one always did
        assert 0.4 <= descendants_cpu_s(others) - before < 0.6
    finally:
        for process in started:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()


def test_cpu_per_step_is_over_all_episodes() -> None:
    assert cpu_ms_per_step([Run(100, 1.0, 0.5), Run(300, 2.0, 0.5)]) == pytest.approx(2.5)
    assert cpu_ms_per_step([]) == 0.0
