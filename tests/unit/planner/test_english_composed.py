"""Sentences composed of independent clauses (no block named twice) read as the union of what each clause says alone,
however the clauses are joined: a list of objects stays with its clause ("orange far from purple and pink, and green
away from red"), a block between two clauses joins the first."""

from hypothesis import given, settings
from hypothesis import strategies as st

from semgoal_core.vocabulary import Literal
from semgoal_planner.english import parse_english

BLOCKS = ("red", "green", "blue", "yellow", "orange", "purple", "cyan", "pink")
JOINS = (" and ", ", ", ", and ", "; ", " and also ", ". ")


def _listed(blocks: list[str]) -> str:
    return blocks[0] if len(blocks) == 1 else ", ".join(blocks[:-1]) + " and " + blocks[-1]


@st.composite
def clauses(draw: st.DrawFn, free: list[str]) -> tuple[str, set[Literal], set[str]]:
    """One clause over blocks of ``free``: its text, its literals and the blocks it names."""
    kind = draw(st.sampled_from(["near", "away", "on", "bin", "out"] if len(free) >= 3 else ["bin", "out"]))
    if kind in ("near", "away"):
        subject, *objects = draw(st.lists(st.sampled_from(free), min_size=2, max_size=3, unique=True))
        phrase = draw(st.sampled_from(["next to", "near", "close to", "beside"] if kind == "near" else
                                      ["away from", "far from"]))
        verb = draw(st.sampled_from(["put ", "place ", "move ", "", "keep "]))
        literals = {Literal("close", tuple(sorted((subject, o), key=BLOCKS.index)), kind == "near") for o in objects}
        return f"{verb}{subject} {phrase} {_listed(objects)}", literals, {subject, *objects}
    if kind == "on":
        upper, lower = draw(st.lists(st.sampled_from(free), min_size=2, max_size=2, unique=True))
        verb = draw(st.sampled_from(["put ", "stack ", "place ", ""]))
        on = draw(st.sampled_from(["on", "on top of", "onto"]))
        return f"{verb}{upper} {on} {lower}", {Literal("above", (upper, lower))}, {upper, lower}
    if kind == "bin":
        binned = draw(st.lists(st.sampled_from(free), min_size=1, max_size=2, unique=True))
        verb = draw(st.sampled_from(["put ", "drop ", "place "]))
        return f"{verb}{_listed(binned)} {draw(st.sampled_from(['in', 'into']))} the bin", \
            {Literal("in_bin", (b,)) for b in binned}, set(binned)
    block = draw(st.sampled_from(free))
    return f"take {block} out of the bin", {Literal("in_bin", (block,), False)}, {block}


@st.composite
def sentences(draw: st.DrawFn) -> tuple[str, set[Literal]]:
    text, literals, named = draw(clauses(list(BLOCKS)))
    for _ in range(draw(st.integers(1, 2))):
        free = [b for b in BLOCKS if b not in named]
        more, said, blocks = draw(clauses(free))
        text, literals, named = text + draw(st.sampled_from(JOINS)) + more, literals | said, named | blocks
    return text, literals


@settings(max_examples=300, deadline=None)
@given(sentences())
def test_independent_clauses_read_as_the_union_of_their_literals(sentence: tuple[str, set[Literal]]) -> None:
    text, expected = sentence
    assert set(parse_english(text, "tabletop")) == expected, text
