"""Predicates on hand-built configurations, edge cases included; literals, layouts, sub-goals."""

import numpy as np
import pytest

from semgoal_core.vocabulary import (
    LAYOUTS,
    THRESHOLDS,
    Literal,
    SubGoal,
    VocabularyError,
    evaluate,
    fallen_blocks,
    parse_literal,
    parse_subgoal,
)

TABLE = 0.4
REST = TABLE + 0.025
FAR_GRIP = np.array([1.3, 0.75, 0.7])
OPEN = 0.1


def truths(scene: str, positions, grip=FAR_GRIP, opening=OPEN, present=None) -> set[str]:
    layout = LAYOUTS[scene]
    vector = evaluate(layout, np.array(positions, dtype=float), np.asarray(grip), opening, TABLE, present)
    return {str(lit) for lit in layout.true_literals(vector)}


def test_layout_sizes_follow_the_paper() -> None:
    assert LAYOUTS["two_blocks"].size == 1 + 2 + 2  # close pair, above both ways, holding
    assert LAYOUTS["three_blocks"].size == 3 + 3  # close pairs, holding
    assert LAYOUTS["desk_cleanup"].size == 4 + 4  # holding, in_bin


def test_close_is_symmetric_and_thresholded() -> None:
    d = THRESHOLDS.close_distance
    assert "close(red,green)" in truths("two_blocks", [[1.2, 0.6, REST], [1.2 + d - 0.001, 0.6, REST]])
    assert "close(red,green)" not in truths("two_blocks", [[1.2, 0.6, REST], [1.2 + d + 0.001, 0.6, REST]])
    layout = LAYOUTS["two_blocks"]
    assert layout.index(Literal("close", ("green", "red"))) == layout.index(Literal("close", ("red", "green")))


def test_above_on_a_stack_and_a_block_resting_offset_on_another() -> None:
    stacked = truths("two_blocks", [[1.2, 0.6, REST], [1.2, 0.6, REST + 0.05]])
    assert {"above(green,red)", "close(red,green)"} <= stacked and "above(red,green)" not in stacked
    offset = truths("two_blocks", [[1.2, 0.6, REST], [1.2 + 0.03, 0.6 + 0.02, REST + 0.05]])  # 3.6 cm off centre
    assert "above(green,red)" in offset
    overhanging = truths("two_blocks", [[1.2, 0.6, REST], [1.2 + 0.05, 0.6 + 0.02, REST + 0.045]])  # tipping off
    assert "above(green,red)" not in overhanging
    side_by_side = truths("two_blocks", [[1.2, 0.6, REST], [1.26, 0.6, REST]])
    assert not any(t.startswith("above") for t in side_by_side)


def test_holding_needs_the_block_between_closed_fingers() -> None:
    block = [1.3, 0.7, REST + 0.1]
    grip = np.array(block)
    assert "holding(red)" in truths("two_blocks", [block, [1.1, 0.5, REST]], grip, opening=0.049)
    assert "holding(red)" not in truths("two_blocks", [block, [1.1, 0.5, REST]], grip, opening=0.1)  # open
    assert "holding(red)" not in truths("two_blocks", [block, [1.1, 0.5, REST]], grip, opening=0.0)  # shut, empty
    assert "holding(red)" not in truths("two_blocks", [block, [1.1, 0.5, REST]], grip + np.array([0.05, 0, 0]), 0.049)


def test_two_blocks_between_the_fingers_are_no_holding_of_either() -> None:
    """A grasp low on a stack pinches the lower block's top edge too: the hand holds one block at most."""
    grip = np.array([1.3, 0.7, REST + 0.037])
    double = truths("two_blocks", [[1.3, 0.7, REST], [1.3, 0.7, REST + 0.05]], grip, opening=0.049)
    assert not any(t.startswith("holding") for t in double)
    absent = truths("three_blocks", [[1.3, 0.7, REST], [1.3, 0.7, REST + 0.05], [1.1, 0.5, REST]], grip, 0.049,
                    present=[True, False, True])
    assert "holding(red)" in absent  # a block slot the scene was built without does not count


def test_a_grasped_block_still_touching_the_table_is_held() -> None:
    block = [1.3, 0.7, REST]
    assert "holding(red)" in truths("two_blocks", [block, [1.1, 0.5, REST]], np.array(block) + np.array([0, 0, 0.005]), 0.048)


def test_in_bin_inside_on_the_rim_and_outside() -> None:
    bin_ = LAYOUTS["desk_cleanup"].scene.bin
    cx, cy = bin_.center
    floor = TABLE + bin_.floor_thickness + 0.025
    rim = TABLE + bin_.floor_thickness + bin_.wall_height
    inside = [cx, cy, floor]
    on_rim = [cx + bin_.inner_half_size[0] + bin_.wall_thickness / 2, cy, rim + 0.025]
    on_table = [1.2, 0.6, REST]
    result = truths("desk_cleanup", [inside, on_rim, on_table, [1.4, 0.6, REST]])
    assert "in_bin(red)" in result
    assert "in_bin(green)" not in result and "in_bin(blue)" not in result


def test_absent_blocks_never_hold() -> None:
    bin_ = LAYOUTS["desk_cleanup"].scene.bin
    positions = [[*bin_.center, TABLE + 0.036]] * 4
    result = truths("desk_cleanup", positions, present=np.array([True, True, False, False]))
    assert result == {"in_bin(red)", "in_bin(green)"}


@pytest.mark.parametrize("scene", sorted(LAYOUTS))
def test_the_vector_is_each_atom_by_its_definition(scene: str) -> None:
    """evaluate's vectorised geometry, atom by atom as the module doc defines it, over random states (pairs near
    each other, stacked, in the bin, in a hand, some slots absent)."""
    layout, t, rng = LAYOUTS[scene], THRESHOLDS, np.random.default_rng(7)
    geometry = layout.scene.bin
    for trial in range(150):
        count = layout.scene.max_blocks
        positions = rng.uniform([1.05, 0.45, REST], [1.55, 1.05, REST + 0.1], (count, 3))
        positions[1] = positions[0] + rng.normal([0.0, 0.0, 0.05], 0.03)
        if geometry is not None and trial % 3 == 0:
            positions[-1, :2] = np.asarray(geometry.center) + rng.uniform(-0.2, 0.2, 2)
        grip, opening = positions[trial % count] + rng.normal(0.0, 0.01, 3), rng.uniform(0.03, 0.06)
        present = rng.uniform(size=count) < 0.8 if trial % 2 else np.ones(count, dtype=bool)
        vector = evaluate(layout, positions, grip, opening, TABLE, present)
        between = [present[i] and np.linalg.norm(positions[i, :2] - grip[:2]) < t.holding_xy
                   and abs(positions[i, 2] - grip[2]) < t.holding_z for i in range(count)]
        closed = t.holding_opening_min <= opening <= t.holding_opening_max
        for entry, (name, args) in enumerate(layout.atoms):
            i, *rest = (layout.objects.index(a) for a in args)
            if name == "close":
                expected = np.linalg.norm(positions[i] - positions[rest[0]]) <= t.close_distance
            elif name == "above":
                dz = positions[i, 2] - positions[rest[0], 2]
                expected = (np.linalg.norm(positions[i, :2] - positions[rest[0], :2]) < t.above_xy
                            and t.above_dz_min < dz < t.above_dz_max)
            elif name == "holding":
                expected = closed and between[i] and sum(between) == 1
            else:
                offset = np.abs(positions[i, :2] - np.asarray(geometry.center))
                expected = ((offset < np.asarray(geometry.inner_half_size)).all()
                            and positions[i, 2] < TABLE + geometry.floor_thickness + geometry.wall_height)
            expected = bool(expected) and all(present[[i, *rest]])
            assert vector[entry] == expected, (trial, name, args)


def test_fallen_blocks_lie_well_below_the_table_top() -> None:
    depth = THRESHOLDS.fallen_depth
    positions = [[1.3, 0.7, REST], [0.9, 0.3, 0.025], [1.3, 1.2, TABLE - depth + 0.001], [1.3, 1.2, TABLE - depth - 0.001]]
    assert fallen_blocks(["red", "green", "blue", "yellow"], np.array(positions), TABLE) == ["green", "yellow"]


@pytest.mark.parametrize("text, expected", [
    ("close(red,green)", Literal("close", ("red", "green"))),
    ("not in_bin(red)", Literal("in_bin", ("red",), False)),
    ("  !Holding( Blue ) ", Literal("holding", ("blue",), False)),
    ("¬above(red, green)", Literal("above", ("red", "green"), False)),
    ("not(in_bin(red))", Literal("in_bin", ("red",), False)),
    (" ! ( close(Red, green) ) ", Literal("close", ("red", "green"), False)),
    ("in(red, bin)", Literal("in_bin", ("red",))),
    ("not inside(blue,box)", Literal("in_bin", ("blue",), False)),
    ("on(red,green)", Literal("above", ("red", "green"))),
])
def test_parse_literal(text: str, expected: Literal) -> None:
    assert parse_literal(text) == expected


@pytest.mark.parametrize("literal, message", [
    ("close(red,purple)", "unknown object 'purple'"),
    ("closer(red,green)", "unknown predicate 'closer'"),
    ("close(red)", "takes 2 argument"),
    ("close(red,red)", "cannot be related to itself"),
    ("in_bin(red)", "not used in scene 'two_blocks'"),
])
def test_validation_names_the_problem(literal: str, message: str) -> None:
    with pytest.raises(VocabularyError, match=message):
        LAYOUTS["two_blocks"].validate(parse_literal(literal))


def test_encode_decode_round_trip_and_contradictions() -> None:
    layout = LAYOUTS["three_blocks"]
    literals = [Literal("close", ("red", "blue")), Literal("holding", ("green",), False)]
    target, mask = layout.encode(literals)
    assert sorted(layout.decode(target, mask)) == sorted(literals)
    with pytest.raises(VocabularyError, match="contradictory"):
        layout.encode([Literal("close", ("red", "blue")), Literal("close", ("blue", "red"), False)])


def test_subgoal_literals_and_parsing() -> None:
    assert SubGoal("put_near", ("blue", "red", "green")).literals() == [
        Literal("close", ("blue", "red")), Literal("close", ("blue", "green")), Literal("holding", ("blue",), False)]
    assert parse_subgoal("put_in_bin(red)", LAYOUTS["desk_cleanup"].scene) == SubGoal("put_in_bin", ("red",))
    with pytest.raises(VocabularyError, match="not available in scene 'two_blocks'"):
        parse_subgoal("put_in_bin(red)", LAYOUTS["two_blocks"].scene)
    with pytest.raises(VocabularyError, match="takes 2 argument"):
        parse_subgoal("put_on(red)")
    with pytest.raises(VocabularyError, match="appears twice"):
        parse_subgoal("put_near(red,red)")


@pytest.mark.parametrize("text", ["put_near(red,green,not blue)", "put_near(red, green, NOT  blue)"])
def test_a_put_near_names_the_blocks_it_keeps_apart_from(text: str) -> None:
    subgoal = parse_subgoal(text, LAYOUTS["three_blocks"].scene)
    assert subgoal == SubGoal("put_near", ("red", "green"), apart=("blue",))
    assert parse_subgoal(str(subgoal)) == subgoal
    assert Literal("close", ("red", "blue"), False) in subgoal.literals()


@pytest.mark.parametrize(("text", "error"), [
    ("put_away(red,green,not blue)", "only put_near"), ("put_near(red,not blue,green)", "after its references"),
    ("put_near(red,green,not green)", "appears twice"), ("put_near(red,green,not purple)", "unknown object 'purple'")])
def test_blocks_to_keep_apart_from_are_checked(text: str, error: str) -> None:
    with pytest.raises(VocabularyError, match=error):
        parse_subgoal(text, LAYOUTS["three_blocks"].scene)


def test_a_semantic_state_must_fit_its_scene() -> None:
    layout = LAYOUTS["desk_cleanup"]
    layout.check_state(("red", "green"), [Literal("in_bin", ("red",)), Literal("holding", ("blue",), False)], ["green"])
    for objects, literals, named, says in (
        (("red", "red"), [], [], "distinct blocks"),
        (("red",), [], [], "2 or 3 or 4"),
        (("red", "purple"), [], [], "distinct blocks"),
        (("red", "green"), [Literal("in_bin", ("blue",))], [], "unknown object 'blue'"),
        (("red", "green"), [Literal("above", ("red", "green"))], [], "not used in scene"),
        (("red", "green"), [], ["blue"], "'blue' is named"),
    ):
        with pytest.raises(VocabularyError, match=says):
            layout.check_state(objects, literals, named)


def test_threshold_margins_measure_the_distance_to_the_nearest_threshold() -> None:
    from semgoal_core.geometry import TABLE_TOP
    from semgoal_core.vocabulary import LAYOUTS, Literal, threshold_margins

    layout = LAYOUTS["two_blocks"]
    positions = np.array([[1.3, 0.7, 0.425], [1.3, 0.797, 0.425]])  # centres 9.7 cm apart: close by 3 mm
    margins = threshold_margins(layout, positions, np.array([1.3, 0.5, 0.6]), TABLE_TOP)
    assert margins[layout.index(Literal("close", ("red", "green")))] == pytest.approx(0.003)
    stacked = np.array([[1.3, 0.7, 0.475], [1.31, 0.7, 0.425]])  # 4 cm inside the 5 cm; 2 cm from either height bound
    margins = threshold_margins(layout, stacked, np.array([1.3, 0.5, 0.6]), TABLE_TOP)
    assert margins[layout.index(Literal("above", ("red", "green")))] == pytest.approx(0.02)
