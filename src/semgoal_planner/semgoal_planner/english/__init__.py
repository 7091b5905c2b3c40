"""Plain-English goals: a sentence becomes the scene's literals, or a refusal that says why.

Offline and grammar-based (the paper's future work asks for "a language interface which can translate
natural language sentences to semantic goals"). Three passes, each small:

1. **Normalise**: lower-case; phrases and synonyms become one canonical word each (``next to`` ->
   ``near``, ``place`` -> ``put``, ``box`` -> ``bin``); fillers go (``please``, ``the``, ``block``, ``is``).
   A word that is neither canonical nor known is refused, naming it.
2. **Parse** the canonical words with a lark Earley grammar (:data:`GRAMMAR`) into clauses: an action, a
   state or an ellipsis (``... but not green``), joined by ``and`` (all at once) or ``then`` (later clauses
   override earlier ones on the same atom: the state at the end).
3. **Resolve** references in the world's blocks (``it``, ``them``, ``all except red``, ``the others``) and
   turn each clause into literals; the scene's vocabulary checks them (:meth:`SemanticLayout.validate`).

What a sentence becomes (``PHRASES`` in the tests hold many more)::

    put the red block in the bin                 in_bin(red)
    clean up the desk but leave green out        in_bin(red) & in_bin(blue) & ... & not in_bin(green)
    stack red on green                           above(red,green)
    keep red away from green and blue            not close(red,green) & not close(red,blue)
    pick up blue                                 holding(blue)
    put orange on the tower                      above(orange,tower_top): the top of the tower standing when planned
    put the bottom block in the bin              in_bin(tower_base): the tower's bottom block when planned
    stack green on blue but don't move red       above(green,blue) & keep(red): red's place as it is when planned
    swap red and green                           swap(red,green): which is on which (or in the bin) when planned
    reverse the tower                            swap(tower_all): the tower standing when planned, upside down

The literals are what the operator is shown before anything moves.
"""

from __future__ import annotations

from collections.abc import Sequence

import lark

from semgoal_core.consistency import ContradictionError, check_consistent
from semgoal_core.vocabulary import LAYOUTS, Literal, SemanticLayout, VocabularyError
from semgoal_planner.english.grammar import Clause, Clauses, parse
from semgoal_planner.english.resolver import (
    ALL_BUT_PREFIX,
    HELD,
    KEEP,
    ON_PREFIX,
    PLACED_WHEN_PLANNED,
    STACK,
    SWAP,
    TOWER_ALL,
    TOWER_BASE,
    TOWER_REST,
    TOWER_TOP,
    UNDER_PREFIX,
    Resolver,
    is_stand_in,
    stacks_in_order,
)
from semgoal_planner.english.words import (
    AFFIRMED,
    ANY_ORDER,
    BUT_LEAVE,
    IN_PLACE,
    INTO_A_TOWER,
    MAX_GOAL_CHARS,
    TOP_DOWN,
    UNDER_A_TOWER,
    LanguageError,
    examples,
    normalise,
)

__all__ = ["ALL_BUT_PREFIX", "HELD", "KEEP", "MAX_GOAL_CHARS", "ON_PREFIX", "PLACED_WHEN_PLANNED", "STACK", "SWAP", "TOWER_ALL",
           "TOWER_BASE", "TOWER_REST", "TOWER_TOP", "UNDER_PREFIX", "LanguageError", "examples", "normalise", "parse_english"]


def parse_english(text: str, scene: str, blocks: Sequence[str] | None = None) -> list[Literal]:
    """The literals a sentence asks for in ``scene`` with ``blocks`` present (default: all of the scene's).

    Clauses joined by ``and`` hold together (a contradiction is refused); a clause after ``then`` overrides
    the earlier ones on the same atom. Raises :class:`LanguageError` with a message naming what is wrong.
    """
    layout = LAYOUTS[scene]
    blocks = tuple(blocks or layout.objects)
    words = normalise(text, scene, blocks)
    try:
        tree = parse(" ".join(words))
    except lark.exceptions.LarkError as error:
        raise LanguageError(_parse_error(words, error, examples(scene, blocks))) from None
    try:
        conjunctions = Clauses().transform(tree)
    except lark.exceptions.VisitError as error:  # a rule that refused its reading ("red except green")
        if isinstance(error.orig_exc, LanguageError):
            raise error.orig_exc from None
        raise
    resolver, goal, before = Resolver(scene, blocks), {}, None
    for conjunction in conjunctions:
        resolved, resolver.carried = [], set()
        for clause in conjunction:
            literals, before = resolver.literals(clause, before)
            resolved.append((before, literals))
        goal, resolved = _carried_over(goal, resolved, resolver)
        stage: dict[tuple[str, tuple[str, ...]], tuple[Literal, bool]] = {}
        for i, (clause, literals) in enumerate(resolved):
            if clause.kind in ("hold", "off_table") and _a_means(clause, [c for c, _ in resolved[i + 1:]], resolver):
                continue  # "pick up red and put it in the bin", "take red off the table and put it on green": how
            for literal, generic in literals:
                try:
                    literal = _validated(layout, literal, blocks)
                except VocabularyError as error:
                    raise LanguageError(str(error)) from None
                kept = stage.get((KEEP, literal.args[:1]))
                if generic and kept and not kept[1]:  # "clean up, but red stays": red kept, not cleaned
                    continue
                if literal.name == KEEP and not generic:
                    stage = {k: (lit, g) for k, (lit, g) in stage.items() if not (g and lit.args[0] == literal.args[0])}
                key = (literal.name, literal.args)
                if key in stage and stage[key][0].value != literal.value:
                    if generic:  # "clean up the desk but leave green out": the named block wins
                        continue
                    if not stage[key][1]:
                        raise LanguageError(f"contradictory goal: both {literal} and {literal.negated()}")
                stage[key] = (literal, generic)
        goal.update({key: literal for key, (literal, _) in _named_places_first(stage).items()})
    placed = {block for literal in goal.values() if literal.name != KEEP  # "pick up blue and keep it": the
              for block in (literal.args if literal.name == STACK else literal.args[:1])}
    goal = {key: lit for key, lit in goal.items() if lit.name != KEEP or lit.args[0] not in placed}  # goal says where
    if all(literal.name == KEEP for literal in goal.values()):  # nothing, or only 'don't move red'
        raise LanguageError(f"the goal asks for no change: say where a block should be, e.g. {resolver.examples}")
    goal = _stacks_left_open(goal)
    try:
        check_consistent(stacks_in_order(list(goal.values())))
    except ContradictionError as error:
        raise LanguageError(str(error)) from None
    return list(goal.values())


def _named_places_first(stage: dict) -> dict:
    """``stage`` without what an 'all' said of a block that a named clause puts in the hand or in a tower ("put everything
    in the bin and stack green on blue": green and blue stay out of the bin, which takes no tower and no held block)."""
    placed = {b for lit, generic in stage.values() if not generic and lit.value and lit.name in ("above", "holding")
              for b in lit.args}
    return {key: (lit, generic) for key, (lit, generic) in stage.items()
            if not (generic and lit.name == "in_bin" and lit.value and lit.args[0] in placed)}


def _stacks_left_open(goal: dict) -> dict:
    """Each tower whose order is left open (:data:`STACK`) without the blocks the goal puts in the bin or the hand
    ("stack everything and put red in the bin": the others); refused where fewer than two are left."""
    away = {lit.args[0] for lit in goal.values() if lit.name in ("in_bin", "holding") and lit.value}
    made = {}
    for key, literal in goal.items():
        if literal.name == STACK:
            blocks = tuple(b for b in literal.args if b not in away)
            if len(blocks) < 2:
                raise LanguageError(f"a tower of {' and '.join(literal.args)} needs two blocks the goal puts nowhere else")
            literal, key = Literal(STACK, blocks), (STACK, blocks)
        made[key] = literal
    return made


def _validated(layout: SemanticLayout, literal: Literal, blocks: tuple[str, ...]) -> Literal:
    """``literal`` checked against the scene; one naming the tower (:data:`TOWER_TOP`, :data:`TOWER_BASE`) is checked
    with another block in its place and kept as it is, for :func:`~semgoal_planner.goals.the_tower` to place."""
    if literal.name == KEEP:
        if not literal.value:
            raise VocabularyError("'not keep' asks for nothing: say where the block should be")
        return literal  # its block named by the resolver, which knows the blocks present
    if literal.name == SWAP:
        if not literal.value:
            raise VocabularyError("'not swap' asks for nothing: say where the blocks should be")
        if literal.args == (TOWER_ALL,) and "above" not in layout.scene.predicates:
            raise VocabularyError(f"in scene {layout.scene.name} no block stands on another (it uses "
                                  f"{', '.join(layout.scene.predicates)}): there is no tower to turn over")
        if not {"above", "in_bin"} & set(layout.scene.predicates):
            raise VocabularyError(f"in scene {layout.scene.name} two blocks have no places to trade (it uses "
                                  f"{', '.join(layout.scene.predicates)}): say where each goes")
        return literal
    if literal.name == STACK:  # never negated: 'not stack' is read as unstacking
        if "above" not in layout.scene.predicates:
            raise VocabularyError(f"in scene {layout.scene.name} no block stands on another (it uses "
                                  f"{', '.join(layout.scene.predicates)}): there is no tower to build")
        return literal
    standing = [arg for arg in literal.args if is_stand_in(arg)]
    if not standing:
        return layout.validate(literal, blocks)
    spare = iter(b for b in blocks if b not in literal.args)
    stand_ins = {arg: next(spare, None) for arg in dict.fromkeys(standing)}  # one block for each end named
    if None in stand_ins.values():
        raise VocabularyError(f"{literal}: a tower needs two blocks besides {' and '.join(literal.args[:1])}")
    layout.validate(Literal(literal.name, tuple(stand_ins.get(a, a) for a in literal.args), literal.value), blocks)
    return literal


Said = list[tuple[Clause, list[tuple[Literal, bool]]]]
"""A stage's clauses as resolved, each with its literals (and whether each is generic)."""


def _carried_over(goal: dict, stage: Said, resolver: Resolver) -> tuple[dict, Said]:
    """What the stages before ``stage`` said that still holds after it, and ``stage`` left to add. A block the stage
    moves loses what was said of it ("... then put green on red"), but for the blocks of a tower moved whole and a block
    left on one the stage stacks on another (:func:`_still_on_it`); a block held before is let go where the stage places
    a block by it or takes another in hand; a swap of blocks said before trades what was said of them ("put red on
    green, then swap them": green on red)."""
    traded = []
    for clause, literals in stage:
        pairs = [lit.args for lit, _ in literals if lit.name == SWAP and len(lit.args) == 2]
        if pairs and any(set(pairs[0]) & set(lit.args) for lit in goal.values()):
            goal = _traded(goal, *pairs[0])
            traded.append(clause)
    stage = [(clause, literals) for clause, literals in stage if clause not in traded]
    moved = {b for clause, _ in stage if not _moves_none(clause) for b in resolver.subjects_of(clause)}
    named = {b for _, literals in stage for lit, _ in literals if lit.value for b in lit.args}  # placed by, or taken
    held = any(lit.name == "holding" and lit.value for _, literals in stage for lit, _ in literals)
    goal = {key: _without(lit, moved) if lit.name == STACK else lit for key, lit in goal.items()
            if not (lit.name == "holding" and lit.value and (held or lit.args[0] in named))}  # the one hand lets go of
    # a block a later stage places another by, or takes another: "pick up red, then put green on red"
    put_on = {lit.args for _, literals in stage for lit, _ in literals if lit.name == "above" and lit.value}
    return {key: lit for key, lit in goal.items() if not moved & set(lit.args) or _within(lit, resolver.carried)
            or _still_on_it(lit, moved, put_on) or _kept_off(lit, moved)}, stage


def _kept_off(literal: Literal, moved: set[str]) -> bool:
    """Whether ``literal`` keeps two blocks apart, or a block not moved off one a later stage moves, which still holds
    ("put purple on the table, then pick up orange": purple is on no block, orange included)."""
    return not literal.value and (literal.name == "close" or (literal.name == "above" and literal.args[0] not in moved))


def _moves_none(clause: Clause) -> bool:
    """Whether a clause leaves every block where it is: one that keeps them, or lets go ("put red on green, then let go
    of green": red stays on it)."""
    return clause.kind in ("keep", "release", "") or (clause.kind == "hold" and clause.negated)


def _still_on_it(literal: Literal, moved: set[str], put_on: set[tuple[str, ...]]) -> bool:
    """Whether ``literal`` puts a block not moved on one that a later stage puts on a third block ("stack red on green
    and then green on blue": red stays on green, the tower grows under it)."""
    if literal.name != "above" or not literal.value or literal.args[0] in moved or literal.args[1] not in moved:
        return False
    upper, lower = literal.args
    return any(block == lower and below != upper for block, below in put_on)


def _without(stack: Literal, moved: set[str]) -> Literal:
    """A tower left open without the blocks a later clause moves ("stack everything, then put red in the bin"), where
    two or more remain."""
    rest = tuple(b for b in stack.args if b not in moved)
    return Literal(STACK, rest) if len(rest) >= 2 else stack


def _traded(goal: dict, a: str, b: str) -> dict:
    """``goal`` after ``a`` and ``b`` trade places: what was said of one is said of the other, and a place only one of
    them had is no longer its own (red in the bin, then swapped with green: green in the bin, red out)."""
    other = {a: b, b: a}
    said = [lit for lit in goal.values() if {a, b} & set(lit.args)]
    after = {key: lit for key, lit in goal.items() if lit not in said}
    for lit in said:
        if lit.name == "close" and set(lit.args) == {a, b}:  # near each other before and after
            after[(lit.name, lit.args)] = lit
            continue
        lit = Literal(lit.name, tuple(other.get(arg, arg) for arg in lit.args), lit.value)
        after[(lit.name, lit.args)] = lit
    for lit in said:
        after.setdefault((lit.name, lit.args), lit.negated() if lit.value else lit)
    return after


def _within(literal: Literal, towers: set[tuple[str, ...]]) -> bool:
    """Whether ``literal`` stacks one block of one of ``towers`` on another."""
    return literal.name == "above" and literal.value and any(set(literal.args) <= set(tower) for tower in towers)


def _a_means(hold: Clause, later: list[Clause], resolver: Resolver) -> bool:
    """Whether a later clause of the same conjunction moves the block a hold clause picks up."""
    held = set(resolver.blocks_of(hold.subjects)) if hold.subjects else set(resolver.last)
    return any(c.kind not in ("hold", "keep", "") and not c.negated and held & set(resolver.subjects_of(c))
               for c in later)


_SHOWN = {"the_base": "the bottom block", "the_top": "the top block", "the_whole": "the whole tower", "the_held": "the block held",
          "the_binned": "the block in the bin", "the_middle": "the middle block", "the_upper": "the block above",
          "the_lower": "the block below", ANY_ORDER: "in any order", AFFIRMED: "is", IN_PLACE: "where it is",
          INTO_A_TOWER: "into a tower", TOP_DOWN: "from the top down", BUT_LEAVE: "but leave", UNDER_A_TOWER: "under the tower"}
"""How the grammar's own words read in a refusal: 'the_base' is 'the bottom block' to the person who said it."""


def _shown(word: str) -> str:
    return _SHOWN.get(word, word.replace("_", " "))


def _parse_error(words: list[str], error: lark.exceptions.LarkError, suggested: str) -> str:
    said = " ".join(map(_shown, words))
    token = getattr(error, "token", None)
    where = f" at {_shown(str(token))!r}" if token is not None and str(token) else " (it ends too soon)"
    return f"cannot read the goal as a sentence{where} (read as: {said!r}): e.g. {suggested}"
