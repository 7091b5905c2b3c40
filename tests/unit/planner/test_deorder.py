"""Deordering a sequential plan: every order that keeps the orderings found is a plan, and no more is kept than
the steps need."""

import random
from pathlib import Path

import pytest

from semgoal_planner.blocksworld import DOMAIN_PATH, problem
from strips_planner.deorder import deorder
from strips_planner.grounding import ground
from strips_planner.pddl import parse_domain, parse_problem
from strips_planner.planner import solve_task

FIXTURES = Path(__file__).parent / "fixtures"


def _task(domain_text: str, problem_text: str):
    domain = parse_domain(domain_text)
    return ground(domain, parse_problem(problem_text, domain))


def _orders(predecessors: list[tuple[int, ...]], rng: random.Random, samples: int):
    """Random orders of the steps that keep every ordering (each step after its predecessors)."""
    for _ in range(samples):
        done: list[int] = []
        while len(done) < len(predecessors):
            ready = [i for i in range(len(predecessors)) if i not in done and set(predecessors[i]) <= set(done)]
            done.append(rng.choice(ready))
        yield done


def _reaches_goal(task, plan) -> bool:
    state = task.init
    for op in plan:
        if not op.applicable(state):
            return False
        state = op.apply(state)
    return task.goal_reached(state)


@pytest.mark.parametrize(("domain", "problem_name"), [
    ("gripper-domain", "gripper-4balls"), ("logistics-domain", "logistics-p1"), ("keys-domain", "keys-vault"),
    ("blocksworld-domain", "blocksworld-sussman")])
def test_every_order_that_keeps_the_orderings_is_a_plan(domain, problem_name) -> None:
    task = _task((FIXTURES / f"{domain}.pddl").read_text(), (FIXTURES / f"{problem_name}.pddl").read_text())
    plan = solve_task(task, "astar", "lmcut").plan
    predecessors = deorder(task, plan)
    assert all(all(p < i for p in preds) for i, preds in enumerate(predecessors))
    for order in _orders(predecessors, random.Random(0), 200):
        assert _reaches_goal(task, [plan[i] for i in order]), [str(plan[i]) for i in order]


def test_random_blocksworld_plans_deorder_soundly() -> None:
    rng = random.Random(3)
    domain_text = DOMAIN_PATH.read_text()
    for blocks in (4, 5, 6, 7):
        for seed in range(5):
            task = _task(domain_text, problem(blocks, seed))
            plan = solve_task(task, "gbfs", "hff").plan
            predecessors = deorder(task, plan)
            for order in _orders(predecessors, rng, 30):
                assert _reaches_goal(task, [plan[i] for i in order])


def test_independent_deliveries_are_unordered_and_each_one_keeps_its_order() -> None:
    """Gripper with two free hands: carrying ball 1 and carrying ball 2 are independent; within each, pick, move,
    drop stay in order."""
    task = _task((FIXTURES / "gripper-domain.pddl").read_text(), (FIXTURES / "gripper-4balls.pddl").read_text())
    plan = solve_task(task, "astar", "lmcut").plan
    predecessors = deorder(task, plan)
    assert any(not preds for preds in predecessors[1:])  # a later step free to go first
    assert sum(map(len, predecessors)) < len(plan) * (len(plan) - 1) // 2  # far from a total order


def test_an_agent_resource_left_out_frees_the_steps_it_alone_ordered() -> None:
    """The desk with one hand: every pick waits for the put before it. Leaving the empty hand out (each agent has
    its own), binning red and binning green are independent, and each put follows its own pick."""
    from semgoal_core.vocabulary import parse_literal
    from semgoal_planner.semantic import SemanticPlanner

    planner = SemanticPlanner("desk_cleanup")
    objects = ("red", "green", "blue", "yellow")
    goal = [parse_literal("in_bin(red)"), parse_literal("in_bin(green)")]
    task = planner.task(objects, [], goal)
    plan = solve_task(task, "bfs").plan
    names = [str(op) for op in plan]
    hand = next(i for i, fact in enumerate(task.facts) if fact.predicate == "hand-empty")
    assert deorder(task, plan) == [(), (0,), (1,), (2,)]  # one hand: a total order
    free = deorder(task, plan, ignore=1 << hand)
    picks = [i for i, name in enumerate(names) if name.startswith("(pick")]
    assert [free[i] for i in picks] == [(), ()] and all(free[i + 1] == (i,) for i in picks), (names, free)
