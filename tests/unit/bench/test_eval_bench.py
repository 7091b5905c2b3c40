"""`./semgoal bench-eval`: its JSON contract, through the dispatcher."""

import json
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[3]


@pytest.mark.slow
@pytest.mark.timeout(600)
def test_bench_eval_reports_both_executors_with_one_and_two_workers() -> None:
    out = subprocess.run([str(ROOT / "semgoal"), "bench-eval", "--episodes", "2", "--json"],
                         capture_output=True, text=True, timeout=580, check=True, cwd="/")
    results = json.loads(out.stdout.strip().splitlines()[-1])
    assert [(r["executor"], r["workers"]) for r in results] == [("local", 1), ("local", 2), ("dask", 1), ("dask", 2)]
    assert all(r["episodes"] == 4 and r["episodes_per_s"] > 0 for r in results)
