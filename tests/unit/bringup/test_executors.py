"""The same evaluation on the local process pool and on a two-worker Dask LocalCluster, whole or in chunks of
episodes: identical rows (every job is seeded by its episodes)."""

import pytest

from semgoal_bringup.experiments.evaluation import evaluate_in_process
from semgoal_bringup.experiments.executors import check_executor
from semgoal_policy.actor import models_dir

TASKS, EPISODES, SEED = ["MA-2", "DC-2"], 8, 3_000_000


def figures(rows) -> list:
    return [(row.agent, {label: {task: vars(tally) for task, tally in results.items()} for label, results in row.per_seed.items()},
             row.seed_steps) for row in rows]


@pytest.mark.slow
@pytest.mark.timeout(600)
def test_local_and_dask_give_the_same_rows() -> None:
    local = evaluate_in_process(["hierarchical"], TASKS, EPISODES, SEED, 1, models_dir(), 2, "local", 0)
    dask = evaluate_in_process(["hierarchical"], TASKS, EPISODES, SEED, 1, models_dir(), 2, "dask", 3)
    assert figures(local) == figures(dask)
    assert [row.episodes(task) for row in local for task in TASKS] == [EPISODES, EPISODES]


def test_an_executor_is_named_right() -> None:
    assert [check_executor(spec) for spec in ("local", "dask", "dask:tcp://127.0.0.1:8786")]
    for bad in ("dask:", "ray", ""):
        with pytest.raises(ValueError, match="local, dask, dask:ADDRESS"):
            check_executor(bad)
