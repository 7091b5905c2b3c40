"""Grounding, heuristics and searches on standard STRIPS domains: optimal lengths, unsolvable tasks."""

import random
import signal
import time
from pathlib import Path

import pytest

from semgoal_planner.blocksworld import DOMAIN_PATH, problem
from strips_planner import heuristics
from strips_planner.grounding import ground
from strips_planner.pddl import parse_domain, parse_problem
from strips_planner.planner import solve_pddl, solve_task
from strips_planner.search import successors

FIXTURES = Path(__file__).parent / "fixtures"
COMBOS = [("bfs", "blind"), ("astar", "blind"), ("astar", "hmax"), ("astar", "lmcut"), ("gbfs", "hff"), ("lazy", "hff"),
          ("lazy", "hmax")]


def fixture(name: str) -> str:
    return (FIXTURES / f"{name}.pddl").read_text()


def validate(domain_text: str, problem_text: str, plan) -> bool:
    """Replays a plan on the grounded task: every step applicable, the goal reached."""
    domain = parse_domain(domain_text)
    task = ground(domain, parse_problem(problem_text, domain))
    state = task.init
    for op in plan:
        match = next(o for o in task.operators if o.name == op.name and o.args == op.args)
        assert match.applicable(state), f"{op} not applicable"
        state = match.apply(state)
    return task.goal_reached(state)


@pytest.mark.parametrize(("search", "heuristic"), COMBOS)
@pytest.mark.parametrize(("domain", "problem_name", "optimal"), [
    ("blocksworld-domain", "blocksworld-sussman", 6), ("gripper-domain", "gripper-4balls", 11)])
def test_every_search_finds_a_valid_plan(search, heuristic, domain, problem_name, optimal) -> None:
    result = solve_pddl(fixture(domain), fixture(problem_name), search, heuristic)
    assert validate(fixture(domain), fixture(problem_name), result.plan)
    if search not in ("gbfs", "lazy"):
        assert len(result.plan) == optimal


@pytest.mark.parametrize("seed", range(5))
def test_lazy_search_evaluates_only_the_states_it_expands(seed: int) -> None:
    """Eager greedy search evaluates every state it generates; lazy search one per expansion, the goal
    state's test included, and it still finds valid plans."""
    text = problem(9, seed)
    eager, lazy = (solve_pddl(DOMAIN_PATH.read_text(), text, search, "hff") for search in ("gbfs", "lazy"))
    assert validate(DOMAIN_PATH.read_text(), text, lazy.plan)
    assert lazy.stats.generated == lazy.stats.expanded
    assert lazy.stats.generated < eager.stats.generated


def test_the_relaxed_plan_takes_each_fact_s_cheapest_achiever_by_hadd() -> None:
    """The goal: by `wide` after three one-step facts (hmax 2, hadd 4) or by `deep` after a chain of two (hmax 3,
    hadd 3). Achievers by hmax give a relaxed plan of 4 steps; by hadd, as Fast Downward takes them, of 3."""
    domain_text = """(define (domain choice) (:requirements :strips)
      (:predicates (p1) (p2) (p3) (q1) (q2) (done))
      (:action a1 :parameters () :precondition () :effect (p1))
      (:action a2 :parameters () :precondition () :effect (p2))
      (:action a3 :parameters () :precondition () :effect (p3))
      (:action wide :parameters () :precondition (and (p1) (p2) (p3)) :effect (done))
      (:action b1 :parameters () :precondition () :effect (q1))
      (:action b2 :parameters () :precondition (q1) :effect (q2))
      (:action deep :parameters () :precondition (q2) :effect (done)))"""
    problem_text = "(define (problem p) (:domain choice) (:init) (:goal (done)))"
    domain = parse_domain(domain_text)
    task = ground(domain, parse_problem(problem_text, domain))
    assert heuristics.heuristic(task, "hmax")(task.init) == 2
    assert heuristics.heuristic(task, "hff")(task.init) == 3


def test_grounding_prunes_unreachable_operators() -> None:
    domain = parse_domain(fixture("gripper-domain"))
    task = ground(domain, parse_problem(fixture("gripper-4balls"), domain))
    # move between 2 rooms (2, a self-move included by the domain: 4), pick/drop 4 balls x 2 rooms x 2 grippers
    assert len(task.operators) == 4 + 16 + 16
    assert "free" in {f.predicate for f in task.facts}


@pytest.mark.parametrize("seed", range(6))
def test_admissible_heuristics_never_exceed_the_optimal_cost(seed: int) -> None:
    text = problem(5, seed)
    domain = parse_domain(DOMAIN_PATH.read_text())
    task = ground(domain, parse_problem(text, domain))
    optimal = len(solve_task(task, "bfs").plan)
    for name in ("hmax", "lmcut"):
        assert heuristics.heuristic(task, name)(task.init) <= optimal
    assert heuristics.heuristic(task, "lmcut")(task.init) >= heuristics.heuristic(task, "hmax")(task.init)
    assert len(solve_task(task, "astar", "lmcut").plan) == optimal


@pytest.mark.parametrize("seed", range(4))
def test_astar_with_hmax_and_blind_finds_optimal_plans(seed: int) -> None:
    domain = parse_domain(DOMAIN_PATH.read_text())
    task = ground(domain, parse_problem(problem(5, seed), domain))
    optimal = len(solve_task(task, "bfs").plan)
    for heuristic in ("hmax", "blind"):
        result = solve_task(task, "astar", heuristic)
        assert len(result.plan) == optimal


@pytest.mark.parametrize(("domain_name", "problem_text"), [
    ("gripper-domain", fixture("gripper-4balls")), ("blocksworld", problem(6, 3)), ("blocksworld", problem(8, 1))])
def test_successor_generator_yields_exactly_the_applicable_operators(domain_name: str, problem_text: str) -> None:
    domain_text = DOMAIN_PATH.read_text() if domain_name == "blocksworld" else fixture(domain_name)
    domain = parse_domain(domain_text)
    task = ground(domain, parse_problem(problem_text, domain))
    frontier, seen = [task.init], {task.init}
    while frontier and len(seen) < 500:  # a slice of the reachable states
        state = frontier.pop()
        expected = sorted((op.apply(state), str(op)) for op in task.operators if op.applicable(state))
        assert sorted((child, str(op)) for child, op in successors(task, state)) == expected
        for child, _ in expected:
            if child not in seen:
                seen.add(child)
                frontier.append(child)


def test_unsolvable_task_returns_no_plan_and_a_reason() -> None:
    domain_text = fixture("blocksworld-domain")
    unsolvable = ("(define (problem p) (:domain blocksworld) (:objects a b) "
                  "(:init (on-table a) (on-table b) (clear a) (clear b)) (:goal (on a b)))")  # no arm-empty: stuck
    for search, heuristic in COMBOS:
        result = solve_pddl(domain_text, unsolvable, search, heuristic)
        assert result.plan is None and result.reason


@pytest.mark.parametrize(("search", "heuristic"), COMBOS)
def test_a_search_stops_when_its_time_is_up_and_says_so(search: str, heuristic: str) -> None:
    """A planner node must answer: a search given seconds stops then, with no plan and the reason."""
    domain = parse_domain(DOMAIN_PATH.read_text())
    task = ground(domain, parse_problem(problem(12, 3), domain))
    start = time.perf_counter()
    result = solve_task(task, search, heuristic, seconds=1e-4)
    elapsed = time.perf_counter() - start
    assert result.plan is None or search in ("gbfs", "lazy")  # the greedy searches may find one at once
    if result.plan is None:
        assert result.stats.timed_out and result.reason.startswith("no plan found in 0.0001 s")
        assert elapsed < 0.5
    assert solve_task(task, "gbfs", "hff", seconds=30.0).plan is not None
    with pytest.raises(ValueError, match="0 \\(no limit\\) or more seconds"):
        task.compiled.search(search, heuristic, -1.0)


def test_negative_preconditions_and_equality_are_honoured() -> None:
    domain_text = """(define (domain toggles) (:requirements :negative-preconditions :equality)
      (:predicates (on ?x) (linked ?x ?y))
      (:action switch-on :parameters (?x ?y) :precondition (and (not (on ?x)) (not (= ?x ?y)) (linked ?x ?y))
               :effect (on ?x)))"""
    problem_text = """(define (problem t) (:domain toggles) (:objects a b)
      (:init (linked a a) (linked b a)) (:goal (and (on b) (not (on a)))))"""
    result = solve_pddl(domain_text, problem_text, "bfs")
    assert [str(op) for op in result.plan] == ["(switch-on b a)"]
    assert solve_pddl(domain_text, problem_text.replace("(on b)", "(on a)"), "bfs").plan is None


def _bfs_length(task, state: int) -> float:
    """The optimal plan length from ``state`` (inf when none), by breadth-first search on the successors."""
    frontier, seen, depth = [state], {state}, 0
    while frontier:
        if any(task.goal_reached(s) for s in frontier):
            return depth
        frontier = [c for s in frontier for c, _ in successors(task, s) if c not in seen and not seen.add(c)]
        depth += 1
    return float("inf")


@pytest.mark.parametrize("seed", range(3))
def test_heuristics_bound_the_optimal_cost_from_states_along_a_walk(seed: int) -> None:
    """hmax <= LM-cut <= h* and hmax <= hFF, on states with more than 64 facts (two words)."""
    domain = parse_domain(DOMAIN_PATH.read_text())
    task = ground(domain, parse_problem(problem(7, seed), domain))
    assert len(task.facts) > 64
    h = {name: heuristics.heuristic(task, name) for name in heuristics.HEURISTICS}
    rng, state = random.Random(seed), task.init
    for _ in range(6):
        optimal = _bfs_length(task, state)
        assert h["hmax"](state) <= h["lmcut"](state) <= optimal
        assert h["hmax"](state) <= h["hff"](state)
        assert h["blind"](state) == (0 if task.goal_reached(state) else 1)
        state = rng.choice(successors(task, state))[0]


def test_a_fact_asked_false_must_be_undone_first_in_the_relaxations() -> None:
    """``use`` asks the machine not busy: from a busy one the relaxations count freeing it too (they ignored negative
    preconditions, and read 1)."""
    domain = parse_domain("""(define (domain machine) (:requirements :negative-preconditions)
      (:predicates (busy) (done))
      (:action use :precondition (not (busy)) :effect (and (done) (busy)))
      (:action free :precondition (busy) :effect (not (busy))))""")
    task = ground(domain, parse_problem("(define (problem p) (:domain machine) (:init (busy)) (:goal (done)))", domain))
    for name in ("hmax", "hff", "lmcut"):
        assert heuristics.heuristic(task, name)(task.init) == 2, name
        assert heuristics.heuristic(task, name)(0) == 1, name  # not busy
    assert heuristics.heuristic(task, "lmcount")(task.init) == 1  # (done): a negation is no fact of a state to count


LOCKS = """(define (domain locks) (:requirements :negative-preconditions)
  (:predicates (on ?x) (locked ?x) (ready))
  (:action switch-on :parameters (?x) :precondition (and (not (on ?x)) (not (locked ?x))) :effect (on ?x))
  (:action switch-off :parameters (?x) :precondition (on ?x) :effect (and (not (on ?x)) (ready)))
  (:action lock :parameters (?x) :precondition (and (not (on ?x)) (ready)) :effect (and (locked ?x) (not (ready))))
  (:action unlock :parameters (?x) :precondition (locked ?x) :effect (not (locked ?x))))"""


@pytest.mark.parametrize("seed", range(8))
def test_heuristics_with_facts_asked_false_bound_the_optimal_cost_in_every_state(seed: int) -> None:
    """Random goals of true and false facts over switches that lock: in every state, hmax <= LM-cut <= h* and
    hmax <= hFF, and a relaxation calls a state a dead end only where it is one."""
    rng = random.Random(seed)
    literals = [f"({p} {x})" for p in ("on", "locked") for x in "abc"] + ["(ready)"]
    goal = " ".join(lit if rng.random() < 0.5 else f"(not {lit})" for lit in rng.sample(literals, 3))
    domain = parse_domain(LOCKS)
    task = ground(domain, parse_problem(f"(define (problem p) (:domain locks) (:objects a b c) (:init (on a)) "
                                        f"(:goal (and {goal})))", domain))
    h = {name: heuristics.heuristic(task, name) for name in ("hmax", "hff", "lmcut")}
    for state in range(1 << len(task.facts)):
        optimal = _bfs_length(task, state)
        assert h["hmax"](state) <= h["lmcut"](state) <= optimal, (goal, task.atoms(state))
        assert h["hmax"](state) <= h["hff"](state)
        assert (h["hff"](state) == float("inf")) <= (optimal == float("inf"))


def test_dead_ends_are_infinite_for_every_relaxed_heuristic() -> None:
    domain_text = """(define (domain roads) (:requirements :strips)
      (:predicates (at ?x) (road ?x ?y))
      (:action walk :parameters (?x ?y) :precondition (and (at ?x) (road ?x ?y)) :effect (and (at ?y) (not (at ?x)))))"""
    problem_text = """(define (problem p) (:domain roads) (:objects a b c)
      (:init (at a) (road a b) (road a c)) (:goal (at b)))"""  # one-way roads: c is a dead end
    domain = parse_domain(domain_text)
    task = ground(domain, parse_problem(problem_text, domain))
    dead_end = next(child for child, op in successors(task, task.init) if op.args == ("a", "c"))
    for name in ("hmax", "hff", "lmcut"):
        assert heuristics.heuristic(task, name)(task.init) == 1
        assert heuristics.heuristic(task, name)(dead_end) == float("inf")


def test_grounding_drops_facts_and_operators_unreachable_even_relaxed() -> None:
    domain_text = """(define (domain locks) (:requirements :strips)
      (:predicates (at ?x) (key) (open))
      (:action walk :parameters (?x ?y) :precondition (at ?x) :effect (and (at ?y) (not (at ?x))))
      (:action unlock :parameters () :precondition (key) :effect (open)))"""
    problem_text = "(define (problem p) (:domain locks) (:objects a b) (:init (at a)) (:goal (at b)))"
    domain = parse_domain(domain_text)
    task = ground(domain, parse_problem(problem_text, domain))
    assert [str(f) for f in task.facts] == ["(at a)", "(at b)"]  # no key, so never open
    assert {op.name for op in task.operators} == {"walk"}
    assert [str(op) for op in solve_task(task, "bfs").plan] == ["(walk a b)"]


def test_a_long_search_stops_on_a_signal() -> None:
    """The C search checks for signals, so Ctrl-C (here an alarm) ends it."""
    def alarm(*_) -> None:
        raise TimeoutError

    domain = parse_domain(DOMAIN_PATH.read_text())
    task = ground(domain, parse_problem(problem(14, 0), domain))  # far beyond breadth-first search
    previous = signal.signal(signal.SIGALRM, alarm)
    signal.setitimer(signal.ITIMER_REAL, 0.2)
    try:
        with pytest.raises(TimeoutError):
            solve_task(task, "bfs")
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


@pytest.mark.parametrize("state", [-1, 1 << 4096, "s"])
def test_bad_states_are_refused_with_a_message(state) -> None:
    domain = parse_domain(fixture("blocksworld-domain"))
    task = ground(domain, parse_problem(fixture("blocksworld-sussman"), domain))
    with pytest.raises((TypeError, OverflowError), match=r"int|convert"):
        heuristics.heuristic(task, "hmax")(state)
    with pytest.raises(ValueError, match="valid: blind"):
        heuristics.heuristic(task, "hadd")
