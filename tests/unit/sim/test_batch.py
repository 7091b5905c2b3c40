"""Worlds stepped in a batch on threads end exactly where the same worlds stepped one by one do."""

import numpy as np
import pytest

from semgoal_core.tasks import get_task
from semgoal_sim.batch import WorldBatch
from semgoal_sim.world import FetchWorld


def test_a_batch_on_threads_steps_each_world_as_alone() -> None:
    starts = [get_task("DC-3").initial_state(seed)[0] for seed in range(3)]
    actions = np.random.default_rng(4).uniform(-1, 1, size=(25, 3, 4))
    alone, batched = ([FetchWorld("desk_cleanup", 3) for _ in starts] for _ in range(2))
    for worlds in (alone, batched):
        for world, start in zip(worlds, starts, strict=True):
            world.reset(start)
    with WorldBatch(batched, threads=2) as batch:
        assert batch.threads == 2
        for step in actions:
            batch.step(step)
    for step in actions:
        for world, action in zip(alone, step, strict=True):
            world.step(action)
    for one, other in zip(alone, batched, strict=True):
        assert np.array_equal(one.data.qpos, other.data.qpos) and one.step_count == other.step_count == 25


class _Failing:
    """A world whose step fails on a negative action, to see where the failure goes."""

    def __init__(self) -> None:
        self.steps = 0

    def step(self, action: np.ndarray) -> None:
        if action[0] < 0:
            raise ValueError("a failing step")
        self.steps += 1


def test_a_step_failing_on_any_thread_is_raised_in_the_callers_and_the_batch_goes_on() -> None:
    worlds = [_Failing() for _ in range(6)]
    with WorldBatch(worlds, threads=2) as batch:
        for failing in range(6):
            actions = np.ones((6, 4))
            actions[failing, 0] = -1
            with pytest.raises(ValueError, match="a failing step"):
                batch.step(actions)
        batch.step(np.ones((6, 4)))
    assert all(world.steps >= 1 for world in worlds)
    with pytest.raises(RuntimeError, match="closed"):
        batch.step(np.ones((6, 4)))
