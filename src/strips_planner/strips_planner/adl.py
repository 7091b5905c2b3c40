"""ADL conditions (``or``, ``imply``, ``forall``, ``exists`` in preconditions and goals), compiled away at grounding.

The reader keeps such a condition as a formula in negation normal form: a :class:`~strips_planner.pddl.Condition`
(a literal) or ``("and", parts)``, ``("or", parts)``, ``("forall", variables, body)``, ``("exists", variables,
body)``, with ``variables`` the (name, type) pairs it binds. Grounding binds an operator's parameters, expands the
quantifiers over the problem's objects, decides the static atoms (their predicate no action changes) and equality,
and turns what is left into disjunctive normal form: one operator per disjunct, each a conjunction of literals, so
the searches and heuristics see STRIPS. Conditional and universal effects are the grounder's
(:mod:`strips_planner.grounding`): their ``forall`` expanded over the objects before grounding, their conditions
ground here like a precondition's.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from itertools import product

from strips_planner.pddl import Action, Atom, Condition, PddlUnsupportedError

MAX_DISJUNCTS = 512
"""Most conjunctions one ground condition may become; a condition beyond is refused (the operators would
multiply)."""

Formula = Condition | tuple
Conjunction = frozenset[Condition]


def negated(formula: Formula) -> Formula:
    """``not formula``, pushed down to the literals (De Morgan, and the quantifiers' duality)."""
    if isinstance(formula, Condition):
        return Condition(formula.atom, not formula.positive)
    kind = formula[0]
    if kind in ("and", "or"):
        return ("or" if kind == "and" else "and", tuple(negated(part) for part in formula[1]))
    return ("exists" if kind == "forall" else "forall", formula[1], negated(formula[2]))


def substituted(formula: Formula, mapping: dict[str, str]) -> Formula:
    """``formula`` with its free variables in ``mapping`` replaced (a quantifier's own variables shadow them)."""
    if isinstance(formula, Condition):
        atom = formula.atom
        return formula._replace(atom=Atom(atom.predicate, tuple(mapping.get(arg, arg) for arg in atom.args)))
    if formula[0] in ("and", "or"):
        return (formula[0], tuple(substituted(part, mapping) for part in formula[1]))
    inner = {var: value for var, value in mapping.items() if var not in {v for v, _ in formula[1]}}
    return (formula[0], formula[1], substituted(formula[2], inner))


def lifted_split(action: Action) -> list[Action]:
    """``action`` as one action per way its condition's ``or``s can go, before grounding: each copy's literals join
    its precondition (so grounding's reachability prunes by them), its quantified parts stay its condition. The
    action itself where there is no condition, or where the split would pass :data:`MAX_DISJUNCTS`."""
    if action.condition is None:
        return [action]
    ways = _lifted_ways(action.condition)
    if ways is None:
        return [action]
    copies = []
    for way in ways:
        literals = tuple(part for part in way if isinstance(part, Condition))
        rest = tuple(part for part in way if not isinstance(part, Condition))
        condition = None if not rest else rest[0] if len(rest) == 1 else ("and", rest)
        copies.append(action._replace(precondition=(*action.precondition, *literals), condition=condition))
    return copies


def _lifted_ways(formula: Formula) -> list[tuple[Formula, ...]] | None:
    """The disjunctive normal form over literals and quantified parts (kept whole); None past :data:`MAX_DISJUNCTS`."""
    if isinstance(formula, Condition) or formula[0] in ("forall", "exists"):
        return [(formula,)]
    parts = [_lifted_ways(part) for part in formula[1]]
    if any(part is None for part in parts):
        return None
    if formula[0] == "or":
        ways = [way for part in parts for way in part]
        return ways if len(ways) <= MAX_DISJUNCTS else None
    ways = [()]
    for part in parts:
        if len(ways) * len(part) > MAX_DISJUNCTS:
            return None
        ways = [a + b for a in ways for b in part]
    return ways


def free_variables(formula: Formula) -> frozenset[str]:
    """The variables ``formula`` reads that no quantifier of its own binds."""
    if isinstance(formula, Condition):
        return frozenset(arg for arg in formula.atom.args if arg.startswith("?"))
    if formula[0] in ("and", "or"):
        return frozenset().union(*map(free_variables, formula[1]))
    return free_variables(formula[2]) - {variable for variable, _ in formula[1]}


def holds(formula: Formula, binding: dict[str, str], truth: Callable[[Atom], bool],
          objects_of: Callable[[str], Iterable[str]]) -> bool:
    """Whether ``formula`` holds with ``binding`` where ``truth`` says which atoms do (the plan validator's check);
    ``objects_of``: the objects of a type, for the quantifiers."""
    if isinstance(formula, Condition):
        atom = Atom(formula.atom.predicate, tuple(binding.get(arg, arg) for arg in formula.atom.args))
        value = atom.args[0] == atom.args[1] if atom.predicate == "=" else truth(atom)
        return value == formula.positive
    kind = formula[0]
    if kind in ("and", "or"):
        test = all if kind == "and" else any
        return test(holds(part, binding, truth, objects_of) for part in formula[1])
    bindings = (dict(binding, **dict(zip((v for v, _ in formula[1]), values, strict=True)))
                for values in product(*(tuple(objects_of(kind_)) for _, kind_ in formula[1])))
    return (all if kind == "forall" else any)(holds(formula[2], b, truth, objects_of) for b in bindings)


def disjuncts(formula: Formula, binding: dict[str, str], static: Callable[[Atom], bool | None],
              objects_of: Callable[[str], Iterable[str]]) -> list[Conjunction]:
    """The ground conjunctions of literals one of which must hold for ``formula`` to, with ``binding``: quantifiers
    expanded, static atoms and equality decided (``static``: an atom's truth where it never changes, else None).
    ``[]``: never holds; ``[frozenset()]``: always. Raises :class:`PddlUnsupportedError` beyond
    :data:`MAX_DISJUNCTS`."""
    if isinstance(formula, Condition):
        atom = Atom(formula.atom.predicate, tuple(binding.get(arg, arg) for arg in formula.atom.args))
        value = atom.args[0] == atom.args[1] if atom.predicate == "=" else static(atom)
        if value is None:
            return [frozenset((Condition(atom, formula.positive),))]
        return [frozenset()] if value == formula.positive else []
    kind = formula[0]
    if kind in ("forall", "exists"):
        variables = [v for v, _ in formula[1]]
        parts = (disjuncts(formula[2], dict(binding, **dict(zip(variables, values, strict=True))), static, objects_of)
                 for values in product(*(tuple(objects_of(type_)) for _, type_ in formula[1])))
    else:  # the literals first: cheap, and a static one often decides the whole
        ordered = sorted(formula[1], key=lambda part: not isinstance(part, Condition))
        parts = (disjuncts(part, binding, static, objects_of) for part in ordered)
    # parts are made one at a time, and the first that decides the whole ends it (psr's rules: 4.5 s of grounding)
    if kind in ("or", "exists"):
        found: set[Conjunction] = set()
        for part in parts:
            if frozenset() in part:
                return [frozenset()]
            found.update(part)
        return _smallest(found)
    result: set[Conjunction] = {frozenset()}
    for part in parts:  # and, forall: every choice of one conjunction per part
        if len(result) * len(part) > 8 * MAX_DISJUNCTS:
            raise PddlUnsupportedError(f"?:?: a condition grounds to more than {MAX_DISJUNCTS} alternatives")
        result = {a | b for a in result for b in part if _consistent(a | b)}
        if len(result) > MAX_DISJUNCTS:
            raise PddlUnsupportedError(f"?:?: a condition grounds to more than {MAX_DISJUNCTS} alternatives")
        if not result:
            return []
    return _smallest(result)


def _consistent(conjunction: Conjunction) -> bool:
    return not any(Condition(c.atom, not c.positive) in conjunction for c in conjunction)


def _smallest(conjunctions: set[Conjunction]) -> list[Conjunction]:
    """Without the conjunctions another one's literals are a subset of (they add nothing to the disjunction), in a
    fixed order, so grounding gives the same operators every time."""
    ordered = sorted(conjunctions, key=lambda c: (len(c), sorted(map(str, c))))
    kept: list[Conjunction] = []
    for conjunction in ordered:
        if not any(k <= conjunction for k in kept):
            kept.append(conjunction)
    if len(kept) > MAX_DISJUNCTS:
        raise PddlUnsupportedError(f"?:?: a condition grounds to more than {MAX_DISJUNCTS} alternatives")
    return kept
