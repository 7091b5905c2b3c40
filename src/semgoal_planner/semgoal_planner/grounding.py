"""Grounding: a parsed domain and problem -> a compact STRIPS task over int bitsets.

1. Objects and fluent predicates (those some action changes) are numbered in sorted name order.
2. Every action's parameters are bound one at a time over the objects of their types, and each static
   precondition (a predicate no action changes, or equality) is checked as soon as its last variable is
   bound, so bindings that can never apply are cut early. Static atoms never enter the state.
3. The C module ``_ground`` instantiates the fluent atoms of every binding, keeps the atoms and operators
   that a relaxed exploration from the initial state reaches (delete effects and negative preconditions
   ignored), numbers the facts in sorted order and builds the operators' masks.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property
from operator import itemgetter
from typing import NamedTuple

from semgoal_planner import _core, _ground
from semgoal_planner.pddl import Action, Atom, Condition, Domain, Problem


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


StaticCheck = tuple[Callable[[tuple], tuple], bool]
"""(a function from a padded binding to the atom, e.g. ("on", 3, 5); whether it must hold)."""


class _Grounder:
    def __init__(self, domain: Domain, problem: Problem) -> None:
        self.domain, self.problem = domain, problem
        fluent = sorted({a.predicate for action in domain.actions for a in (*action.add, *action.delete)})
        self.predicates = tuple(fluent)
        self.predicate_index = {name: i for i, name in enumerate(fluent)}
        self.objects = tuple(sorted(problem.objects))  # the domain's constants among them
        self.index = {name: i for i, name in enumerate(self.objects)}
        self.static = {self._key(a, name=True) for a in problem.init if a.predicate not in self.predicate_index}
        constants = sorted(domain.constants)
        # a binding padded with these holds every name a static atom needs, so one itemgetter builds it
        self.pad_names = (*constants, "=", *domain.predicates)
        self.pad = (*map(self.index.__getitem__, constants), "=", *domain.predicates)
        self.by_type = {kind: [(i,) for i, name in enumerate(self.objects)
                               if domain.is_subtype(problem.objects[name], kind)] for kind in domain.types}

    def _key(self, atom: Atom, name: bool = False) -> tuple:
        """The atom over object indices: (predicate index, *objects), or (predicate name, *objects)."""
        predicate = atom.predicate if name else self.predicate_index[atom.predicate]
        return (predicate, *map(self.index.__getitem__, atom.args))

    def _static_holds(self, atom: tuple, positive: bool) -> bool:
        truth = atom[1] == atom[2] if atom[0] == "=" else atom in self.static
        return truth == positive

    def _action(self, action: Action) -> tuple:
        """The action as :func:`_ground.ground` takes it: its name, parameter count, bindings and the
        templates of its fluent preconditions and effects."""
        params = [v for v, _ in action.parameters]
        position = {v: i for i, v in enumerate(params)}
        slot_of = {**position, **{name: len(params) + i for i, name in enumerate(self.pad_names)}}
        checks: list[list[StaticCheck]] = [[] for _ in range(len(params) + 1)]
        pre: list[tuple[int, ...]] = []
        pre_neg: list[tuple[int, ...]] = []
        for cond in action.precondition:
            atom = cond.atom
            if atom.predicate in self.predicate_index:
                (pre if cond.positive else pre_neg).append(self._template(atom, position))
            else:  # checked once its last parameter is bound
                depth = max((position[a] + 1 for a in atom.args if a in position), default=0)
                checks[depth].append((_getter(slot_of[atom.predicate], *map(slot_of.__getitem__, atom.args)),
                                      cond.positive))
        return (action.name, len(params), self._bindings(action, checks), pre, pre_neg,
                [self._template(a, position) for a in action.add], [self._template(a, position) for a in action.delete])

    def _template(self, atom: Atom, position: dict[str, int]) -> tuple[int, ...]:
        """(predicate index, *arguments): a parameter's position, or ~object for a constant."""
        return (self.predicate_index[atom.predicate],
                *(position[a] if a in position else ~self.index[a] for a in atom.args))

    def _bindings(self, action: Action, checks: list[list[StaticCheck]]) -> list[tuple[int, ...]]:
        """Every binding (object indices) whose static preconditions hold, bound one parameter at a time."""
        params = action.parameters
        partial: list[tuple] = [()]
        for depth in range(len(params) + 1):
            if checks[depth]:
                pad = (0,) * (len(params) - depth) + self.pad
                partial = [b for b in partial
                           if all(self._static_holds(atom(b + pad), positive) for atom, positive in checks[depth])]
            if depth < len(params):
                objects = self.by_type.get(params[depth][1], [])
                partial = [b + o for b in partial for o in objects]
        return partial

    def ground(self) -> Task:
        fluent = [c for c in self.problem.goal if c.atom.predicate in self.predicate_index]
        positive = [c for c in fluent if c.positive]
        facts, init, goal, goal_neg, unreached, operators = _ground.ground(
            self.predicates, self.objects, 1 + max(map(len, self.domain.predicates.values()), default=0),
            [self._key(a) for a in self.problem.init if a.predicate in self.predicate_index],
            [self._key(c.atom) for c in positive], [self._key(c.atom) for c in fluent if not c.positive],
            list(map(self._action, self.domain.actions)), Atom, Operator)
        return Task(tuple(facts), init, goal, goal_neg, tuple(operators), self._unsolvable_reason({positive[i] for i in unreached}))

    def _unsolvable_reason(self, unreached: set[Condition]) -> str:
        """Why the goal can never hold: its first literal that is static and false, or not reachable."""
        for cond in self.problem.goal:
            if cond in unreached:
                return f"goal {cond.atom} is not reachable from the initial state"
            if cond.atom.predicate not in self.predicate_index and not self._static_holds(self._key(cond.atom, name=True),
                                                                                          cond.positive):
                return f"goal {'' if cond.positive else 'not '}{cond.atom} can never hold (static)"
        return ""


def _getter(*slots: int) -> Callable[[tuple], tuple]:
    """A function from a padded binding to the tuple of its items at ``slots``: ``itemgetter``, which
    returns a bare item, not a 1-tuple, when given one slot."""
    if len(slots) == 1:
        return lambda padded: (padded[slots[0]],)
    return itemgetter(*slots)


def ground(domain: Domain, problem: Problem) -> Task:
    return _Grounder(domain, problem).ground()
