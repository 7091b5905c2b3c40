"""Task samplers: seeded, reproducible, never interpenetrating, on the table, matching their premise."""

import itertools

import numpy as np
import pytest

from semgoal_core.tasks import MIN_SEPARATION, SPAWN_HIGH, SPAWN_LOW, TASKS, get_task
from semgoal_core.vocabulary import LAYOUTS, SCENES


@pytest.mark.parametrize("name", list(TASKS))
def test_starts_are_reproducible_and_valid(name: str) -> None:
    task = TASKS[name]
    for seed in range(50):
        positions, goal = task.initial_state(seed)
        again, goal_again = task.initial_state(seed)
        np.testing.assert_array_equal(positions, again)
        assert goal == goal_again
        assert positions.shape == (task.n_blocks, 3)
        assert np.all(positions[:, :2] >= SPAWN_LOW - 0.005) and np.all(positions[:, :2] <= SPAWN_HIGH + 0.005)
        for a, b in itertools.combinations(positions, 2):
            if abs(a[2] - b[2]) < 0.01:  # side by side: no interpenetration
                assert np.linalg.norm(a[:2] - b[:2]) >= min(MIN_SEPARATION, 0.06) - 1e-9
        layout = LAYOUTS[task.scene]
        for literal in goal:
            layout.validate(literal)
    assert not np.array_equal(task.initial_state(0)[0], task.initial_state(1)[0])


def test_premises_of_the_tasks() -> None:
    mc = TASKS["MC-3"].initial_state(7)[0]
    assert min(np.linalg.norm(a - b) for a, b in itertools.combinations(mc, 2)) >= 0.15
    ma = TASKS["MA-3"].initial_state(7)[0]
    assert max(np.linalg.norm(a - b) for a, b in itertools.combinations(ma, 2)) < 0.09
    swap, goal = TASKS["Swap-2"].initial_state(7)
    assert abs(abs(swap[0, 2] - swap[1, 2]) - 0.05) < 0.002
    bottom = int(np.argmin(swap[:, 2]))
    assert goal[0].name == "above" and goal[0].args[0] == SCENES["two_blocks"].objects[bottom]


def test_task_lookup_is_forgiving_and_helpful() -> None:
    assert get_task("dc-4").name == "DC-4"
    with pytest.raises(KeyError, match="tasks are MC-2, MA-2"):
        get_task("MC-9")
