"""Delete-relaxation heuristics: blind, hmax (admissible), hFF (informative), LM-cut (admissible).

All of them ignore delete effects, negative preconditions and negative goals, which only relaxes the
task further, so hmax and LM-cut stay admissible (Bonet & Geffner 2001; Hoffmann & Nebel 2001;
Helmert & Domshlak 2009). A heuristic is built once per task and then called with a state (int bitset).

Actions cost 1, so hmax is the layer of a relaxed planning graph where the goal first appears, and
hFF the size of a relaxed plan extracted backwards through those layers, as in FF. Both run on whole
bitsets: one ``&`` per operator and layer. LM-cut changes operator costs between its rounds, so it runs a
Dijkstra over facts instead.
"""

from __future__ import annotations

import heapq
from collections.abc import Callable
from typing import NamedTuple

from semgoal_planner.grounding import Task

INF = float("inf")
Heuristic = Callable[[int], float]


def bits(mask: int) -> list[int]:
    """Indices of the set bits of ``mask``, lowest first."""
    out = []
    while mask:
        low = mask & -mask
        out.append(low.bit_length() - 1)
        mask ^= low
    return out


def relaxed_layers(operators: list[tuple[int, int]], state: int, goal: int) -> list[int] | None:
    """Facts reached after 0, 1, 2 ... relaxed steps from ``state`` until ``goal`` holds; None if never."""
    layers = [state]
    reached = state
    pending = operators
    while reached & goal != goal:
        grown, waiting = reached, []
        for op in pending:
            if op[0] & reached == op[0]:
                grown |= op[1]
            else:
                waiting.append(op)
        if grown == reached:
            return None
        reached, pending = grown, waiting
        layers.append(reached)
    return layers


def blind(task: Task) -> Heuristic:
    return lambda state: 0.0 if task.goal_reached(state) else 1.0


def _pre_add(task: Task) -> list[tuple[int, int]]:
    """(precondition, add) masks of the operators that can add something."""
    return [(op.pre, op.add) for op in task.operators if op.add]


def hmax(task: Task) -> Heuristic:
    operators, goal = _pre_add(task), task.goal

    def h(state: int) -> float:
        layers = relaxed_layers(operators, state, goal)
        return INF if layers is None else float(len(layers) - 1)

    return h


def hff(task: Task) -> Heuristic:
    """Relaxed plan size: each open fact is achieved by an operator applicable one layer earlier."""
    operators, goal = _pre_add(task), task.goal
    achievers: dict[int, list[tuple[int, int]]] = {}
    for pre, add in operators:
        for f in bits(add):
            achievers.setdefault(f, []).append((pre, add))

    def h(state: int) -> float:
        layers = relaxed_layers(operators, state, goal)
        if layers is None:
            return INF
        open_at: list[int] = [0] * len(layers)  # per layer, the facts first reached there still to achieve
        for f in bits(goal & ~state):
            open_at[_first_layer(layers, 1 << f)] |= 1 << f
        size = 0
        for layer in range(len(layers) - 1, 0, -1):
            below = layers[layer - 1]
            while open_at[layer]:
                f = open_at[layer] & -open_at[layer]
                pre, add = next(op for op in achievers[f.bit_length() - 1] if op[0] & below == op[0])
                size += 1
                open_at[layer] &= ~add
                open_at[layer - 1] &= ~add
                for p in bits(pre & ~state):
                    open_at[_first_layer(layers, 1 << p)] |= 1 << p
        return float(size)

    return h


def _first_layer(layers: list[int], fact: int) -> int:
    for i, reached in enumerate(layers):
        if reached & fact:
            return i
    raise ValueError("fact not reached")


class _CostedTask:
    """Operators as fact-index lists for Dijkstra with changing costs, plus two artificial facts: the
    goal (added by a zero-cost operator that needs the goal facts) and "true" (in every state, and
    the precondition of operators that have none, so that every operator has a supporter)."""

    def __init__(self, task: Task) -> None:
        n = len(task.facts)
        self.goal_fact, self.true_fact = n, n + 1
        self.pre = [bits(op.pre) or [self.true_fact] for op in task.operators] + [bits(task.goal) or [self.true_fact]]
        self.add = [bits(op.add) for op in task.operators] + [[self.goal_fact]]
        self.base_cost = [1] * len(task.operators) + [0]
        self.consumers: list[list[int]] = [[] for _ in range(n + 2)]
        for o, pre in enumerate(self.pre):
            for f in pre:
                self.consumers[f].append(o)
        self.achievers: list[list[int]] = [[] for _ in range(n + 2)]
        for o, adds in enumerate(self.add):
            for f in adds:
                self.achievers[f].append(o)

    def hmax(self, state: list[int], cost: list[int]) -> _Hmax:
        """Dijkstra over facts. Facts pop in order of cost, so an operator's last precondition to pop
        is a costliest one: its supporter."""
        result = _Hmax([INF] * len(self.consumers), [-1] * len(self.pre), [0] * len(self.pre))
        fact_cost, supporter, op_max = result
        missing = [len(p) for p in self.pre]
        heap = [(0, f) for f in state]
        for f in state:
            fact_cost[f] = 0
        consumers = self.consumers
        while heap:
            value, f = heapq.heappop(heap)
            if value > fact_cost[f]:
                continue
            for o in consumers[f]:
                missing[o] -= 1
                if not missing[o]:
                    supporter[o], op_max[o] = f, value
                    self._offer(result, o, value + cost[o], heap)
        return result

    def lower(self, result: _Hmax, cost: list[int], cheaper: set[int]) -> None:
        """Update ``result`` after the operators in ``cheaper`` got cheaper (costs only ever fall, so only
        what they reach can change): the incremental hmax of Helmert & Domshlak's LM-cut."""
        fact_cost, supporter, op_max = result
        heap: list[tuple[int, int]] = []
        for o in cheaper:
            self._offer(result, o, op_max[o] + cost[o], heap)
        consumers, pre = self.consumers, self.pre
        while heap:
            value, f = heapq.heappop(heap)
            if value > fact_cost[f]:
                continue
            for o in consumers[f]:
                if supporter[o] == f:  # the costliest precondition fell: find the new one
                    top = max(pre[o], key=fact_cost.__getitem__)
                    supporter[o] = top
                    if fact_cost[top] < op_max[o]:
                        op_max[o] = fact_cost[top]
                        self._offer(result, o, op_max[o] + cost[o], heap)

    def _offer(self, result: _Hmax, o: int, value: int, heap: list[tuple[int, int]]) -> None:
        fact_cost = result.fact_cost
        for g in self.add[o]:
            if value < fact_cost[g]:
                fact_cost[g] = value
                heapq.heappush(heap, (value, g))


class _Hmax(NamedTuple):
    fact_cost: list[float]
    supporter: list[int]
    """Per operator, a costliest precondition (-1: none, or the operator is unreachable)."""
    op_max: list[int]
    """Per operator, the cost of its supporter: the cost of reaching all its preconditions."""


def lmcut(task: Task) -> Heuristic:
    """Sum of the costs of disjunctive action landmarks found by repeated hmax cuts."""
    relaxed = _CostedTask(task)
    goal_fact, add, consumers = relaxed.goal_fact, relaxed.add, relaxed.consumers

    def h(state: int) -> float:
        facts = [*bits(state), relaxed.true_fact]
        cost = list(relaxed.base_cost)
        hmax = relaxed.hmax(facts, cost)
        fact_cost, supporter = hmax.fact_cost, hmax.supporter
        if fact_cost[goal_fact] == INF:
            return INF
        total = 0
        while fact_cost[goal_fact] > 0:
            # goal zone: facts that reach the goal through zero-cost operators (via their supporters)
            zone, stack = {goal_fact}, [goal_fact]
            while stack:
                for o in relaxed.achievers[stack.pop()]:
                    f = supporter[o]
                    if cost[o] == 0 and f >= 0 and f not in zone:
                        zone.add(f)
                        stack.append(f)
            # forward from the state, through operators whose supporter is reached, stopping at the zone
            reached = set(facts)
            stack = list(facts)
            cut: set[int] = set()
            while stack:
                f = stack.pop()
                for o in consumers[f]:
                    if supporter[o] == f:
                        adds = add[o]
                        if not zone.isdisjoint(adds):
                            cut.add(o)
                            continue
                        for g in adds:
                            if g not in reached:
                                reached.add(g)
                                stack.append(g)
            step = min(cost[o] for o in cut)
            if step == 0:  # a degenerate cut: stop here, the sum so far is still a lower bound
                break
            total += step
            for o in cut:
                cost[o] -= step
            relaxed.lower(hmax, cost, cut)
        return float(total)

    return h


HEURISTICS: dict[str, Callable[[Task], Heuristic]] = {"blind": blind, "hmax": hmax, "hff": hff, "lmcut": lmcut}
ADMISSIBLE = {"blind", "hmax", "lmcut"}
