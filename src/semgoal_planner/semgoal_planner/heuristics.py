"""Delete-relaxation heuristics: blind, hmax (admissible), hFF (informative), LM-cut (admissible).

All of them ignore delete effects, negative preconditions and negative goals, which only relaxes the
task further, so hmax and LM-cut stay admissible (Bonet & Geffner 2001; Hoffmann & Nebel 2001;
Helmert & Domshlak 2009). A heuristic is built once per task and then called with a state (int bitset).
"""

from __future__ import annotations

import heapq
from collections.abc import Callable

from semgoal_planner.grounding import Task

INF = float("inf")
Heuristic = Callable[[int], float]


def _bits(mask: int) -> list[int]:
    out, i = [], 0
    while mask:
        if mask & 1:
            out.append(i)
        mask >>= 1
        i += 1
    return out


class RelaxedTask:
    """Operators as index lists, plus an artificial goal operator (its add effect is fact ``goal_fact``)."""

    def __init__(self, task: Task) -> None:
        n = len(task.facts)
        self.goal_fact = n
        self.n_facts = n + 1
        self.pre = [_bits(op.pre) for op in task.operators] + [_bits(task.goal)]
        self.add = [_bits(op.add) for op in task.operators] + [[self.goal_fact]]
        self.base_cost = [1.0] * len(task.operators) + [0.0]
        self.goal_op = len(self.pre) - 1
        self.consumers: list[list[int]] = [[] for _ in range(self.n_facts)]
        for o, pre in enumerate(self.pre):
            for f in pre:
                self.consumers[f].append(o)
        self.no_pre = [o for o, pre in enumerate(self.pre) if not pre]
        self.achievers: list[list[int]] = [[] for _ in range(self.n_facts)]
        for o, adds in enumerate(self.add):
            for f in adds:
                self.achievers[f].append(o)

    def explore(self, state: int, cost: list[float], combine_sum: bool) -> tuple[list[float], list[int]]:
        """Generalised Dijkstra: fact costs (hmax or hadd) and each fact's cheapest achiever (-1: none)."""
        fact_cost = [INF] * self.n_facts
        achiever = [-1] * self.n_facts
        missing = [len(p) for p in self.pre]
        op_value = [0.0] * len(self.pre)
        heap: list[tuple[float, int]] = []
        for f in _bits(state):
            fact_cost[f] = 0.0
            heap.append((0.0, f))

        def fire(o: int) -> None:
            value = op_value[o] + cost[o]
            for f in self.add[o]:
                if value < fact_cost[f]:
                    fact_cost[f], achiever[f] = value, o
                    heapq.heappush(heap, (value, f))

        for o in self.no_pre:
            fire(o)
        while heap:
            value, f = heapq.heappop(heap)
            if value > fact_cost[f]:
                continue
            if f == self.goal_fact:
                break
            for o in self.consumers[f]:
                op_value[o] = op_value[o] + value if combine_sum else max(op_value[o], value)
                missing[o] -= 1
                if missing[o] == 0:
                    fire(o)
        return fact_cost, achiever


def blind(task: Task) -> Heuristic:
    return lambda state: 0.0 if task.goal_reached(state) else 1.0


def hmax(task: Task) -> Heuristic:
    relaxed = RelaxedTask(task)
    return lambda state: relaxed.explore(state, relaxed.base_cost, combine_sum=False)[0][relaxed.goal_fact]


def hff(task: Task) -> Heuristic:
    """Size of a relaxed plan extracted from hadd's best achievers."""
    relaxed = RelaxedTask(task)

    def h(state: int) -> float:
        fact_cost, achiever = relaxed.explore(state, relaxed.base_cost, combine_sum=True)
        if fact_cost[relaxed.goal_fact] == INF:
            return INF
        plan, stack, seen = set(), list(relaxed.pre[relaxed.goal_op]), set()
        while stack:
            f = stack.pop()
            if f in seen or fact_cost[f] == 0.0:
                continue
            seen.add(f)
            o = achiever[f]
            if o not in plan:
                plan.add(o)
                stack.extend(relaxed.pre[o])
        return float(len(plan))

    return h


def lmcut(task: Task) -> Heuristic:
    """Sum of the costs of disjunctive action landmarks found by repeated hmax cuts."""
    relaxed = RelaxedTask(task)
    goal_fact = relaxed.goal_fact

    def h(state: int) -> float:
        cost = list(relaxed.base_cost)
        total = 0.0
        while True:
            fact_cost, _ = relaxed.explore(state, cost, combine_sum=False)
            if fact_cost[goal_fact] == INF:
                return INF
            if fact_cost[goal_fact] == 0.0:
                return total
            # precondition choice: each operator's costliest precondition (ties: first)
            pcf = [max(pre, key=fact_cost.__getitem__) if pre else -1 for pre in relaxed.pre]
            # goal zone: facts that reach the goal through zero-cost operators
            zone, stack = {goal_fact}, [goal_fact]
            while stack:
                f = stack.pop()
                for o in relaxed.achievers[f]:
                    if cost[o] == 0.0 and pcf[o] >= 0 and fact_cost[pcf[o]] < INF and pcf[o] not in zone:
                        zone.add(pcf[o])
                        stack.append(pcf[o])
            # forward from the state (and precondition-free operators) without entering the zone
            reached = set(_bits(state))
            frontier = list(reached)
            cut: set[int] = set()
            candidates = list(relaxed.no_pre)
            while frontier or candidates:
                ops = candidates + [o for f in frontier for o in relaxed.consumers[f] if pcf[o] == f]
                candidates, frontier = [], []
                for o in ops:
                    if any(f in zone for f in relaxed.add[o]):
                        cut.add(o)
                        continue
                    for f in relaxed.add[o]:
                        if f not in reached:
                            reached.add(f)
                            frontier.append(f)
            step = min(cost[o] for o in cut)
            if step == 0.0:  # a degenerate cut: stop here, the sum so far is still a lower bound
                return total
            total += step
            for o in cut:
                cost[o] -= step

    return h


HEURISTICS: dict[str, Callable[[Task], Heuristic]] = {"blind": blind, "hmax": hmax, "hff": hff, "lmcut": lmcut}
ADMISSIBLE = {"blind", "hmax", "lmcut"}
