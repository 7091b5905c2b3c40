"""Goals no world can satisfy, found from the literals alone, so they are refused where they are typed.

What the predicates' geometry (:mod:`semgoal_core.vocabulary`) rules out:

- one hand holds one block: ``holding(x) & holding(y)``;
- ``above`` climbs (``z`` grows by 3 to 7 cm a step), so it has no cycle: ``above(x,y) & above(y,x)``;
- ``above(x,y)`` puts the centres within 0.05 m in the plane and 0.07 m in height, 0.086 m apart at most,
  inside ``close``'s 0.10 m: ``above(x,y) & not close(x,y)``;
- a literal and its negation, and a block related to itself.
"""

from __future__ import annotations

from collections.abc import Iterable
from itertools import pairwise

from semgoal_core.vocabulary import Literal


class ContradictionError(ValueError):
    """A goal that no world can satisfy; the message names the literals that conflict."""


def contradictions(literals: Iterable[Literal]) -> list[str]:
    """Each conflict among ``literals``, in words that name the literals; empty when they can hold together."""
    literals = list(literals)
    true = [lit for lit in literals if lit.value]
    found = []
    values: dict[tuple[str, frozenset[str] | tuple[str, ...]], Literal] = {}
    for lit in literals:
        key = _atom(lit)
        if key in values and values[key].value != lit.value:
            found.append(f"both {values[key]} and {lit}")
        values.setdefault(key, lit)
        if len(lit.args) == 2 and lit.args[0] == lit.args[1]:
            found.append(f"{lit}: a block cannot be related to itself")
    held = [lit for lit in true if lit.name == "holding"]
    if len({lit.args for lit in held}) > 1:
        found.append(f"{' and '.join(map(str, held))}: one hand holds one block at a time")
    above = [lit for lit in true if lit.name == "above"]
    cycle = _cycle([lit.args for lit in above if lit.args[0] != lit.args[1]])
    if cycle:
        found.append(f"{' and '.join(str(Literal('above', pair)) for pair in cycle)}: a block cannot be above a "
                     "block that is above it")
    for lit in above:
        apart = values.get(("close", frozenset(lit.args)))
        if apart is not None and not apart.value:
            found.append(f"{lit} and {apart}: a block resting on another is close to it")
    return found


def check_consistent(literals: Iterable[Literal]) -> None:
    """Raise :class:`ContradictionError` naming every conflict among ``literals``."""
    found = contradictions(literals)
    if found:
        raise ContradictionError(f"contradictory goal: {'; '.join(found)}")


def _atom(lit: Literal) -> tuple[str, frozenset[str] | tuple[str, ...]]:
    """The atom a literal speaks of (``close`` is symmetric)."""
    return lit.name, frozenset(lit.args) if lit.name == "close" else lit.args


def _cycle(edges: list[tuple[str, ...]]) -> list[tuple[str, str]]:
    """One cycle of the ``above`` relation as its pairs in order, or empty (a depth-first search from the
    pairs in the order given, so the cycle reads as it was typed)."""
    successors: dict[str, list[str]] = {}
    for below_of, on in edges:
        successors.setdefault(below_of, []).append(on)
    done: set[str] = set()

    def visit(block: str, path: list[str]) -> list[str]:
        if block in path:
            return [*path[path.index(block):], block]
        if block in done:
            return []
        for nxt in successors.get(block, []):
            cycle = visit(nxt, [*path, block])
            if cycle:
                return cycle
        done.add(block)
        return []

    for start in successors:
        cycle = visit(start, [])
        if cycle:
            return list(pairwise(cycle))
    return []
