"""`./semgoal train dagger` end to end at a tiny size: an iteration with whole tasks, a resume that carries on from
it, and a run folder that is not overwritten."""

import csv
import json

import pytest

from semgoal_bringup.experiments import dagger
from semgoal_policy import actor as actor_io


@pytest.mark.slow
def test_a_run_resumes_from_its_last_iteration_and_exports_the_actor(tmp_path, capsys) -> None:
    run_dir = tmp_path / "run"
    tiny = ["--subgoal-episodes", "2", "--epochs", "1", "--envs", "2", "--run-dir", str(run_dir)]
    assert dagger.main(["--iterations", "1", "--task-episodes", "1", *tiny]) == 0
    assert dagger.main(["--iterations", "1", "--task-episodes", "0", *tiny]) == 2
    assert "holds a run" in capsys.readouterr().err
    assert dagger.main(["--iterations", "2", "--task-episodes", "0", "--resume", *tiny]) == 0
    with (run_dir / "progress.csv").open() as f:
        rows = list(csv.DictReader(f))
    assert [row["iteration"] for row in rows] == ["1", "2"]
    first, second = (int(row["states"]) for row in rows)
    assert first > 2 * 50 and second == first + 2 * 50  # the tasks' states, then two sub-goal episodes more
    assert float(rows[0]["task_success"]) > 0.0
    meta = json.loads((run_dir / "export" / "actor.json").read_text())
    assert [row["iteration"] for row in meta["dagger"]["progress"]] == [1, 2]
    actor_io.load(run_dir / "export", "two_blocks")  # the object actor, for any scene
