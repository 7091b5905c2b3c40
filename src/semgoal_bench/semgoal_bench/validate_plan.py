"""Check a plan against a PDDL task by executing it on the lifted actions, without the planner's grounding:
each step's action exists, its arguments are objects of the parameters' types, its precondition holds
(equality included), its conditional and universal effects take place where their conditions hold before it, and the
goal holds at the end, derived predicates read from their rules in each state; where the problem minimises total-cost, it prints the
plan's cost, summed from the actions' increases. A second opinion on ``plan-pddl``'s plans where VAL is not
at hand.

    source tools/env.sh && python -m semgoal_bench.validate_plan DOMAIN PROBLEM PLAN
Exit 0 valid, 1 invalid (the reason on stderr).
"""

from __future__ import annotations

import sys
from itertools import product
from pathlib import Path

from strips_planner.adl import holds
from strips_planner.axioms import derived_atoms
from strips_planner.pddl import Atom, Condition, Domain, Problem, parse_domain, parse_problem


def _holds(condition: Condition, state: set[Atom]) -> bool:
    atom = condition.atom
    value = atom.args[0] == atom.args[1] if atom.predicate == "=" else atom in state
    return value == condition.positive


def _bind(atom: Atom, binding: dict[str, str]) -> Atom:
    return Atom(atom.predicate, tuple(binding.get(a, a) for a in atom.args))


def invalid_step(domain: Domain, problem: Problem, plan: list[tuple[str, ...]]) -> str | None:
    """None for a valid plan, else why not (naming the step)."""
    actions = {action.name: action for action in domain.actions}
    objects = {**domain.constants, **problem.objects}
    state = set(problem.init)

    def of_type(kind: str) -> list[str]:
        return [name for name, own in objects.items() if domain.is_subtype(own, kind)]

    def seen(state: set[Atom]) -> set[Atom]:  # the state with its derived atoms
        return state | derived_atoms(domain.axioms, state, of_type) if domain.axioms else state

    for number, (name, *args) in enumerate(plan, 1):
        before = seen(state)
        action = actions.get(name)
        if action is None or len(args) != len(action.parameters):
            return f"step {number} ({name} {' '.join(args)}): no such action with {len(args)} arguments"
        binding = dict(zip((variable for variable, _ in action.parameters), args, strict=True))
        for arg, (_, kind) in zip(args, action.parameters, strict=True):
            if arg not in objects or not domain.is_subtype(objects[arg], kind):
                return f"step {number}: {arg!r} is not an object of type {kind}"
        unmet = [c for c in action.precondition if not _holds(Condition(_bind(c.atom, binding), c.positive), before)]
        if unmet:
            return f"step {number} ({name} {' '.join(args)}): precondition {unmet[0]} does not hold"
        if action.condition is not None and not holds(action.condition, binding, before.__contains__, of_type):
            return f"step {number} ({name} {' '.join(args)}): its precondition's condition does not hold"
        adds, deletes = {_bind(a, binding) for a in action.add}, {_bind(a, binding) for a in action.delete}
        for effect in action.effects:
            for values in product(*(of_type(kind) for _, kind in effect.variables)):
                bound = dict(binding, **dict(zip((variable for variable, _ in effect.variables), values, strict=True)))
                if effect.condition is None or holds(effect.condition, bound, before.__contains__, of_type):
                    (adds if effect.literal.positive else deletes).add(_bind(effect.literal.atom, bound))
        state = (state - deletes) | adds
    state = seen(state)
    unmet = [c for c in problem.goal if not _holds(c, state)]
    if not unmet and problem.goal_condition is not None and not holds(problem.goal_condition, {}, state.__contains__,
                                                                      of_type):
        return "the goal's condition does not hold at the end"
    return f"the goal {unmet[0]} does not hold at the end" if unmet else None


def plan_cost(domain: Domain, problem: Problem, plan: list[tuple[str, ...]]) -> int:
    """The total-cost of a valid plan: each step's increase, a function term looked up in ``:init``."""
    actions = {action.name: action for action in domain.actions}
    total = 0
    for name, *args in plan:
        action = actions[name]
        amount = action.cost
        if isinstance(amount, Atom):
            amount = problem.values[_bind(amount, dict(zip((v for v, _ in action.parameters), args, strict=True)))]
        total += amount
    return total


def read_plan(text: str) -> list[tuple[str, ...]]:
    """``(move a b)`` lines (comments after ';' ignored) -> name-and-arguments tuples, lower case."""
    steps = []
    for line in text.lower().splitlines():
        line = line.split(";", 1)[0].strip()
        if line:
            steps.append(tuple(line.strip("()").split()))
    return steps


def main(argv: list[str]) -> int:
    domain_path, problem_path, plan_path = map(Path, argv)
    domain = parse_domain(domain_path.read_text())
    problem = parse_problem(problem_path.read_text(), domain)
    plan = read_plan(plan_path.read_text())
    reason = invalid_step(domain, problem, plan)
    if reason:
        print(f"invalid: {reason}", file=sys.stderr)
        return 1
    if problem.minimise_cost:
        print(f"cost {plan_cost(domain, problem, plan)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
