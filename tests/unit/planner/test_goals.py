"""Goal parsing: tasks and literal conjunctions; every bad goal is a GoalError with a message."""

import itertools

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from semgoal_core.vocabulary import LAYOUTS, Literal
from semgoal_planner.executive import Executive, Observation
from semgoal_planner.goals import GoalError, parse_goal, read_goal
from semgoal_planner.semantic import SemanticPlanner

BLOCKS = ("red", "green", "blue")


def test_conjunctions_with_every_separator() -> None:
    goal = parse_goal("close(red,green) & not close(red, blue) and close(green,blue), holding(red)",
                      "three_blocks", BLOCKS, [])
    assert goal == [Literal("close", ("red", "green")), Literal("close", ("red", "blue"), False),
                    Literal("close", ("green", "blue")), Literal("holding", ("red",))]


def test_literals_may_be_joined_by_semicolons_and_name_the_predicates_as_people_do() -> None:
    goal = parse_goal("on(red,green); near(red, blue); held(green)", "tabletop", BLOCKS, [])
    assert goal == [Literal("above", ("red", "green")), Literal("close", ("red", "blue")), Literal("holding", ("green",))]
    assert parse_goal("(and (on red green) (not (inbin blue)))", "tabletop", BLOCKS, []) == [
        Literal("above", ("red", "green")), Literal("in_bin", ("blue",), False)]


def test_pddl_goal_syntax_reads_as_the_same_literals() -> None:
    goal = parse_goal("(AND (close red green) (not (close red blue)) (holding red))", "three_blocks", BLOCKS, [])
    assert goal == [Literal("close", ("red", "green")), Literal("close", ("red", "blue"), False),
                    Literal("holding", ("red",))]
    assert parse_goal("(close red green)", "three_blocks", BLOCKS, []) == [Literal("close", ("red", "green"))]


@pytest.mark.parametrize("text", ["(and)", "(close red green", "(and (close red green)) x", "((close red green))",
                                  "(not (and (close red green) (close red blue)))", "(or (close red green))"])
def test_pddl_goals_beyond_a_conjunction_of_literals_are_refused(text: str) -> None:
    with pytest.raises(GoalError, match=r"PDDL goals are|unknown predicate"):
        parse_goal(text, "three_blocks", BLOCKS, [])


def test_task_names_are_case_insensitive_and_resolved_against_the_state() -> None:
    goal = parse_goal("dc-2", "desk_cleanup", ("red", "green"), [])
    assert Literal("in_bin", ("red",)) in goal and Literal("holding", ("green",), False) in goal
    for said in ("DC 2", "dc_2", " Dc-2 ", "DC2", "run DC-2", "task dc2", "please do the task DC-2", "DC-2 please", "Task: DC-2"):
        assert read_goal(said, "desk_cleanup", ("red", "green")).task == "DC-2"


def test_not_is_read_in_any_case() -> None:
    assert parse_goal("NOT in_bin(red) & Not(holding(green))", "desk_cleanup", ("red", "green"), []) == [
        Literal("in_bin", ("red",), False), Literal("holding", ("green",), False)]


@pytest.mark.parametrize(("text", "words"), [
    ("close(red,purple)", "unknown object 'purple'"),
    ("hover(red)", "unknown predicate 'hover'"),
    ("close(red)", "takes 2 argument"),
    ("above(red,green)", "not used in scene"),
    ("close(red,green) & not close(green,red)", "contradictory"),
    ("close(red,green) &", "cannot read goal"),
    ("MC-2", "runs in scene two_blocks"),
    ("DC-4", "runs in scene desk_cleanup"),
])
def test_bad_goals_are_explained(text: str, words: str) -> None:
    with pytest.raises(GoalError, match=words):
        parse_goal(text, "three_blocks", BLOCKS, [])


def test_task_needing_other_blocks_is_refused() -> None:
    with pytest.raises(GoalError, match="needs blocks red, green, blue, yellow"):
        parse_goal("DC-4", "desk_cleanup", BLOCKS, [])
    with pytest.raises(GoalError, match="no block is on another"):
        parse_goal("Swap-2", "two_blocks", ("red", "green"), [])


@settings(max_examples=300, deadline=None)
@given(st.text(alphabet="()&,! ~abcdeglnortu_-MCAD234", max_size=40) | st.text(max_size=30))
def test_fuzzed_goal_strings_never_raise_anything_but_goal_errors(text: str) -> None:
    try:
        goal = parse_goal(text, "three_blocks", BLOCKS, [])
    except GoalError as error:
        assert str(error)
    else:
        assert goal and all(lit.name in ("close", "holding") for lit in goal)


@pytest.mark.parametrize(("scene", "text", "named"), [
    ("two_blocks", "holding(red) & holding(green)", "holding(red) and holding(green): one hand"),
    ("two_blocks", "above(red,green) & above(green,red)", "above(red,green) and above(green,red)"),
    ("two_blocks", "above(red,green) & not close(red,green)", "above(red,green) and not close(red,green)"),
    ("desk_cleanup", "in_bin(red) & not in_bin(red)", "both in_bin(red) and not in_bin(red)"),
    ("three_blocks", "close(red,red)", "close(red,red): a block cannot be related to itself"),
])
def test_contradictions_are_refused_before_any_state_naming_the_literals(scene: str, text: str, named: str) -> None:
    """Where the goal is read (``read_goal``: the planner node, the console's Preview), before any state."""
    with pytest.raises(GoalError, match=named.replace("(", r"\(").replace(")", r"\)")):
        read_goal(text, scene, LAYOUTS[scene].objects)


def test_a_goal_is_read_once_then_planned_and_run_without_the_parser(monkeypatch) -> None:
    """The planner node's path: the request is read where it enters, and from there to the sub-goal it publishes
    nothing reads the goal again (every reader is made to fail after the first read)."""
    from semgoal_planner import english, goals
    from semgoal_planner import executive as executive_module

    blocks = ("red", "green")
    said = "put the red block in the bin"
    goal = read_goal(said, "desk_cleanup", blocks)

    def refuse(*_args, **_kwargs):
        raise AssertionError("the goal was read again")

    for module, name in ((goals, "parse_english"), (goals, "parse_literal"), (goals, "split_literals"),
                         (english, "parse_english"), (goals, "read_goal"), (executive_module, "read_goal")):
        monkeypatch.setattr(module, name, refuse)
    executive = Executive(SemanticPlanner("desk_cleanup"))
    executive.observe(Observation(blocks, [Literal("in_bin", (b,), False) for b in blocks], 0))
    ok, message = executive.set_goal(goal)
    assert ok, message
    assert executive.goal == [Literal("in_bin", ("red",))] and said in message
    assert executive.active is not None and executive.active.subgoal.kind == "pick"


TABLETOP = ("red", "green", "blue", "yellow", "orange")


def on(*chain: str) -> list[Literal]:
    """A tower's facts, bottom first."""
    return [Literal("above", (top, below)) for below, top in itertools.pairwise(chain)]


@pytest.mark.parametrize(("text", "state", "expected"), [
    ("put the orange block on the tower", on("red", "green", "blue"), [Literal("above", ("orange", "blue"))]),
    ("stack orange on the tower", on("yellow", "red"), [Literal("above", ("orange", "red"))]),
    ("put orange next to the tower", on("red", "green", "blue"), [Literal("close", ("red", "orange"))]),
    ("keep orange away from the pile", on("blue", "red"), [Literal("close", ("blue", "orange"), False)]),
    # the block the goal moves is set aside: on top of the tower already, or a tower of its own with one block
    ("put orange on the tower", on("red", "green", "orange"), [Literal("above", ("orange", "green"))]),
    ("put orange on the tower", on("red", "green") + on("blue", "orange"), [Literal("above", ("orange", "green"))]),
    ("put orange on the tower", on("blue", "orange"), [Literal("above", ("orange", "blue"))]),
    # blocks put on the tower one after another: each on the one before
    ("put orange on the tower, then put yellow on the tower", on("red", "green"),
     [Literal("above", ("orange", "green")), Literal("above", ("yellow", "orange"))]),
    # several blocks put on it: each on the one before; 'the rest': every block not in it, in the order of the world's
    ("put orange and yellow on the tower", on("red", "green"),
     [Literal("above", ("orange", "green")), Literal("above", ("yellow", "orange"))]),
    ("put blue in the bin and the rest on the tower", on("red", "green"),
     [Literal("in_bin", ("blue",)), Literal("above", ("yellow", "green")), Literal("above", ("orange", "yellow"))]),
    # a block counted in the tower from either end, or its middle one
    ("put the second block from the top in the bin", on("red", "green", "blue", "yellow"), [Literal("in_bin", ("blue",))]),
    ("put the third block from the bottom next to orange", on("red", "green", "blue", "yellow"),
     [Literal("close", ("blue", "orange"))]),
    ("put the middle block in the bin", on("red", "green", "blue"), [Literal("in_bin", ("green",))]),
    ("swap the top two blocks", on("red", "green", "blue"),
     [Literal("above", ("green", "blue")), Literal("above", ("blue", "green"), False), Literal("above", ("blue", "red"))]),
    # the tower the goal builds, whatever stands
    ("build a tower of red and green, then put yellow next to the tower", on("blue", "orange"),
     [Literal("above", ("green", "red")), Literal("close", ("red", "yellow"))]),
    ("stack blue on red, then put orange on the tower", [], [Literal("above", ("blue", "red")),
                                                            Literal("above", ("orange", "blue"))]),
    # the tower's ends said as blocks: moved themselves, and never said to be off themselves
    ("put the top block in the bin", on("red", "green", "blue"), [Literal("in_bin", ("blue",))]),
    ("put the bottom block in the bin", on("red", "green", "blue"), [Literal("in_bin", ("red",))]),
    ("put the top block next to the bottom block", on("red", "green", "blue"), [Literal("close", ("red", "blue"))]),
    ("put the whole tower in the bin", on("red", "green", "blue"),
     [Literal("in_bin", (b,)) for b in ("red", "green", "blue")]),
    ("keep orange away from the entire stack", on("red", "green"),
     [Literal("close", (b, "orange"), False) for b in ("red", "green")]),
    ("take the top block off the tower", on("red", "green"),
     [Literal("above", ("green", b), False) for b in ("red", "blue", "yellow", "orange")]),
])
def test_the_tower_is_the_one_standing_when_the_goal_is_planned(text: str, state: list[Literal],
                                                                expected: list[Literal]) -> None:
    goal = read_goal(text, "tabletop", TABLETOP)
    assert parse_goal(text, "tabletop", TABLETOP, state) == expected
    assert goal.instantiate("tabletop", TABLETOP, state) == expected  # read once, placed when planned


def test_a_counted_block_must_be_in_the_tower() -> None:
    tower = on("red", "green", "blue", "yellow")
    with pytest.raises(GoalError, match=r"the tower has 4 blocks \(red, green, blue, yellow, from the bottom\), not 5"):
        parse_goal("put the fifth block from the top in the bin", "tabletop", TABLETOP, tower)
    with pytest.raises(GoalError, match="so no middle one"):
        parse_goal("put the middle block in the bin", "tabletop", TABLETOP, tower)


@pytest.mark.parametrize(("state", "words"), [
    ([], "no tower stands now"),
    ([Literal("in_bin", ("red",))], "no tower stands now"),
    (on("red", "green") + on("blue", "yellow"), r"2 towers stand now \(topped by green, yellow\)"),
])
def test_the_tower_must_be_one(state: list[Literal], words: str) -> None:
    goal = read_goal("put orange on the tower", "tabletop", TABLETOP)
    with pytest.raises(GoalError, match=words):
        goal.instantiate("tabletop", TABLETOP, state)


@pytest.mark.parametrize(("state", "expected"), [
    (on("red", "green"), [Literal("above", ("red", "green")), Literal("above", ("green", "red"), False)]),
    (on("green", "red"), [Literal("above", ("green", "red")), Literal("above", ("red", "green"), False)]),
    ([Literal("in_bin", ("green",))], [Literal("in_bin", ("red",)), Literal("in_bin", ("green",), False)]),
    ([Literal("in_bin", ("red",))], [Literal("in_bin", ("green",)), Literal("in_bin", ("red",), False)]),
])
def test_two_blocks_swapped_trade_the_places_they_have_when_planned(state: list[Literal],
                                                                    expected: list[Literal]) -> None:
    assert read_goal("swap green and red", "tabletop", TABLETOP).instantiate("tabletop", TABLETOP, state) == expected


def test_two_blocks_swapped_in_a_tower_keep_it_standing() -> None:
    """Green on blue, red on green: swapped, red stands on blue and green on red."""
    goal = read_goal("swap red and green", "tabletop", TABLETOP).instantiate("tabletop", TABLETOP, on("blue", "green", "red"))
    assert goal == [Literal("above", ("green", "red")), Literal("above", ("red", "green"), False),
                    Literal("above", ("red", "blue"))]


@pytest.mark.parametrize(("state", "words"), [
    ([], "neither is on the other, and both are out of the bin"),
    ([Literal("in_bin", ("red",)), Literal("in_bin", ("green",))], "both are in the bin"),
])
def test_blocks_with_no_places_to_trade_are_not_swapped(state: list[Literal], words: str) -> None:
    with pytest.raises(GoalError, match=words):
        read_goal("swap red and green", "tabletop", TABLETOP).instantiate("tabletop", TABLETOP, state)


@pytest.mark.parametrize(("text", "state", "tower"), [
    # nothing standing: the order named
    ("stack everything", [], ("red", "green", "blue", "yellow", "orange")),
    # the tallest tower standing stays at the bottom, the others on it in the order named
    ("stack everything", on("blue", "yellow") + on("orange", "green", "red"), ("orange", "green", "red", "blue", "yellow")),
    ("stack red, green and blue in any order", on("blue", "green", "yellow"), ("blue", "green", "red")),
    # a tower in the bin is no foot for a new one
    ("stack everything", [*on("blue", "yellow"), Literal("in_bin", ("blue",))], ("red", "green", "blue", "yellow", "orange")),
    # the goal's own 'x on y' kept, its pair moving as one, and the standing part it allows kept
    ("stack everything and put red on orange", on("blue", "yellow", "green"), ("blue", "yellow", "green", "orange", "red")),
    ("stack everything and put yellow on red", on("blue", "yellow", "green"), ("red", "yellow", "green", "blue", "orange")),
])
def test_a_tower_whose_order_is_left_open_is_ordered_by_what_stands_when_planned(text: str, state: list[Literal],
                                                                              tower: tuple[str, ...]) -> None:
    goal = read_goal(text, "tabletop", TABLETOP)
    placed = goal.instantiate("tabletop", TABLETOP, state)
    assert {lit for lit in placed if lit.name == "above"} == set(on(*tower))
    assert len(placed) == len(dict.fromkeys(placed))


@pytest.mark.parametrize(("text", "state", "tower"), [
    # an end named, the others in the order named between
    ("stack everything with yellow at the bottom", [], ("yellow", "red", "green", "blue", "orange")),
    ("stack all the blocks with red on top", [], ("green", "blue", "yellow", "orange", "red")),
    ("put all the blocks in one tower with the green one at the bottom and red at the top", [],
     ("green", "blue", "yellow", "orange", "red")),
    ("stack everything with orange on top and blue at the bottom", [], ("blue", "red", "green", "yellow", "orange")),
    # a tower standing kept only where it starts at the named bottom, and only up to the named top
    ("stack everything with yellow at the bottom", on("blue", "green"), ("yellow", "red", "green", "blue", "orange")),
    ("stack everything with blue at the bottom", on("blue", "green"), ("blue", "green", "red", "yellow", "orange")),
    ("stack everything with green on top", on("blue", "red", "green"), ("blue", "red", "yellow", "orange", "green")),
    # a block the goal puts in the bin afterwards leaves the others' tower whole
    ("stack all the blocks with red at the bottom, then put yellow in the bin", [], ("red", "green", "blue", "orange")),
])
def test_a_tower_left_open_keeps_the_end_the_goal_names(text: str, state: list[Literal], tower: tuple[str, ...]) -> None:
    placed = read_goal(text, "tabletop", TABLETOP).instantiate("tabletop", TABLETOP, state)
    assert {lit for lit in placed if lit.name == "above" and lit.value} == set(on(*tower))


def test_a_tower_left_open_is_planned_from_the_tower_standing() -> None:
    """Three blocks of five already stand: two steps for each of the two others, none to rebuild."""
    state = on("blue", "green", "red")
    executive = Executive(SemanticPlanner("tabletop"))
    executive.observe(Observation(TABLETOP, state, 0))
    ok, message = executive.set_goal("build one big tower")
    assert ok, message
    assert [str(s.subgoal) for s in executive.steps] == ["pick(yellow)", "put_on(yellow,red)", "pick(orange)",
                                                         "put_on(orange,yellow)"]


def test_a_tower_left_open_with_its_top_named_is_planned_from_what_stands_below_it() -> None:
    """Red tops a tower of three: it comes off, the two under it stay, and it goes back on last."""
    executive = Executive(SemanticPlanner("tabletop"))
    executive.observe(Observation(TABLETOP, on("blue", "green", "red"), 0))
    ok, message = executive.set_goal("stack everything with red on top")
    assert ok, message
    assert [str(s.subgoal) for s in executive.steps] == ["pick(red)", "put_on_table(red)", "pick(yellow)",
                                                         "put_on(yellow,green)", "pick(orange)", "put_on(orange,yellow)",
                                                         "pick(red)", "put_on(red,orange)"]
