"""Forward state-space searches over a grounded task: breadth-first, A*, greedy best-first.

Breadth-first and A* with an admissible heuristic return shortest plans (unit action costs). Each
search returns the plan as a list of operators, or None when the reachable state space holds no goal
state. States are ints, so the closed list is a plain dict from state to its parent link.
"""

from __future__ import annotations

import heapq
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass

from semgoal_planner.grounding import Operator, Task
from semgoal_planner.heuristics import INF, Heuristic, bits


@dataclass
class SearchStats:
    expanded: int = 0
    generated: int = 0


class Successors:
    """The (child state, operator) pairs of a state.

    Each operator is filed under one of its preconditions, the one that the fewest operators need, so a
    state only looks at operators whose filed fact holds (unstack(a,b) under on(a,b), not arm-empty).
    Only the state's set bits are visited."""

    def __init__(self, task: Task) -> None:
        uses: dict[int, int] = {}
        for op in task.operators:
            for f in bits(op.pre):
                uses[f] = uses.get(f, 0) + 1
        self.free: list[tuple[int, int, int, int, Operator]] = []
        self.by_fact: dict[int, list[tuple[int, int, int, int, Operator]]] = {}
        for op in task.operators:
            entry = (op.pre, op.pre_neg, ~op.delete, op.add, op)
            if op.pre:
                key = min(bits(op.pre), key=uses.__getitem__)
                self.by_fact.setdefault(1 << key, []).append(entry)
            else:
                self.free.append(entry)

    def __call__(self, state: int) -> list[tuple[int, Operator]]:
        out = [(state & keep | add, op) for _, neg, keep, add, op in self.free if not state & neg]
        by_fact = self.by_fact
        rest = state
        while rest:
            low = rest & -rest
            rest ^= low
            for pre, neg, keep, add, op in by_fact.get(low, ()):
                if state & pre == pre and not state & neg:
                    out.append((state & keep | add, op))
        return out


def _plan(parents: dict[int, tuple[int, Operator] | None], state: int) -> list[Operator]:
    plan = []
    while (link := parents[state]) is not None:
        state, op = link
        plan.append(op)
    return plan[::-1]


def breadth_first(task: Task, heuristic: Heuristic | None = None, stats: SearchStats | None = None) -> list[Operator] | None:
    stats = stats or SearchStats()
    goal, goal_neg = task.goal, task.goal_neg
    if task.goal_reached(task.init):
        return []
    successors = Successors(task)
    parents: dict[int, tuple[int, Operator] | None] = {task.init: None}
    queue = deque([task.init])
    while queue:
        state = queue.popleft()
        stats.expanded += 1
        for child, op in successors(state):
            if child in parents:
                continue
            stats.generated += 1
            parents[child] = (state, op)
            if child & goal == goal and not child & goal_neg:
                return _plan(parents, child)
            queue.append(child)
    return None


def astar(task: Task, heuristic: Heuristic, stats: SearchStats | None = None) -> list[Operator] | None:
    """A* (f = g + h; ties to the larger g); optimal when ``heuristic`` is admissible."""
    stats = stats or SearchStats()
    successors = Successors(task)
    best_g = {task.init: 0}
    parents: dict[int, tuple[int, Operator] | None] = {task.init: None}
    h0 = heuristic(task.init)
    if h0 == INF:
        return None
    heap = [(h0, 0, 0, task.init)]
    counter = 0
    while heap:
        _, neg_g, _, state = heapq.heappop(heap)
        g = -neg_g
        if g > best_g[state]:
            continue
        if task.goal_reached(state):
            return _plan(parents, state)
        stats.expanded += 1
        for child, op in successors(state):
            if g + 1 >= best_g.get(child, INF):
                continue
            h = heuristic(child)
            stats.generated += 1
            if h == INF:
                continue
            best_g[child], parents[child] = g + 1, (state, op)
            counter += 1
            heapq.heappush(heap, (g + 1 + h, -(g + 1), counter, child))
    return None


def greedy_best_first(task: Task, heuristic: Heuristic, stats: SearchStats | None = None) -> list[Operator] | None:
    """Expands the state of lowest h first (FIFO among ties); fast, not optimal."""
    stats = stats or SearchStats()
    successors = Successors(task)
    parents: dict[int, tuple[int, Operator] | None] = {task.init: None}
    h0 = heuristic(task.init)
    if h0 == INF:
        return None
    heap = [(h0, 0, task.init)]
    counter = 0
    while heap:
        _, _, state = heapq.heappop(heap)
        if task.goal_reached(state):
            return _plan(parents, state)
        stats.expanded += 1
        for child, op in successors(state):
            if child in parents:
                continue
            parents[child] = (state, op)
            h = heuristic(child)
            stats.generated += 1
            if h == INF:
                continue
            counter += 1
            heapq.heappush(heap, (h, counter, child))
    return None


SEARCHES: dict[str, Callable[..., list[Operator] | None]] = {
    "bfs": breadth_first, "astar": astar, "gbfs": greedy_best_first,
}
DEFAULT_HEURISTIC = {"bfs": "blind", "astar": "lmcut", "gbfs": "hff"}
