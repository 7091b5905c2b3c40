"""Two via-ROS evaluations at once on one host: each graph on a ROS domain of its own
(:mod:`semgoal_ros.domains`), neither disturbing the other: both run every episode and solve DC-2."""

import json
import re
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[2]
EPISODES = 3


@pytest.mark.timeout(900)
def test_two_via_ros_evaluations_side_by_side() -> None:
    runs = [subprocess.Popen([str(ROOT / "semgoal"), "eval", "--tasks", "DC-2", "--episodes", "1", "--seeds", "1",
                              "--jobs", "1", "--via-ros", "--ros-episodes", str(EPISODES), "--seed", str(seed), "--json"],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for seed in (3_000_000, 3_000_100)]
    outputs = [run.communicate(timeout=840) for run in runs]
    for run, (out, err) in zip(runs, outputs, strict=True):
        assert run.returncode == 0, err[-3000:]
        assert json.loads(out.strip().splitlines()[-1])["DC-2"]["hierarchical (via ROS)"] == 1.0, out + err[-2000:]
    domains = [re.search(r"graph on ROS domain (\d+)", err)[1] for _, err in outputs]
    assert domains[0] != domains[1], domains
