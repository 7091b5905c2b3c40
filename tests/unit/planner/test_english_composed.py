"""Sentences composed of independent clauses (no block named twice), each with its verb, read as the union of what each
clause says alone, however the clauses are joined (at once or in turn): a list of objects stays with its clause
("orange far from purple and pink, and green away from red"), a block between two clauses joins the first, a later
clause keeps what an earlier one said of other blocks."""

from hypothesis import given, settings
from hypothesis import strategies as st

from semgoal_core.vocabulary import Literal
from semgoal_planner.english import parse_english

BLOCKS = ("red", "green", "blue", "yellow", "orange", "purple", "cyan", "pink")
JOINS = (" and ", ", ", ", and ", "; ", " and also ", ". ", " but ", ", then ")
PAIRED = ("near", "away", "not near", "together", "apart", "on", "not on")
"""The clauses over two or more blocks; the others name one or two."""


def _listed(blocks: list[str]) -> str:
    return blocks[0] if len(blocks) == 1 else ", ".join(blocks[:-1]) + " and " + blocks[-1]


def _close(a: str, b: str, value: bool) -> Literal:
    return Literal("close", tuple(sorted((a, b), key=BLOCKS.index)), value)


@st.composite
def clauses(draw: st.DrawFn, free: list[str], kinds: tuple[str, ...]) -> tuple[str, set[Literal], set[str]]:
    """One clause of ``kinds`` over blocks of ``free``: its text, its literals and the blocks it names."""
    kind = draw(st.sampled_from([k for k in kinds if len(free) >= 3 or k not in PAIRED]))
    if kind in ("near", "away", "not near"):
        subject, *objects = draw(st.lists(st.sampled_from(free), min_size=2, max_size=3, unique=True))
        listed = _listed(objects)
        text = {"near": f"{draw(st.sampled_from(['put', 'place', 'move']))} {subject} "
                        f"{draw(st.sampled_from(['next to', 'near', 'close to', 'beside']))} {listed}",
                "away": f"{draw(st.sampled_from(['keep', 'move']))} {subject} {draw(st.sampled_from(['away from', 'far from']))} "
                        f"{listed}",
                "not near": f"{subject} {draw(st.sampled_from(['should not be', 'must not be']))} next to {listed}"}[kind]
        return text, {_close(subject, o, kind == "near") for o in objects}, {subject, *objects}
    if kind in ("together", "apart"):
        group = draw(st.lists(st.sampled_from(free), min_size=2, max_size=3, unique=True))
        pairs = [(a, b) for i, a in enumerate(group) for b in group[i + 1:]]
        said = draw(st.sampled_from(["together", "next to each other"] if kind == "together" else
                                    ["apart", "away from each other"]))
        return f"{draw(st.sampled_from(['put', 'move']))} {_listed(group)} {said}", \
            {_close(a, b, kind == "together") for a, b in pairs}, set(group)
    if kind in ("on", "not on"):
        upper, lower = draw(st.lists(st.sampled_from(free), min_size=2, max_size=2, unique=True))
        if kind == "not on":
            return f"don't put {upper} on {lower}", {Literal("above", (upper, lower), False)}, {upper, lower}
        on = draw(st.sampled_from(["on", "on top of", "onto"]))
        return f"{draw(st.sampled_from(['put', 'stack', 'place']))} {upper} {on} {lower}", \
            {Literal("above", (upper, lower))}, {upper, lower}
    if kind == "bin":
        binned = draw(st.lists(st.sampled_from(free), min_size=1, max_size=2, unique=True))
        return f"{draw(st.sampled_from(['put', 'drop', 'place']))} {_listed(binned)} in the bin", \
            {Literal("in_bin", (b,)) for b in binned}, set(binned)
    block = draw(st.sampled_from(free))
    return {"out": (f"take {block} out of the bin", {Literal("in_bin", (block,), False)}),
            "not bin": (draw(st.sampled_from([f"don't put {block} in the bin", f"keep {block} out of the bin"])),
                        {Literal("in_bin", (block,), False)}),
            "hold": (f"{draw(st.sampled_from(['pick up', 'hold', 'grab']))} {block}", {Literal("holding", (block,))}),
            "keep": (draw(st.sampled_from([f"leave {block} alone", f"don't move {block}", f"keep {block} where it is"])),
                     {Literal("keep", (block,))}),
            "table": (f"put {block} on the table", {Literal("holding", (block,), False), Literal("in_bin", (block,), False),
                                                    *(Literal("above", (block, o), False) for o in BLOCKS if o != block)}),
            }[kind] + ({block},)


@st.composite
def sentences(draw: st.DrawFn) -> tuple[str, set[Literal]]:
    """Two or three clauses: the first says where a block goes (a goal of keeps alone is refused), one at most takes a
    block in hand."""
    kinds = ("near", "away", "not near", "together", "apart", "on", "not on", "bin", "out", "not bin", "table")
    text, literals, named = draw(clauses(list(BLOCKS), kinds))
    held = False
    for _ in range(draw(st.integers(1, 2))):
        more, said, blocks = draw(clauses([b for b in BLOCKS if b not in named], (*kinds, "keep", *(() if held else ("hold",)))))
        held |= any(lit.name == "holding" and lit.value for lit in said)
        text, literals, named = text + draw(st.sampled_from(JOINS)) + more, literals | said, named | blocks
    return text, literals


@settings(max_examples=400, deadline=None)
@given(sentences())
def test_independent_clauses_read_as_the_union_of_their_literals(sentence: tuple[str, set[Literal]]) -> None:
    text, expected = sentence
    assert set(parse_english(text, "tabletop")) == expected, text
