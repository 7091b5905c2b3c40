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
from semgoal_planner.heuristics import INF, Heuristic


@dataclass
class SearchStats:
    expanded: int = 0
    generated: int = 0


class Successors:
    """Applicable operators per state, found through the operators' first precondition fact."""

    def __init__(self, task: Task) -> None:
        self.free = [op for op in task.operators if not op.pre]
        self.by_fact: dict[int, list[Operator]] = {}
        for op in task.operators:
            if op.pre:
                lowest = (op.pre & -op.pre).bit_length() - 1
                self.by_fact.setdefault(lowest, []).append(op)
        self.fact_bits = sorted(self.by_fact)

    def __call__(self, state: int):
        for op in self.free:
            if not state & op.pre_neg:
                yield op
        for f in self.fact_bits:
            if state >> f & 1:
                for op in self.by_fact[f]:
                    if state & op.pre == op.pre and not state & op.pre_neg:
                        yield op


def _plan(parents: dict[int, tuple[int, Operator] | None], state: int) -> list[Operator]:
    plan = []
    while (link := parents[state]) is not None:
        state, op = link
        plan.append(op)
    return plan[::-1]


def breadth_first(task: Task, heuristic: Heuristic | None = None, stats: SearchStats | None = None) -> list[Operator] | None:
    stats = stats or SearchStats()
    if task.goal_reached(task.init):
        return []
    successors = Successors(task)
    parents: dict[int, tuple[int, Operator] | None] = {task.init: None}
    queue = deque([task.init])
    while queue:
        state = queue.popleft()
        stats.expanded += 1
        for op in successors(state):
            child = (state & ~op.delete) | op.add
            if child in parents:
                continue
            stats.generated += 1
            parents[child] = (state, op)
            if task.goal_reached(child):
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
        for op in successors(state):
            child = (state & ~op.delete) | op.add
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
        for op in successors(state):
            child = (state & ~op.delete) | op.add
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
