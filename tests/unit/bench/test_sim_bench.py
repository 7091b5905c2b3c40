"""`./semgoal bench-sim`: its JSON contract, through the dispatcher."""

import json
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[3]


@pytest.mark.slow
def test_bench_sim_reports_every_scene_and_the_reference() -> None:
    out = subprocess.run([str(ROOT / "semgoal"), "bench-sim", "--steps", "50", "--repeats", "1", "--json"],
                         capture_output=True, text=True, timeout=240, check=True, cwd="/")
    result = json.loads(out.stdout.strip().splitlines()[-1])
    rates = result["steps_per_second"]
    assert {"two_blocks", "three_blocks", "desk_cleanup_4", "reference:FetchPickAndPlace-v4"} <= set(rates)
    assert all(rate > 0 for rate in rates.values())
    assert set(result["ratio_to_reference"]) == {"two_blocks", "three_blocks", "desk_cleanup_4"}
