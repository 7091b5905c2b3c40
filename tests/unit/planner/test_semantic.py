"""Scene domains, Plan2Goals and plan simulation: the planner speaks the vocabulary's sub-goals."""

import itertools
import re
import time

import pytest

from semgoal_core.tasks import TASKS
from semgoal_core.vocabulary import LAYOUTS, SCENES, Literal, SubGoal, parse_literal
from semgoal_planner.goals import parse_goal
from semgoal_planner.semantic import PlanningError, SemanticPlanner, placed_twice, plan2goal
from strips_planner.grounding import Operator
from strips_planner.planner import solve_task

STARTS = {  # a typical start state of each task (true literals)
    "MC-2": [], "MA-2": [Literal("close", ("red", "green"))],
    "Swap-2": [Literal("close", ("red", "green")), Literal("above", ("green", "red"))],
    "MC-3": [], "MA-3": [Literal("close", p) for p in (("red", "green"), ("red", "blue"), ("green", "blue"))],
    "DC-2": [], "DC-3": [], "DC-4": [],
}
OPTIMAL = {"MC-2": 2, "MA-2": 2, "Swap-2": 4, "MC-3": 4, "MA-3": 4, "DC-2": 4, "DC-3": 6, "DC-4": 8}


def test_plan2goal_maps_every_action_to_its_subgoal() -> None:
    op = Operator("put_near_both", ("red", "green", "blue"), 0, 0, 0, 0)
    assert plan2goal(op) == SubGoal("put_near", ("red", "green", "blue"))
    near_not = plan2goal(Operator("put_near", ("red", "green", "blue"), 0, 0, 0, 0))
    assert near_not == SubGoal("put_near", ("red", "green"), apart=("blue",))
    assert str(near_not) == "put_near(red,green,not blue)"
    assert near_not.literals() == [Literal("close", ("red", "green")), Literal("close", ("red", "blue"), False),
                                   Literal("holding", ("red",), False)]
    assert plan2goal(Operator("pick", ("red", "green"), 0, 0, 0, 0)).literals() == [Literal("holding", ("red",))]


@pytest.mark.parametrize("task_name", list(TASKS))
def test_every_task_gets_a_shortest_plan_of_scene_subgoals(task_name: str) -> None:
    task = TASKS[task_name]
    planner = SemanticPlanner(task.scene)
    goal = parse_goal(task_name, task.scene, task.blocks, STARTS[task_name])
    steps = planner.plan(task.blocks, STARTS[task_name], goal)
    assert len(steps) == OPTIMAL[task_name]
    assert {s.kind for s in steps} <= set(SCENES[task.scene].subgoal_types)
    planner.simulate(task.blocks, STARTS[task_name], goal, steps)  # raises if invalid


def test_swap_plan_unstacks_before_stacking() -> None:
    planner = SemanticPlanner("two_blocks")
    goal = parse_goal("Swap-2", "two_blocks", ("red", "green"), STARTS["Swap-2"])
    assert goal[0] == Literal("above", ("red", "green"))
    steps = [str(s) for s in planner.plan(("red", "green"), STARTS["Swap-2"], goal)]
    assert steps[0] == "pick(green)" and steps[-1] == "put_on(red,green)"


def test_simulation_explains_what_is_wrong() -> None:
    planner = SemanticPlanner("desk_cleanup")
    blocks, goal = ("red", "green"), [Literal("in_bin", ("red",))]
    with pytest.raises(PlanningError, match=r"step 0 put_in_bin\(red\) cannot run: it needs holding\(red\)"):
        planner.simulate(blocks, [], goal, [SubGoal("put_in_bin", ("red",))])
    with pytest.raises(PlanningError, match=r"step 3 put_in_bin\(red\) cannot run"):  # numbered as in the plan
        planner.simulate(blocks, [], goal, [SubGoal("put_in_bin", ("red",))], first_index=3)
    with pytest.raises(PlanningError, match=r"does not reach the goal: .*in_bin\(red\)"):
        planner.simulate(blocks, [], goal, [SubGoal("pick", ("red",)), SubGoal("put_on_table", ("red",))])
    with pytest.raises(PlanningError, match="not an action"):
        planner.simulate(blocks, [], goal, [SubGoal("pick", ("yellow",))])


def test_unreachable_goal_is_reported() -> None:
    planner = SemanticPlanner("desk_cleanup")
    state = [Literal("holding", ("red",))]
    # holding two blocks at once is impossible: hand-empty is needed for every pick
    goal = [Literal("holding", ("red",)), Literal("holding", ("green",))]
    with pytest.raises(PlanningError, match="no plan reaches"):
        planner.plan(("red", "green"), state, goal)


@pytest.mark.parametrize("scene, goal, named", [
    ("desk_cleanup", "holding(red) & in_bin(red)", "holding(red) and in_bin(red) cannot hold together"),
    ("desk_cleanup", "in_bin(green) & holding(red) & holding(green)", "in_bin(green) and holding(green) cannot hold together"),
    ("two_blocks", "above(red,green) & above(green,red)", "above(red,green) and above(green,red) cannot hold together"),
    ("desk_cleanup", "holding(red) & in_bin(red)", "pick(red), the only action that makes holding(red) true, makes "
     "in_bin(red) false; put_in_bin(red), the only action that makes in_bin(red) true, makes holding(red) false"),
    ("two_blocks", "above(red,green) & not close(red,green)",
     "put_on(red,green), the only action that makes above(red,green) true, makes close(red,green) true"),
    ("two_blocks", "holding(red) & holding(green)",
     "pick(red), the only action that makes holding(red) true, needs the free gripper that holding(green) takes"),
    ("two_blocks", "holding(red) & above(green,red)",
     "pick(red), the only action that makes holding(red) true, needs above(green,red) false"),
    ("tabletop", "above(green,red) & in_bin(red)",  # "stack red and green in the bin": no tower stands in the bin
     "put_on(green,red), the only action that makes above(green,red) true, needs in_bin(red) false"),
])
def test_an_unreachable_goal_names_the_literals_that_conflict(scene: str, goal: str, named: str) -> None:
    """Not only "no state reachable", but which of the goal's literals exclude each other and, where
    the actions that make one true show it, the domain's reason. Some of these goals never reach a planner
    (``semgoal_core.consistency`` refuses them where they are typed); the planner explains them all the same."""
    objects = ("red", "green")
    literals = [LAYOUTS[scene].validate(parse_literal(part)) for part in goal.split(" & ")]
    with pytest.raises(PlanningError, match=re.escape(named)):
        SemanticPlanner(scene).plan(objects, [], literals)


def test_every_three_block_put_says_where_the_block_ends_up_with_respect_to_both_others() -> None:
    """No action leaves the moved block's closeness to a bystander to the frame."""
    blocks = ("red", "green", "blue")
    task = SemanticPlanner("three_blocks").task(blocks, [], [Literal("close", ("red", "green"))])
    puts = [plan2goal(op) for op in task.operators if op.name != "pick"]
    assert puts and all(len(put.references) + len(put.apart) == 2 for put in puts)


@pytest.mark.parametrize(("start", "goal", "puts"), [
    # green is carried away from red: from blue too (no put promises less), but nothing relies on that
    (["close(red,green)", "close(red,blue)"], "close(red,blue) & not close(red,green)", ["put_away(green,red)"]),
    (["close(red,green)", "close(green,blue)"], "close(red,blue) & not close(red,green) & close(green,blue)",
     ["put_near(red,blue,not green)"]),
    ([], "MC-3", ["put_near(blue,green)", "put_near(red,blue,green)"]),  # apart from red only until red comes
    ([], "not close(red,green) & close(red,blue) & close(green,blue)", ["put_near(blue,green)", "put_near(red,blue,not green)"]),
])
def test_a_step_sends_every_promise_the_plan_relies_on(start: list[str], goal: str, puts: list[str]) -> None:
    planner, blocks = SemanticPlanner("three_blocks"), ("red", "green", "blue")
    state = [parse_literal(text) for text in start]
    goal_literals = parse_goal(goal, "three_blocks", blocks, state)
    steps = planner.plan(blocks, state, goal_literals)
    assert [str(step) for step in steps if step.kind != "pick"] == puts
    planner.simulate(blocks, state, goal_literals, steps)


def test_a_step_typed_without_its_whole_effect_runs_as_the_action_that_promises_it() -> None:
    planner = SemanticPlanner("three_blocks")
    blocks, start = ("red", "green", "blue"), [Literal("close", ("red", "green"))]
    goal = [Literal("close", ("red", "green"), False)]
    planner.simulate(blocks, start, goal, [SubGoal("pick", ("red",)), SubGoal("put_away", ("red", "green"))])
    near = [Literal("close", ("red", "blue"))]
    planner.simulate(blocks, [], near, [SubGoal("pick", ("red",)), SubGoal("put_near", ("red", "blue"))])
    with pytest.raises(PlanningError, match="does not reach the goal"):  # kept apart from blue: not near it
        planner.simulate(blocks, [], near, [SubGoal("pick", ("red",)), SubGoal("put_near", ("red", "green"), ("blue",))])


@pytest.mark.parametrize(("scene", "goal"), [
    ("tabletop", "holding(red) & in_bin(red)"), ("tabletop", "holding(red) & above(red,green)"),
    ("tabletop", "in_bin(red) & above(red,green)"), ("tabletop", "above(red,green) & above(red,blue)"),
    ("tabletop", "above(red,green) & above(blue,green)"), ("tabletop", "above(red,green) & holding(green)"),
    ("tabletop", "above(red,green) & in_bin(green)"), ("desk_cleanup", "holding(red) & in_bin(red)"),
    ("two_blocks", "holding(red) & above(red,green)"), ("two_blocks", "above(red,green) & holding(green)"),
])
def test_a_block_asked_into_two_places_is_refused_at_once(scene: str, goal: str) -> None:
    """With six blocks on the tabletop a search took minutes to prove that no plan reaches such a goal. The check
    is sound: over three blocks, a search through every state the scene's domain reaches finds none either."""
    literals = [parse_literal(part) for part in goal.split(" & ")]
    planner = SemanticPlanner(scene)
    assert placed_twice(literals)
    exhaustive = solve_task(planner.task(LAYOUTS[scene].objects[:3], [], literals), "bfs", "blind")
    assert exhaustive.plan is None and not exhaustive.stats.timed_out
    start = time.perf_counter()
    with pytest.raises(PlanningError, match="cannot hold together"):
        planner.plan(LAYOUTS[scene].objects, [], literals)
    assert time.perf_counter() - start < 0.5
    assert not placed_twice([Literal("above", ("red", "green")), Literal("above", ("green", "blue")),
                             Literal("in_bin", ("yellow",)), Literal("holding", ("orange",))])


def test_a_goal_no_shortest_plan_is_found_for_in_time_gets_a_longer_one() -> None:
    """Every block of five close to every other: a shortest-plan search runs for minutes, the greedy one that takes
    over after the time given finds a plan that runs."""
    objects = LAYOUTS["tabletop"].objects
    goal = [Literal("close", pair) for pair in itertools.combinations(objects[:5], 2)]
    planner = SemanticPlanner("tabletop", seconds=0.05)
    start = time.perf_counter()
    steps = planner.plan(objects, [], goal)
    assert time.perf_counter() - start < 2.0
    planner.simulate(objects, [], goal, steps)
    with pytest.raises(PlanningError, match=r"no plan found in 0.0002 s by a shortest-plan search and a greedy one"):
        SemanticPlanner("tabletop", seconds=1e-4).plan(objects, [], goal)
