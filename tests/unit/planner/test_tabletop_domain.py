"""The tabletop's domain: towers of any height, the bin and closeness in one plan, from semantic states."""

import itertools

import pytest

from semgoal_core.tasks import TABLETOP_TASKS, stacked
from semgoal_core.vocabulary import SCENES, Literal, SubGoal
from semgoal_planner.english import parse_english
from semgoal_planner.goals import parse_goal
from semgoal_planner.semantic import PlanningError, SemanticPlanner

SIX = SCENES["tabletop"].objects[:6]
PLANNER = SemanticPlanner("tabletop")


def _puts(steps: list[SubGoal]) -> list[SubGoal]:
    return [step for step in steps if step.kind != "pick"]


def test_the_tabletop_plans_with_a_star() -> None:
    assert PLANNER.search == "astar"
    assert SemanticPlanner("desk_cleanup").search == "bfs"


@pytest.mark.parametrize("order", [SIX, SIX[::-1]], ids=["red at the bottom", "purple at the bottom"])
def test_a_tower_of_six_is_planned_bottom_up_in_either_order(order: tuple[str, ...]) -> None:
    steps = PLANNER.plan(SIX, [], stacked(order))
    assert _puts(steps) == [SubGoal("put_on", (top, bottom)) for bottom, top in itertools.pairwise(order)]
    assert len(steps) == 10


def test_a_tower_is_taken_down_from_the_top() -> None:
    state = stacked(SIX)
    goal = [Literal("above", pair, False) for pair in itertools.permutations(SIX, 2)]
    steps = PLANNER.plan(SIX, state, goal)
    assert [step.block for step in steps if step.kind == "pick"] == list(SIX[:0:-1])
    assert len(steps) == 10


def test_a_block_under_another_is_freed_before_it_moves() -> None:
    state = stacked(("red", "green", "blue"))
    steps = PLANNER.plan(SIX, state, [Literal("in_bin", ("red",))])
    assert [step.block for step in steps if step.kind == "pick"][-1] == "red"
    assert steps[-1] == SubGoal("put_in_bin", ("red",))
    assert len(steps) == 6


def test_towers_the_bin_and_closeness_in_one_plan() -> None:
    goal = [*stacked(("red", "green", "blue")), Literal("in_bin", ("yellow",)), Literal("close", ("orange", "red")),
            Literal("close", ("purple", "yellow"), False)]
    steps = PLANNER.plan(SIX, [Literal("close", ("purple", "yellow"))], goal)
    PLANNER.simulate(SIX, [Literal("close", ("purple", "yellow"))], goal, steps)
    assert {step.kind for step in steps} == {"pick", "put_on", "put_in_bin", "put_near", "put_away"}


def test_nothing_is_stacked_on_a_block_in_the_bin() -> None:
    with pytest.raises(PlanningError, match=r"put_on\(green,red\) cannot run: it needs not in_bin\(red\)"):
        PLANNER.simulate(SIX, [Literal("in_bin", ("red",))], [Literal("above", ("green", "red"))],
                         [SubGoal("pick", ("green",)), SubGoal("put_on", ("green", "red"))])
    steps = PLANNER.plan(SIX, [Literal("in_bin", ("red",))], [Literal("above", ("green", "red"))])
    assert steps[0] == SubGoal("pick", ("red",)) and steps[-1] == SubGoal("put_on", ("green", "red"))
    assert len(steps) == 4


@pytest.mark.parametrize("name", list(TABLETOP_TASKS))
def test_every_tabletop_task_is_planned_from_its_start(name: str) -> None:
    task = TABLETOP_TASKS[name]
    start = stacked(task.blocks) if name.startswith("Unstack") else []
    goal = parse_goal(name, task.scene, task.blocks, start)
    steps = PLANNER.plan(task.blocks, start, goal)
    PLANNER.simulate(task.blocks, start, goal, steps)
    assert {step.kind for step in steps} <= set(SCENES["tabletop"].subgoal_types)


def test_a_sentence_asks_for_a_tower_and_the_bin_on_the_tabletop() -> None:
    goal = parse_english("stack green on red, then blue on green, and put purple in the bin", "tabletop", SIX)
    assert set(goal) == {*stacked(("red", "green", "blue")), Literal("in_bin", ("purple",))}
    steps = PLANNER.plan(SIX, [], goal)
    tower = [step for step in _puts(steps) if step.kind == "put_on"]
    assert tower == [SubGoal("put_on", ("green", "red")), SubGoal("put_on", ("blue", "green"))]
    assert SubGoal("put_in_bin", ("purple",)) in steps and len(steps) == 6


def test_blocks_go_in_the_bin_before_a_tower_is_built_beside_them() -> None:
    """What is done stays done: a block picked beside a finished tower can knock it over, so the turns that bin come
    first where the plan's orderings allow (Sort), the others in their order; the plan still runs to the goal."""
    goal = [*stacked(("red", "green", "blue")), Literal("in_bin", ("yellow",)), Literal("in_bin", ("orange",)),
            Literal("close", ("purple", "red"))]
    steps = PLANNER.plan(SIX, [], goal)
    PLANNER.simulate(SIX, [], goal, steps)
    kinds = [step.kind for step in _puts(steps)]
    assert kinds[:2] == ["put_in_bin", "put_in_bin"] and kinds.count("put_on") == 2


def test_a_turn_begun_in_the_hand_stays_first_and_one_ending_in_it_last() -> None:
    state = [Literal("holding", ("green",))]
    goal = [*stacked(("red", "green")), Literal("in_bin", ("blue",)), Literal("holding", ("yellow",))]
    steps = PLANNER.plan(SIX, state, goal)
    PLANNER.simulate(SIX, state, goal, steps)
    assert steps[0] == SubGoal("put_on", ("green", "red")) and steps[-1] == SubGoal("pick", ("yellow",))
