"""Grounding: a parsed domain and problem -> a compact STRIPS task over int bitsets.

Each pass is linear in what it produces and mostly C-level ``map`` over whole columns (one atom of
one action across all its bindings) rather than a Python loop per operator.
1. Every action's parameters are bound one at a time over objects of their types, and each static
   precondition (a predicate no action changes, or equality) is checked as soon as its last variable is
   bound, so bindings that can never apply are cut early. Static atoms never enter the state.
2. The fluent atoms the candidates mention get one bit each, in sorted order, and the candidates become
   operators over those bits.
3. A relaxed exploration in C (delete effects and negative preconditions ignored) finds the atoms and
   candidates reachable from the initial state. Usually that is all of them and the task is done;
   otherwise the unreachable ones are dropped and the bits renumbered.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass
from functools import cached_property
from itertools import count, repeat
from operator import itemgetter
from typing import NamedTuple

from semgoal_planner import _core
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

    @cached_property
    def compiled(self) -> _core.Task:
        """This task for the C searches and heuristics (built on first use)."""
        return _core.Task(len(self.facts), self.operators, self.init, self.goal, self.goal_neg)


Template = Callable[[tuple[str, ...]], GroundAtom]


def _template(atom: Atom, slot_of: dict[str, int]) -> Template:
    """A function from a binding to this atom instantiated, e.g. values -> ("on", "b1", "b2"), for the
    static checks. The binding tuple also holds the predicate names, so one C-level itemgetter builds the
    whole tuple."""
    if not atom.args:
        ground_atom = (atom.predicate,)
        return lambda values: ground_atom
    return itemgetter(slot_of[atom.predicate], *(slot_of[a] for a in atom.args))


class _Schema:
    """An action compiled for grounding: static checks by binding depth, and its other atoms."""

    def __init__(self, action: Action, names: tuple[str, ...], fluent: set[str]) -> None:
        """``names``: the constants, then the predicates, which follow the parameters in a binding."""
        self.action = action
        params = [v for v, _ in action.parameters]
        slot_of = {name: i for i, name in enumerate(params + list(names))}
        self.static_checks: list[list[tuple[Template, bool]]] = [[] for _ in range(len(params) + 1)]
        self.pre: list[Atom] = []
        self.pre_neg: list[Atom] = []
        for cond in action.precondition:
            if cond.atom.predicate == "=" or cond.atom.predicate not in fluent:
                depth = max((params.index(a) + 1 for a in cond.atom.args if a in params), default=0)
                self.static_checks[depth].append((_template(cond.atom, slot_of), cond.positive))
            else:
                (self.pre if cond.positive else self.pre_neg).append(cond.atom)


class _Candidates:
    """One action's bindings, with its atoms as columns (one list per atom, one entry per binding)."""

    def __init__(self, schema: _Schema, bindings: list[tuple[str, ...]]) -> None:
        action = schema.action
        self.name = action.name
        self.args = bindings
        values = {var: list(map(itemgetter(i), bindings)) for i, (var, _) in enumerate(action.parameters)}

        def column(atom: Atom) -> list[GroundAtom]:
            """The atom under every binding: tuples zipped from the predicate and argument columns."""
            parts = [values.get(arg) or repeat(arg, len(bindings)) for arg in atom.args]
            return list(zip(repeat(atom.predicate, len(bindings)), *parts, strict=True))

        self.columns = [list(map(column, atoms)) for atoms in (schema.pre, schema.pre_neg, action.add, action.delete)]

    def number(self, first_seen: dict[GroundAtom, int], mentions: Iterator[int]) -> None:
        """Replace each atom by its id: the number of its first mention, counted by ``mentions``."""
        self.columns = [[list(map(first_seen.setdefault, column, mentions)) for column in columns]
                        for columns in self.columns]

    def masks(self, bit_of: list[int]) -> list[list[int]]:
        """Per kind (pre, pre_neg, add, delete), every binding's mask, given each atom id's bit (1 << bit)."""
        out = []
        for columns in self.columns:
            masks = [0] * len(self.args)
            for column in columns:
                masks = list(map(int.__or__, masks, map(bit_of.__getitem__, column)))
            out.append(masks)
        return out


class _Grounder:
    def __init__(self, domain: Domain, problem: Problem) -> None:
        self.domain, self.problem = domain, problem
        self.fluent = {a.predicate for action in domain.actions for a in (*action.add, *action.delete)}
        self.static = {(a.predicate, *a.args) for a in problem.init if a.predicate not in self.fluent}
        self.names = (*sorted(domain.constants), "=", *domain.predicates)
        self.by_type = {kind: sorted(o for o, t in problem.objects.items() if domain.is_subtype(t, kind))
                        for kind in domain.types}

    def _static_holds(self, atom: GroundAtom, positive: bool) -> bool:
        truth = atom[1] == atom[2] if atom[0] == "=" else atom in self.static
        return truth == positive

    def bindings(self, schema: _Schema) -> list[tuple[str, ...]]:
        """Every binding of the parameters whose static preconditions hold, bound one parameter at a time."""
        params = schema.action.parameters
        partial: list[tuple[str, ...]] = [()]
        for depth in range(len(params) + 1):
            checks = schema.static_checks[depth]
            if checks:
                pad = ("",) * (len(params) - depth) + self.names
                partial = [b for b in partial
                           if all(self._static_holds(t(b + pad), positive) for t, positive in checks)]
            if depth < len(params):
                objects = [(o,) for o in self.by_type.get(params[depth][1], [])]
                partial = [b + o for b in partial for o in objects]
        return partial

    def ground(self) -> Task:
        groups = []
        for action in self.domain.actions:
            schema = _Schema(action, self.names, self.fluent)
            groups.append(_Candidates(schema, self.bindings(schema)))
        first_seen: dict[GroundAtom, int] = {}
        mentions = count()
        init = [(a.predicate, *a.args) for a in self.problem.init if a.predicate in self.fluent]
        init_ids = set(map(first_seen.setdefault, init, mentions))
        for group in groups:
            group.number(first_seen, mentions)
        atoms = sorted(first_seen)
        task = self._task(groups, atoms, first_seen, next(mentions), init_ids)
        reached, fired = task.compiled.reachable()
        if reached == (1 << len(atoms)) - 1 and len(fired) == len(task.operators):
            return task
        kept = [atoms[i] for i in _bits(reached)]
        return self._task(groups, kept, first_seen, next(mentions), init_ids, set(fired))

    def _task(self, groups: list[_Candidates], facts: list[GroundAtom], first_seen: dict[GroundAtom, int],
              ids: int, init_ids: set[int], fired: set[int] | None = None) -> Task:
        """The task over ``facts`` (one bit each, in that order; other atoms are dropped) with the candidates
        numbered ``fired`` (all when None). ``ids``: the number of atom ids handed out."""
        bit_of = [0] * ids
        for bit, atom in enumerate(facts):
            bit_of[first_seen[atom]] = 1 << bit
        operators = []
        for group in groups:
            pre, pre_neg, add, delete = group.masks(bit_of)
            delete = [d & ~a for d, a in zip(delete, add, strict=True)]
            fields = zip(repeat(group.name), group.args, pre, pre_neg, add, delete)
            operators += map(tuple.__new__, repeat(Operator), fields)  # Operator(*f), at C speed
        if fired is not None:
            operators = [op for i, op in enumerate(operators) if i in fired]
        goal, goal_neg, reason = self._goal({atom: 1 << bit for bit, atom in enumerate(facts)})
        return Task(tuple(Atom(a[0], a[1:]) for a in facts), sum(bit_of[i] for i in init_ids), goal, goal_neg,
                    tuple(operators), reason)

    def _goal(self, bit_of: dict[GroundAtom, int]) -> tuple[int, int, str]:
        """Goal and negated-goal masks, and why the goal can never hold ("" when it may)."""
        reason, goal, goal_neg = "", 0, 0
        for cond in self.problem.goal:
            atom = (cond.atom.predicate, *cond.atom.args)
            if atom[0] == "=" or atom[0] not in self.fluent:
                if not self._static_holds(atom, cond.positive):
                    reason = f"goal {'' if cond.positive else 'not '}{cond.atom} can never hold (static)"
            elif cond.positive and not bit_of.get(atom):
                reason = f"goal {cond.atom} is not reachable from the initial state"
            elif cond.positive:
                goal |= bit_of[atom]
            else:
                goal_neg |= bit_of.get(atom, 0)
        return goal, goal_neg, reason


def _bits(mask: int) -> list[int]:
    """Indices of the set bits of ``mask``, lowest first."""
    out = []
    while mask:
        low = mask & -mask
        out.append(low.bit_length() - 1)
        mask ^= low
    return out


def ground(domain: Domain, problem: Problem) -> Task:
    return _Grounder(domain, problem).ground()
