"""Goal families beyond the benchmark's eight tasks (issue 51): seeded draws of a start and a goal over a scene's
vocabulary, for `./semgoal eval-goals`. Starts come from every task sampler of the scene; desk starts may have
blocks in the bin already, so that goals must take them out again.

- ``stack`` (two_blocks): ``above(x,y)`` either way round, from MC-2, MA-2 and Swap-2 starts.
- ``close-pattern`` (three_blocks): each pair close or not, any of the eight patterns, from MC-3 and MA-3 starts.
- ``bin-subset`` (desk_cleanup): a subset of the blocks in the bin (perhaps none), the others explicitly out,
  from desks with 2-4 blocks and a random subset of them binned.
- ``hold`` (every scene): hold a named block at the end, from any of the scene's task starts.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from semgoal_core import tasks
from semgoal_core.vocabulary import LAYOUTS, SCENES, evaluate, parse_literal

AWAY = (1.3, 0.75, 0.9)
"""Where the gripper is taken to be when a start is judged: open, well above the blocks."""


@dataclass(frozen=True)
class GoalCase:
    """One episode: the blocks' start (one row per block, the scene's first ``len(positions)`` objects) and the goal."""

    family: str
    seed: int
    positions: np.ndarray
    goal: str


def _task_start(rng: np.random.Generator, scene: str, seed: int) -> tuple[np.ndarray, tuple[str, ...]]:
    """A start from one of the scene's task samplers, and the blocks in it."""
    task = tasks.TASKS[str(rng.choice(tasks.scene_tasks(scene)))]
    return task.initial_state(seed)[0], SCENES[scene].objects[:task.n_blocks]


def _stack(rng: np.random.Generator, scene: str, seed: int) -> tuple[np.ndarray, str]:
    positions, blocks = _task_start(rng, scene, seed)
    top, bottom = rng.permutation(blocks)[:2]
    return positions, f"above({top},{bottom})"


def _close_pattern(rng: np.random.Generator, scene: str, seed: int) -> tuple[np.ndarray, str]:
    positions, blocks = _task_start(rng, scene, seed)
    literals = [f"{'' if rng.uniform() < 0.5 else 'not '}close({a},{b})" for a, b in itertools.combinations(blocks, 2)]
    return positions, " & ".join(literals)


def _bin_subset(rng: np.random.Generator, scene: str, seed: int) -> tuple[np.ndarray, str]:
    positions, blocks = _task_start(rng, scene, seed)
    positions = positions.copy()
    binned = [i for i in range(len(blocks)) if rng.uniform() < 0.5]
    if binned:
        bin_ = SCENES[scene].bin
        floor = tasks.TABLE_TOP + bin_.floor_thickness + tasks.BLOCK_HALF_SIZE
        positions[binned] = np.column_stack([bin_.slots(len(binned)), np.full(len(binned), floor)])
    wanted = {block for block in blocks if rng.uniform() < 0.5}
    return positions, " & ".join(f"{'' if block in wanted else 'not '}in_bin({block})" for block in blocks)


def _hold(rng: np.random.Generator, scene: str, seed: int) -> tuple[np.ndarray, str]:
    positions, blocks = _task_start(rng, scene, seed)
    return positions, f"holding({rng.choice(blocks)})"


Draw = Callable[[np.random.Generator, str, int], tuple[np.ndarray, str]]
FAMILIES: dict[str, dict[str, Draw]] = {
    "two_blocks": {"stack": _stack, "hold": _hold},
    "three_blocks": {"close-pattern": _close_pattern, "hold": _hold},
    "desk_cleanup": {"bin-subset": _bin_subset, "hold": _hold},
}


def goal_cases(scene: str, family: str, episodes: int, seed: int) -> list[GoalCase]:
    """``episodes`` draws of ``family`` in ``scene``, none whose goal already holds at its start (drawn again);
    case i depends only on ``seed + i``."""
    draw = FAMILIES[scene][family]
    cases = []
    for i in range(episodes):
        for again in itertools.count():
            positions, goal = draw(np.random.default_rng([seed + i, again]), scene, seed + i + again * 7919)
            if not holds_at_start(scene, positions, goal):
                break
        cases.append(GoalCase(family, seed + i, positions, goal))
    return cases


def holds_at_start(scene: str, positions: np.ndarray, goal: str) -> bool:
    """Whether every literal of ``goal`` holds on blocks at ``positions``, the gripper open and away."""
    layout = LAYOUTS[scene]
    padded, present = np.zeros((layout.scene.max_blocks, 3)), np.arange(layout.scene.max_blocks) < len(positions)
    padded[: len(positions)] = positions
    true = set(layout.true_literals(evaluate(layout, padded, np.array(AWAY), 0.1, tasks.TABLE_TOP, present)))
    return all((literal in true) if literal.value else (literal.negated() not in true)
               for literal in map(parse_literal, goal.split(" & ")))
