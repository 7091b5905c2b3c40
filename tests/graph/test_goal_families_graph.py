"""Goal families through the node graph: `eval-goals --via-ros` resets the sim to each case's own
start (ResetWorld.positions), sends its goals one after the other, and the episodes end as they do in process."""

import json
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[2]

CASES = [
    ("two_blocks", "chain,arrange", 6_000_000, 2, 4),
    # chains whose second goal starts with the first one's last decision still followed (one step of
    # latency): in process once followed the new plan a step early, and 6000006 ended otherwise than via ROS
    ("three_blocks", "chain", 6_000_006, 2, 2),
]


@pytest.mark.timeout(600)
@pytest.mark.parametrize("scene, families, seed, episodes, ros_episodes", CASES)
def test_goal_families_via_ros_end_as_in_process(scene: str, families: str, seed: int, episodes: int,
                                                 ros_episodes: int) -> None:
    run = subprocess.run([str(ROOT / "semgoal"), "eval-goals", "--scene", scene, "--families", families,
                          "--episodes", str(episodes), "--seed", str(seed), "--via-ros", "--ros-episodes",
                          str(ros_episodes), "--json"], capture_output=True, text=True, timeout=540)
    assert run.returncode == 0, run.stderr[-3000:]
    summary = next(json.loads(line) for line in run.stderr.splitlines() if line.startswith('{"via_ros"'))["via_ros"]
    assert summary["episodes"] == ros_episodes and summary["same_as_in_process"] == ros_episodes, run.stderr[-3000:]
    rates = json.loads(run.stdout.strip().splitlines()[-1])
    assert set(rates) == {f"{scene}/{family}" for family in families.split(",")} | {"overall", "fell_off"}
