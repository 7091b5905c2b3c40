"""The eight tasks of the paper (Figure 4) and the tabletop's: seeded initial-state samplers and goal literals.
No MuJoCo.

Initial states are block centres on the table, resting (z = table + half size), never closer than
:data:`MIN_SEPARATION` (no interpenetration), inside :data:`SPAWN_LOW`..:data:`SPAWN_HIGH` (reachable,
clear of the bin). Stacked starts put the top block on the bottom one; the world settles them.

Every task goal also asks that nothing is held at the end: a task is done when the blocks are placed.
"""

from __future__ import annotations

import itertools
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from semgoal_core.geometry import TABLE_TOP
from semgoal_core.vocabulary import BLOCK_HALF_SIZE, SCENES, Literal

REST_Z = TABLE_TOP + BLOCK_HALF_SIZE
SPAWN_LOW = np.array([1.15, 0.50])
SPAWN_HIGH = np.array([1.45, 0.85])
"""Area (x, y) where blocks start: within easy reach of the arm and clear of the desk-cleanup bin."""
MIN_SEPARATION = 0.07
"""Minimum centre distance of two blocks at the start (a 5 cm block's diagonal is 0.071 m)."""
FAR_APART = 0.15
"""'Far apart' starts (MC-2, MC-3): well beyond the close threshold of 0.09 m."""
CLOSE_RANGE = (0.06, 0.085)
"""'Close' starts (MA-2, MA-3): centre distances in this range, under the close threshold."""


@dataclass(frozen=True)
class Task:
    """A task: its scene, how many blocks, how to sample a start, and the goal literals."""

    name: str
    scene: str
    n_blocks: int
    description: str
    sample: Callable[[np.random.Generator, tuple[str, ...]], tuple[np.ndarray, list[Literal]]]
    """(rng, blocks) -> (block centres (N, 3), goal literals). Swap-2's goal depends on the start."""

    @property
    def blocks(self) -> tuple[str, ...]:
        return SCENES[self.scene].objects[: self.n_blocks]

    def initial_state(self, seed: int) -> tuple[np.ndarray, list[Literal]]:
        """Block centres and goal literals for episode ``seed`` (same seed, same start)."""
        positions, goal = self.sample(np.random.default_rng(seed), self.blocks)
        return positions, goal + self.released()

    def released(self) -> list[Literal]:
        """Every task ends with nothing in the gripper."""
        return [Literal("holding", (block,), False) for block in self.blocks]


def _resting(xy: np.ndarray) -> np.ndarray:
    return np.column_stack([xy, np.full(len(xy), REST_Z)])


def scatter(rng: np.random.Generator, count: int, min_distance: float = MIN_SEPARATION,
            low: np.ndarray = SPAWN_LOW, high: np.ndarray = SPAWN_HIGH) -> np.ndarray:
    """``count`` resting block centres, pairwise at least ``min_distance`` apart (rejection sampling)."""
    for _ in range(10_000):
        xy = rng.uniform(low, high, size=(count, 2))
        if all(np.linalg.norm(a - b) >= min_distance for a, b in itertools.combinations(xy, 2)):
            return _resting(xy)
    raise RuntimeError(f"cannot place {count} blocks {min_distance} m apart in the spawn area")


def cluster(rng: np.random.Generator, count: int,
            low: np.ndarray = SPAWN_LOW, high: np.ndarray = SPAWN_HIGH) -> np.ndarray:
    """``count`` resting blocks, every pair at a centre distance within :data:`CLOSE_RANGE`."""
    near, far = CLOSE_RANGE
    for _ in range(10_000):
        xy = [rng.uniform(low + far, high - far)]
        while len(xy) < count:
            anchor = xy[rng.integers(len(xy))]
            angle, radius = rng.uniform(0, 2 * np.pi), rng.uniform(near, far)
            xy.append(anchor + radius * np.array([np.cos(angle), np.sin(angle)]))
        pairs = [np.linalg.norm(a - b) for a, b in itertools.combinations(xy, 2)]
        if all(near <= d <= far for d in pairs):
            return _resting(np.array(xy))
    raise RuntimeError(f"cannot sample a cluster of {count} blocks")


def stack(rng: np.random.Generator, order: tuple[int, int]) -> np.ndarray:
    """Two blocks, ``order[1]`` resting on ``order[0]`` (a few mm of xy offset)."""
    positions = np.zeros((2, 3))
    base = rng.uniform(SPAWN_LOW, SPAWN_HIGH)
    positions[order[0]] = [*base, REST_Z]
    positions[order[1]] = _on_top(rng, base)
    return positions


def stack_among(rng: np.random.Generator, count: int,
                low: np.ndarray = SPAWN_LOW, high: np.ndarray = SPAWN_HIGH) -> np.ndarray:
    """``count`` blocks in random order: one resting on another, the others scattered around them."""
    positions = scatter(rng, count - 1, low=low, high=high)
    return np.vstack([positions, _on_top(rng, positions[0, :2])])[rng.permutation(count)]


def _on_top(rng: np.random.Generator, base_xy: np.ndarray) -> np.ndarray:
    return np.array([*(base_xy + rng.uniform(-0.004, 0.004, 2)), REST_Z + 2 * BLOCK_HALF_SIZE + 0.001])


def _pairs(blocks: tuple[str, ...], value: bool) -> list[Literal]:
    return [Literal("close", pair, value) for pair in itertools.combinations(blocks, 2)]


def _move_close(rng, blocks):
    return scatter(rng, len(blocks), FAR_APART), _pairs(blocks, True)


def _move_apart(rng, blocks):
    return cluster(rng, len(blocks)), _pairs(blocks, False)


def _swap(rng, blocks):
    bottom, top = (0, 1) if rng.uniform() < 0.5 else (1, 0)
    return stack(rng, (bottom, top)), [Literal("above", (blocks[bottom], blocks[top]))]


def _desk_cleanup(rng, blocks):
    return scatter(rng, len(blocks)), [Literal("in_bin", (block,)) for block in blocks]


TASK_STEP_BUDGET = 600
"""Control steps per task episode for every agent (24 s of sim time; the expert needs 27 to 165)."""

TASKS: dict[str, Task] = {
    task.name: task
    for task in (
        Task("MC-2", "two_blocks", 2, "two blocks far apart: move them close", _move_close),
        Task("MA-2", "two_blocks", 2, "two blocks close: move them apart", _move_apart),
        Task("Swap-2", "two_blocks", 2, "one block stacked on the other: swap their order", _swap),
        Task("MC-3", "three_blocks", 3, "three blocks far apart: bring all close to each other", _move_close),
        Task("MA-3", "three_blocks", 3, "three blocks close: move all apart", _move_apart),
        Task("DC-2", "desk_cleanup", 2, "two blocks on the desk: put them in the bin", _desk_cleanup),
        Task("DC-3", "desk_cleanup", 3, "three blocks on the desk: put them in the bin", _desk_cleanup),
        Task("DC-4", "desk_cleanup", 4, "four blocks on the desk: put them in the bin", _desk_cleanup),
    )
}


TABLETOP_SPAWN_LOW = np.array([1.12, 0.48])
TABLETOP_SPAWN_HIGH = np.array([1.48, 0.75])
"""Where tabletop blocks start: wider than the paper's area in x, for eight blocks; the open fingers clear the bin's
front wall (the bin is deeper than the desk's: two rows; at y 0.777 they stood on it)."""
TABLETOP_SEPARATION = 0.10
"""Least centre distance (m) of two blocks at a tabletop start: the open fingers, coming down on one, miss the other
(``semgoal_core.geometry.clear_of``). Closer, they knocked over a tower built on the other."""


def spread(rng: np.random.Generator, count: int, min_distance: float = TABLETOP_SEPARATION,
           low: np.ndarray = TABLETOP_SPAWN_LOW, high: np.ndarray = TABLETOP_SPAWN_HIGH) -> np.ndarray:
    """``count`` resting block centres, pairwise at least ``min_distance`` apart, placed one by one (eight blocks
    10 cm apart are too dense for :func:`scatter`'s all-at-once rejection)."""
    for _ in range(1_000):
        xy: list[np.ndarray] = []
        for _ in range(200 * count):
            spot = rng.uniform(low, high)
            if all(np.linalg.norm(spot - other) >= min_distance for other in xy):
                xy.append(spot)
                if len(xy) == count:
                    return _resting(np.array(xy))
    raise RuntimeError(f"cannot place {count} blocks {min_distance} m apart in the spawn area")


HOME_GRIP_XY = np.array([1.342, 0.749])
"""Where the gripper waits at the start of an episode, in the table plane (the benchmark's home pose), 0.13 m above the
table: a tower there stands in its way."""
HOME_CLEARANCE = 0.12
"""Least distance (m) in the table plane of a starting tower from :data:`HOME_GRIP_XY`: nearer, the hand at home
knocked a tower of six over as the episode began."""


TOWER_MARGIN = 0.06
"""How much further in (m) than other blocks a starting tower stands: one 7 cm from the table's edge was pushed over
it as its blocks came off."""


def tower(rng: np.random.Generator, count: int, low: np.ndarray = TABLETOP_SPAWN_LOW + TOWER_MARGIN,
          high: np.ndarray = TABLETOP_SPAWN_HIGH - TOWER_MARGIN) -> np.ndarray:
    """``count`` blocks stacked in object order (the first at the bottom), each a few mm off the one below, clear of
    the gripper's home (:data:`HOME_CLEARANCE`) when the area leaves room."""
    base = rng.uniform(low, high)
    for _ in range(1_000):
        if np.linalg.norm(base - HOME_GRIP_XY) >= HOME_CLEARANCE or np.array_equal(low, high):
            break
        base = rng.uniform(low, high)
    positions = [np.array([*base, REST_Z])]
    while len(positions) < count:
        positions.append(_on_top(rng, positions[-1][:2]) + np.array([0.0, 0.0, positions[-1][2] - REST_Z]))
    return np.array(positions)


def stacked(blocks: Sequence[str]) -> list[Literal]:
    """The literals of a tower of ``blocks``, the first at the bottom."""
    return [Literal("above", (top, bottom)) for bottom, top in itertools.pairwise(blocks)]


def _on_table(rng, count):
    return spread(rng, count)


def _tower(rng, blocks):
    return _on_table(rng, len(blocks)), stacked(blocks)


def _two_towers(rng, blocks):
    half = len(blocks) // 2
    return _on_table(rng, len(blocks)), stacked(blocks[:half]) + stacked(blocks[half:])


def _sort(rng, blocks):
    """Three blocks in a tower, the rest in the bin."""
    return _on_table(rng, len(blocks)), stacked(blocks[:3]) + [Literal("in_bin", (block,)) for block in blocks[3:]]


def _unstack(rng, blocks):
    """A tower taken down: no block on another."""
    return tower(rng, len(blocks)), [Literal("above", pair, False) for pair in itertools.permutations(blocks, 2)]


def _clean(rng, blocks):
    return _on_table(rng, len(blocks)), [Literal("in_bin", (block,)) for block in blocks]


TABLETOP_TASKS: dict[str, Task] = {
    task.name: task
    for task in (
        *(Task(f"Tower-{n}", "tabletop", n, f"{n} blocks on the table: build a tower, the first colour at the bottom",
               _tower) for n in range(3, 8)),
        Task("Two-towers", "tabletop", 6, "six blocks on the table: two towers of three", _two_towers),
        Task("Sort", "tabletop", 5, "five blocks on the table: three in a tower, two in the bin", _sort),
        Task("Unstack-6", "tabletop", 6, "a tower of six: every block on the table", _unstack),
        *(Task(f"Clean-{n}", "tabletop", n, f"{n} blocks on the table: put them in the bin", _clean)
          for n in (4, 6, 8)),
    )
}
"""The tabletop's tasks (beyond the paper). Tower-7 and Clean-8 are meant to test more blocks than an actor trained
with; the shipped actor's sub-goal episodes drew 2 to 8 blocks (``SubgoalEnv``), so for it they are not zero-shot."""
ALL_TASKS: dict[str, Task] = {**TASKS, **TABLETOP_TASKS}


def goal_in_state(task: Task, true_literals: list[Literal]) -> list[Literal]:
    """The task's goal for the world as it is now: Swap-2 reads which block is on top; the others are fixed."""
    if task.sample is _swap:
        stacked = [lit for lit in true_literals if lit.name == "above"]
        if not stacked:
            raise ValueError(f"{task.name} swaps a stacked pair, but no block is on another now")
        top, bottom = stacked[0].args
        goal = [Literal("above", (bottom, top))]
    else:
        goal = task.sample(np.random.default_rng(0), task.blocks)[1]
    return goal + task.released()


def scene_tasks(scene: str) -> tuple[str, ...]:
    """The tasks set in ``scene``: the paper's in Table 1's order."""
    return tuple(name for name, task in ALL_TASKS.items() if task.scene == scene)


def is_task_name(text: str) -> bool:
    """Whether ``text`` names a task (case-insensitive, its hyphen a space, '_' or nothing: ``tower 5``, ``DC3``;
    said as an order: ``run DC-3``, ``task MC-2 please``)."""
    return _named_task(text) is not None


def _named_task(text: str) -> str | None:
    """The name of the task ``text`` names, else None."""
    key = _task_key(text)
    return next((name for name in ALL_TASKS if _task_key(name) == key), None)


_TASK_ORDERED = re.compile(r"^(?:(?:please|now)\s+)?(?:(?:run|do|start|perform|execute|solve|try)\s+(?:the\s+)?(?:task\s+)?|"
                           r"(?:the\s+)?task:?\s+)|\s+(?:task|please)$")


def _task_key(name: str) -> str:
    return re.sub(r"[\s_\-\u2013]+", "", _TASK_ORDERED.sub("", name.strip().lower()))


_SEPARATORS = re.compile(r"\s*(?:&&?|∧|;|\band\b|,(?![^()]*\)))\s*", re.IGNORECASE)


def split_literals(text: str) -> list[str]:
    """``a(x) & not b(x,y), c(y)`` -> the literal texts (commas inside parentheses are arguments), also from PDDL's
    ``(and (a x) (not (b x y)))``; ValueError for an empty goal or an empty part."""
    if text.strip().startswith("("):
        return _pddl_literals(text)
    parts = [p.strip() for p in _SEPARATORS.split(text.strip())]
    if not text.strip() or any(not p for p in parts):
        raise ValueError(f"cannot read goal {text!r}: expected a task ({', '.join(ALL_TASKS)}) or literals joined by '&'")
    return parts


def _pddl_literals(text: str) -> list[str]:
    """PDDL's goal syntax, a literal or a conjunction of them, as literal texts: ``(and (in_bin red) (not (close red
    green)))`` -> ``['in_bin(red)', 'not close(red,green)']``."""
    tokens = re.findall(r"\(|\)|[^\s()]+", text)
    expected = f"cannot read goal {text!r}: PDDL goals are '(pred a b)', '(not (pred a b))' or '(and ...)' of those"

    def literal(i: int) -> tuple[list[str], int]:
        if i + 1 >= len(tokens) or tokens[i] != "(" or tokens[i + 1] in "()":
            raise ValueError(expected)
        head, i = tokens[i + 1].lower(), i + 2
        if head in ("and", "not"):
            parts = []
            while i < len(tokens) and tokens[i] == "(":
                part, i = literal(i)
                parts += part
            if i >= len(tokens) or tokens[i] != ")" or (head == "not" and (len(parts) != 1 or
                                                                          parts[0].startswith("not "))):
                raise ValueError(expected)
            return (parts if head == "and" else [f"not {parts[0]}"]), i + 1
        args = []
        while i < len(tokens) and tokens[i] not in "()":
            args.append(tokens[i])
            i += 1
        if i >= len(tokens) or tokens[i] != ")":
            raise ValueError(expected)
        return [f"{head}({','.join(args)})"], i + 1

    parts, end = literal(0)
    if end != len(tokens) or not parts:
        raise ValueError(expected)
    return parts


def goal_form(text: str) -> str:
    """How a goal is written: ``"task"`` (``DC-3``), ``"literals"`` (``in_bin(red) & not close(red,green)``:
    literal syntax has parentheses) or ``"text"`` (a sentence)."""
    if is_task_name(text):
        return "task"
    return "literals" if "(" in text or ")" in text else "text"


def get_task(name: str) -> Task:
    """Look a task up by its name (case-insensitive), or raise with the list of valid names."""
    if (task_name := _named_task(name)) is not None:
        return ALL_TASKS[task_name]
    raise KeyError(f"unknown task {name!r}: tasks are {', '.join(ALL_TASKS)}")
