"""Deordering: the orderings between a sequential plan's steps that its preconditions and effects need, no more.

A step j stays after a step i (i before j in the sequence) where

1. **i supports j**: i is the last step before j that makes one of j's preconditions as j needs it (true, or
   false for a negative precondition), or the last that makes a goal fact as the goal needs it (j is then the
   goal);
2. **i would break a support**: a support from a step p to a step c on a fact that i, earlier than p, sets the
   other way (i stays before p) or that i, later than c, sets the other way (c stays before i).

Every fact a step or the goal needs then has a support no other step can come between: by the criterion of
partial-order causal-link planning, every order of the steps that keeps these is a plan that reaches the goal
(Bäckström, "Computational aspects of reordering plans", JAIR 1998, calls such a result a deordering). The
facts in ``ignore`` (each agent's own resource, such as an empty hand) take no part: the steps are then ordered as
if every agent had its own. A plan with conditional effects or derived predicates keeps its order: what a step makes
true depends there on the state it runs in.
"""

from __future__ import annotations

from collections.abc import Sequence

from strips_planner.grounding import Operator, Task


def deorder(task: Task, plan: Sequence[Operator], ignore: int = 0) -> list[tuple[int, ...]]:
    """For each step of ``plan`` (a valid plan of ``task``), the earlier steps it must follow directly: the kept
    orderings without those that follow from others (a transitive reduction), each tuple ascending."""
    count = len(plan)
    if task.axioms or any(op.effects for op in plan):
        return [() if step == 0 else (step - 1,) for step in range(count)]
    after: list[set[int]] = [set() for _ in range(count + 1)]  # index count: the goal
    needs = [(op.pre & ~ignore, op.pre_neg & ~ignore) for op in plan]
    needs.append((task.goal & ~ignore, task.goal_neg & ~ignore))
    for consumer, (true_needed, false_needed) in enumerate(needs):
        for wanted, facts in ((True, true_needed), (False, false_needed)):
            for fact in _bits(facts):
                supporter = _last_setting(plan, consumer, fact, wanted)
                if supporter is not None:
                    after[consumer].add(supporter)
                for breaker in range(count):
                    if breaker not in (supporter, consumer) and _sets(plan[breaker], fact, not wanted):
                        if supporter is not None and breaker < supporter:
                            after[supporter].add(breaker)
                        elif breaker > consumer:
                            after[breaker].add(consumer)
    return transitive_reduction(after[:count])


def _bits(mask: int) -> list[int]:
    return [i for i in range(mask.bit_length()) if mask >> i & 1]


def _sets(op: Operator, fact: int, value: bool) -> bool:
    """Whether applying ``op`` leaves ``fact`` at ``value`` whatever it was (adds win over deletes)."""
    bit = 1 << fact
    return bool(op.add & bit) if value else bool(op.delete & bit and not op.add & bit)


def _last_setting(plan: Sequence[Operator], before: int, fact: int, value: bool) -> int | None:
    """The last step before index ``before`` that sets ``fact`` to ``value``; None: the initial state does."""
    return next((i for i in range(min(before, len(plan)) - 1, -1, -1) if _sets(plan[i], fact, value)), None)


def transitive_reduction(after: Sequence[set[int]]) -> list[tuple[int, ...]]:
    """Each step's predecessors (every one earlier in the sequence) less those implied through another step."""
    reach: list[set[int]] = []  # every step each one must follow, directly or not
    for preds in after:
        reach.append(set(preds).union(*(reach[p] for p in preds)))
    return [tuple(sorted(p for p in preds if not any(p in reach[q] for q in preds if q != p))) for preds in after]


__all__ = ["deorder", "transitive_reduction"]
