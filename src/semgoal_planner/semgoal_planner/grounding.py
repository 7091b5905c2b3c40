"""Grounding: a parsed domain and problem -> a compact STRIPS task over int bitsets.

Two passes, each linear in what it produces. First every action's parameters are bound one at a time
over objects of their types, and each static precondition (a predicate no action changes, or equality)
is checked as soon as its last variable is bound, so bindings that can never apply are cut early. Then a
relaxed exploration (delete effects and negative preconditions ignored) keeps the candidates whose
fluent preconditions become reachable: each candidate waits on a counter of unreached preconditions and
fires when it hits zero. Static atoms leave the state, which keeps only reachable fluent facts, one bit
each.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from operator import itemgetter
from typing import NamedTuple

from semgoal_planner.pddl import Action, Atom, Domain, Problem

GroundAtom = tuple[str, ...]
"""(predicate, *arguments): a hashable atom that is cheap to build while grounding."""


class Operator(NamedTuple):
    """A ground action: precondition, add and delete sets as bit masks over the task's facts."""

    name: str
    args: tuple[str, ...]
    pre: int
    pre_neg: int
    add: int
    delete: int

    def applicable(self, state: int) -> bool:
        return state & self.pre == self.pre and not state & self.pre_neg

    def apply(self, state: int) -> int:
        return (state & ~self.delete) | self.add

    def __str__(self) -> str:
        return f"({' '.join((self.name, *self.args))})"


@dataclass(frozen=True)
class Task:
    facts: tuple[Atom, ...]
    """Bit i of a state is ``facts[i]``."""
    init: int
    goal: int
    goal_neg: int
    operators: tuple[Operator, ...]
    unsolvable_reason: str = ""
    """Set when grounding alone proves the goal unreachable (a static or unreachable goal atom)."""

    def goal_reached(self, state: int) -> bool:
        return state & self.goal == self.goal and not state & self.goal_neg

    def atoms(self, state: int) -> list[Atom]:
        return [fact for i, fact in enumerate(self.facts) if state >> i & 1]


Template = Callable[[list[str]], GroundAtom]


def _template(atom: Atom, slot_of: dict[str, int]) -> Template:
    """A function from a binding to this atom instantiated, e.g. values -> ("on", "b1", "b2").

    The binding list also holds the predicate names, so one C-level itemgetter builds the whole tuple."""
    if not atom.args:
        ground_atom = (atom.predicate,)
        return lambda values: ground_atom
    return itemgetter(slot_of[atom.predicate], *(slot_of[a] for a in atom.args))


class _Candidate(NamedTuple):
    """A binding of an action whose static preconditions hold, its other atoms instantiated."""

    name: str
    args: tuple[str, ...]
    pre: set[GroundAtom]
    pre_neg: list[GroundAtom]
    add: list[GroundAtom]
    delete: list[GroundAtom]


class _Schema:
    """An action compiled for grounding: typed parameters, static checks by binding depth, templates."""

    def __init__(self, action: Action, names: list[str], fluent: set[str]) -> None:
        """``names``: the constants, then the predicates, which follow the parameters in a binding."""
        self.action = action
        params = [v for v, _ in action.parameters]
        slot_of = {name: i for i, name in enumerate(params + names)}
        self.static_checks: list[list[tuple[Template, bool]]] = [[] for _ in range(len(params) + 1)]
        self.pre, self.pre_neg = [], []
        for cond in action.precondition:
            template = _template(cond.atom, slot_of)
            if cond.atom.predicate == "=" or cond.atom.predicate not in fluent:
                depth = max((params.index(a) + 1 for a in cond.atom.args if a in params), default=0)
                self.static_checks[depth].append((template, cond.positive))
            else:
                (self.pre if cond.positive else self.pre_neg).append(template)
        self.add = [_template(a, slot_of) for a in action.add]
        self.delete = [_template(a, slot_of) for a in action.delete]


class _Grounder:
    def __init__(self, domain: Domain, problem: Problem) -> None:
        self.domain, self.problem = domain, problem
        self.fluent = {a.predicate for action in domain.actions for a in (*action.add, *action.delete)}
        self.static = {(a.predicate, *a.args) for a in problem.init if a.predicate not in self.fluent}
        self.names = [*sorted(domain.constants), "=", *domain.predicates]
        self.by_type = {kind: sorted(o for o, t in problem.objects.items() if domain.is_subtype(t, kind))
                        for kind in domain.types}

    def _static_holds(self, atom: GroundAtom, positive: bool) -> bool:
        truth = atom[1] == atom[2] if atom[0] == "=" else atom in self.static
        return truth == positive

    def bindings(self, schema: _Schema):
        """Every binding (parameter values, then constants and predicate names) whose static
        preconditions hold. The list is reused between bindings: copy what you keep."""
        params = schema.action.parameters
        values = [""] * len(params) + self.names
        checks = schema.static_checks
        domains = [self.by_type.get(kind, []) for _, kind in params]

        def extend(depth: int):
            if not all(self._static_holds(t(values), positive) for t, positive in checks[depth]):
                return
            if depth == len(params):
                yield values
                return
            for obj in domains[depth]:
                values[depth] = obj
                yield from extend(depth + 1)

        yield from extend(0)

    def ground(self) -> Task:
        candidates = [candidate for action in self.domain.actions for candidate in self._candidates(action)]
        reached = self._relaxed_reachable(candidates)
        fluents = sorted(a for a in reached if a[0] in self.fluent)
        index = {atom: 1 << i for i, atom in enumerate(fluents)}

        def mask(atoms) -> int:
            bits = 0
            for atom in atoms:
                bits |= index.get(atom, 0)
            return bits

        operators = []
        for c in candidates:
            if c.pre <= reached:
                add = mask(c.add)
                operators.append(Operator(c.name, c.args, mask(c.pre), mask(c.pre_neg), add, mask(c.delete) & ~add))
        goal, goal_neg, reason = self._goal(index)
        return Task(tuple(Atom(a[0], a[1:]) for a in fluents), mask((a.predicate, *a.args) for a in self.problem.init),
                    goal, goal_neg, tuple(operators), reason)

    def _candidates(self, action: Action) -> list[_Candidate]:
        schema = _Schema(action, self.names, self.fluent)
        n = len(action.parameters)
        return [_Candidate(action.name, tuple(values[:n]), {t(values) for t in schema.pre},
                           [t(values) for t in schema.pre_neg], [t(values) for t in schema.add],
                           [t(values) for t in schema.delete]) for values in self.bindings(schema)]

    def _relaxed_reachable(self, candidates: list) -> set[GroundAtom]:
        """Atoms reachable when delete effects and negative preconditions are ignored."""
        reached = {(a.predicate, *a.args) for a in self.problem.init if a.predicate in self.fluent}
        waiting: dict[GroundAtom, list[int]] = {}
        missing = []
        ready = []
        for i, candidate in enumerate(candidates):
            unmet = [a for a in candidate.pre if a not in reached]
            missing.append(len(unmet))
            for atom in unmet:
                waiting.setdefault(atom, []).append(i)
            if not unmet:
                ready.append(i)
        while ready:
            for atom in candidates[ready.pop()].add:
                if atom not in reached:
                    reached.add(atom)
                    for j in waiting.pop(atom, ()):
                        missing[j] -= 1
                        if not missing[j]:
                            ready.append(j)
        return reached

    def _goal(self, index: dict[GroundAtom, int]) -> tuple[int, int, str]:
        """Goal and negated-goal masks, and why the goal can never hold ("" when it may)."""
        reason, goal, goal_neg = "", 0, 0
        for cond in self.problem.goal:
            atom = (cond.atom.predicate, *cond.atom.args)
            if atom[0] == "=" or atom[0] not in self.fluent:
                if not self._static_holds(atom, cond.positive):
                    reason = f"goal {'' if cond.positive else 'not '}{cond.atom} can never hold (static)"
            elif cond.positive and atom not in index:
                reason = f"goal {cond.atom} is not reachable from the initial state"
            elif cond.positive:
                goal |= index[atom]
            else:
                goal_neg |= index.get(atom, 0)
        return goal, goal_neg, reason


def ground(domain: Domain, problem: Problem) -> Task:
    return _Grounder(domain, problem).ground()
