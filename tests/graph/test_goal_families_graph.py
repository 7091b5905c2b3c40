"""Goal families through the node graph (issue 51): `eval-goals --via-ros` resets the sim to each case's own
start (ResetWorld.positions), sends its goals one after the other, and the episodes end as they do in process."""

import json
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[2]


@pytest.mark.timeout(600)
def test_chains_via_ros_end_as_in_process() -> None:
    run = subprocess.run([str(ROOT / "semgoal"), "eval-goals", "--scene", "two_blocks", "--families", "chain,arrange",
                          "--episodes", "2", "--via-ros", "--ros-episodes", "4", "--json"],
                         capture_output=True, text=True, timeout=540)
    assert run.returncode == 0, run.stderr[-3000:]
    summary = next(json.loads(line) for line in run.stderr.splitlines() if line.startswith('{"via_ros"'))["via_ros"]
    assert summary["episodes"] == 4 and summary["same_as_in_process"] == 4, run.stderr[-3000:]
    rates = json.loads(run.stdout.strip().splitlines()[-1])
    assert set(rates) == {"two_blocks/chain", "two_blocks/arrange", "overall"}
