"""The planner benchmark's ratio: timeouts become bounds, never silent drops or made-up numbers."""

from semgoal_planner.bench import speedup


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
