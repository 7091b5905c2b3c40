"""Conditional and universal effects (``when``, ``forall`` in an effect): read, ground with reachability through
them, applied in C and in Python as PDDL says (every condition read before the action, deletes before adds), planned
by every search, and the plans checked by the validator, which applies the lifted effects on its own."""

import random
from pathlib import Path

import pytest
from random_conditions import evaluate_text, random_condition

from semgoal_bench.validate_plan import invalid_step, read_plan
from strips_planner.deorder import deorder
from strips_planner.grounding import ground
from strips_planner.pddl import Atom, Condition, Effect, PddlUnsupportedError, parse_domain, parse_problem, parse_sexpr
from strips_planner.planner import solve_pddl, solve_task
from strips_planner.search import SEARCHES

FIXTURES = Path(__file__).parent / "fixtures"
BRIEFCASE = (FIXTURES / "briefcase-domain.pddl").read_text()
BRIEFCASE_3 = (FIXTURES / "briefcase-3.pddl").read_text()
SHORTEST = 8
"""Put p1 and p2 in, go to the office, put p3 in and take p1 out, go to the shop, take p2 out, go home."""


def _task(domain_text: str, problem_text: str):
    domain = parse_domain(domain_text)
    problem = parse_problem(problem_text, domain)
    return domain, problem, ground(domain, problem)


def test_a_universal_conditional_effect_is_read_with_its_variables_and_condition() -> None:
    move = parse_domain(BRIEFCASE).actions[0]
    assert move.add == (Atom("is-at", ("?l",)),) and move.delete == (Atom("is-at", ("?m",)),)
    inside = Condition(Atom("in", ("?x",)))
    assert move.effects == (Effect((("?x", "portable"),), inside, Condition(Atom("at", ("?x", "?l")))),
                            Effect((("?x", "portable"),), inside, Condition(Atom("at", ("?x", "?m")), False)))


@pytest.mark.parametrize("search", SEARCHES)
def test_every_search_plans_the_briefcase_and_the_validator_accepts_it(search: str) -> None:
    domain, problem, _ = _task(BRIEFCASE, BRIEFCASE_3)
    result = solve_pddl(BRIEFCASE, BRIEFCASE_3, search)
    plan = read_plan("\n".join(map(str, result.plan)))
    assert invalid_step(domain, problem, plan) is None
    if search in ("bfs", "astar"):  # A*'s default with conditional effects is hmax: admissible
        assert len(plan) == SHORTEST


def test_the_validator_refuses_a_plan_that_counts_on_an_effect_whose_condition_does_not_hold() -> None:
    domain, problem, _ = _task(BRIEFCASE, BRIEFCASE_3)
    plan = read_plan("(put-in p1 home)\n(move home office)\n(move office shop)\n(move shop home)")  # p2 stays home
    assert "does not hold at the end" in invalid_step(domain, problem, plan)


def test_lmcut_is_refused_on_conditional_effects_naming_hmax() -> None:
    _, _, task = _task(BRIEFCASE, BRIEFCASE_3)
    assert task.conditional_effects > 0
    with pytest.raises(PddlUnsupportedError, match=r"lmcut does not take conditional effects.*hmax"):
        solve_task(task, "astar", "lmcut")


def test_an_unknown_search_on_conditional_effects_is_named() -> None:
    _, _, task = _task(BRIEFCASE, BRIEFCASE_3)
    with pytest.raises(ValueError, match="unknown search 'nosuch'"):
        solve_task(task, "nosuch")


def test_an_atom_reached_only_through_a_conditional_effect_is_grounded_and_planned() -> None:
    domain = """(define (domain relay) (:requirements :conditional-effects)
      (:predicates (armed) (lit) (done))
      (:action arm :effect (armed))
      (:action fire :effect (when (armed) (lit)))
      (:action finish :precondition (lit) :effect (done)))"""
    problem = "(define (problem p) (:domain relay) (:init) (:goal (done)))"
    result = solve_pddl(domain, problem, "bfs")
    assert [str(step) for step in result.plan] == ["(arm)", "(fire)", "(finish)"]


def test_an_effect_the_precondition_decides_is_the_operators_own_or_is_dropped() -> None:
    domain = """(define (domain decided) (:requirements :conditional-effects :negative-preconditions)
      (:predicates (p) (q) (r) (s))
      (:action a :precondition (and (p) (not (q)))
       :effect (and (when (p) (r)) (when (q) (s)) (when (and (p) (s)) (not (p))))))"""
    problem = "(define (problem x) (:domain decided) (:init (p) (s)) (:goal (r)))"
    _, _, task = _task(domain, problem)
    (op,) = task.operators
    bit = {fact.predicate: 1 << i for i, fact in enumerate(task.facts)}
    assert op.add == bit["r"]  # (p) holds whenever a applies
    assert op.effects == ((bit["s"], 0, 0, bit["p"]),)  # (q) never holds then: its effect is gone; (p) is asked


def test_an_unconditional_universal_effect_becomes_the_operators_own() -> None:
    domain = """(define (domain sweep) (:requirements :typing)
      (:types spot) (:predicates (dirty ?s - spot) (swept))
      (:action sweep :effect (and (swept) (forall (?s - spot) (not (dirty ?s))))))"""
    problem = """(define (problem x) (:domain sweep) (:objects a b c - spot)
      (:init (dirty a) (dirty c)) (:goal (and (swept) (not (dirty a)) (not (dirty c)))))"""
    _, _, task = _task(domain, problem)
    (op,) = task.operators
    assert op.effects == () and task.atoms(op.delete) == [Atom("dirty", ("a",)), Atom("dirty", ("c",))]


def test_adds_win_over_deletes_and_every_condition_reads_the_state_before() -> None:
    """``swap`` exchanges two flags: each condition reads the flags as they were, not as the other effect left
    them; and an atom both deleted (under a condition) and added is true after."""
    domain = """(define (domain flags) (:requirements :conditional-effects :negative-preconditions)
      (:predicates (up ?f) (kept))
      (:action swap :parameters (?f ?g)
       :effect (and (when (up ?f) (and (up ?g) (not (up ?f)))) (when (up ?g) (and (up ?f) (not (up ?g))))))
      (:action keep :effect (and (kept) (when (kept) (not (kept))))))"""
    problem = "(define (problem x) (:domain flags) (:objects a b) (:init (up a)) (:goal (and (up b) (kept))))"
    _, _, task = _task(domain, problem)
    ops = {str(op): op for op in task.operators}
    bit = {str(fact): 1 << i for i, fact in enumerate(task.facts)}
    up_a, up_b, kept = bit["(up a)"], bit["(up b)"], bit["(kept)"]
    assert ops["(swap a b)"].apply(up_a) == up_b and ops["(swap a b)"].apply(up_a | up_b) == up_a | up_b
    assert ops["(keep)"].apply(kept) == kept
    for state in range(1 << len(task.facts)):
        expected = {child for child, _ in task.compiled.successors(state)}
        assert expected == {op.apply(state) for op in task.operators if op.applicable(state)}


@pytest.mark.parametrize("seed", range(60))
def test_c_and_python_apply_random_conditional_effects_as_the_lifted_text_says(seed: int) -> None:
    """Random conditions on a ``when`` and on a ``when`` under a ``forall``, every state of a small world: the
    searches' successors (C) and :meth:`Operator.apply` both give the state the effect's text gives, read straight
    off it."""
    rng = random.Random(seed)
    first, second = random_condition(rng, 2, ["?x", "?y"]), random_condition(rng, 2, ["?x", "?y", "?z"])
    domain_text = f"""(define (domain rnd) (:requirements :adl)
      (:predicates (p ?a) (q ?a ?b) (r ?a) (done ?a ?b))
      (:action act :parameters (?x ?y)
       :effect (and (done ?x ?y) (when {first} (q ?y ?x)) (forall (?z) (when {second} (not (p ?z))))))
      (:action flip :parameters (?x ?y) :effect (and (p ?x) (not (p ?y)) (q ?x ?y) (not (q ?y ?x)))))"""
    problem_text = "(define (problem rnd) (:domain rnd) (:objects a b) (:init (r a) (p a)) (:goal (done a b)))"
    _, _, task = _task(domain_text, problem_text)
    facts = {fact: i for i, fact in enumerate(task.facts)}
    fluent = [Atom("p", (o,)) for o in "ab"] + [Atom("q", (o, t)) for o in "ab" for t in "ab"]
    assert set(fluent) <= set(facts)
    acts = {op.args: op for op in task.operators if op.name == "act"}
    for mask in range(1 << len(fluent)):
        true = {atom for i, atom in enumerate(fluent) if mask >> i & 1}
        state = sum(1 << facts[atom] for atom in true)
        truth = {*true, Atom("r", ("a",))}.__contains__
        children = {op_index: child for child, op_index in task.compiled.successors(state)}
        for (x, y), op in acts.items():
            binding = {"?x": x, "?y": y}
            after = (true | {Atom("done", (x, y))}
                     | ({Atom("q", (y, x))} if evaluate_text(parse_sexpr(first), binding, truth) else set()))
            after -= {Atom("p", (z,)) for z in "ab"
                      if evaluate_text(parse_sexpr(second), {**binding, "?z": z}, truth)}
            expected = sum(1 << facts[atom] for atom in after)
            assert op.apply(state) == expected, (first, second, sorted(map(str, true)), x, y)
            assert children[task.operators.index(op)] == expected


def test_a_plan_with_conditional_effects_keeps_its_order_when_deordered() -> None:
    _, _, task = _task(BRIEFCASE, BRIEFCASE_3)
    plan = solve_task(task, "bfs").plan
    assert deorder(task, plan) == [()] + [(step,) for step in range(len(plan) - 1)]


LEVELS = """(define (domain levels) (:requirements :adl)
  (:types thing level)
  (:predicates (at-level ?x - thing ?l - level) (next ?a ?b - level))
  (:action raise :parameters (?x - thing)
   :effect (forall (?a ?b - level) (when (and (at-level ?x ?a) (next ?a ?b))
                                      (and (at-level ?x ?b) (not (at-level ?x ?a)))))))"""


def test_an_effect_whose_static_condition_never_holds_reaches_nothing() -> None:
    """Of the forall's 16 pairs of levels only two are a step the static next facts allow: the others can never fire,
    so the levels they alone would add are no facts of the task (l3: nothing leads there), and the plan climbs."""
    *_, task = _task(LEVELS, """(define (problem p) (:domain levels) (:objects box - thing l0 l1 l2 l3 - level)
      (:init (at-level box l0) (next l0 l1) (next l1 l2)) (:goal (at-level box l2)))""")
    assert {str(fact) for fact in task.facts} == {"(at-level box l0)", "(at-level box l1)", "(at-level box l2)"}
    (operator,) = task.operators
    assert len(operator.effects) == 2  # l0 -> l1, l1 -> l2
    assert [op.name for op in solve_task(task, "bfs", "blind").plan] == ["raise", "raise"]
