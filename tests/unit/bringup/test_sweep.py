"""`./semgoal sweep`: seeds as jobs; a seed whose training process is killed mid-run is resumed from its
checkpoint (its progress goes on from the last evaluation, none repeated), not restarted."""

import json
import os
import signal
import subprocess
import time
from pathlib import Path

import pytest

from semgoal_bringup.experiments.sweep import parse_seeds

ROOT = Path(__file__).parents[3]


def test_seeds_are_read_as_ranges_and_lists() -> None:
    assert parse_seeds("81-83") == [81, 82, 83] and parse_seeds("5, 9-10") == [5, 9, 10]
    for bad in ("", "90-81", "a-b", "5,5", "-3"):
        with pytest.raises(ValueError, match="81"):
            parse_seeds(bad)


SWEEP_SETTINGS = ["--steps", "1200", "--eval-every", "400", "--eval-episodes", "1", "--final-eval-episodes", "1",
                  "--learning-starts", "200"]


def _sweep(runs: Path, executor: str) -> tuple[subprocess.Popen, int]:
    """A one-seed sweep started, and the pid of its training process once that has written a checkpoint."""
    sweep = subprocess.Popen([str(ROOT / "semgoal"), "sweep", "--recipe", "two_blocks", "--seeds", "5", "--workers", "1",
                              "--executor", executor, "--runs-dir", str(runs), *SWEEP_SETTINGS],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    progress = runs / "seed5" / "progress.csv"
    deadline = time.monotonic() + 300
    while not (progress.exists() and len(progress.read_text().splitlines()) >= 2 and (runs / "seed5" / "checkpoint.pt").exists()):
        assert time.monotonic() < deadline and sweep.poll() is None, sweep.communicate()[1][-3000:]
        time.sleep(0.5)
    training = subprocess.run(["pgrep", "-f", f"train --recipe two_blocks --seed 5 --resume .*{runs}"],
                              capture_output=True, text=True).stdout.split()
    assert len(training) == 1, training
    return sweep, int(training[0])


def _resumed(sweep: subprocess.Popen, runs: Path) -> tuple[dict, str]:
    """The sweep's result once it ends, checked: the seed trained to the end, its evaluations never repeated."""
    out, err = sweep.communicate(timeout=400)
    assert sweep.returncode == 0, err[-3000:]
    result = json.loads(out.strip().splitlines()[-1])
    assert result["seed"] == 5 and result["env_steps"] >= 1200, result
    steps = [int(line.split(",")[0]) for line in (runs / "seed5" / "progress.csv").read_text().splitlines()[1:]]
    assert steps == sorted(set(steps)) and steps[-1] >= 1200, steps  # none repeated: resumed, not restarted
    return result, err


@pytest.mark.slow
@pytest.mark.timeout(600)
def test_a_seed_killed_mid_training_is_resumed_from_its_checkpoint(tmp_path: Path) -> None:
    sweep, training = _sweep(tmp_path, "local")
    os.kill(training, signal.SIGKILL)
    result, err = _resumed(sweep, tmp_path)
    assert result["attempts"] == 2 and "resuming from its checkpoint" in err


@pytest.mark.slow
@pytest.mark.timeout(600)
def test_a_dask_worker_killed_mid_training_takes_its_training_along_and_the_seed_is_resumed(tmp_path: Path) -> None:
    sweep, training = _sweep(tmp_path, "dask")
    worker = int(Path(f"/proc/{training}/stat").read_text().rsplit(")", 1)[1].split()[1])  # the job's process
    os.kill(worker, signal.SIGKILL)
    deadline = time.monotonic() + 10
    while Path(f"/proc/{training}").exists() and Path(f"/proc/{training}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z":
        assert time.monotonic() < deadline, "the training process outlived its Dask worker"
        time.sleep(0.1)
    result, _ = _resumed(sweep, tmp_path)
    assert result["attempts"] == 1  # the job ran again from the start on a new worker, the run from its checkpoint
