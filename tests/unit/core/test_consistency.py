"""Goals no world can satisfy are found from their literals, each conflict named."""

import pytest

from semgoal_core.consistency import ContradictionError, check_consistent, contradictions
from semgoal_core.vocabulary import parse_literal


def goal(text: str):
    return [parse_literal(part) for part in text.split(" & ")]


@pytest.mark.parametrize("text, named", [
    ("holding(red) & holding(green)", "holding(red) and holding(green): one hand"),
    ("above(red,green) & above(green,red)", "above(red,green) and above(green,red): a block cannot be above"),
    ("above(red,green) & above(green,blue) & above(blue,red)", "above(red,green) and above(green,blue) and "
                                                               "above(blue,red)"),
    ("in_bin(red) & not in_bin(red)", "both in_bin(red) and not in_bin(red)"),
    ("close(red,green) & not close(green,red)", "both close(red,green) and not close(green,red)"),
    ("close(red,red)", "close(red,red): a block cannot be related to itself"),
    ("above(red,green) & not close(red,green)", "above(red,green) and not close(red,green): a block resting"),
    ("above(green,red) & not close(red,green)", "above(green,red) and not close(red,green)"),
])
def test_each_contradiction_is_named(text: str, named: str) -> None:
    found = contradictions(goal(text))
    assert any(named in line for line in found), found
    with pytest.raises(ContradictionError, match="contradictory goal"):
        check_consistent(goal(text))


@pytest.mark.parametrize("text", [
    "holding(red) & not holding(green)",
    "above(red,green) & above(green,blue)",
    "above(red,green) & close(red,green) & not close(red,blue)",
    "not above(red,green) & not above(green,red)",
    "holding(red) & holding(red)",
    "in_bin(red) & in_bin(green) & not close(red,green)",
])
def test_goals_a_world_can_satisfy_pass(text: str) -> None:
    assert contradictions(goal(text)) == []
