"""ADL conditions in preconditions and goals (``or``, ``imply``, ``forall``, ``exists``): read, ground to STRIPS
operators, planned, and the plans checked by the validator, which evaluates the conditions on its own."""

import pytest
from random_conditions import evaluate_text, random_condition

from semgoal_bench.validate_plan import invalid_step
from strips_planner import adl
from strips_planner.pddl import Atom, Condition, PddlUnsupportedError, parse_domain, parse_problem, parse_sexpr
from strips_planner.planner import solve_pddl

# A truck with areas front to back: a package is loaded into an area only while every area nearer the door is free
# (the IPC's trucks), a door opens with either key, and a room is left only when some light in it is off.
DOMAIN = """(define (domain depot) (:requirements :adl :typing)
  (:types area key room - object)
  (:predicates (free ?a - area) (closer ?a ?b - area) (loaded ?a - area) (has ?k - key) (opens ?k - key)
               (open) (in ?r - room) (door ?r ?s - room) (lit ?r - room))
  (:action load :parameters (?a - area)
   :precondition (and (free ?a) (forall (?b - area) (imply (closer ?b ?a) (free ?b))))
   :effect (and (loaded ?a) (not (free ?a))))
  (:action unlock :parameters (?k - key)
   :precondition (or (and (has ?k) (opens ?k)) (open))
   :effect (open))
  (:action leave :parameters (?r ?s - room)
   :precondition (and (in ?r) (door ?r ?s) (open) (exists (?t - room) (and (= ?t ?r) (not (lit ?t)))))
   :effect (and (in ?s) (not (in ?r))))
  (:action switch-off :parameters (?r - room) :precondition (lit ?r) :effect (not (lit ?r))))"""
PROBLEM = """(define (problem p) (:domain depot)
  (:objects a1 a2 a3 - area k1 k2 - key r1 r2 - room)
  (:init (free a1) (free a2) (free a3) (closer a1 a2) (closer a1 a3) (closer a2 a3) (has k2) (opens k2)
         (in r1) (door r1 r2) (lit r1) (lit r2))
  (:goal (and (in r2) (forall (?a - area) (loaded ?a)))))"""


def test_conditions_are_read_in_negation_normal_form() -> None:
    domain = parse_domain(DOMAIN)
    load, unlock, leave = domain.actions[:3]
    assert load.precondition == (Condition(Atom("free", ("?a",))),)
    assert load.condition == ("forall", (("?b", "area"),),
                              ("or", (Condition(Atom("closer", ("?b", "?a")), False), Condition(Atom("free", ("?b",))))))
    assert unlock.precondition == () and unlock.condition[0] == "or"
    assert leave.condition[0] == "exists"
    negated = adl.negated(load.condition)
    assert negated[0] == "exists" and negated[2][0] == "and"


def test_an_adl_task_is_planned_and_the_plan_holds_step_by_step() -> None:
    result = solve_pddl(DOMAIN, PROBLEM, "bfs")
    plan = [str(op) for op in result.plan]
    # the areas fill from the door back: a3 first (nothing behind it), then a2, then a1
    assert [p for p in plan if p.startswith("(load")] == ["(load a3)", "(load a2)", "(load a1)"]
    assert "(switch-off r1)" in plan and plan.index("(switch-off r1)") < plan.index("(leave r1 r2)")
    domain = parse_domain(DOMAIN)
    problem = parse_problem(PROBLEM, domain)
    steps = [(op.name, *op.args) for op in result.plan]
    assert invalid_step(domain, problem, steps) is None
    assert invalid_step(domain, problem, [("load", "a1")]) is not None  # a2 and a3 are still free
    assert invalid_step(domain, problem, steps[:-1]) is not None  # the goal's forall does not hold yet


@pytest.mark.parametrize("search", ["astar", "gbfs", "lazy"])
def test_every_search_plans_it(search: str) -> None:
    result = solve_pddl(DOMAIN, PROBLEM, search)
    domain = parse_domain(DOMAIN)
    assert invalid_step(domain, parse_problem(PROBLEM, domain), [(op.name, *op.args) for op in result.plan]) is None


def test_an_or_becomes_one_lifted_action_per_way_before_grounding() -> None:
    unlock = parse_domain(DOMAIN).actions[1]
    copies = adl.lifted_split(unlock)
    assert [copy.precondition for copy in copies] == [
        (Condition(Atom("has", ("?k",))), Condition(Atom("opens", ("?k",)))), (Condition(Atom("open", ())),)]
    assert all(copy.condition is None and copy.name == "unlock" for copy in copies)


def test_a_goal_that_static_facts_decide_is_planned_as_its_one_way() -> None:
    decided = PROBLEM.replace("(:goal (and (in r2) (forall (?a - area) (loaded ?a))))",
                              "(:goal (or (and (in r2) (closer a1 a2)) (and (loaded a1) (closer a3 a1))))")
    assert [str(op) for op in solve_pddl(DOMAIN, decided, "bfs").plan][-1] == "(leave r1 r2)"


@pytest.mark.parametrize("search", ["bfs", "astar", "lazy"])
def test_a_goal_with_a_choice_reaches_one_of_its_ways_and_the_plan_says_nothing_else(search: str) -> None:
    open_choice = PROBLEM.replace("(:goal (and (in r2) (forall (?a - area) (loaded ?a))))",
                                  "(:goal (or (in r2) (and (loaded a2) (loaded a3))))")
    result = solve_pddl(DOMAIN, open_choice, search)
    domain = parse_domain(DOMAIN)
    steps = [(op.name, *op.args) for op in result.plan]
    assert invalid_step(domain, parse_problem(open_choice, domain), steps) is None
    if search != "lazy":  # the shortest way: the two loads, not unlock, switch off and leave
        assert [str(op) for op in result.plan] == ["(load a3)", "(load a2)"]


def test_a_goal_condition_that_can_never_hold_is_unsolvable_with_the_reason() -> None:
    never = PROBLEM.replace("(forall (?a - area) (loaded ?a))", "(exists (?a - area) (closer ?a ?a))")
    result = solve_pddl(DOMAIN, never, "bfs")
    assert result.plan is None and "can never hold" in result.reason


def test_a_condition_that_grounds_to_too_many_alternatives_is_refused() -> None:
    many = DOMAIN.replace("(forall (?b - area) (imply (closer ?b ?a) (free ?b)))",
                          "(forall (?b - area) (or (free ?b) (loaded ?b)))")
    objects = " ".join(f"a{i}" for i in range(1, 12))
    problem = PROBLEM.replace("a1 a2 a3 - area", f"{objects} - area")
    with pytest.raises(PddlUnsupportedError, match="more than 512 alternatives"):
        solve_pddl(many, problem, "bfs")


@pytest.mark.parametrize("seed", range(100))
def test_the_grounded_operators_apply_exactly_where_the_condition_holds(seed: int) -> None:
    """Random conditions, every state of a small world: some operator of a binding applies where the lifted
    condition holds there (evaluated directly, as the validator does), and none where it does not."""
    import random

    from strips_planner.grounding import ground

    rng = random.Random(seed)
    condition = random_condition(rng, 3, ["?x", "?y"])
    domain_text = f"""(define (domain rnd) (:requirements :adl)
      (:predicates (p ?a) (q ?a ?b) (r ?a) (done ?a ?b))
      (:action act :parameters (?x ?y) :precondition {condition} :effect (done ?x ?y))
      (:action flip :parameters (?x ?y) :effect (and (p ?x) (not (p ?y)) (q ?x ?y) (not (q ?y ?x)))))"""
    problem_text = """(define (problem rnd) (:domain rnd) (:objects a b)
      (:init (r a) (p a) (q a b)) (:goal (done a a)))"""
    domain = parse_domain(domain_text)
    problem = parse_problem(problem_text, domain)
    task = ground(domain, problem)
    fluent_atoms = [Atom("p", (o,)) for o in "ab"] + [Atom("q", (o, t)) for o in "ab" for t in "ab"]
    facts = {fact: i for i, fact in enumerate(task.facts)}
    for mask in range(1 << len(fluent_atoms)):
        true = {atom for i, atom in enumerate(fluent_atoms) if mask >> i & 1}
        state = sum(1 << facts[atom] for atom in true if atom in facts)
        if any(atom not in facts for atom in true):
            continue  # a state grounding proved unreachable: nothing to compare
        truth = {*true, Atom("r", ("a",))}.__contains__
        for x in "ab":
            for y in "ab":
                lifted = evaluate_text(parse_sexpr(condition), {"?x": x, "?y": y}, truth)
                grounded = any(op.applicable(state) for op in task.operators if op.name == "act" and op.args == (x, y))
                assert grounded == lifted, (condition, sorted(map(str, true)), x, y)
