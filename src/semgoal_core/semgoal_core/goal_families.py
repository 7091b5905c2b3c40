"""Goal families beyond the benchmark's eight tasks: seeded draws of a start and a goal over a scene's
vocabulary, for `./semgoal eval-goals`. Starts come from every task sampler of the scene; desk starts may have
blocks in the bin already, so that goals must take them out again.

- ``stack`` (two_blocks): ``above(x,y)`` either way round, from MC-2, MA-2 and Swap-2 starts.
- ``arrange`` (two_blocks): every literal over the pair stated (one on the other either way, side by side, or
  apart), from the same starts.
- ``close-pattern`` (three_blocks): each pair close or not, any of the eight patterns, from MC-3 and MA-3 starts.
- ``bin-subset`` (desk_cleanup): a subset of the blocks in the bin (perhaps none), the others explicitly out,
  from desks with 2-4 blocks and a random subset of them binned.
- ``tower`` (tabletop): a tower of two to five random blocks in a random order, from any tabletop task's start (towers
  to take down among them).
- ``tower-bin-close`` (tabletop): a tower of two or three, one or two other blocks in the bin, and one more block
  next to the tower's foot or away from it: every predicate in one goal.
- ``hold`` (every scene): hold a named block at the end, from any of the scene's task starts.
- ``chain`` (every scene): two goals of the scene's other families in one episode, the second from where the
  first left the world (a block in the hand, say); the second asks for something the first did not.
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
    """One episode: the blocks' start (one row per block, the scene's first ``len(positions)`` objects) and the
    goals, achieved one after the other without a reset (one goal but in chains)."""

    family: str
    seed: int
    positions: np.ndarray
    goals: tuple[str, ...]

    @property
    def text(self) -> str:
        """The goals as an operator reads them: ``above(red,green) -> holding(green)``."""
        return " -> ".join(self.goals)


def _task_start(rng: np.random.Generator, scene: str, seed: int) -> tuple[np.ndarray, tuple[str, ...]]:
    """A start from one of the scene's task samplers, and the blocks in it."""
    task = tasks.get_task(str(rng.choice(tasks.scene_tasks(scene))))
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


def _arrange(rng: np.random.Generator, scene: str, seed: int) -> tuple[np.ndarray, str]:
    """Every literal over the pair stated: one on the other (either way), side by side, or apart."""
    positions, blocks = _task_start(rng, scene, seed)
    a, b = rng.permutation(blocks)[:2]
    patterns = (f"above({a},{b}) & not above({b},{a}) & close({a},{b})",
                f"close({a},{b}) & not above({a},{b}) & not above({b},{a})",
                f"not close({a},{b}) & not above({a},{b}) & not above({b},{a})")
    return positions, patterns[rng.integers(len(patterns))]


def _tower(rng: np.random.Generator, scene: str, seed: int) -> tuple[np.ndarray, str]:
    positions, blocks = _task_start(rng, scene, seed)
    order = rng.permutation(blocks)[:int(rng.integers(2, min(len(blocks), 5) + 1))]
    return positions, " & ".join(map(str, tasks.stacked(order)))


def _tower_bin_close(rng: np.random.Generator, scene: str, seed: int) -> tuple[np.ndarray, str]:
    positions, blocks = _task_start(rng, scene, seed)
    while len(blocks) < 4:  # a tower, a block in the bin and one beside: at least four blocks
        positions, blocks = _task_start(rng, scene, seed + 1)
    order = list(rng.permutation(blocks))
    height = int(rng.integers(2, min(3, len(blocks) - 2) + 1))
    binned = int(rng.integers(1, min(2, len(blocks) - height - 1) + 1))
    tower, bin_blocks, beside = order[:height], order[height:height + binned], order[height + binned]
    literals = [*map(str, tasks.stacked(tower)), *(f"in_bin({block})" for block in bin_blocks),
                f"{'' if rng.uniform() < 0.5 else 'not '}close({beside},{tower[0]})"]
    return positions, " & ".join(literals)


def _hold(rng: np.random.Generator, scene: str, seed: int) -> tuple[np.ndarray, str]:
    positions, blocks = _task_start(rng, scene, seed)
    return positions, f"holding({rng.choice(blocks)})"


def _chain(rng: np.random.Generator, scene: str, seed: int) -> tuple[np.ndarray, tuple[str, str]]:
    """A start and goal of one family, then a goal of another (or the same) with a literal the first lacks."""
    singles = [draw for name, draw in FAMILIES[scene].items() if name != "chain"]
    positions, first = singles[rng.integers(len(singles))](rng, scene, seed)
    present = set(SCENES[scene].objects[:len(positions)])
    while True:
        _, second = singles[rng.integers(len(singles))](rng, scene, seed)
        literals = [parse_literal(text) for text in second.split(" & ")]
        if (not set(second.split(" & ")) <= set(first.split(" & "))
                and all(set(literal.args) <= present for literal in literals)):
            return positions, (first, second)


Draw = Callable[[np.random.Generator, str, int], tuple[np.ndarray, str | tuple[str, ...]]]
FAMILIES: dict[str, dict[str, Draw]] = {
    "two_blocks": {"stack": _stack, "arrange": _arrange, "hold": _hold, "chain": _chain},
    "three_blocks": {"close-pattern": _close_pattern, "hold": _hold, "chain": _chain},
    "desk_cleanup": {"bin-subset": _bin_subset, "hold": _hold, "chain": _chain},
    "tabletop": {"tower": _tower, "tower-bin-close": _tower_bin_close, "hold": _hold, "chain": _chain},
}


def goal_cases(scene: str, family: str, episodes: int, seed: int) -> list[GoalCase]:
    """``episodes`` draws of ``family`` in ``scene``, none whose (first) goal already holds at its start (drawn again);
    case i depends only on ``seed + i``."""
    draw = FAMILIES[scene][family]
    cases = []
    for i in range(episodes):
        for again in itertools.count():
            positions, goals = draw(np.random.default_rng([seed + i, again]), scene, seed + i + again * 7919)
            goals = (goals,) if isinstance(goals, str) else goals
            if not holds_at_start(scene, positions, goals[0]):
                break
        cases.append(GoalCase(family, seed + i, positions, goals))
    return cases


def holds_at_start(scene: str, positions: np.ndarray, goal: str) -> bool:
    """Whether every literal of ``goal`` holds on blocks at ``positions``, the gripper open and away."""
    layout = LAYOUTS[scene]
    padded, present = np.zeros((layout.scene.max_blocks, 3)), np.arange(layout.scene.max_blocks) < len(positions)
    padded[: len(positions)] = positions
    true = set(layout.true_literals(evaluate(layout, padded, np.array(AWAY), 0.1, tasks.TABLE_TOP, present)))
    return all((literal in true) if literal.value else (literal.negated() not in true)
               for literal in map(parse_literal, goal.split(" & ")))
