"""Derived predicates (``:derived``): their layers, and their atoms in a state.

A derived atom holds where a rule of its predicate makes it hold, from the state's own atoms and the derived atoms
below it, and is false where none does (negation as failure). A rule may use its own predicate (``upstream`` in psr
follows a line device by device), but not through a negation: the predicates are put in layers, each rule's negated
derived predicates in lower layers than its own (a stratification; Thiébaux, Hoffmann & Nebel 2005), and a layer
is made true to its fixed point before the next. A domain with no such layering is refused.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from itertools import product

from strips_planner.adl import holds
from strips_planner.pddl import Atom, Axiom, Condition, PddlUnsupportedError


def _uses(formula, positive: bool = True) -> Iterable[tuple[str, bool]]:
    """(predicate, used positively) of every literal of a formula in negation normal form."""
    if isinstance(formula, Condition):
        yield formula.atom.predicate, formula.positive == positive
    elif formula[0] in ("and", "or"):
        for part in formula[1]:
            yield from _uses(part, positive)
    else:
        yield from _uses(formula[2], positive)


def layers(axioms: Iterable[Axiom]) -> dict[str, int]:
    """Each derived predicate's layer: at least that of every derived predicate its rules use, and above that of
    every one they use negated. :class:`PddlUnsupportedError` where a predicate depends on its own negation."""
    axioms = list(axioms)
    derived = {axiom.predicate for axiom in axioms}
    layer = dict.fromkeys(derived, 0)
    for _ in range(len(derived) + 1):
        changed = False
        for axiom in axioms:
            for predicate, positive in _uses(axiom.condition):
                if predicate in derived:
                    least = layer[predicate] + (0 if positive else 1)
                    if layer[axiom.predicate] < least:
                        layer[axiom.predicate], changed = least, True
        if not changed:
            return layer
    cyclic = sorted(predicate for predicate in derived if layer[predicate] >= len(derived))
    raise PddlUnsupportedError(f"?:?: derived predicates that depend on their own negation (no stratification): "
                               f"{', '.join(cyclic)}")


def derived_atoms(axioms: list[Axiom], state: set[Atom], objects_of: Callable[[str], Iterable[str]]) -> set[Atom]:
    """The derived atoms that hold in ``state`` (its own atoms; any derived ones in it are ignored), rule by rule to
    each layer's fixed point: the plan validator's reading, on the lifted rules."""
    by_layer = layers(axioms)
    derived = set(by_layer)
    true = {atom for atom in state if atom.predicate not in derived}
    for level in sorted(set(by_layer.values())):
        rules = [axiom for axiom in axioms if by_layer[axiom.predicate] == level]
        changed = True
        while changed:
            changed = False
            for axiom in rules:
                variables = [variable for variable, _ in axiom.parameters]
                for values in product(*(tuple(objects_of(kind)) for _, kind in axiom.parameters)):
                    atom = Atom(axiom.predicate, values)
                    if atom not in true and holds(axiom.condition, dict(zip(variables, values, strict=True)),
                                                  true.__contains__, objects_of):
                        true.add(atom)
                        changed = True
    return {atom for atom in true if atom.predicate in derived}
