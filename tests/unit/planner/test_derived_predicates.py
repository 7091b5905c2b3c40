"""Derived predicates (``:derived``): read, layered, ground to rules, made again in every state the searches meet (C)
and in Python, planned by every search, and the plans checked by the validator, which reads the lifted rules."""

import pytest

from semgoal_bench.validate_plan import invalid_step, read_plan
from strips_planner.axioms import derived_atoms, layers
from strips_planner.deorder import deorder
from strips_planner.grounding import ground
from strips_planner.heuristics import heuristic
from strips_planner.pddl import Atom, PddlError, PddlUnsupportedError, parse_domain, parse_problem
from strips_planner.planner import solve_task
from strips_planner.search import SEARCHES

# A circuit: a node is lit when it is the source or a closed wire joins it to a lit node (a rule through its own
# predicate), and dark when it is not lit (through a negation, so a layer above).
CIRCUIT = """(define (domain circuit) (:requirements :derived-predicates :negative-preconditions)
  (:predicates (wire ?a ?b) (closed ?a ?b) (source ?n) (lit ?n) (dark ?n))
  (:derived (lit ?n) (or (source ?n) (exists (?m) (and (lit ?m) (closed ?m ?n)))))
  (:derived (dark ?n) (not (lit ?n)))
  (:action close :parameters (?a ?b) :precondition (and (wire ?a ?b) (not (closed ?a ?b))) :effect (closed ?a ?b))
  (:action open :parameters (?a ?b) :precondition (closed ?a ?b) :effect (not (closed ?a ?b))))"""
PROBLEM = """(define (problem p) (:domain circuit) (:objects n1 n2 n3 n4)
  (:init (source n1) (wire n1 n2) (wire n2 n3) (wire n3 n4) (wire n1 n3) (closed n1 n2))
  (:goal (and (lit n4) (dark n2))))"""
SHORTEST = 3
"""Open n1-n2 (n2 goes dark), close n1-n3 and n3-n4."""


def _task():
    domain = parse_domain(CIRCUIT)
    problem = parse_problem(PROBLEM, domain)
    return domain, problem, ground(domain, problem)


def _objects(domain, problem):
    return lambda kind: [name for name, own in problem.objects.items() if domain.is_subtype(own, kind)]


def test_the_rules_are_read_and_layered_above_their_negations() -> None:
    domain = parse_domain(CIRCUIT)
    assert [axiom.predicate for axiom in domain.axioms] == ["lit", "dark"] and domain.derived == {"lit", "dark"}
    assert layers(domain.axioms) == {"lit": 0, "dark": 1}


@pytest.mark.parametrize(("text", "error", "words"), [
    (CIRCUIT.replace(":effect (closed ?a ?b))", ":effect (and (closed ?a ?b) (lit ?b)))"), PddlError,
     "action close changes lit"),
    (CIRCUIT.replace("(:derived (dark ?n) (not (lit ?n)))", "(:derived (dark ?n) (not (lit ?n))) "
                     "(:derived (lit ?n) (dark ?n))"), PddlUnsupportedError, "depend on their own negation"),
])
def test_a_derived_predicate_set_by_an_action_or_defined_through_its_own_negation_is_refused(text, error, words):
    with pytest.raises(error, match=words):
        domain = parse_domain(text)
        ground(domain, parse_problem(PROBLEM, domain))


def test_a_derived_atom_in_the_initial_state_is_refused() -> None:
    domain = parse_domain(CIRCUIT)
    with pytest.raises(PddlError, match="derived atoms follow from the state"):
        parse_problem(PROBLEM.replace("(source n1)", "(source n1) (lit n3)"), domain)


def test_the_initial_state_holds_what_its_rules_make_and_no_more() -> None:
    _, _, task = _task()
    assert {str(atom) for atom in task.atoms(task.init) if atom.predicate in ("lit", "dark")} == {
        "(lit n1)", "(lit n2)", "(dark n3)", "(dark n4)"}


@pytest.mark.parametrize("search", SEARCHES)
def test_every_search_plans_through_the_rules_and_the_validator_accepts_it(search: str) -> None:
    domain, problem, task = _task()
    result = solve_task(task, search)
    plan = read_plan("\n".join(map(str, result.plan)))
    assert invalid_step(domain, problem, plan) is None
    if search in ("bfs", "astar"):
        assert len(plan) == SHORTEST


def test_the_validator_reads_a_derived_goal_that_does_not_hold() -> None:
    domain, problem, _ = _task()
    assert "does not hold at the end" in invalid_step(domain, problem, read_plan("(close n1 n3)\n(close n3 n4)"))


def test_the_searches_c_and_python_and_the_lifted_rules_agree_in_every_state() -> None:
    """Every state of the wires: the C successors, :meth:`Task.successor` and the validator's reading of the lifted
    rules give the same derived atoms."""
    domain, problem, task = _task()
    closed = [i for i, fact in enumerate(task.facts) if fact.predicate == "closed"]
    objects = _objects(domain, problem)
    static = {atom for atom in problem.init if atom.predicate in ("source", "wire")}
    for mask in range(1 << len(closed)):
        state = task.closed(sum(1 << bit for k, bit in enumerate(closed) if mask >> k & 1))
        base = {task.facts[bit] for bit in closed if state >> bit & 1}
        assert set(task.atoms(state & task.derived)) == derived_atoms(domain.axioms, base | static, objects)
        children = {index: child for child, index in task.compiled.successors(state)}
        for index, op in enumerate(task.operators):
            if op.applicable(state):
                assert children[index] == task.successor(state, op)


def test_admissible_heuristics_stay_below_the_optimal_cost_with_rules() -> None:
    _, _, task = _task()
    optimal = len(solve_task(task, "bfs").plan)
    assert heuristic(task, "hmax")(task.init) <= heuristic(task, "lmcut")(task.init) <= optimal
    assert heuristic(task, "hff")(task.init) < float("inf")


def test_a_plan_under_rules_keeps_its_order_when_deordered() -> None:
    _, _, task = _task()
    plan = solve_task(task, "bfs").plan
    assert deorder(task, plan) == [()] + [(step,) for step in range(len(plan) - 1)]
    assert Atom("lit", ("n4",)) in task.facts
