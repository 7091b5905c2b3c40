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

The literals are what the operator is shown before anything moves.
"""

from __future__ import annotations

import functools
import itertools
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace

import lark

from semgoal_core.consistency import ContradictionError, check_consistent
from semgoal_core.vocabulary import BLOCK_COLOURS, LAYOUTS, Literal, VocabularyError

MAX_GOAL_CHARS = 2_000
"""Longest sentence read (characters): an operator's goal is a line; longer input is refused at once."""

PHRASES: tuple[tuple[str, str], ...] = (
    # phrases before the words they contain; the order matters
    (r"make sure( that)?|i( would|'d) like( you)?( to)?|i want( you)?( to)?|i need( you)?( to)?|"
     r"(can|could|would|will) you( please)?|let'?s|go ahead and|where (it|they) (is|are)|as (it|they) (is|are)", ""),
    (r"to (be|end up|stay|remain|sit)|(ends?|ending|winds?) up", ""),  # "I'd like red to be next to blue"
    (r"the other (two|three)", "other"),
    (r"as well as|as well|along with", "and"),
    (r"(knock|tear|topple|take)( over| down)?( the| your)? (tower|stack|pile)( over| down)?|"
     r"(knock|topple)( over| down)?", "unstack"),  # "knock the tower over", "knock it over"
    (r"(build|make|form|create)( a| the)? (tower|stack|pile)( with| of| from| out of)?|tower", "stack"),
    (r"by (itself|themselves)|on (its|their) own|all alone", "apart"),
    (r"and then|after that|afterwards|after this|once done|when done|followed by|so that|so|such that|;", "then"),
    (r"don'?t|do not|never|no longer|isn'?t|aren'?t|is not|are not|should not|shouldn'?t|must not|mustn'?t|"
     r"doesn'?t|does not|won'?t|not", "not"),
    (r"(all|every|everything|each)( the| of the)?( blocks?| cubes?| ones?)? but", "all except"),
    (r"((keep|leave|with)( the| an| your)? )?(holding nothing|hold nothing|hand empty|gripper empty|"
     r"empty[- ]handed|empty (hand|gripper))", "and release all"),
    (r"nothing|none( of them| of the (blocks|cubes))?|no (two )?(blocks?|cubes?|ones?)", "all not"),
    (r"without", "and not"),  # "put red near green without touching blue"
    (r"(?<!the )(rests?|resting)(?= (on|upon|atop|onto|in|inside|into)\b)", ""),  # "green rests on red", not "the rest"
    (r"((all|both|each)( of)? )?the (blocks|cubes|objects)", "all"),
    (r"(and )?(except for|except|other than|save for)", "except"),  # "clear the desk, except for red"
    (r"but(?=( (and|or|the|" + "|".join(BLOCK_COLOURS) + r"|block|cube|one))+( then\b|$))", "except"),  # "... but blue"
    (r"but", "and"),
    (r"in (the|your|its) (hand|gripper|grip|fingers)|in hand|in the air|held|holding|grasped", "held"),
    (r"together with", "near"),
    (r"close together|near each other|close to each other|next to each other|beside each other|side by side|"
     r"together|neighbou?rs|(touch|touches|touching|adjacent)( each other| one another)?(?= (and|then)\b|$)",
     "together"),
    (r"(far from|away from|apart from) (each other|one another)", "apart"),
    (r"apart from", "away"),
    (r"far apart|apart|separated", "apart"),
    (r"over to", "to"),
    (r"on (the )?top(?! of)", "on other"),  # "put red on top": on the other block
    (r"on top of|on to|onto|upon|atop|on|above|over", "on"),
    (r"next to|close to|near to|adjacent to|beside|besides|alongside|nearby|by the side of|right by|near|with|"
     r"towards|toward|up to|in between|between|touch|touches|touching|neighbou?ring|neighbou?r (of|to)|"
     r"closer to|closer", "near"),
    (r"finally|lastly|next|at the end|in the end", "then"),
    (r"far away from|away from|far from|apart from|distant from|clear of", "away"),
    (r"out of|outside of|outside|out from", "out"),
    (r"into|inside of|inside|within|in", "in"),
    (r"underneath|beneath|below|under", "under"),
    (r"off of|off", "off"),
    (r"close", "together"),
    (r"far", "apart"),
    (r"pick up|pick|grab|grasp|lift up|lift|hold on to|hold onto|hold up|take hold of|hold|seize|raise", "pick"),
    (r"let go of|let go|release|set down|put down|lay down|drop off", "release"),
    (r"clean up|clean|tidy up|tidy|clear up|clear off|clear away|clear|(throw|toss|chuck|put) away|dump|"
     r"discard|dispose of|get rid of|fill up|fill", "clean"),
    (r"empty out|empty", "empty"),
    (r"spread out|spread apart|spread|split up|split|scatter|pull apart|separate|space out|isolate|single out",
     "separate"),
    (r"put together|bring together|push together|gather|group|cluster|bunch up|bunch|collect|pair up|pair", "group"),
    (r"take down|unstack", "unstack"),
    (r"pull|retrieve|fetch|extract", "take"),
    (r"place|set|move|bring|get|carry|throw|toss|stick|position|transfer|shift|drop|slide|push|stow|store|deposit|"
     r"return|lay|put", "put"),
    (r"pile|stack", "stack"),
    (r"remove|take away", "remove"),
    (r"keep|leave|have|let", "keep"),
    (r"everything|every|each|all of them|all of|all", "all"),
    (r"the others|others|the other|other|the rest|rest|remaining ones|remaining|another|any other", "other"),
    (r"those|these|they|them", "them"),
    (r"(the|a|an|this|that) (block|cube|one)|this|that|it", "it"),
    (r"basket|box|container|tray|trash can|trash|bucket|crate|bin", "bin"),
    (r"tabletop|table top|table|desk|workspace|surface", "table"),
)
"""(regular expression over whole words, canonical word): applied in order."""

FILLERS = frozenset({
    "please", "the", "a", "an", "of", "robot", "now", "again", "back", "also", "too", "just", "some", "your",
    "my", "our", "its", "their", "block", "blocks", "cube", "cubes", "one", "ones", "piece", "pieces", "object",
    "objects", "thing", "things", "is", "are", "be", "been", "being", "should", "must", "stay", "stays",
    "remain", "remains", "end", "ends", "there", "here", "sure", "make", "go", "goes", "belong", "belongs",
    "first", "firstly", "start", "begin", "alone", "untouched", "sit", "sits", "sitting", "lie", "lies", "lying",
    "stand", "stands", "standing",
})
"""Words that carry nothing for the goal."""

CANONICAL = frozenset({
    "and", "then", "not", "on", "near", "away", "out", "in", "under", "off", "pick", "release", "clean",
    "empty", "separate", "group", "unstack", "put", "stack", "remove", "keep", "held", "together", "apart",
    "all", "except", "other", "them", "it", "bin", "table", "to", "from", "up", "down", "take", "both", "only",
})
"""The words the grammar reads (besides the colours)."""

GRAMMAR = r"""
start: conj ("then" conj)*
conj: clause ("and" clause)*

clause: NOT? action              -> act
      | NOT? action "except" refs -> act_except
      | refs NOT? condition      -> state
      | refs NOT? condition "except" refs -> state_except
      | NOT? condition           -> ellipsis_state
      | NOT? refs                -> ellipsis_refs
      | refs NOT                 -> ellipsis_refs_negated

action: ("put" | "keep") refs dest          -> put
      | "put" refs "down" (near | away | in_bin) -> put
      | "put" refs                           -> release
      | ("put" refs "down" | "put" "down" refs | "release" refs?) -> release
      | "stack" refs dest_on                 -> put
      | "stack" refs                         -> stack_unsaid
      | "take" refs ("out" ("bin" | "from" "bin")? | "from" "bin")  -> out_bin
      | "take" refs ("off" refs? | "from" refs) -> off
      | "take" refs dest_to                   -> put
      | "take" refs "up"?                     -> hold
      | "remove" refs ("from" "bin" | "out" "bin"?)? -> out_bin
      | "remove" refs ("from" | "off") refs   -> off
      | ("remove" | "take") refs ("from" | "off") "table" -> clean
      | "pick" refs "up"?                     -> hold
      | "pick" refs "up"? "off" refs          -> off
      | "pick" refs "up"? "from" refs         -> hold
      | "pick" refs "up"? ("out" ("bin" | "from" "bin")? | "from" "bin") -> out_bin
      | ("put" | "keep" | "pick") refs "up"? "held" -> hold
      | "keep" "held" refs                    -> hold
      | "clean" ("table" | "bin")?            -> clean_all
      | "clean" ("table" | "bin")? "except" refs -> clean_all_except
      | "keep"? "table" ("clean" | "empty")  -> clean_all
      | "keep"? "bin" "empty"                -> empty
      | "clean" refs ("in" "bin" | "table")?  -> clean
      | "bin" refs                            -> clean
      | "put" refs "off" "table"              -> clean
      | "empty" "bin"                         -> empty
      | "empty" refs ("out" "bin"?)?          -> empty_refs
      | "group" refs? "together"?             -> together
      | "group" refs near                     -> group_near
      | "separate" refs? ("apart" | "out")?   -> apart
      | "separate" refs ("from" | "away") refs -> separate_from
      | "unstack" refs?                       -> unstack
      | "unstack" refs ("on" | "down")        -> unstack
      | "keep" refs                           -> keep

condition: dest | "held" -> held

dest: in_bin | out_of_bin | near | away | on | under | off_of | on_table | "together" -> together | "apart" -> apart
dest_on: on | on_table
dest_to: in_bin | near | on | on_table
in_bin: ("in" | "to") "bin"
out_of_bin: "out" "bin"? | "from" "bin"
near: ("near" | "to") refs
away: "away" refs?
on: "on" refs
under: "under" refs
off_of: "off" refs
on_table: ("on" | "to") "table" | "down" "on"? "table"?

refs: ref ("and" ref)*
ref: COLOUR                      -> colour
   | "only" COLOUR               -> only
   | "all" ("except" refs)?      -> all
   | "both"                      -> all
   | "other"                     -> other
   | "it"                        -> it
   | "them"                      -> them

NOT: "not"
COLOUR: """ + " | ".join(f'"{c}"' for c in BLOCK_COLOURS) + r"""
%ignore " "
"""


OPPOSABLE = frozenset({"in_bin", "out_bin", "hold", "release", "near", "away", "on", "under"})
"""Relations whose opposite is one literal per block, so 'all except red' and 'only red' can give it to the
blocks left out (the opposite of 'on the table' or 'apart' is no single place)."""


class LanguageError(ValueError):
    """A sentence that cannot be read as a goal of the scene: the message names the word or the problem."""


@dataclass(frozen=True)
class Ref:
    """A reference to blocks before the world is known: colours, ``all`` (minus some), ``other``, ``it``, ``them``."""

    kind: str
    colours: tuple[str, ...] = ()
    excluded: tuple[Ref, ...] = ()


@dataclass(frozen=True)
class Clause:
    """One relation the sentence states: ``kind`` over ``subjects`` (and ``objects``), maybe negated."""

    kind: str
    subjects: tuple[Ref, ...] = ()
    objects: tuple[Ref, ...] = ()
    negated: bool = False
    elliptic: bool = False
    """Borrows what it lacks (the relation, or the subjects) from the clause before it."""


def examples(scene: str, blocks: Sequence[str]) -> str:
    """Goals the scene can state with the blocks present, quoted: what a refusal suggests saying instead."""
    predicates = LAYOUTS[scene].scene.predicates
    first, second, last = blocks[0], blocks[1 % len(blocks)], blocks[-1]
    said = []
    if "in_bin" in predicates:
        said += [f"put {first} in the bin", f"take {second} out of the bin"]
    if len(blocks) > 1 and "above" in predicates:
        said.append(f"stack {second} on {first}")
    if len(blocks) > 1 and "close" in predicates:
        said += [f"put {second} next to {first}", f"keep {last} away from {first}"]
    if "holding" in predicates:
        said.append(f"pick up {last}")
    return ", ".join(f"'{s}'" for s in said[:3])


def normalise(text: str, scene: str, blocks: Sequence[str]) -> list[str]:
    """The canonical words of ``text``; raises :class:`LanguageError` naming a word it does not know (with the
    ``blocks`` present, by colour, and goals the scene can state)."""
    if len(text) > MAX_GOAL_CHARS:
        raise LanguageError(f"the goal is {len(text)} characters long; at most {MAX_GOAL_CHARS} are read")
    text = " " + re.sub(r"[,.!?:]+", lambda m: " " if m.group() == ":" else " and ", text.lower()) + " "
    text = re.sub(r"\bboth\b(?= (" + "|".join(BLOCK_COLOURS) + r")\b)", " ", text)  # "both red and green"
    text = _EXCEPTION_AFTER_ALL.sub(_as_exception, text)  # "everything in the bin apart from green"
    text = _COUNTED.sub(lambda match: _all_counted(match, blocks), text)  # "the two blocks", "all three"
    text = re.sub(r"&+", " and ", text)
    text = re.sub(r"\b(it|that|there|here|what)'s\b", r"\1 is", text)
    text = re.sub(r"\b(they|we|you)'re\b", r"\1 are", text)
    for pattern, canonical in PHRASES:
        text = re.sub(rf"(?<![\w'])(?:{pattern})(?![\w'])", f" {canonical} ", " ".join(text.split()))
    words = _joined([w for w in text.split() if w not in FILLERS])
    unknown = [w for w in words if w not in CANONICAL and w not in BLOCK_COLOURS]
    if unknown:
        raise LanguageError(f"unknown word {unknown[0]!r}: goals name blocks by colour ({', '.join(blocks)}) "
                            f"and say where they go, e.g. {examples(scene, blocks)}")
    while words and words[0] in ("and", "then"):
        words.pop(0)
    while words and words[-1] in ("and", "then"):
        words.pop()
    if not words:
        raise LanguageError(f"the goal says nothing to do: e.g. {examples(scene, blocks)}")
    return words


NUMBERS = {"two": 2, "three": 3, "four": 4, "five": 5, "six": 6, "seven": 7, "eight": 8}
_COUNTED = re.compile(r"\b(?:(?:all|both)(?: of)?(?: the)? (?P<all>" + "|".join(NUMBERS) + r")(?: blocks| cubes| ones)?"
                      r"|the (?P<the>" + "|".join(NUMBERS) + r") (?:blocks|cubes|ones))\b")
"""A count of blocks meant as all of them: 'all three blocks', 'both of the two', 'the two blocks'."""


def _all_counted(match: re.Match, blocks: Sequence[str]) -> str:
    """'all' where the count is the number of blocks present, else the refusal names the blocks there are."""
    said = match["all"] or match["the"]
    if NUMBERS[said] != len(blocks):
        raise LanguageError(f"{match[0]!r} speaks of {said} blocks, but this world has {len(blocks)} "
                            f"({', '.join(blocks)}): name the blocks by colour")
    return " all "


_EXCEPTION_AFTER_ALL = re.compile(
    r"\b((?:all|every|everything|each)\b.*?) (?:apart from|aside from|besides|but for)"
    r"(?=(?: (?:and|or|the|block|blocks|cube|cubes|one|ones|" + "|".join(BLOCK_COLOURS) + r"))+ *$)")
"""'apart from', 'besides' after 'all' and before the blocks that end the sentence: an exception, not a place,
where the words between say where the blocks go (in 'keep every block apart from green' it is the place)."""
_PLACE = re.compile(r"\b(in|into|inside|on|onto|to|near|next|beside|close|out|off|up|held|holding)\b")


def _as_exception(match: re.Match) -> str:
    said = match[1]
    return f"{said} except" if _PLACE.search(said) else match[0]


def _joined(words: list[str]) -> list[str]:
    """Runs of connectives as one ("red, and green" -> "red and green"; "and, then" -> "then")."""
    joined: list[str] = []
    for word in words:
        if joined and word in ("and", "then") and joined[-1] in ("and", "then"):
            joined[-1] = "then" if "then" in (word, joined[-1]) else "and"
        else:
            joined.append(word)
    return joined


@functools.cache
def _parser() -> lark.Lark:
    return lark.Lark(GRAMMAR, parser="earley", lexer="standard", ambiguity="explicit")


class _Clauses(lark.Transformer):
    """Parse tree -> a list of conjunctions, each a list of :class:`Clause`."""

    def start(self, conjunctions: list) -> list[list[Clause]]:
        return conjunctions

    def conj(self, clauses: list) -> list[Clause]:
        return clauses

    def _ambig(self, alternatives: list) -> object:
        # the reading with the fewest clauses ("put red and green in the bin" is one clause, not two), then the
        # longest exception ("all except red and blue" leaves out both)
        return min(alternatives, key=_reading_cost)

    # -- clauses ------------------------------------------------------------------------------------
    def act(self, items: list) -> Clause:
        negated = len(items) == 2
        return replace(items[-1], negated=negated)

    def act_except(self, items: list) -> Clause:
        return replace(_excepting(items[-2], items[-1]), negated=len(items) == 3)

    def state(self, items: list) -> Clause:
        subjects, *rest = items
        return replace(rest[-1], subjects=subjects, negated=len(rest) == 2)

    def state_except(self, items: list) -> Clause:  # "all in the bin except yellow"
        return _excepting(self.state(items[:-1]), items[-1])

    def ellipsis_state(self, items: list) -> Clause:
        return replace(items[-1], negated=len(items) == 2, elliptic=True)

    def ellipsis_refs(self, items: list) -> Clause:
        return Clause("", subjects=items[-1], negated=len(items) == 2, elliptic=True)

    def ellipsis_refs_negated(self, items: list) -> Clause:  # "..., blue should not"
        return Clause("", subjects=items[0], negated=True, elliptic=True)

    def condition(self, items: list) -> Clause:
        return items[0]

    # -- actions ------------------------------------------------------------------------------------
    def put(self, items: list) -> Clause:
        return replace(items[-1], subjects=items[0])

    def release(self, items: list) -> Clause:
        refs = _refs_in(items)
        return Clause("release", subjects=refs[0] if refs else ())  # "... and let go": the block before

    def out_bin(self, items: list) -> Clause:
        return Clause("out_bin", subjects=items[0])

    def off(self, items: list) -> Clause:
        refs = _refs_in(items)
        return Clause("off", subjects=refs[0], objects=refs[1] if len(refs) > 1 else ())

    def hold(self, items: list) -> Clause:
        refs = _refs_in(items)
        return Clause("hold", subjects=refs[0] if refs else ())

    def clean_all(self, _: list) -> Clause:
        return Clause("in_bin", subjects=(Ref("all"),))

    def clean_all_except(self, items: list) -> Clause:
        return Clause("in_bin", subjects=(Ref("all", excluded=items[-1]),))

    def clean(self, items: list) -> Clause:
        return Clause("in_bin", subjects=items[0])

    def empty(self, _: list) -> Clause:
        return Clause("out_bin", subjects=(Ref("all"),))

    def empty_refs(self, items: list) -> Clause:
        return Clause("out_bin", subjects=items[0])

    def together(self, items: list) -> Clause:
        return Clause("together", subjects=items[0] if items else (Ref("all"),))

    def apart(self, items: list) -> Clause:
        return Clause("apart", subjects=items[0] if items else (Ref("all"),))

    def group_near(self, items: list) -> Clause:
        return replace(items[1], subjects=items[0])

    def stack_unsaid(self, _: list) -> Clause:
        raise LanguageError("say which block goes on which: e.g. 'stack red on green'")

    def separate_from(self, items: list) -> Clause:
        return Clause("away", subjects=items[0], objects=items[1])

    def keep(self, items: list) -> Clause:
        return Clause("keep", subjects=items[0])

    def unstack(self, items: list) -> Clause:
        refs = _refs_in(items)
        return Clause("unstack", subjects=refs[0] if refs else (Ref("all"),))

    # -- destinations -------------------------------------------------------------------------------
    def dest(self, items: list) -> Clause:
        return items[0]

    dest_on = dest_to = dest

    def in_bin(self, _: list) -> Clause:
        return Clause("in_bin")

    def out_of_bin(self, _: list) -> Clause:
        return Clause("out_bin")

    def near(self, items: list) -> Clause:
        return Clause("near", objects=items[0])

    def away(self, items: list) -> Clause:
        return Clause("away", objects=items[0] if items else ())

    def off_of(self, items: list) -> Clause:
        return Clause("off", objects=items[0])

    def on(self, items: list) -> Clause:
        return Clause("on", objects=items[0])

    def under(self, items: list) -> Clause:
        return Clause("under", objects=items[0])

    def on_table(self, _: list) -> Clause:
        return Clause("table")

    def held(self, _: list) -> Clause:
        return Clause("hold")

    # -- references ---------------------------------------------------------------------------------
    def refs(self, items: list) -> tuple[Ref, ...]:
        return tuple(items)

    def colour(self, items: list) -> Ref:
        return Ref("colours", (str(items[0]),))

    def only(self, items: list) -> Ref:
        return Ref("only", (str(items[0]),))

    def all(self, items: list) -> Ref:
        return Ref("all", excluded=items[0] if items else ())

    def other(self, _: list) -> Ref:
        return Ref("other")

    def it(self, _: list) -> Ref:
        return Ref("it")

    def them(self, _: list) -> Ref:
        return Ref("them")


def _excepting(clause: Clause, excluded: tuple[Ref, ...]) -> Clause:
    """``clause`` with ``excluded`` left out of its ``all``; refused where it names no ``all``."""
    if not any(ref.kind == "all" for ref in clause.subjects):
        raise LanguageError("'except' follows 'all' or 'every block': e.g. 'put all except red in the bin'")
    subjects = tuple(replace(ref, excluded=ref.excluded + excluded) if ref.kind == "all" else ref
                     for ref in clause.subjects)
    return replace(clause, subjects=subjects)


def _refs_in(items: list) -> list:
    """The reference tuples (and clauses) among a rule's children, tokens left out."""
    return [i for i in items if not isinstance(i, lark.Token)]


def _reading_cost(node: object) -> tuple[int, int]:
    """How a reading ranks, lower first: its clauses, then minus the blocks its exceptions leave out."""
    if isinstance(node, Ref):
        clauses, excluded = _reading_cost(node.excluded)
        return clauses, excluded - len(node.excluded)
    if isinstance(node, Clause):
        return 1, _reading_cost((node.subjects, node.objects))[1]
    if isinstance(node, (list, tuple)):
        costs = [_reading_cost(n) for n in node]
        return sum(c for c, _ in costs), sum(e for _, e in costs)
    return 0, 0


class _Resolver:
    """References -> blocks of the world, clauses -> literals, in the order the sentence says them."""

    def __init__(self, scene: str, blocks: Sequence[str]) -> None:
        self.scene, self.blocks = scene, tuple(blocks)
        self.examples = examples(scene, blocks)
        self.mentioned: list[str] = []
        self.last: tuple[str, ...] = ()
        """The blocks the clause before was about (what 'it' names)."""
        self.last_named: tuple[str, ...] = ()
        """Every block the clause before named, subjects and objects (what 'them' names)."""

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
                if colour not in self.blocks:
                    raise LanguageError(f"there is no {colour} block here: the blocks are {', '.join(self.blocks)}")
            return ref.colours
        if ref.kind == "all":
            excluded = set(self.blocks_of(ref.excluded))
            return tuple(b for b in self.blocks if b not in excluded)
        if ref.kind == "other":  # not the blocks named before, nor the clause's own ("red on top") where some remain
            unnamed = tuple(b for b in self.blocks if b not in self.mentioned)
            others = tuple(b for b in unnamed if b not in besides) or unnamed
            if not others:
                raise LanguageError("'the other(s)': every block is already named")
            return others
        if ref.kind == "it":
            if besides and set(self.last) <= set(besides):  # "red next to green, not on it": 'it' is green
                named = tuple(b for b in self.last_named if b not in besides)
                if len(named) == 1:
                    return named
            if len(self.last) == 1:
                return self.last
            if len(self.blocks) == 1:
                return self.blocks
            raise LanguageError(f"'it' or 'the block' is ambiguous: say which block ({', '.join(self.blocks)})")
        if self.last_named:  # them
            return self.last_named
        raise LanguageError(f"'them' is ambiguous: say which blocks ({', '.join(self.blocks)})")

    def subjects_of(self, clause: Clause) -> tuple[str, ...]:
        """The blocks a clause is about (those of the clause before where it names none)."""
        return self.blocks_of(clause.subjects) if clause.subjects else self.last

    def literals(self, clause: Clause, before: Clause | None) -> tuple[list[tuple[Literal, bool]], Clause]:
        """The clause's literals, each with whether it is generic (said of all blocks or the others, so a
        literal on a named block overrides it), and the clause as completed (an ellipsis borrows from
        ``before``)."""
        if clause.elliptic:
            if before is None:
                raise LanguageError(f"the goal starts mid-sentence: say what to do, e.g. {self.examples}")
            if clause.kind:  # "... and away from blue": the subjects of the clause before
                clause = replace(clause, subjects=clause.subjects or before.subjects, elliptic=False)
            else:  # "... but not green": the relation of the clause before
                clause = replace(before, subjects=clause.subjects, negated=before.negated != clause.negated)
        subjects = self.subjects_of(clause)
        if not subjects:
            raise LanguageError(f"say which block: {', '.join(self.blocks)}")
        objects = self.blocks_of(clause.objects, besides=subjects)
        self.mentioned += [b for b in (*subjects, *objects) if b not in self.mentioned]
        generic = any(ref.kind in ("all", "other") for ref in clause.subjects)
        said = [(lit, generic) for lit in self._relation(clause.kind, subjects, objects)]
        if not said and objects:
            raise LanguageError(f"{' and '.join(subjects)} cannot be {clause.kind} itself: say which block")
        # "all except red" and "only red": the blocks left out explicitly not
        excluded = [b for ref in clause.subjects if ref.kind == "all" for b in self.blocks_of(ref.excluded)]
        if any(ref.kind == "only" for ref in clause.subjects):
            excluded += [b for b in self.blocks if b not in subjects and b not in objects]
        if excluded and clause.kind not in ("together", "apart"):  # a group says nothing of those left out
            if clause.kind not in OPPOSABLE:
                raise LanguageError(f"'except' or 'only' leaves {' and '.join(excluded)} unclear here: "
                                    "say where they go")
            said += [(lit.negated(), False) for b in excluded for lit in self._relation(clause.kind, (b,), objects)]
        self.last = subjects
        self.last_named = subjects + tuple(b for b in objects if b not in subjects)
        resolved = replace(clause, subjects=(Ref("colours", subjects),), objects=(Ref("colours", objects),) if objects else ())
        return [(lit.negated() if clause.negated else lit, g) for lit, g in said], resolved

    def _relation(self, kind: str, subjects: tuple[str, ...], objects: tuple[str, ...]) -> Iterable[Literal]:
        others = lambda block: [b for b in self.blocks if b != block]  # noqa: E731
        if kind == "in_bin":
            return (Literal("in_bin", (s,)) for s in subjects)
        if kind == "out_bin":
            return (Literal("in_bin", (s,), False) for s in subjects)
        if kind == "keep":  # "keep it there": nothing to change
            return []
        if kind == "hold":
            if len(subjects) > 1:
                raise LanguageError(f"the hand holds one block at a time, not {' and '.join(subjects)}")
            return [Literal("holding", subjects)]
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
        if kind in ("on", "under"):
            if len(objects) > 1 or len(subjects) > 1:
                raise LanguageError("a block goes on one block, and one block on it: say which on which")
            return (Literal("above", p if kind == "on" else p[::-1]) for p in pairs)
        if kind == "off":
            return (Literal("above", (s, o), False) for s in subjects for o in (objects or others(s)) if s != o)
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


def parse_english(text: str, scene: str, blocks: Sequence[str] | None = None) -> list[Literal]:
    """The literals a sentence asks for in ``scene`` with ``blocks`` present (default: all of the scene's).

    Clauses joined by ``and`` hold together (a contradiction is refused); a clause after ``then`` overrides
    the earlier ones on the same atom. Raises :class:`LanguageError` with a message naming what is wrong.
    """
    layout = LAYOUTS[scene]
    blocks = tuple(blocks or layout.objects)
    words = normalise(text, scene, blocks)
    try:
        tree = _parser().parse(" ".join(words))
    except lark.exceptions.LarkError as error:
        raise LanguageError(_parse_error(words, error, examples(scene, blocks))) from None
    try:
        conjunctions = _Clauses().transform(tree)
    except lark.exceptions.VisitError as error:  # a rule that refused its reading ("red except green")
        if isinstance(error.orig_exc, LanguageError):
            raise error.orig_exc from None
        raise
    resolver, goal, before = _Resolver(scene, blocks), {}, None
    for conjunction in conjunctions:
        resolved = []
        for clause in conjunction:
            literals, before = resolver.literals(clause, before)
            resolved.append((before, literals))
        moved = {b for clause, _ in resolved if clause.kind not in ("keep", "") for b in resolver.subjects_of(clause)}
        # "... then put green on red": what earlier stages said of a block moved now no longer holds
        goal = {key: lit for key, lit in goal.items() if not moved & set(lit.args)}
        stage: dict[tuple[str, tuple[str, ...]], tuple[Literal, bool]] = {}
        for i, (clause, literals) in enumerate(resolved):
            if clause.kind == "hold" and _a_means(clause, [c for c, _ in resolved[i + 1:]], resolver):
                continue  # "pick up red and put it in the bin": the picking is how, not where it ends
            for literal, generic in literals:
                try:
                    literal = layout.validate(literal, blocks)
                except VocabularyError as error:
                    raise LanguageError(str(error)) from None
                key = (literal.name, literal.args)
                if key in stage and stage[key][0].value != literal.value:
                    if generic:  # "clean up the desk but leave green out": the named block wins
                        continue
                    if not stage[key][1]:
                        raise LanguageError(f"contradictory goal: both {literal} and {literal.negated()}")
                stage[key] = (literal, generic)
        goal.update({key: literal for key, (literal, _) in stage.items()})
    if not goal:
        raise LanguageError(f"the goal asks for no change: say where a block should be, e.g. {resolver.examples}")
    try:
        check_consistent(goal.values())
    except ContradictionError as error:
        raise LanguageError(str(error)) from None
    return list(goal.values())


def _a_means(hold: Clause, later: list[Clause], resolver: _Resolver) -> bool:
    """Whether a later clause of the same conjunction moves the block a hold clause picks up."""
    held = set(resolver.blocks_of(hold.subjects)) if hold.subjects else set(resolver.last)
    return any(c.kind not in ("hold", "keep", "") and not c.negated and held & set(resolver.subjects_of(c))
               for c in later)


def _parse_error(words: list[str], error: lark.exceptions.LarkError, suggested: str) -> str:
    said = " ".join(words)
    token = getattr(error, "token", None)
    where = f" at {str(token)!r}" if token is not None and str(token) else " (it ends too soon)"
    return f"cannot read the goal as a sentence{where} (read as: {said!r}): e.g. {suggested}"
