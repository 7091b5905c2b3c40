"""Grounding: a parsed domain and problem -> a compact STRIPS task over int bitsets.

Only operators reachable in the relaxed task (delete effects and negative preconditions ignored) are
instantiated: parameters are bound one at a time and every precondition whose arguments are bound is
checked at once, against the relaxed-reachable atoms for fluents and exactly for static predicates and
equality. Static atoms then leave the state, which keeps only fluent facts, one bit each.
"""

from __future__ import annotations

from dataclasses import dataclass

from semgoal_planner.pddl import Action, Atom, Condition, Domain, Problem


@dataclass(frozen=True)
class Operator:
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


def _substitute(atom: Atom, binding: dict[str, str]) -> Atom:
    return Atom(atom.predicate, tuple(binding.get(a, a) for a in atom.args))


def _holds_static(cond: Condition, atom: Atom, static: set[Atom]) -> bool:
    truth = atom.args[0] == atom.args[1] if atom.predicate == "=" else atom in static
    return truth == cond.positive


class _Grounder:
    def __init__(self, domain: Domain, problem: Problem) -> None:
        self.domain, self.problem = domain, problem
        fluent = {a.predicate for action in domain.actions for a in (*action.add, *action.delete)}
        self.fluent = fluent
        self.static = {a for a in problem.init if a.predicate not in fluent}
        self.by_type: dict[str, list[str]] = {}
        for kind in domain.types:
            self.by_type[kind] = sorted(o for o, t in problem.objects.items() if domain.is_subtype(t, kind))

    def bindings(self, action: Action, reachable: set[Atom]):
        """Every parameter binding whose checkable preconditions hold (relaxed for fluents)."""
        params = [v for v, _ in action.parameters]
        # check each precondition as soon as its last variable is bound
        checks: list[list[Condition]] = [[] for _ in range(len(params) + 1)]
        for cond in action.precondition:
            depth = max((params.index(a) + 1 for a in cond.atom.args if a in params), default=0)
            is_static = cond.atom.predicate == "=" or cond.atom.predicate not in self.fluent
            if cond.positive or is_static:
                checks[depth].append(cond)
        binding: dict[str, str] = {}

        def ok(depth: int) -> bool:
            for cond in checks[depth]:
                atom = _substitute(cond.atom, binding)
                if atom.predicate == "=" or atom.predicate not in self.fluent:
                    if not _holds_static(cond, atom, self.static):
                        return False
                elif atom not in reachable:
                    return False
            return True

        def extend(depth: int):
            if not ok(depth):
                return
            if depth == len(params):
                yield dict(binding)
                return
            var, kind = action.parameters[depth]
            for obj in self.by_type.get(kind, []):
                binding[var] = obj
                yield from extend(depth + 1)
            binding.pop(var, None)

        yield from extend(0)

    def ground(self) -> Task:
        reachable = set(self.problem.init)
        changed = True
        while changed:  # relaxed exploration to a fixpoint
            changed = False
            for action in self.domain.actions:
                for binding in list(self.bindings(action, reachable)):
                    for atom in action.add:
                        ground_atom = _substitute(atom, binding)
                        if ground_atom not in reachable:
                            reachable.add(ground_atom)
                            changed = True
        facts = tuple(sorted((a for a in reachable if a.predicate in self.fluent), key=str))
        index = {fact: i for i, fact in enumerate(facts)}

        def mask(atoms) -> int:
            return sum(1 << index[a] for a in set(atoms) if a in index)

        operators = []
        for action in self.domain.actions:
            for binding in self.bindings(action, reachable):
                pre = [_substitute(c.atom, binding) for c in action.precondition
                       if c.positive and c.atom.predicate in self.fluent]
                neg = [_substitute(c.atom, binding) for c in action.precondition
                       if not c.positive and c.atom.predicate in self.fluent]
                add = [_substitute(a, binding) for a in action.add]
                delete = [_substitute(a, binding) for a in action.delete if _substitute(a, binding) not in add]
                args = tuple(binding[v] for v, _ in action.parameters)
                operators.append(Operator(action.name, args, mask(pre), mask(neg), mask(add), mask(delete)))
        reason = ""
        goal, goal_neg = [], []
        for cond in self.problem.goal:
            atom = cond.atom
            if atom.predicate == "=" or atom.predicate not in self.fluent:
                if not _holds_static(cond, atom, self.static):
                    reason = f"goal {'' if cond.positive else 'not '}{atom} can never hold (static)"
            elif cond.positive and atom not in index:
                reason = f"goal {atom} is not reachable from the initial state"
            elif cond.positive:
                goal.append(atom)
            else:
                goal_neg.append(atom)
        init = mask(a for a in self.problem.init if a in index)
        return Task(facts, init, mask(goal), mask(goal_neg), tuple(operators), reason)


def ground(domain: Domain, problem: Problem) -> Task:
    return _Grounder(domain, problem).ground()
