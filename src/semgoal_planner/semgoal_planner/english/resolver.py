"""Pass 3: references resolved in the world's blocks ('it', 'them', 'all except red', 'the others'), each
clause turned into the scene's literals."""

from __future__ import annotations

import itertools
from collections.abc import Iterable, Sequence
from dataclasses import replace

from semgoal_core.vocabulary import LAYOUTS, Literal
from semgoal_planner.english.grammar import ANY_ORDER_TOWER, OPPOSABLE, Clause, Ref
from semgoal_planner.english.words import UNORDERED_TOWER, LanguageError, examples

TOWER_TOP, TOWER_BASE, TOWER_ALL, TOWER_REST = "tower_top", "tower_base", "tower_all", "tower_rest"
"""What 'the tower' stands for in a goal's literals until it is planned (:func:`~semgoal_planner.goals.the_tower`):
its top block where a block goes on it, its bottom one where a block goes near it or away from it."""
TOWER_PLACES = {"on": TOWER_TOP, "near": TOWER_BASE, "away": TOWER_BASE}
TOWER_ENDS = {"top": TOWER_TOP, "base": TOWER_BASE, "whole": TOWER_ALL}
"""'the top block', 'the bottom block': the tower's ends, as subjects or objects of any relation; 'the whole tower':
each of its blocks, as a subject."""
OTHERS = ("other", "the_other")
"""The blocks not named: 'the others', and 'the other block', which must be one."""
TOP_PREFIX, BOTTOM_PREFIX, TOWER_MIDDLE = "tower_top_", "tower_bottom_", "tower_middle"
"""'the second block from the top' (``tower_top_2``), '... from the bottom' (``tower_bottom_2``), 'the middle block':
in a goal's literals until it is planned (:func:`~semgoal_planner.goals.the_tower`)."""
HELD = "block_held"
"""'whatever you are holding': ``block_held`` in a goal's literals until it is planned
(:func:`~semgoal_planner.goals.relative`)."""
IN_BIN_BLOCK = "block_in_bin"
"""'the block that is in the bin': ``block_in_bin`` in a goal's literals until it is planned
(:func:`~semgoal_planner.goals.relative`)."""
ON_PREFIX, UNDER_PREFIX = "block_on_", "block_under_"
"""'the block on red', 'the block under green': ``block_on_red``, ``block_under_green`` in a goal's literals until it is
planned (:func:`~semgoal_planner.goals.relative`)."""
SWAP = "swap"
"""A goal's stand-in ``swap(a,b)`` until it is planned (:func:`~semgoal_planner.goals.swapped`): the two blocks
trade places, which only the world then can say (which is on which, which is in the bin)."""
STACK = "stack"
"""A goal's stand-in ``stack(a,b,...)`` until it is planned (:func:`~semgoal_planner.goals.stacked`): one tower of the
blocks in an order the goal leaves open ("stack everything"), which the world then suggests."""
ALL_BUT_PREFIX = "all_but_"
"""'every block except the one you are holding': ``all_but_block_held`` (the prefix before any other stand-in) in a goal's
literals until it is planned (:func:`~semgoal_planner.goals.every_block_but`): which block is left out, only the world
can say then."""
KEEP = "keep"
"""A goal's stand-in ``keep(a)`` until it is planned (:func:`~semgoal_planner.goals.kept`): 'don't move red', 'leave
the rest alone' keep a block's place as the world has it then."""
PLACED_WHEN_PLANNED = {
    TOWER_TOP: "the top block of the tower standing when the goal is planned",
    TOWER_BASE: "the bottom block of the tower standing when the goal is planned",
    TOWER_ALL: "each block of the tower standing when the goal is planned",
    TOWER_REST: "each block not in the tower standing when the goal is planned",
    SWAP: "the two blocks trade the places they have when the goal is planned (the one on the other goes under it, "
          "onto what the other stood on, or the one in the bin comes out); swap(tower_all): the tower standing then, "
          "built again upside down",
    HELD: "the block in the hand when the goal is planned",
    IN_BIN_BLOCK: "the one block in the bin when the goal is planned",
    TOP_PREFIX: "(tower_top_K) the K-th block from the top of the tower standing when the goal is planned",
    BOTTOM_PREFIX: "(tower_bottom_K) the K-th block from the bottom of the tower standing when the goal is planned",
    TOWER_MIDDLE: "the middle block of the tower standing when the goal is planned (of an odd number of blocks)",
    ON_PREFIX: "(block_on_COLOUR) the block standing on that block when the goal is planned",
    UNDER_PREFIX: "(block_under_COLOUR) the block that block stands on when the goal is planned",
    STACK: "one tower of these blocks, in an order left open: what already stands of it (its tallest part on the "
           "table) at the bottom, the others on it in the order named",
    ALL_BUT_PREFIX: "(all_but_X) each block but the one stand-in X names when the goal is planned",
    KEEP: "the block's place as it is when the goal is planned: in the bin or not, in the hand or not, on which block "
          "(not closeness: another block may still be put next to it); a block the goal itself moves is not kept",
}
"""What each stand-in of a goal's literals means, for people reading them (``./semgoal parse-goal``)."""


def stack_order(blocks: Sequence[str], fixed: Iterable[tuple[str, str]], standing: Iterable[Sequence[str]],
                bottom: str | None = None, top: str | None = None) -> list[str]:
    """The order, bottom first, of one tower of ``blocks`` whose order a goal left open (:data:`STACK`). Each pair the
    goal ``fixed`` (upper, lower) is kept, its run of blocks moving as one; the goal's ``bottom`` block (on no other)
    goes first and its ``top`` block (none on it) last; the most of a tower already ``standing`` (bottom first, on the
    table) that all this allows stays at the bottom; the other runs go on it in the order named."""
    below = {upper: lower for upper, lower in fixed if upper in blocks and lower in blocks}
    on = {lower: upper for upper, lower in below.items()}
    runs = {}  # each run by its lowest block
    for block in (b for b in blocks if b not in below):
        runs[block] = [block]
        while runs[block][-1] in on and on[runs[block][-1]] not in runs[block]:
            runs[block].append(on[runs[block][-1]])
    last = next((low for low, run in runs.items() if run[-1] == top), None)

    def kept(tower: Sequence[str]) -> tuple[int, list[str]]:
        """How many of the tower's blocks stay as they stand, and the runs, lowest block first, that keep them."""
        lowest, height = [], 0
        if bottom in runs and tower[:1] != [bottom]:
            return 0, []
        while height < len(tower) and tower[height] in runs and tower[height] not in lowest:
            run = runs[tower[height]]
            if run[:len(tower) - height] != list(tower[height:height + len(run)]) or (
                    tower[height] == last and len(lowest) + 1 < len(runs)):  # the top run stays for the top
                break
            lowest.append(tower[height])
            height = min(height + len(run), len(tower))
        return height, lowest

    height, lowest = max((kept(list(tower)) for tower in standing), default=(0, []), key=lambda found: found[0])
    first = lowest if height >= 2 else [bottom] if bottom in runs else []
    then = [low for low in runs if low not in first and low != last] + ([last] if last and last not in first else [])
    return [b for low in (*first, *then) for b in runs[low]]


def stacks_in_order(literals: Sequence[Literal], standing: Iterable[Sequence[str]] = ()) -> list[Literal]:
    """``literals`` with each tower left open (:data:`STACK`) made 'x on y' in the order :func:`stack_order` chooses:
    the goal's own 'x on y' kept, a block it puts on none of the others at the bottom ("stack everything with red at
    the bottom") and one it puts none of them on at the top, the most of a tower ``standing`` (bottom first) kept at
    the bottom."""
    fixed = [lit.args for lit in literals if lit.name == "above" and lit.value]
    denied = {lit.args for lit in literals if lit.name == "above" and not lit.value}
    standing = list(standing)
    made = []
    for literal in literals:
        if literal.name != STACK:
            made.append(literal)
            continue
        blocks = literal.args
        bottom = next((b for b in blocks if all((b, o) in denied for o in blocks if o != b)), None)
        top = next((b for b in blocks if all((o, b) in denied for o in blocks if o != b)), None)
        order = stack_order(blocks, fixed, standing, bottom, top)
        made += [Literal("above", (upper, lower)) for lower, upper in itertools.pairwise(order)]
    return made


def is_stand_in(name: str) -> bool:
    """Whether a literal's argument stands for a block only the world can name when the goal is planned."""
    return name in PLACED_WHEN_PLANNED or name.startswith((ON_PREFIX, UNDER_PREFIX, TOP_PREFIX, BOTTOM_PREFIX,
                                                          ALL_BUT_PREFIX))


def is_tower_place(name: str) -> bool:
    """Whether a literal's argument stands for a block of 'the tower' (its top, bottom, a level, all or the rest)."""
    return name in (TOWER_TOP, TOWER_BASE, TOWER_ALL, TOWER_REST, TOWER_MIDDLE) or name.startswith((TOP_PREFIX,
                                                                                                   BOTTOM_PREFIX))
"""The relations 'the tower' may be the object of, and which of its blocks each one means."""


class Resolver:
    """References -> blocks of the world, clauses -> literals, in the order the sentence says them."""

    def __init__(self, scene: str, blocks: Sequence[str]) -> None:
        self.scene, self.blocks = scene, tuple(blocks)
        self.examples = examples(scene, blocks)
        self.mentioned: list[str] = []
        self.last: tuple[str, ...] = ()
        """The blocks the clause before was about (what 'it' names)."""
        self.last_named: tuple[str, ...] = ()
        """Every block the clause before named, subjects and objects (what 'them' names)."""
        self.last_built = False
        """Whether the clause before built a tower (what 'it' names then)."""
        self.stated: Clause | None = None
        """The last clause that said its relation (what an ellipsis such as 'but not green' borrows)."""
        self.tower_named = False
        """Whether a clause before named the tower as a whole, or as where a block goes (what 'the rest' leaves out)."""
        self.built_top: str | None = None
        """The top block of the last tower a clause built ("put red on green and blue on top": blue goes on red)."""
        self.object_it: tuple[str, ...] | None = None
        """What 'it' named as the clause before's place, which the next clause's 'it' in that place names too ("put
        blue next to it and yellow away from it")."""
        self.carried: set[tuple[str, ...]] = set()
        """The towers built before that 'it' moves whole ("stack red, green and blue, then put it next to yellow"):
        their bottom blocks move, and what stands on them stays."""

    def blocks_of(self, refs: Iterable[Ref], besides: tuple[str, ...] = ()) -> tuple[str, ...]:
        """The blocks ``refs`` name; ``besides``: the clause's subjects, which an object's 'it' is not."""
        found: list[str] = []
        for ref in refs:
            for block in self._one(ref, besides):
                if block not in found:
                    found.append(block)
        return tuple(found)

    def _one(self, ref: Ref, besides: tuple[str, ...]) -> tuple[str, ...]:
        if ref.kind in ("colours", "only"):
            for colour in ref.colours:
                if colour not in self.blocks and not is_stand_in(colour):  # a resolved clause's stand-ins
                    raise LanguageError(f"there is no {colour} block here: the blocks are {', '.join(self.blocks)}")
            return ref.colours
        if ref.kind in ("upper", "lower"):  # "the block on red": the one standing on it when planned
            self._one(Ref("colours", ref.colours), besides)  # refused where red is not here
            return ((ON_PREFIX if ref.kind == "upper" else UNDER_PREFIX) + ref.colours[0],)
        if ref.kind == "held":  # "whatever you are holding": the block in the hand when planned
            return (HELD,)
        if ref.kind == "binned":  # "the block that is in the bin": the one there when planned
            return (IN_BIN_BLOCK,)
        if ref.kind == "level":  # "the second block from the top": counted in the tower when planned
            said = ref.colours[0]
            return (TOWER_MIDDLE if said == "the_middle" else
                    (TOP_PREFIX if said.startswith("the_top") else BOTTOM_PREFIX) + said[-1],)
        if ref.kind == "tower":  # placed by literals(), which knows the relation
            return ("tower",)
        if ref.kind in TOWER_ENDS:  # "the top block": stands in the literals until the goal is planned
            return (TOWER_ENDS[ref.kind],)
        if ref.kind == "all":
            excluded = set(self.blocks_of(ref.excluded))
            if TOWER_ALL in excluded:  # "all except the tower": which blocks, only the world can say when planned
                if len(excluded) > 1:
                    raise LanguageError("leave out either the tower or blocks named one by one, not both: e.g. "
                                        "'put every block except the tower in the bin'")
                return (TOWER_REST,)
            placed_later = [b for b in excluded if is_stand_in(b)]
            if placed_later:  # "all except the block you are holding": which one, only the world can say when planned
                if len(excluded) > 1:
                    raise LanguageError("leave out one block named by where it is, or blocks named by colour, not "
                                        "both: e.g. 'put every block except the one you are holding in the bin'")
                return (ALL_BUT_PREFIX + placed_later[0],)
            return tuple(b for b in self.blocks if b not in excluded)
        if ref.kind == "both":  # "red next to green and blue away from both": the two the clause before named
            pair = tuple(b for b in self.last_named if b not in besides)
            if len(pair) == 2:
                return pair
            if len(self.blocks) == 2:
                return self.blocks
            raise LanguageError(f"'both' is ambiguous: say which two blocks ({', '.join(self.blocks)})")
        if ref.kind in OTHERS:  # not the blocks named before, nor the clause's own ("red on top") where some remain
            if self.tower_named:  # "orange on the tower and the rest in the bin": nor the tower's blocks, which only
                return (TOWER_REST,)  # the world can say when planned
            unnamed = tuple(b for b in self.blocks if b not in self.mentioned)
            others = tuple(b for b in unnamed if b not in besides)
            if not others and set(unnamed) & set(besides):  # "red next to green, and blue away from the others": the
                others = tuple(b for b in self.blocks if b not in besides)  # blocks other than the clause's own
            others = others or unnamed
            if not others:
                raise LanguageError("'the other(s)': every block is already named")
            if ref.kind == "the_other" and len(others) > 1:
                raise LanguageError(f"'the other block' could be any of {', '.join(others)}: say which by colour, or "
                                    "'the others' for all of them")
            return others
        if ref.kind == "it":
            if self.last == (TOWER_ALL,) and besides:  # "reverse the tower and put yellow on it": the tower, where
                return ("tower",)  # a block goes on it or by it
            if self.last_built and not set(besides) & set(self.last):  # "make a tower of red and green, put blue next
                if besides:  # to it"; "..., put it in the bin": its bottom block, the tower on it
                    return ("tower",)
                self.carried.add(self.last)
                return self.last[:1]
            if besides and set(self.last) <= set(besides):  # "red next to green, not on it": 'it' is green
                named = tuple(b for b in self.last_named if b not in besides)
                if len(named) == 1:
                    return named
            if len(self.last) == 1:
                return self.last
            if len(self.blocks) == 1:
                return self.blocks
            raise LanguageError(f"'it' or 'the block' is ambiguous: say which block ({', '.join(self.blocks)})")
        if len(self.last) >= 2 and not set(self.last) & set(besides):  # "put red and green next to blue and yellow away
            return self.last  # from them": the blocks the clause before moved
        return self.last_named or self.blocks  # them: those named before, or, said first, every block here

    def subjects_of(self, clause: Clause) -> tuple[str, ...]:
        """The blocks a clause is about (those of the clause before where it names none); 'the other' is not a block the
        clause names ("put the other block on red", "swap red with the other block")."""
        if not clause.subjects:
            return self.last
        named = tuple(block for ref in (*clause.subjects, *clause.objects) if ref.kind == "colours" for block in ref.colours)
        return self.blocks_of(clause.subjects, besides=named if any(ref.kind in OTHERS for ref in clause.subjects) else ())

    def literals(self, clause: Clause, before: Clause | None) -> tuple[list[tuple[Literal, bool]], Clause]:
        """The clause's literals, each with whether it is generic (said of all blocks or the others, so a
        literal on a named block overrides it), and the clause as completed (an ellipsis borrows from
        ``before``)."""
        borrows_relation = clause.elliptic and not clause.kind
        if clause.elliptic:
            if before is None:
                raise LanguageError(f"the goal starts mid-sentence: say what to do, e.g. {self.examples}")
            stated = self.stated or before  # "red in the bin, not green and not blue": each 'not' against 'in the bin'
            if clause.kind:  # "... and away from blue": the subjects of the clause before
                clause = replace(clause, subjects=clause.subjects or before.subjects, elliptic=False)
            elif stated.kind == "together" and clause.negated and not stated.negated:  # "red and green together, but
                clause = replace(clause, kind="away", objects=stated.subjects, elliptic=False, negated=False)  # not blue"
            else:  # "... but not green": the relation of the clause that said one
                clause = replace(stated, subjects=clause.subjects,
                                 negated=not clause.affirmed and stated.negated != clause.negated)
        unordered = clause.kind == ANY_ORDER_TOWER or (clause.kind == "tower" and (
            len(clause.subjects) < 2 or any(ref.kind != "colours" for ref in clause.subjects)))
        if unordered and clause.negated:  # "make them touch but not stack": none of them on another
            clause, unordered = replace(clause, kind="tower"), False
        if clause.kind == "release" and not self.last and clause.subjects and all(r.kind == "it" for r in clause.subjects):
            clause = replace(clause, subjects=(Ref("held"),))  # "drop it", said first: the block in the hand
        if clause.kind == "unstack" and self.last_built and clause.subjects and all(r.kind == "it" for r in clause.subjects):
            clause = replace(clause, subjects=(Ref("colours", self.last),))  # "build a tower ..., then knock it down":
            # each of its blocks off the others
        subjects = self.subjects_of(clause)
        if clause.kind == "on" and clause.subjects and all(r.kind in ("all", "other") and not r.excluded for r in
                                                            clause.subjects) and Ref("tower") in clause.objects:
            subjects = (TOWER_REST,)  # "put the rest on the tower": the blocks not in it, each on the one before
        if not subjects and clause.kind == "release":  # "let go" with nothing picked before: the hand empty
            subjects = self.blocks
        if not subjects and unordered and len(self.blocks) == 2 and not clause.negated:  # "build a tower" where two
            subjects = self.blocks  # blocks are all there is: the two, either on the other
        if not subjects:
            raise LanguageError(UNORDERED_TOWER if clause.kind in ("tower", ANY_ORDER_TOWER) else
                                f"say which block: {', '.join(self.blocks)}")
        if clause.kind == "on" and clause.objects == (Ref("other"),) and self.built_top and self.built_top not in subjects:
            objects = (self.built_top,)  # "... and blue on top": on the tower just built, not on a block not named
        elif (self.object_it and clause.objects == (Ref("it"),) and not set(self.object_it) & set(subjects)
              and clause.kind != "on"):  # the same place as the clause before's 'it' (no block goes on one that has one)
            objects = self.object_it
        else:
            objects = self.blocks_of(clause.objects, besides=subjects)
        self.object_it = objects if clause.objects == (Ref("it"),) else None
        if borrows_relation and clause.kind == "on" and not clause.negated and len(objects) == 1 \
                and self.built_top not in (None, *subjects, *objects):  # "stack green on red, then blue (and yellow)":
            objects = (self.built_top,)  # on green, as red has a block on it already
        if set(subjects) & set(objects) & set(PLACED_WHEN_PLANNED) or (TOWER_TOP in subjects and "tower" in objects):
            raise LanguageError("a block of the tower cannot be placed on or by itself: name the other block")
        if ({TOWER_ALL, TOWER_REST} & set(objects) and clause.kind not in ("near", "away")) or (
                {TOWER_ALL, TOWER_REST} & set(subjects) and clause.kind in ("on", "under", "hold")
                and not (subjects == (TOWER_REST,) and objects == ("tower",))):
            raise LanguageError("the whole tower goes in the bin, onto the table, near or away from a block: its "
                                "blocks cannot go on one block, or into one hand")
        if "tower" in objects:
            if clause.kind not in TOWER_PLACES:
                raise LanguageError(f"a block goes on the tower, next to it or away from it: e.g. "
                                    f"'put {subjects[0]} on the tower'")
            objects = tuple(TOWER_PLACES[clause.kind] if b == "tower" else b for b in objects)
        if clause.kind == "out_bin" and all(s.startswith(ON_PREFIX) or (is_tower_place(s) and s not in (TOWER_ALL, TOWER_REST))
                                            for s in subjects):
            clause = replace(clause, kind="off")  # "remove the top block", "the block on red": off, not out of the bin
        if clause.negated and clause.kind == "unstack":  # not every 'not above' at once: that is no state at all
            raise LanguageError("'not unstack' asks for nothing: a tower left standing needs no goal; say where the "
                                "blocks should be, e.g. 'stack red on green'")
        if clause.kind == "table" and clause.negated:  # "red should not be on the table": as "nothing on the table"
            if "in_bin" not in LAYOUTS[self.scene].scene.predicates:
                raise LanguageError(f"'not on the table' leaves open where {' and '.join(subjects)} should be: say where, "
                                    f"e.g. 'put {subjects[0]} on {next(b for b in self.blocks if b not in subjects)}' or "
                                    f"'hold {subjects[0]}'")
            clause = replace(clause, kind="in_bin", negated=False)  # where the scene has a bin, into it
        self.mentioned += [b for b in (*subjects, *objects) if b not in self.mentioned]
        self.tower_named |= TOWER_ALL in subjects or bool(set(objects) & {TOWER_TOP, TOWER_BASE, TOWER_ALL})
        generic = any(ref.kind in ("all", "other") for ref in clause.subjects)
        said = [(lit, generic) for lit in (self._unordered_tower(subjects, objects) if unordered else
                                           self._relation(clause.kind, subjects, objects, clause.negated))]
        if not said and objects:
            raise LanguageError(f"{' and '.join(subjects)} cannot be {clause.kind} itself: say which block")
        # "all except red" and "only red": the blocks left out explicitly not
        excluded = [b for ref in clause.subjects if ref.kind == "all" for b in self.blocks_of(ref.excluded)]
        if (clause.kind == "table" and not clause.negated) or clause.kind == "keep":  # "put every block but red on the
            excluded = []  # table", "don't move anything except red": red is left free, not cleared into the bin as the
            # blocks 'only' leaves out are
        if any(ref.kind == "only" for ref in clause.subjects):
            excluded += [b for b in self.blocks if b not in subjects and b not in objects]
        if excluded == [TOWER_ALL]:  # "clear the table except the tower": it stays as it stands
            said.append((Literal(KEEP, (TOWER_ALL,)), False))
            excluded = []
        if excluded and clause.kind == "table" and "in_bin" in LAYOUTS[self.scene].scene.predicates:
            said += [(Literal("in_bin", (b,)), False) for b in excluded]  # "leave only blue on the table": the rest
            excluded = []  # cleared into the bin
        if excluded and clause.kind not in ("together", "apart") and not unordered:  # a group says nothing of those left out
            if clause.kind not in OPPOSABLE:
                raise LanguageError(f"'except' or 'only' leaves {' and '.join(excluded)} unclear here: "
                                    "say where they go")
            said += [(lit.negated(), False) for b in excluded for lit in self._relation(clause.kind, (b,), objects)]
        self.last = subjects
        self.last_built = clause.kind == "tower" and not clause.negated and not unordered
        if clause.kind in ("on", "tower") and not clause.negated and not unordered and not any(map(is_stand_in, subjects)):
            self.built_top = subjects[-1]
        self.last_named = subjects + tuple(b for b in objects if b not in subjects)
        resolved = replace(clause, subjects=(Ref("colours", subjects),), objects=(Ref("colours", objects),) if objects else ())
        if not borrows_relation:
            self.stated = resolved
        return [(lit.negated() if clause.negated else lit, g) for lit, g in said], resolved

    def _unordered_tower(self, subjects: tuple[str, ...], objects: tuple[str, ...]) -> list[Literal]:
        """'stack everything', 'build a tower of them': one tower of ``subjects``, its order left to the world."""
        if objects or any(is_stand_in(block) for block in subjects):
            raise LanguageError(UNORDERED_TOWER)
        if len(subjects) < 2:
            raise LanguageError(f"a tower needs two or more blocks, not only {subjects[0]}: {UNORDERED_TOWER}")
        return [Literal(STACK, subjects)]

    def _relation(self, kind: str, subjects: tuple[str, ...], objects: tuple[str, ...],
                  negated: bool = False) -> Iterable[Literal]:
        """The literals of ``kind`` over the blocks; ``negated``: said with 'not', so several blocks 'not on green'
        are each not on it, where said plainly they stand one on another."""
        others = lambda block: [b for b in self.blocks if b != block]  # noqa: E731
        if kind in ("in_bin", "off_table"):
            return (Literal("in_bin", (s,)) for s in subjects)
        if kind == "out_bin":
            return (Literal("in_bin", (s,), False) for s in subjects)
        if kind == "keep":  # "don't move red": red's place kept, as it is when planned
            return (Literal(KEEP, (s,)) for s in subjects)
        if kind == "hold":  # two held at once are refused by the consistency check, unless a later clause of the
            return (Literal("holding", (s,)) for s in subjects)  # conjunction moves them ("pick up red and green and put
            # both in the bin"); "red and green should not be held": neither is
        if kind == "release":
            return (Literal("holding", (s,), False) for s in subjects)
        if kind == "away" and not objects:  # "move green away": from every other block; on a desk, into the bin
            if "close" not in LAYOUTS[self.scene].scene.predicates:
                return (Literal("in_bin", (s,)) for s in subjects)
            return (Literal("close", (s, o), False) for s in subjects for o in others(s))
        if kind == "apart" and len(subjects) == 1:  # "separate red": from every other block
            return (Literal("close", (subjects[0], o), False) for o in others(subjects[0]))
        if kind in ("near", "away", "on", "under") and not objects:
            raise LanguageError(f"say which block it goes {kind.replace('_', ' ')}")
        pairs = [(s, o) for s in subjects for o in objects if s != o]
        if kind == "near":
            return (Literal("close", p) for p in pairs)
        if kind == "away":
            return (Literal("close", p, False) for p in pairs)
        if kind == "on" and objects == (TOWER_TOP,) and (subjects == (TOWER_REST,) or not any(map(is_stand_in, subjects))):
            return (Literal("above", (s, TOWER_TOP)) for s in subjects)  # "put orange and red on the tower", "the rest":
            # each on the one put there before
        if kind == "on" and negated and not set(objects) & set(subjects):  # "neither red nor blue on green", "red not
            return (Literal("above", pair) for pair in pairs)  # on blue or yellow": each not on any of them
        if (kind == "on" and len(objects) == 1 and len(subjects) > 1 and objects[0] not in subjects
                and not any(map(is_stand_in, (*subjects, *objects)))):
            chain = (*objects, *subjects)  # "put yellow, orange and purple on red": each on the one named before it
            return (Literal("above", (upper, lower)) for lower, upper in itertools.pairwise(chain))
        if kind in ("on", "under"):
            if len(objects) > 1 or len(subjects) > 1:
                raise LanguageError("a block goes on one block, and one block on it: say which on which")
            return (Literal("above", p if kind == "on" else p[::-1]) for p in pairs)
        if kind == "off":
            return (Literal("above", (s, o), False) for s in subjects for o in (objects or others(s)) if s != o)
        if kind == "tower" and negated:  # "do not stack red and green": none of them on another, either way; "do not
            if len(subjects) == 1:  # stack red": on no other block
                return (Literal("above", (subjects[0], o)) for o in others(subjects[0]))
            return (Literal("above", pair) for pair in itertools.permutations(subjects, 2))
        if kind == "tower":  # the first named at the bottom
            return (Literal("above", (top, bottom)) for bottom, top in itertools.pairwise(subjects))
        if kind == "swap":  # two blocks, or (TOWER_ALL,): "reverse the tower", the one standing when planned
            if len(subjects) != 2 and subjects != (TOWER_ALL,):
                raise LanguageError(f"'swap' trades the places of two blocks, not {len(subjects)}: say which two")
            return [Literal(SWAP, subjects)]
        if kind == "unstack":
            return (Literal("above", (s, o), False) for s in subjects for o in others(s))
        if kind in ("together", "apart"):
            if len(subjects) < 2:
                raise LanguageError(f"'{kind}' needs two or more blocks")
            return (Literal("close", p, kind == "together") for p in itertools.combinations(subjects, 2))
        return self._on_table(subjects)

    def _on_table(self, subjects: tuple[str, ...]) -> Iterable[Literal]:
        """On the table: out of the hand, and (where the scene says so) out of the bin, on no block."""
        predicates = LAYOUTS[self.scene].scene.predicates
        for s in subjects:
            yield Literal("holding", (s,), False)
            if "in_bin" in predicates:
                yield Literal("in_bin", (s,), False)
            if "above" in predicates:
                yield from (Literal("above", (s, o), False) for o in self.blocks if o != s)
