"""Action costs (the IPC's :action-costs): read from PDDL, counted only under (:metric minimize (total-cost)),
and minimised by breadth-first (then uniform-cost) search and by A* with every admissible heuristic."""

import heapq
import random
from pathlib import Path

import pytest

from semgoal_bench.validate_plan import invalid_step, plan_cost, read_plan
from semgoal_planner.blocksworld import DOMAIN_PATH, problem
from strips_planner import heuristics
from strips_planner.grounding import Task, ground
from strips_planner.pddl import PddlError, PddlUnsupportedError, parse_domain, parse_problem
from strips_planner.plan_pddl import main as plan_pddl_main
from strips_planner.planner import solve_pddl, solve_task
from strips_planner.search import successors

FIXTURES = Path(__file__).parent / "fixtures"
ROADS = (FIXTURES / "roads-domain.pddl").read_text()
DETOUR = (FIXTURES / "roads-detour.pddl").read_text()


@pytest.mark.parametrize(("search", "heuristic"), [("bfs", "blind"), ("astar", "blind"), ("astar", "hmax"),
                                                    ("astar", "lmcut"), ("astar", "hff")])
def test_the_cheapest_route_beats_the_shortest(search: str, heuristic: str) -> None:
    result = solve_pddl(ROADS, DETOUR, search, heuristic)
    assert [str(op) for op in result.plan] == ["(start)", "(drive a b)", "(drive b c)", "(drive c d)"]
    assert result.cost == 6


def test_greedy_search_finds_a_valid_plan_and_says_its_cost() -> None:
    result = solve_pddl(ROADS, DETOUR, "gbfs")
    domain = parse_domain(ROADS)
    problem_ = parse_problem(DETOUR, domain)
    plan = [(op.name, *op.args) for op in result.plan]
    assert invalid_step(domain, problem_, plan) is None
    assert result.cost == plan_cost(domain, problem_, plan) >= 6


@pytest.mark.parametrize("search", ["gbfs", "lazy"])
def test_greedy_search_is_guided_as_if_every_action_cost_one_and_reports_the_real_cost(search: str) -> None:
    """As LAMA's first iteration: the ferry (one step, cost 50) looks nearer than the road (four steps, cost 6)."""
    result = solve_pddl(ROADS, DETOUR, search, "hff")
    assert [str(op) for op in result.plan] == ["(ferry a d)"]
    assert result.cost == 50


def test_without_the_metric_every_action_costs_one() -> None:
    result = solve_pddl(ROADS, DETOUR.replace("(:metric minimize (total-cost))", ""), "bfs")
    assert [str(op) for op in result.plan] == ["(ferry a d)"]
    assert result.cost is None


def test_plan_pddl_prints_the_cost_and_the_validator_agrees(tmp_path: Path, capsys) -> None:
    domain_path, problem_path = FIXTURES / "roads-domain.pddl", FIXTURES / "roads-detour.pddl"
    assert plan_pddl_main([str(domain_path), str(problem_path), "--search", "astar"]) == 0
    out = capsys.readouterr().out
    assert out.splitlines()[-1] == "; cost = 6"
    domain = parse_domain(ROADS)
    assert plan_cost(domain, parse_problem(DETOUR, domain), read_plan(out)) == 6


def _cheapest(task: Task) -> float:
    """The optimal plan cost by Dijkstra over the successors (inf when the goal is unreachable)."""
    index = {op: i for i, op in enumerate(task.operators)}
    frontier, best = [(0, task.init)], {task.init: 0}
    while frontier:
        cost, state = heapq.heappop(frontier)
        if cost > best[state]:
            continue
        if task.goal_reached(state):
            return cost
        for child, op in successors(task, state):
            c = cost + task.costs[index[op]]
            if c < best.get(child, float("inf")):
                best[child] = c
                heapq.heappush(frontier, (c, child))
    return float("inf")


@pytest.mark.parametrize("seed", range(5))
def test_searches_and_admissible_heuristics_agree_with_dijkstra_on_random_costs(seed: int) -> None:
    """Blocksworld with each operator's cost drawn from 0-4 (zero-cost operators included)."""
    domain = parse_domain(DOMAIN_PATH.read_text())
    unit = ground(domain, parse_problem(problem(4, seed), domain))
    rng = random.Random(seed)
    task = Task(unit.facts, unit.init, unit.goal, unit.goal_neg, unit.operators,
                costs=tuple(rng.randint(0, 4) for _ in unit.operators))
    optimal = _cheapest(task)
    for name in ("hmax", "lmcut", "blind"):
        assert heuristics.heuristic(task, name)(task.init) <= optimal
    for search, heuristic in (("bfs", "blind"), ("astar", "blind"), ("astar", "hmax"), ("astar", "lmcut")):
        assert solve_task(task, search, heuristic).cost == optimal, (search, heuristic)
    assert solve_task(task, "gbfs", "hff").cost >= optimal


def test_a_cost_per_operator_is_required_and_non_negative() -> None:
    domain = parse_domain(DOMAIN_PATH.read_text())
    unit = ground(domain, parse_problem(problem(3, 0), domain))
    with pytest.raises(ValueError, match="costs"):
        _ = Task(unit.facts, unit.init, unit.goal, unit.goal_neg, unit.operators, costs=(1,)).compiled
    with pytest.raises(ValueError, match="costs are ints from 0"):
        _ = Task(unit.facts, unit.init, unit.goal, unit.goal_neg, unit.operators,
                 costs=(-1,) * len(unit.operators)).compiled


@pytest.mark.parametrize(("domain_text", "problem_text", "error", "words"), [
    (ROADS.replace("(increase (total-cost) 50)", "(increase (fuel) 50)"), DETOUR, PddlUnsupportedError,
     "numeric effects other than"),
    (ROADS.replace("(increase (total-cost) 50)", "(increase (total-cost) -5)"), DETOUR, PddlUnsupportedError,
     "non-negative integers"),
    (ROADS.replace("(length ?from ?to - place) - number", "(length ?from ?to - place) - place"), DETOUR,
     PddlUnsupportedError, "only number-valued functions"),
    (ROADS, DETOUR.replace("minimize", "maximize"), PddlUnsupportedError, "the only metric supported"),
    (ROADS, DETOUR.replace("(= (length c d) 1)", "(= (width c d) 1)"), PddlUnsupportedError, "in :functions"),
    (ROADS, DETOUR.replace("(= (length c d) 1)", ""), PddlError, r"costs \(length c d\), which :init gives no value"),
    # numeric fluents' conditions: valid PDDL outside the fragment (exit 3), not an unknown predicate (exit 2)
    (ROADS.replace("(road ?from ?to) (engine-on))", "(road ?from ?to) (engine-on) (< (length ?from ?to) 5))"), DETOUR,
     PddlUnsupportedError, r"numeric conditions \(< \.\.\.\)"),
    (ROADS, DETOUR.replace("(:goal (at d))", "(:goal (and (at d) (>= (total-cost) 3)))"), PddlUnsupportedError,
     r"numeric conditions \(>= \.\.\.\)"),
    (ROADS, DETOUR.replace("(:goal (at d))", "(:goal (and (at d) (= (total-cost) 6)))"), PddlUnsupportedError,
     r"numeric conditions \(= \.\.\.\)"),
])
def test_cost_constructs_outside_the_fragment_are_named(domain_text, problem_text, error, words) -> None:
    with pytest.raises(error, match=words):
        solve_pddl(domain_text, problem_text, "astar")


def test_undeclared_equality_and_negative_preconditions_are_read_with_a_warning(tmp_path: Path, capsys) -> None:
    """As Fast Downward reads them (IPC's tidybot and snake use them without declaring them)."""
    domain = """(define (domain d) (:requirements :strips)
      (:predicates (at ?x) (seen ?x))
      (:action go :parameters (?from ?to) :precondition (and (at ?from) (not (= ?from ?to)) (not (seen ?to)))
       :effect (and (at ?to) (seen ?to) (not (at ?from)))))"""
    (tmp_path / "d.pddl").write_text(domain)
    (tmp_path / "p.pddl").write_text("(define (problem p) (:domain d) (:objects a b) (:init (at a)) (:goal (at b)))")
    assert plan_pddl_main([str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl")]) == 0
    captured = capsys.readouterr()
    assert captured.out.splitlines() == ["(go a b)"]
    assert "warning: (= ...) is used without :equality" in captured.err
    assert "warning: negative preconditions are used without :negative-preconditions" in captured.err
