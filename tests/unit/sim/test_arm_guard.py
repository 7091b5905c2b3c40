"""The separation guard of two arms: distances between links, who yields, and that it leaves apart arms alone."""

import numpy as np
import pytest

from semgoal_sim.arm_guard import MIN_GAP, RELEASE, SEPARATION, ArmGuard, chain_distance, segment_distance


def test_segment_distance_is_the_closest_pair_of_points() -> None:
    rng = np.random.default_rng(3)
    samples = np.linspace(0.0, 1.0, 401)
    for _ in range(200):
        p0, p1, q0, q1 = rng.normal(size=(4, 3))
        dense = np.linalg.norm((p0 + np.outer(samples, p1 - p0))[:, None] - (q0 + np.outer(samples, q1 - q0))[None], axis=2)
        assert segment_distance(p0, p1, q0, q1) == pytest.approx(dense.min(), abs=5e-3)
    crossing = segment_distance(np.array([0.0, 0, 0]), np.array([1.0, 0, 0]), np.array([0.5, -1, 0]), np.array([0.5, 1, 0]))
    assert crossing == pytest.approx(0.0)
    point = segment_distance(np.array([0.0, 0, 0]), np.array([0.0, 0, 0]), np.array([1.0, 1, 0]), np.array([1.0, 1, 0]))
    assert point == pytest.approx(np.sqrt(2))


def chains(first_grip_x: float, second_grip_x: float, y: float = 0.75) -> np.ndarray:
    """Two straight arms reaching from across the table at the grips' x, level."""
    def arm(shoulder_x: float, grip_x: float) -> np.ndarray:
        return np.array([[shoulder_x + (grip_x - shoulder_x) * t, y, 0.6] for t in (0.0, 0.4, 0.7, 0.9, 1.0)])

    return np.stack([arm(0.72, first_grip_x), arm(1.88, second_grip_x)])


def test_arms_apart_keep_their_commands() -> None:
    guard = ArmGuard(step_size=0.05)
    actions = np.array([[0.2, 0.1, -0.3, 0.5], [-0.2, 0.0, 0.1, -1.0]])
    far = chains(1.1, 1.5)
    assert chain_distance(far[0], far[1]) > SEPARATION + 0.1
    np.testing.assert_array_equal(guard(far, actions, np.array([0.5, 0.5]), np.array([False, False])), actions)
    assert guard.right_of_way is None and guard.yields == 0


def test_the_arm_without_a_block_draws_back_and_the_other_waits_for_room() -> None:
    guard = ArmGuard(step_size=0.05)
    close = chains(1.25, 1.40)
    toward = np.array([[1.0, 0.0, 0.0, -1.0], [-1.0, 0.0, 0.0, 0.2]])  # each moves towards the other
    sent = guard(close, toward, np.array([0.45, 0.45]), np.array([True, False]))
    assert guard.right_of_way == 0 and guard.yields == 1
    assert sent[1, 0] > 0 and sent[1, 2] == 1.0  # the second draws back towards its shoulder (+x) and rises
    assert sent[1, 3] == 0.0  # an empty hand's fingers stay as they are
    assert sent[0, 0] == 0.0 and sent[0, 3] == -1.0  # the first waits in the plane, squeezing its block


def test_the_right_of_way_is_kept_until_the_arms_are_well_apart() -> None:
    guard = ArmGuard(step_size=0.05)
    still = np.zeros((2, 4))
    guard(chains(1.25, 1.40), np.array([[1.0, 0, 0, 0], [0, 0, 0, 0]]), np.array([0.6, 0.6]), np.array([False, False]))
    assert guard.right_of_way == 0  # the moving one goes on, the still one yields
    guard(chains(1.2, 1.2 + (SEPARATION + RELEASE) / 2), still, np.array([0.6, 0.6]), np.array([False, False]))
    assert guard.right_of_way == 0  # apart, but not yet by RELEASE
    guard(chains(1.05, 1.55), still, np.array([0.6, 0.6]), np.array([False, False]))
    assert guard.right_of_way is None
    guard.reset()
    assert (guard.right_of_way, guard.yields) == (None, 0)


def test_a_yielding_arm_keeps_a_block_in_hand_over_its_own_table_edge() -> None:
    guard = ArmGuard(step_size=0.05, edges=np.array([1.095, 1.505]))
    close = chains(1.09, 1.27)  # the first arm, at its own edge, yields to the second, which holds a block
    sent = guard(close, np.array([[0.0, 0.0, 0.0, -1.0], [-1.0, 0.0, 0.0, -1.0]]), np.array([0.45, 0.45]),
                 np.array([True, True]))
    assert guard.right_of_way == 1 and sent[0, :2].tolist() == [0.0, 0.0] and sent[0, 2] == 1.0 and sent[0, 3] == -1.0
    empty = ArmGuard(step_size=0.05, edges=np.array([1.095, 1.505]))
    sent = empty(close, np.array([[0.0, 0.0, 0.0, 0.0], [-1.0, 0.0, 0.0, -1.0]]), np.array([0.45, 0.45]),
                 np.array([False, True]))
    assert sent[0, 0] < 0  # an empty hand draws back over the edge


def test_links_within_the_least_gap_make_the_first_arm_stop_towards_the_other_and_the_other_draw_away() -> None:
    """Forearms touched with the chains 19.5 cm apart: while the links themselves are within MIN_GAP, the arm with the
    right of way loses the part of its command towards the other, and the other moves away from it (DC-4 start
    3,000,005: taken only on steps where the gap shrank, the first's full command on the next one closed 2.2 cm)."""
    guard = ArmGuard(step_size=0.05)
    apart = chains(1.1, 1.5)  # the chains far apart: only the links' own distance says they are close
    towards = np.array([1.0, 0.0, 0.0])  # from the first arm's nearest point to the second's
    actions = np.array([[1.0, 0.5, 0.0, -1.0], [0.0, 0.0, 0.0, 0.0]])
    heights, holding = np.array([0.6, 0.6]), np.array([True, False])
    assert guard(apart, actions, heights, holding, MIN_GAP + 0.01, towards).tolist() == actions.tolist()
    for _ in range(2):  # closer than MIN_GAP, and then no closer than the step before: the links still within it
        sent = guard(apart, actions, heights, holding, MIN_GAP - 0.01, towards)
        assert guard.right_of_way == 0
        assert sent[0, 0] == pytest.approx(0.0) and sent[0, 1] == pytest.approx(0.5)  # sideways it goes on
        assert sent[1, 0] > 0 and sent[1, 1] == pytest.approx(0.0)  # away from the first's nearest point


def test_an_arm_going_down_to_grasp_is_at_work_and_keeps_the_right_of_way() -> None:
    """Two arms reaching for blocks 13 cm apart took turns drawing back for 350 control steps (Clean-6, start
    3,000,003): the one going down to grasp counted as still, so each conflict went to the other."""
    guard = ArmGuard(step_size=0.05)
    descending = np.array([[0.0, 0.0, -0.6, 0.0], [-1.0, 0.0, 0.0, 0.0]])
    sent = guard(chains(1.25, 1.40), descending, np.array([0.45, 0.6]), np.array([False, False]))
    assert guard.right_of_way == 0 and sent[0].tolist() == descending[0].tolist()
    assert sent[1, 0] > 0  # the reaching one draws back
