"""Grounding: a parsed domain and problem -> a compact STRIPS task over int bitsets.

1. Objects are numbered in sorted name order, and predicates too, the fluent ones (those some action changes)
   first; every action's atoms become integer templates once, for both C passes.
2. A relaxed exploration (the C module ``_explore``) finds every action's bindings whose positive
   preconditions, static ones included, can ever hold together, by joining them over the atoms reached from
   the initial state; no binding is enumerated that a precondition rules out. Static atoms never enter the state.
3. The C module ``_ground`` instantiates the fluent atoms of those bindings, numbers the facts in sorted order,
   builds the operators' masks and finds goal atoms no operator reaches.

Conditional and universal effects: a ``forall`` in an effect is expanded over the problem's objects before
grounding, and both passes take every conditional add as an add (reachability relaxed further: a condition may
never hold); each ground operator then keeps its own adds, and each conditional effect becomes masks of its
condition (one per way an ADL condition can hold), adds and deletes, read in the state the operator applies to.

Derived predicates: every derived atom the types allow counts as reached, and each rule becomes one ground rule per
way its condition can hold; a task's states hold the derived facts its rules make (:meth:`Task.closed`).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable
from functools import cached_property
from itertools import groupby, product
from operator import itemgetter
from typing import NamedTuple

from strips_planner import _core, _explore, _ground, adl, axioms
from strips_planner.collector import collector_paused
from strips_planner.pddl import ROOT_TYPE, Action, Atom, Condition, Domain, Effect, PddlError, Problem


class Operator(NamedTuple):
    """A ground action: precondition, add and delete sets as bit masks over the task's facts."""

    name: str
    args: tuple[str, ...]
    pre: int
    pre_neg: int
    add: int
    delete: int
    effects: tuple[tuple[int, int, int, int], ...] = ()
    """Conditional effects: each (pre, pre_neg, add, delete), its adds and deletes made where its condition holds in
    the state the operator applies to."""

    def applicable(self, state: int) -> bool:
        return state & self.pre == self.pre and not state & self.pre_neg

    def apply(self, state: int) -> int:
        """The state after: every condition read before, the deletes made before the adds (an atom both added and
        deleted is true after)."""
        add, delete = self.add, self.delete
        for pre, pre_neg, more, less in self.effects:
            if state & pre == pre and not state & pre_neg:
                add, delete = add | more, delete | less
        return (state & ~delete) | add

    def __str__(self) -> str:
        return f"({' '.join((self.name, *self.args))})"


class Task:
    """A grounded task: facts, initial state, goal and operators over int bitsets."""

    def __init__(self, facts: tuple[Atom, ...], init: int, goal: int, goal_neg: int, operators: tuple[Operator, ...],
                 unsolvable_reason: str = "", costs: tuple[int, ...] | None = None,
                 axioms: tuple[tuple[int, int, int, int], ...] = (), derived: int = 0) -> None:
        self.facts = facts
        """Bit i of a state is ``facts[i]``."""
        self.init, self.goal, self.goal_neg, self.operators = init, goal, goal_neg, operators
        self.unsolvable_reason = unsolvable_reason
        """Set when grounding alone proves the goal unreachable (a static or unreachable goal atom)."""
        self.costs = costs
        """Each operator's cost where the problem minimises total-cost; None: every action costs 1."""
        self.axioms, self.derived = axioms, derived
        """The derived predicates' ground rules, each (layer, head mask, pos, neg), layer by layer, and the mask of the
        derived facts: a state holds them as its rules make them (:meth:`closed`)."""

    def closed(self, state: int) -> int:
        """``state`` with its derived facts as the rules make them, layer by layer to each one's fixed point."""
        if not self.axioms:
            return state
        state &= ~self.derived
        for _, layer in groupby(self.axioms, key=itemgetter(0)):
            rules = list(layer)
            changed = True
            while changed:
                changed = False
                for _, head, pos, neg in rules:
                    if not state & head and state & pos == pos and not state & neg:
                        state, changed = state | head, True
        return state

    def successor(self, state: int, operator: Operator) -> int:
        """The state after ``operator``, its derived facts made again."""
        return self.closed(operator.apply(state))

    def cost(self, plan: list[int]) -> int:
        """The cost of a plan given as operator indices (its length where actions cost 1)."""
        return sum(self.costs[i] for i in plan) if self.costs is not None else len(plan)

    def goal_reached(self, state: int) -> bool:
        return state & self.goal == self.goal and not state & self.goal_neg

    def atoms(self, state: int) -> list[Atom]:
        return [fact for i, fact in enumerate(self.facts) if state >> i & 1]

    @cached_property
    def conditional_effects(self) -> int:
        """How many conditional effects the operators have (LM-cut takes none)."""
        return sum(len(op.effects) for op in self.operators)

    @cached_property
    def compiled(self) -> _core.Task:
        """This task for the C searches and heuristics (built on first use)."""
        return _core.Task(len(self.facts), self.operators, self.init, self.goal, self.goal_neg, self.costs, self.axioms,
                          self.derived)

    @cached_property
    def compiled_unit_cost(self) -> _core.Task:
        """This task with every action costing 1, which the greedy searches are guided by (:mod:`.search`)."""
        if self.costs is None:
            return self.compiled
        return _core.Task(len(self.facts), self.operators, self.init, self.goal, self.goal_neg, None, self.axioms,
                          self.derived)


GOAL_REACHED = "#goal"
"""The fact, and the name of the operators that make it, standing for a goal with several ways to it ('#' is in no
PDDL name): the searches reach it, and plans leave those operators out (:func:`strips_planner.search.search`)."""


def _masks(literals: Iterable[Condition], index: dict[Atom, int]) -> tuple[int, int] | None:
    """(positive, negative) bit masks of ground ``literals`` over the facts ``index`` numbers; None where a positive
    one is no fact (never reached, so never true) or the two overlap."""
    pre = pre_neg = 0
    for literal in literals:
        bit = index.get(literal.atom)
        if bit is None:
            if literal.positive:
                return None
            continue
        if literal.positive:
            pre |= 1 << bit
        else:
            pre_neg |= 1 << bit
    return None if pre & pre_neg else (pre, pre_neg)


class _Grounder:
    """Numbers predicates, objects and every action's atoms once. Fluent predicates come first, so a fluent
    atom's key is the same for the exploration, which reads every predicate, and for ``_ground``, which reads
    only the fluent ones."""

    def __init__(self, domain: Domain, problem: Problem) -> None:
        self.domain, self.problem = domain, problem
        self.objects = tuple(sorted(problem.objects))  # the domain's constants among them
        self.index = {name: i for i, name in enumerate(self.objects)}
        self._types: dict[str, tuple[int, ...] | None] = {}
        self._read_by: dict[int, tuple[str, ...]] = {}  # an effect -> the variables its condition reads
        self._masks_by: dict[tuple, list[tuple[int, int] | None]] = {}  # (effect, values read) -> its ways' masks
        split = [copy for action in domain.actions for copy in adl.lifted_split(action)]
        fluent = sorted({a.predicate for action in split
                         for a in (*action.add, *action.delete, *(e.literal.atom for e in action.effects))}
                        | domain.derived)
        mentioned = {a.predicate for a in problem.init} | {c.atom.predicate for action in split
                                                           for c in action.precondition}
        static = sorted((set(domain.predicates) | mentioned) - set(fluent) - {"="})
        self.predicates = tuple(fluent)
        self.number = {name: i for i, name in enumerate((*fluent, *static))}
        self.init = [self._key(a) for a in problem.init]
        self.actions = [self._universal_expanded(action) for action in split]
        """The domain's actions, one per way an ADL condition's ``or``s go (:func:`adl.lifted_split`), their effects'
        ``forall``s expanded."""
        copies = Counter(action.name for action in self.actions)
        self.conditional = {f"{a.name}#{i}": a for i, a in enumerate(self.actions)
                            if a.condition is not None or a.effects or copies[a.name] > 1}
        """The actions whose operators :meth:`_with_conditions` finishes, under a name of their own while grounded
        ('#' is no PDDL name's)."""
        self.derived_atoms = [Atom(p, args) for p in sorted(domain.derived)
                              for args in product(*(self._objects_of_type(k) for k in domain.predicates[p]))]
        """Every derived atom the types allow: reached, for grounding, as any of them may come to hold."""

    def is_fluent(self, predicate: str) -> bool:
        return self.number.get(predicate, len(self.predicates)) < len(self.predicates)

    def _key(self, atom: Atom) -> tuple[int, ...]:
        """The atom over indices: (predicate number, *object indices)."""
        return (self.number[atom.predicate], *map(self.index.__getitem__, atom.args))

    def _objects_of(self, kind: str) -> tuple[int, ...] | None:
        """The objects of a type, or None when every object is one (nothing to check)."""
        if kind == ROOT_TYPE:
            return None
        if kind not in self._types:
            members = tuple(i for i, name in enumerate(self.objects)
                            if self.domain.is_subtype(self.problem.objects[name], kind))
            self._types[kind] = None if len(members) == len(self.objects) else members
        return self._types[kind]

    def _templates(self, action: Action) -> tuple[tuple, tuple]:
        """The action as :func:`_explore.explore` reads it (per parameter the objects it may take, its positive
        preconditions, its checks: equalities and negative static preconditions, and its add effects) and as
        :func:`_ground.ground` takes it (its fluent preconditions and effects), each atom a template:
        (predicate number, *arguments), an argument being a parameter's position or ~object for a constant."""
        position = {v: i for i, (v, _) in enumerate(action.parameters)}
        adds = (*action.add, *(e.literal.atom for e in action.effects if e.literal.positive))
        joined, filters, pre, pre_neg, add, delete = _ground.templates(
            tuple(action.precondition), adds, tuple(action.delete), position, self.index, self.number,
            len(self.predicates))
        schema = (tuple(self._objects_of(kind) for _, kind in action.parameters), joined, filters, add)
        return schema, (action.name, len(position), pre, pre_neg, add, delete)

    def ground(self) -> Task:
        own = {id(action): name for name, action in self.conditional.items()}
        templates = [(schema, (own.get(id(action), action.name), *rest))
                     for action in self.actions for schema, (_, *rest) in [self._templates(action)]]
        arity = max((len(key) - 1 for key in self.init), default=0)
        width = 1 + max(arity, *map(len, self.domain.predicates.values()), 0)
        derived_keys = [self._key(atom) for atom in self.derived_atoms]
        bindings = _explore.explore(len(self.number), len(self.objects), width, self.init + derived_keys,
                                    [schema for schema, _ in templates])
        goal, never, options = self.problem.goal, "", []
        if self.problem.goal_condition is not None:
            options = adl.disjuncts(self.problem.goal_condition, {}, self._static_truth, self._objects_of_type)
            if not options:
                never = "the goal's condition can never hold: the static facts rule out every way to it"
            elif len(options) == 1:
                goal, options = (*goal, *sorted(options[0])), []
        fluent = [c for c in goal if self.is_fluent(c.atom.predicate)]
        positive = [c for c in fluent if c.positive]
        nfluent = len(self.predicates)
        facts, init, goal_mask, goal_neg, unreached, operators = _ground.ground(
            self.predicates, self.objects, width, [key for key in self.init if key[0] < nfluent] + derived_keys,
            [self._key(c.atom) for c in positive], [self._key(c.atom) for c in fluent if not c.positive],
            [(name, nparams, found, *atoms) for (_, (name, nparams, *atoms)), found in zip(templates, bindings,
                                                                                           strict=True)],
            Atom, Operator)
        if self.conditional:
            operators = self._with_conditions(operators, facts)
        if len(options) > 1:  # the goal's ways, each an operator that only marks the goal reached
            facts, goal_mask = [*facts, Atom(GOAL_REACHED, ())], goal_mask | 1 << len(facts)
            index = {fact: i for i, fact in enumerate(facts)}
            ways = [Operator(GOAL_REACHED, (), *masks, 1 << (len(facts) - 1), 0)
                    for option in options if (masks := _masks(option, index)) is not None]
            never = never or ("" if ways else "no way to the goal's condition is reachable from the initial state")
            operators += ways
        costs = self._costs(operators) if self.problem.minimise_cost else None
        rules, derived = self._axioms(facts) if self.domain.axioms else ((), 0)
        task = Task(tuple(facts), init, goal_mask, goal_neg, tuple(operators),
                    never or self._unsolvable_reason({positive[i] for i in unreached}, goal), costs, rules, derived)
        task.init = task.closed(init)  # every derived atom was in it, for reachability: now those its rules make
        return task

    def _axioms(self, facts: list[Atom]) -> tuple[tuple[tuple[int, int, int, int], ...], int]:
        """The derived predicates' ground rules, each (layer, head mask, pos, neg): one per way its condition can hold
        (as an ADL precondition's), layer by layer (:func:`axioms.layers`); and the mask of the derived facts."""
        index = {fact: i for i, fact in enumerate(facts)}
        layer = axioms.layers(self.domain.axioms)
        derived = sum(1 << index[atom] for atom in self.derived_atoms)
        rules = []
        for axiom in self.domain.axioms:
            variables = [variable for variable, _ in axiom.parameters]
            for values in product(*(self._objects_of_type(kind) for _, kind in axiom.parameters)):
                head = 1 << index[Atom(axiom.predicate, values)]
                binding = dict(zip(variables, values, strict=True))
                for way in adl.disjuncts(axiom.condition, binding, self._static_truth, self._objects_of_type):
                    masks = _masks(way, index)
                    if masks is not None:
                        rules.append((layer[axiom.predicate], head, *masks))
        return tuple(sorted(rules, key=lambda rule: rule[0])), derived

    # -- ADL conditions (strips_planner.adl) ------------------------------------------------------------
    def _static_truth(self, atom: Atom) -> bool | None:
        """An atom's truth where its predicate never changes (from ``:init``), else None."""
        if self.is_fluent(atom.predicate):
            return None
        return atom.predicate in self.number and self._key(atom) in self._static_init

    @cached_property
    def _static_init(self) -> set[tuple[int, ...]]:
        return set(self.init)

    def _objects_of_type(self, kind: str) -> tuple[str, ...]:
        members = self._objects_of(kind)
        return self.objects if members is None else tuple(self.objects[i] for i in members)

    def _universal_expanded(self, action: Action) -> Action:
        """``action`` with each effect under a ``forall`` once per binding of its variables to the problem's objects;
        one under no ``when`` joins the action's own adds or deletes."""
        if not action.effects:
            return action
        add, delete, effects = list(action.add), list(action.delete), []
        for effect in action.effects:
            variables = [variable for variable, _ in effect.variables]
            for values in product(*(self._objects_of_type(kind) for _, kind in effect.variables)):
                mapping = dict(zip(variables, values, strict=True))
                literal = adl.substituted(effect.literal, mapping)
                if effect.condition is None:
                    (add if literal.positive else delete).append(literal.atom)
                elif not self._never(condition := adl.substituted(effect.condition, mapping)):
                    effects.append(Effect((), condition, literal))
        return action._replace(add=tuple(add), delete=tuple(delete), effects=tuple(effects))

    def _never(self, condition: adl.Formula) -> bool:
        """Whether an effect's condition, its ``forall`` bound, is false whatever the action's parameters: one of its
        conjuncts a static or equality literal over objects only that does not hold (settlers: most pairs of levels a
        ``forall`` takes are no step the ``DIFF-STONE`` facts allow)."""
        parts = condition[1] if isinstance(condition, tuple) and condition[0] == "and" else (condition,)
        for part in parts:
            if isinstance(part, Condition) and not any(arg.startswith("?") for arg in part.atom.args):
                atom = part.atom
                truth = atom.args[0] == atom.args[1] if atom.predicate == "=" else self._static_truth(atom)
                if truth is not None and truth != part.positive:
                    return True
        return False

    def _with_effects(self, operator: Operator, action: Action, binding: dict[str, str], index: dict[Atom, int]
                      ) -> Operator:
        """``operator`` with its action's own adds and deletes only (both grounding passes took the conditional adds
        as adds, and left out the deletes they add) and its conditional effects: one per way each effect's
        condition can hold, less what the precondition already asks, effects of the same condition merged; one
        whose condition the precondition implies is the operator's own, one whose condition contradicts it is
        dropped."""
        add = delete = 0
        merged: dict[tuple[int, int], tuple[int, int]] = {}
        for atom in action.add:
            add |= 1 << index[_bound(atom, binding)]
        for atom in action.delete:
            bit = index.get(_bound(atom, binding))
            delete |= 0 if bit is None else 1 << bit
        for effect in action.effects:
            bit = index.get(_bound(effect.literal.atom, binding))
            if bit is None:  # the delete of an atom that is never true
                continue
            for masks in self._condition_masks(effect, binding, index):
                if masks is None or masks[0] & operator.pre_neg or masks[1] & operator.pre:
                    continue
                condition = (masks[0] & ~operator.pre, masks[1] & ~operator.pre_neg)
                if condition == (0, 0):
                    add, delete = (add | 1 << bit, delete) if effect.literal.positive else (add, delete | 1 << bit)
                    continue
                adds, deletes = merged.get(condition, (0, 0))
                merged[condition] = (adds | 1 << bit, deletes) if effect.literal.positive else (adds, deletes | 1 << bit)
        return operator._replace(add=add, delete=delete & ~add,
                                 effects=tuple((*condition, *masks) for condition, masks in merged.items()))

    def _condition_masks(self, effect: Effect, binding: dict[str, str], index: dict[Atom, int]
                         ) -> list[tuple[int, int] | None]:
        """The masks of each way ``effect``'s condition can hold with ``binding`` (None for a way through a fact never
        reached); a compound one worked out once per effect and values of the variables it reads, which the operators of
        an action share."""
        key = None
        if not isinstance(effect.condition, Condition):  # one literal is cheaper to ground than to look up
            read = self._read_by.get(id(effect))
            if read is None:
                read = self._read_by[id(effect)] = tuple(sorted(adl.free_variables(effect.condition)))
            key = (id(effect), *(binding.get(variable, variable) for variable in read))
        masks = self._masks_by.get(key)
        if masks is None:
            ways = adl.disjuncts(effect.condition, binding, self._static_truth, self._objects_of_type)
            masks = [_masks(way, index) for way in ways]
            if key is not None:
                self._masks_by[key] = masks
        return masks

    def _with_conditions(self, operators: list[Operator], facts: list[Atom]) -> list[Operator]:
        """Each operator of an action with an ADL condition as one operator per way its condition can hold (its
        disjuncts over fluent literals), none where it never can, under its action's name, with its conditional
        effects (:meth:`_with_effects`); the others as they are."""
        index = {fact: i for i, fact in enumerate(facts)}
        result = []
        for operator in operators:
            action = self.conditional.get(operator.name)
            if action is None:
                result.append(operator)
                continue
            operator = operator._replace(name=action.name)
            binding = dict(zip((variable for variable, _ in action.parameters), operator.args, strict=True))
            if action.effects:
                operator = self._with_effects(operator, action, binding, index)
            if action.condition is None:
                result.append(operator)
                continue
            for conjunction in adl.disjuncts(action.condition, binding, self._static_truth, self._objects_of_type):
                masks = _masks(conjunction, index)
                if masks is not None and not (operator.pre | masks[0]) & (operator.pre_neg | masks[1]):
                    result.append(operator._replace(pre=operator.pre | masks[0], pre_neg=operator.pre_neg | masks[1]))
        return result

    def _costs(self, operators: list[Operator]) -> tuple[int, ...]:
        """Each operator's cost: its action's amount, a function term's value looked up in ``:init``."""
        actions = {action.name: action for action in self.domain.actions}
        costs = []
        for operator in operators:
            if operator.name == GOAL_REACHED:
                costs.append(0)
                continue
            action = actions[operator.name]
            amount = action.cost
            if isinstance(amount, Atom):
                binding = dict(zip((variable for variable, _ in action.parameters), operator.args, strict=True))
                term = Atom(amount.predicate, tuple(binding.get(arg, arg) for arg in amount.args))
                if term not in self.problem.values:
                    raise PddlError(f"?:?: {operator} costs {term}, which :init gives no value")
                amount = self.problem.values[term]
            costs.append(amount)
        return tuple(costs)

    def _unsolvable_reason(self, unreached: set[Condition], goal: tuple[Condition, ...]) -> str:
        """Why the goal can never hold: its first literal that is static and false, or not reachable."""
        for cond in goal:
            if cond in unreached:
                return f"goal {cond.atom} is not reachable from the initial state"
            atom = cond.atom
            if not self.is_fluent(atom.predicate):
                holds = atom.args[0] == atom.args[1] if atom.predicate == "=" else self._key(atom) in self._static_init
                if holds != cond.positive:
                    return f"goal {'' if cond.positive else 'not '}{atom} can never hold (static)"
        return ""


def _bound(atom: Atom, binding: dict[str, str]) -> Atom:
    return Atom(atom.predicate, tuple(binding.get(arg, arg) for arg in atom.args))


@collector_paused
def ground(domain: Domain, problem: Problem) -> Task:
    return _Grounder(domain, problem).ground()
