"""The planner benchmark's ratio: timeouts become bounds, never silent drops or made-up numbers."""

import sys
from pathlib import Path

import pytest

from semgoal_bench.planner import OURS_RUNNER, phase_speedup, run_one, speedup
from semgoal_planner.blocksworld import DOMAIN_PATH, problem


def result(ms: float | None, status: str = "ok") -> dict:
    return {"length": 4 if ms else None, "median_ms": ms, "status": status}


def test_speedup_is_pyperplan_over_ours() -> None:
    assert speedup(result(2.0), result(20.0), 60) == (10.0, "")


def test_a_pyperplan_timeout_gives_a_lower_bound_and_ours_an_upper_bound() -> None:
    assert speedup(result(600.0), result(None, "timeout (60 s)"), 60) == (100.0, "lower")
    assert speedup(result(None, "timeout (60 s)"), result(30_000.0), 60) == (0.5, "upper")


def test_no_ratio_when_neither_finished_or_one_failed() -> None:
    assert speedup(result(None, "timeout (60 s)"), result(None, "timeout (60 s)"), 60) == (None, "")
    assert speedup(result(2.0), result(None, "error: boom"), 60) == (None, "")


def test_phase_speedup_splits_parse_and_ground_from_search() -> None:
    ours = {**result(3.0), "parse_ground_runs": [0.001] * 3, "search_ms": 2.0}
    theirs = {**result(25.0), "parse_ground_runs": [0.005] * 3, "search_ms": 20.0}
    assert phase_speedup(ours, theirs, "parse_ground") == 5.0
    assert phase_speedup(ours, theirs, "search") == 10.0
    assert phase_speedup(ours, result(None, "timeout (60 s)"), "search") is None


def test_a_search_that_ran_out_of_time_keeps_its_parse_and_ground_compared_first_run_with_first_run() -> None:
    ours = {**result(3.0), "parse_ground_runs": [0.002, 0.001, 0.001], "search_ms": 2.0}
    theirs = {**result(None, "timeout (60 s)"), "parse_ground_runs": [0.010]}
    assert phase_speedup(ours, theirs, "parse_ground") == 5.0
    assert phase_speedup(ours, theirs, "search") is None
    assert phase_speedup(ours, {**result(None, "timeout (60 s)"), "parse_ground_runs": []}, "parse_ground") is None


@pytest.mark.slow
def test_a_runner_out_of_time_still_reports_its_parse_and_ground(tmp_path: Path) -> None:
    """Parse + ground is timed in a process of its own, without the search that runs out of time: every repeat."""
    prob = tmp_path / "bw-12.pddl"
    prob.write_text(problem(12, seed=1))
    row = run_one(sys.executable, OURS_RUNNER, DOMAIN_PATH, prob, "bfs", "blind", repeats=3, timeout=4)
    assert row["status"] == "timeout (4 s)" and row["median_ms"] is None
    assert len(row["parse_ground_runs"]) == 3 and 0 < row["parse_ground_ms"] < 100


@pytest.mark.slow
def test_our_runner_times_both_phases(tmp_path: Path) -> None:
    prob = tmp_path / "bw-4.pddl"
    prob.write_text(problem(4, seed=1))
    row = run_one(sys.executable, OURS_RUNNER, DOMAIN_PATH, prob, "astar", "hmax", repeats=2, timeout=60)
    assert row["status"] == "ok" and row["length"] == 8
    # parse + ground is timed again in a process of its own, so it may exceed a whole run's median on a busy machine
    assert row["parse_ground_ms"] > 0 and len(row["parse_ground_runs"]) == 2
    assert 0 < row["search_ms"] < row["median_ms"]
