"""Heuristics: blind, the delete relaxation's hmax (admissible), hFF (informative) and LM-cut (admissible), and
the landmark count.

They run in C (``_core.c``) inside the searches; :func:`heuristic` evaluates one on a single state, for
tests and for inspecting a task. All of them ignore delete effects (Bonet & Geffner 2001; Hoffmann & Nebel 2001;
Helmert & Domshlak 2009), so hmax and LM-cut stay admissible. A fact that a precondition, a condition or the goal asks
false has a relaxed fact for its negation, true where the fact is not and made by what deletes it, as in a
finite-domain translation (Fast Downward's, where it is the false value of a binary variable): ignoring negative
preconditions, as they did, hid what must be undone first (schedule's busy machines). Actions cost 1, or their own
costs where the task has them.
A conditional effect is, relaxed, an action of its own (its action's precondition and its condition, its adds, its
action's cost): hmax stays admissible, hFF counts an action once however many of its effects its relaxed plan uses,
and LM-cut, which would not stay admissible so, is refused on such tasks. A derived predicate's rule is an action of
cost 0 (its body, its head), and a derived fact asked false is left out, as in Fast Downward's relaxations.

- blind: 0 in a goal state, else the cheapest action's cost (1 without costs).
- hmax: the cost of the goal's costliest fact in the relaxed task (a Dijkstra over facts).
- hFF: the cost of a relaxed plan made of each needed fact's cheapest achiever, traced back from the goal.
- LM-cut: the sum of the costs of disjunctive action landmarks found by repeated hmax cuts, with the
  incremental hmax update between cuts.
- lmcount: LAMA's landmark count (Richter & Westphal 2010): of the facts every plan makes true at some point
  (Zhu & Givan's landmarks, found once from the initial state), those not yet true anywhere on the path to a
  state, plus those of the others false again that are needed again: the goals, and each one that is a
  precondition of every operator adding a landmark not yet reached (a greedy-necessary ordering; Hoffmann, Porteous
  & Sebastia 2004). It depends on the path, so it guides the greedy searches only; :func:`heuristic` takes the facts
  passed on the way, or the state as the path's only state.

The greedy searches take several heuristics joined by ``+`` (``hff+lmcount``, LAMA's pair): one open list each,
taking turns.
"""

from __future__ import annotations

from collections.abc import Callable

from strips_planner.grounding import Task

HEURISTICS = ("blind", "hmax", "hff", "lmcut", "lmcount")
GREEDY_ONLY = ("lmcount",)
Heuristic = Callable[..., float]


def heuristic(task: Task, name: str) -> Heuristic:
    """``name``'s estimate of the plan length from a state (an int bitset over ``task.facts``); inf when
    the goal is unreachable even relaxed. The landmark count also takes ``passed``: the facts true in some earlier
    state of the path to it (by default none: the state is the path's only one)."""
    if name not in HEURISTICS:
        raise ValueError(f"unknown heuristic {name!r}; valid: {', '.join(HEURISTICS)}")
    compiled = task.compiled
    return lambda state, passed=None: compiled.heuristic(name, state, passed)
