"""Forward state-space searches over a grounded task: breadth-first, A*, greedy best-first (eager and lazy).

The searches run in C (``_core.c``) on the task's bit masks; this module names them and maps the plan's
operator indices back to operators. Breadth-first and A* with an admissible heuristic return shortest
plans, or cheapest where the task has action costs (breadth-first then runs as uniform-cost search);
greedy best-first is fast and not optimal: ``gbfs`` evaluates every state it generates, ``lazy`` only the
states it expands (their successors wait under the parent's h), as Fast Downward's lazy search does; by default
``lazy`` takes LAMA's pair, hFF and the landmark count in turn (``hff+lmcount``). Under action costs the greedy
searches count every action as 1, as LAMA's first iteration does (Fast Downward's ``lama-first``: its heuristics and
its search with ``cost_type=one``): on 66 problems of 22 IPC domains with costs (the first three of each, 10 s) this
solved 57 against 50 with the costs; the plan's cost is still the one reported.
Successors come in a fixed order, so a search returns the same plan every time.
"""

from __future__ import annotations

from strips_planner.grounding import GOAL_REACHED, Operator, Task

SEARCHES = ("bfs", "astar", "gbfs", "lazy")
GREEDY = ("gbfs", "lazy")
DEFAULT_HEURISTIC = {"bfs": "blind", "astar": "lmcut", "gbfs": "hff", "lazy": "hff+lmcount"}


class SearchStats:
    __slots__ = ("cost", "expanded", "generated", "timed_out")

    def __init__(self, expanded: int = 0, generated: int = 0, cost: int = 0) -> None:
        self.expanded, self.generated, self.cost = expanded, generated, cost
        self.timed_out = False
        """Whether the search's time ran out before it found a plan or ran out of states."""


def search(task: Task, name: str, heuristic: str, stats: SearchStats | None = None,
           seconds: float = 0.0) -> list[Operator] | None:
    """The plan found by search ``name`` guided by ``heuristic`` (A* keeps reopening states reached more
    cheaply, greedy best-first never revisits one); None when no reachable state satisfies the goal, or when
    ``seconds`` (0: no limit) ran out first (``stats.timed_out``; the clock is read every 16 expansions)."""
    compiled = task.compiled_unit_cost if name in GREEDY else task.compiled
    plan, expanded, generated, timed_out = compiled.search(name, heuristic, seconds)
    if stats is not None:
        stats.expanded, stats.generated, stats.timed_out = expanded, generated, timed_out
        stats.cost = task.cost(plan) if plan is not None else 0
    return None if plan is None else [task.operators[i] for i in plan if task.operators[i].name != GOAL_REACHED]


def successors(task: Task, state: int) -> list[tuple[int, Operator]]:
    """The (child state, operator) pairs of ``state``, in the order the searches generate them."""
    return [(child, task.operators[i]) for child, i in task.compiled.successors(state)]
