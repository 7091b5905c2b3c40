"""Goal families: seeded, each draw a start the scene can hold and a goal its vocabulary states."""

import numpy as np
import pytest

from semgoal_core.goal_families import FAMILIES, goal_cases, holds_at_start
from semgoal_core.tasks import TABLE_TOP
from semgoal_core.vocabulary import LAYOUTS, SCENES, evaluate, parse_literal


@pytest.mark.parametrize(("scene", "family"), [(s, f) for s, families in FAMILIES.items() for f in families])
def test_cases_are_seeded_and_speak_the_scene(scene: str, family: str) -> None:
    cases = goal_cases(scene, family, 12, 6_000_000)
    again = goal_cases(scene, family, 12, 6_000_000)
    assert [c.goals for c in cases] == [c.goals for c in again]
    assert all(np.array_equal(a.positions, b.positions) for a, b in zip(cases, again, strict=True))
    for case in cases:
        objects = SCENES[scene].objects[:len(case.positions)]
        for text in (literal for goal in case.goals for literal in goal.split(" & ")):
            LAYOUTS[scene].validate(parse_literal(text), objects)
    assert len({c.goals for c in cases}) > 1  # a family, not one goal
    assert not any(holds_at_start(scene, c.positions, c.goals[0]) for c in cases)  # none solved before it starts
    assert all(len(c.goals) == (2 if family == "chain" else 1) for c in cases)


@pytest.mark.parametrize("scene", list(FAMILIES))
def test_a_chain_asks_for_something_its_first_goal_did_not(scene: str) -> None:
    for case in goal_cases(scene, "chain", 20, 6_000_000):
        first, second = (set(goal.split(" & ")) for goal in case.goals)
        assert not second <= first


def test_desk_starts_may_have_blocks_in_the_bin() -> None:
    """Some starts bin blocks already (goals must take them out), and the predicates agree they are in it."""
    layout, binned = LAYOUTS["desk_cleanup"], []
    for case in goal_cases("desk_cleanup", "bin-subset", 20, 1):
        positions = np.zeros((layout.scene.max_blocks, 3))
        present = np.arange(layout.scene.max_blocks) < len(case.positions)
        positions[: len(case.positions)] = case.positions
        vector = evaluate(layout, positions, np.array([1.3, 0.75, 0.9]), 0.1, TABLE_TOP, present)
        binned.append(sum(lit.name == "in_bin" for lit in layout.true_literals(vector)))
    assert max(binned) >= 2, binned

