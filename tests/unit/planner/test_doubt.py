"""Holding the planner's decisions while a literal it relies on is unsure, for a bounded number of steps."""

import math

import pytest

from semgoal_core.vocabulary import Literal
from semgoal_planner.doubt import Doubt, unsure_literals

CLOSE, IN_BIN = Literal("close", ("red", "green"), True), Literal("in_bin", ("red",), False)


def test_only_unsure_literals_the_plan_relies_on_count() -> None:
    relied_on = [Literal("close", ("red", "green"), False)]  # the goal asks for the opposite value: same atom
    assert unsure_literals([CLOSE, IN_BIN], [0.6, 0.5], relied_on, 0.9) == [(CLOSE, 0.6)]
    assert unsure_literals([CLOSE, IN_BIN], [0.95, 0.5], relied_on, 0.9) == []
    assert unsure_literals([CLOSE, IN_BIN], [], relied_on, 0.9) == []  # the simulator's states: always sure
    assert unsure_literals([CLOSE], [math.nan], relied_on, 0.9) == [(CLOSE, 0.0)]


def test_confidences_that_do_not_match_the_literals_are_refused() -> None:
    with pytest.raises(ValueError, match="2 confidences for 1 literals"):
        unsure_literals([CLOSE], [1.0, 1.0], [CLOSE], 0.9)


def test_the_planner_waits_a_bounded_time_then_takes_the_state_as_it_is() -> None:
    doubt, unsure = Doubt(threshold=0.9, wait_steps=3), [(CLOSE, 0.6)]
    assert not doubt.holds(unsure, 9, episode=1)  # the first state of a world is always taken
    assert [doubt.holds(unsure, step, episode=1) for step in range(10, 15)] == [True, True, True, False, False]
    assert not doubt.holds([], 15, episode=1)
    assert doubt.holds(unsure, 16, episode=1)  # a new doubt waits again


def test_the_first_state_after_a_world_reset_is_never_held() -> None:
    """Held, it left the planner deciding on the world before the reset: a goal sent next was planned on the old
    world's last state, and in lockstep the new world waited for ever on a sub-goal stamped with the old steps."""
    doubt, unsure = Doubt(threshold=0.9, wait_steps=25), [(CLOSE, 0.0)]
    assert not doubt.holds(unsure, 0, episode=1)
    assert doubt.holds(unsure, 262, episode=1)
    assert not doubt.holds(unsure, 0, episode=2)  # a new episode
    assert doubt.holds(unsure, 1, episode=2)
    assert not doubt.holds(unsure, 0, episode=2)  # the step count went back: a world started again
