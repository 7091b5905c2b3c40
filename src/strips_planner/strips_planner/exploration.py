"""Relaxed exploration: the bindings of each action whose positive preconditions can ever hold together.

Starting from the initial atoms (fluent and static), every newly reached atom seeds each precondition it
matches, and the action's other positive preconditions are joined against the atoms reached so far (the
semi-naive evaluation of Datalog-style grounders). A binding is thus only ever built from atoms that hold in
the relaxed task (delete effects and negative fluent preconditions ignored), never by enumerating object
combinations first. Types, equality and negative static preconditions are checked as soon as their variables
are bound; a parameter that no positive precondition mentions ranges over the objects of its type.

Arguments are object indices; a template argument ``a >= 0`` is the action's parameter ``a`` and ``~a`` the
object ``a`` (a constant), as :mod:`strips_planner.grounding` writes them.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable, Iterable
from operator import itemgetter

Row = tuple[int, ...]
Template = tuple[int, ...]
Filter = Callable[[list], bool]


class Relation:
    """The reached atoms of one predicate, each with the number of its arrival, and hash indices on the
    argument positions joins look up (their lists in arrival order)."""

    def __init__(self) -> None:
        self.rows: dict[Row, int] = {}
        self._indices: dict[tuple[int, ...], tuple[Callable[[Row], Row], dict[Row, list[Row]]]] = {}

    def add(self, row: Row, arrival: int) -> bool:
        if row in self.rows:
            return False
        self.rows[row] = arrival
        for key, index in self._indices.values():
            index.setdefault(key(row), []).append(row)
        return True

    def index(self, positions: tuple[int, ...]) -> dict[Row, list[Row]]:
        found = self._indices.get(positions)
        if found is None:
            key = _picker(positions)
            index: dict[Row, list[Row]] = {}
            for row in self.rows:
                index.setdefault(key(row), []).append(row)
            found = self._indices[positions] = (key, index)
        return found[1]


def _picker(positions: tuple[int, ...]) -> Callable[[Row], Row]:
    """The tuple of a row's entries at ``positions`` (an index key), as one C call where it can be."""
    if len(positions) > 1:
        return itemgetter(*positions)
    if positions:
        (position,) = positions
        return lambda row: (row[position],)
    return lambda _: ()


class Schema:
    """An action as the exploration needs it."""

    __slots__ = ("adds", "filters", "joined", "name", "types")

    def __init__(self, name: str, types: tuple[frozenset[int] | None, ...], joined: tuple[tuple[str, Template], ...],
                 filters: tuple[tuple[frozenset[int], Filter], ...] = (), adds: tuple[tuple[str, Template], ...] = ()) -> None:
        self.name = name
        self.types = types
        """Per parameter, the objects it may take (None: any)."""
        self.joined = joined
        """Positive preconditions, fluent or static: (predicate, arguments)."""
        self.filters = filters
        """(parameters a check reads, the check on the binding so far): equality and negative static atoms."""
        self.adds = adds


class _Step:
    """One step of a join: look a precondition's atoms up by its bound arguments, or (``relation`` None) range
    a parameter that no positive precondition mentions over its type (an index holding its objects under ``()``)."""

    __slots__ = ("binds", "earlier", "filters", "index", "key", "relation", "same")

    def __init__(self, relation: Relation | None, index: dict[Row, list[Row]], key: Template,
                 binds: tuple[tuple[int, int], ...], same: tuple[tuple[int, int], ...], earlier: int,
                 filters: list[Filter]) -> None:
        self.relation, self.index = relation, index
        self.key = key
        """The bound arguments (parameters or ~constants) whose objects are the index's key."""
        self.binds = binds
        """(row position, parameter) for parameters this step binds first."""
        self.same = same
        """(row position, row position) that must agree (a parameter repeated in one atom)."""
        self.earlier = earlier
        """1: only atoms that arrived before the seed; 0: the seed itself too (a precondition listed before it)."""
        self.filters = filters


class _Seeding:
    """How an arriving atom seeds one precondition of one schema."""

    __slots__ = ("args", "filters", "schema", "steps")

    def __init__(self, schema: int, args: Template, filters: list[Filter], steps: list[_Step]) -> None:
        self.schema, self.args, self.steps = schema, args, steps
        self.filters = filters
        """Checks whose parameters the seed alone binds."""


class Exploration:
    def __init__(self, schemas: Iterable[Schema], init: Iterable[tuple[str, Row]], object_count: int) -> None:
        self.schemas = list(schemas)
        self.everything = tuple((obj,) for obj in range(object_count))
        """What a parameter without a type to check ranges over."""
        self.relations: dict[str, Relation] = {}
        self.bindings: list[set[Row]] = [set() for _ in self.schemas]
        self.queue: deque[tuple[Relation, Row]] = deque()
        self.arrivals = 0
        for predicate, row in init:
            self._reach(self.relation(predicate), row)

    def relation(self, predicate: str) -> Relation:
        relation = self.relations.get(predicate)
        if relation is None:
            relation = self.relations[predicate] = Relation()
        return relation

    def run(self) -> list[list[Row]]:
        """Every reachable binding of every schema, sorted (the order a nested enumeration would give)."""
        seedings: dict[Relation, list[_Seeding]] = {}
        for s, schema in enumerate(self.schemas):
            if not schema.joined:
                filters, steps = self._plan(schema, frozenset(), -1)
                if all(check([None] * len(schema.types)) for check in filters):
                    self._join(s, [None] * len(schema.types), steps, 0, self.arrivals)
            for i, (predicate, args) in enumerate(schema.joined):
                filters, steps = self._plan(schema, frozenset(a for a in args if a >= 0), i)
                seedings.setdefault(self.relation(predicate), []).append(_Seeding(s, args, filters, steps))
        while self.queue:
            relation, row = self.queue.popleft()
            arrival = relation.rows[row]
            for seeding in seedings.get(relation, ()):
                values = self._seed(self.schemas[seeding.schema], seeding.args, row)
                if values is not None and all(check(values) for check in seeding.filters):
                    self._join(seeding.schema, values, seeding.steps, 0, arrival)
        return [sorted(found) for found in self.bindings]

    def _reach(self, relation: Relation, row: Row) -> None:
        if relation.add(row, self.arrivals):
            self.arrivals += 1
            self.queue.append((relation, row))

    @staticmethod
    def _seed(schema: Schema, args: Template, row: Row) -> list | None:
        """The binding an atom gives a precondition it matches, or None."""
        values: list = [None] * len(schema.types)
        for arg, obj in zip(args, row, strict=True):
            if arg < 0:
                if ~arg != obj:
                    return None
            elif values[arg] is None:
                allowed = schema.types[arg]
                if allowed is not None and obj not in allowed:
                    return None
                values[arg] = obj
            elif values[arg] != obj:
                return None
        return values

    def _plan(self, schema: Schema, bound: frozenset[int], seed: int) -> tuple[list[Filter], list[_Step]]:
        """The checks a seed of precondition ``seed`` allows at once, and the join after it: preconditions with
        the most bound arguments first, then the parameters no precondition mentions.

        A binding is found once, by the last of its atoms to arrive: preconditions listed before the seed may
        use atoms up to the seed's arrival, those after it only earlier ones."""
        bound = set(bound)
        pending = list(schema.filters)
        now = self._take(pending, bound)
        todo = [(i, c) for i, c in enumerate(schema.joined) if i != seed]
        steps: list[_Step] = []
        while todo:
            i, (predicate, args) = max(todo, key=lambda c: (sum(a < 0 or a in bound for a in c[1][1]), -len(c[1][1])))
            todo.remove((i, (predicate, args)))
            positions = tuple(p for p, a in enumerate(args) if a < 0 or a in bound)
            first: dict[int, int] = {}
            same = []
            for p, a in enumerate(args):
                if a >= 0 and a not in bound:
                    if a in first:
                        same.append((p, first[a]))
                    else:
                        first[a] = p
            relation = self.relation(predicate)
            bound |= first.keys()
            steps.append(_Step(relation, relation.index(positions), tuple(args[p] for p in positions),
                               tuple((p, a) for a, p in first.items()), tuple(same), int(i > seed),
                               self._take(pending, bound)))
        for a in range(len(schema.types)):
            if a not in bound:
                bound.add(a)
                allowed = schema.types[a]
                choices = self.everything if allowed is None else tuple((obj,) for obj in sorted(allowed))
                steps.append(_Step(None, {(): choices}, (), ((0, a),), (), 0, self._take(pending, bound)))
        return now, steps

    @staticmethod
    def _take(pending: list, bound: set[int]) -> list[Filter]:
        """The checks whose parameters are all bound now, removed from ``pending``."""
        ready = [check for check in pending if check[0] <= bound]
        for check in ready:
            pending.remove(check)
        return [check for _, check in ready]

    def _join(self, s: int, values: list, steps: list[_Step], k: int, seed_arrival: int) -> None:
        if k == len(steps):
            self._found(s, tuple(values))
            return
        step = steps[k]
        types = self.schemas[s].types
        rows = step.index.get(tuple(values[a] if a >= 0 else ~a for a in step.key), ())
        arrivals, last = (None, 0) if step.relation is None else (step.relation.rows, seed_arrival - step.earlier)
        same, binds, filters, last_step = step.same, step.binds, step.filters, k + 1 == len(steps)
        for row in rows:
            if arrivals is not None and arrivals[row] > last:
                break  # the index lists atoms in arrival order
            if same and any(row[p] != row[q] for p, q in same):
                continue
            for p, a in binds:
                allowed = types[a]
                if allowed is not None and row[p] not in allowed:
                    break
                values[a] = row[p]
            else:
                if filters and not all(check(values) for check in filters):
                    continue
                if last_step:
                    self._found(s, tuple(values))
                else:
                    self._join(s, values, steps, k + 1, seed_arrival)
        for _, a in step.binds:
            values[a] = None

    def _found(self, s: int, binding: Row) -> None:
        found = self.bindings[s]
        if binding in found:
            return
        found.add(binding)
        for predicate, args in self.schemas[s].adds:
            self._reach(self.relation(predicate), tuple(binding[a] if a >= 0 else ~a for a in args))
