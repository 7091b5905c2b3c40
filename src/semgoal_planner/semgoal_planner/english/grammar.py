"""Pass 2: the canonical words parsed by a lark Earley grammar into clauses (an action, a state or an
ellipsis), joined by 'and' (at once) or 'then' (later clauses override earlier ones)."""

from __future__ import annotations

import functools
from dataclasses import dataclass, replace

import lark
from lark.parse_tree_builder import ParseTreeBuilder
from lark.parsers.earley_forest import ForestToParseTree, SymbolNode

from semgoal_core.vocabulary import BLOCK_COLOURS
from semgoal_planner.english.words import LanguageError

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
      | refs "affirmed"          -> ellipsis_refs_affirmed

action: ("put" | "keep") refs dest          -> put
      | ("put" refs "down" | "release" refs) (near | away | in_bin | on | on_table) -> put
      | "put" refs                           -> release
      | ("put" refs "down" | "put" "down" refs | "release" refs?) -> release
      | "stack" refs dest_on                 -> put
      | "stack" refs?                        -> stack_unsaid
      | "stack" "anyorder" refs?             -> stack_any_order
      | "take" refs ("out" ("bin" | "from" "bin")? | "from" "bin")  -> out_bin
      | "take" refs ("off" refs? | "from" refs) -> off
      | "take" refs dest_to                   -> put
      | ("put" | "take") refs "from" ("bin" | refs) dest_to -> put
      | "take" refs "up"?                     -> hold
      | "remove" refs ("from" "bin" | "out" "bin"?)? -> out_bin
      | "remove" refs ("from" | "off") refs   -> off
      | "remove" refs "off"                   -> off
      | ("remove" | "take") refs ("from" | "off") "table" -> off_table
      | "pick" refs "up"?                     -> hold
      | "pick" refs "up"? "off" refs?         -> off
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
      | "put" refs "off" "table"              -> off_table
      | "empty" "bin" on_table?               -> empty
      | "empty" refs ("out" "bin"?)?          -> empty_refs
      | "group" refs? "together"?             -> together
      | "group" refs near                     -> group_near
      | "separate" refs? ("apart" | "out")?   -> apart
      | "separate" refs ("from" | "away") refs -> separate_from
      | "swap" refs?                          -> swap
      | "swap" refs near                      -> swap_with
      | "unstack" (refs | on_table)?          -> unstack
      | "unstack" refs ("on" | "down")        -> unstack
      | "unstack" refs "off" refs             -> off
      | "unstack" refs on_table               -> put
      | "keep" refs "inplace"?                -> keep

condition: dest | "held" -> held

dest: in_bin | out_of_bin | near | away | on | under | off_of | on_table | "together" -> together | "apart" -> apart
dest_on: on | under | on_table
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
   | "both"                      -> both
   | "other"                     -> other
   | "the_other"                 -> the_other
   | "it"                        -> it
   | "them"                      -> them
   | "the_tower"                 -> tower
   | "the_top"                   -> top
   | "the_base"                  -> base
   | "the_whole"                 -> whole
   | "the_upper" COLOUR          -> upper
   | "the_held"                  -> held_block
   | "the_binned"                -> binned_block
   | LEVEL                       -> level
   | "the_lower" COLOUR          -> lower

NOT: "not"
LEVEL: /the_(top|bottom)[2-8]/ | "the_middle"
COLOUR: """ + " | ".join(f'"{c}"' for c in BLOCK_COLOURS) + r"""
%ignore " "
"""


ANY_ORDER_TOWER = "tower_any_order"
"""The clause kind of a tower whose order is said to be left open."""
OPPOSABLE = frozenset({"in_bin", "off_table", "out_bin", "hold", "release", "near", "away", "on", "under"})
"""Relations whose opposite is one literal per block, so 'all except red' and 'only red' can give it to the
blocks left out (the opposite of 'on the table' or 'apart' is no single place)."""


@dataclass(frozen=True)
class Ref:
    """A reference to blocks before the world is known: colours, ``all`` (minus some), ``both``, ``other``
    (``the_other``: one block, said in the singular), ``it``,
    ``them``, ``tower`` (the tower standing when the goal is planned), ``top`` and ``base`` (its top and bottom
    blocks), ``upper`` and ``lower`` (the block on, or under, the one of ``colours`` when planned), ``held`` (the block in the hand
    when planned), ``level`` (a block counted in the tower: ``the_top2``, ``the_bottom3``, ``the_middle``)."""

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
    affirmed: bool = False
    """An ellipsis said with its verb ('... and green is'): the relation holds, whatever the clause before denied."""
    """Borrows what it lacks (the relation, or the subjects) from the clause before it."""


@functools.cache
def parser() -> lark.Lark:
    return lark.Lark(GRAMMAR, parser="earley", lexer="standard", ambiguity="forest")


def parse(words: str) -> lark.Tree:
    """The parse tree of canonical ``words``, its readings with more clauses than the fewest left out (``_ambig``
    nodes hold the readings left, which :class:`Clauses` ranks). Each "and" may join refs or clauses, so a list of
    n blocks reads 2^(n-1) ways: expanding them all took 4 s for two lists of eight. LarkError where none."""
    root = parser().parse(words)
    _keep_fewest_clauses(root)
    return ForestToParseTree(lark.Tree, _tree_shapes(), None, resolve_ambiguity=False).transform(root)


@functools.cache
def _tree_shapes() -> dict:
    """What lark's explicit mode builds trees with (keyword tokens dropped, ``?`` rules inlined), for the forest."""
    return ParseTreeBuilder(parser().rules, lark.Tree, False, True, False).create_callback(None)


def _keep_fewest_clauses(root: SymbolNode) -> None:
    """Prune the parse forest to the derivations with the fewest clauses: a count that adds up over a derivation, so
    the fewest at each node (bottom up, each node once) make the fewest in all. (A node's derivations are its
    ``_children`` in lark-parser 0.12's forest, the version pinned.)"""
    fewest: dict[int, int] = {}
    reached: set[int] = set()
    stack: list[tuple[SymbolNode, bool]] = [(root, False)]
    while stack:
        node, below_done = stack.pop()
        if below_done:
            costs = {packed: sum(fewest.get(id(child), 0) for child in (packed.left, packed.right)
                                 if isinstance(child, SymbolNode)) for packed in node.children}
            best = min(costs.values())
            node._children = {packed for packed, cost in costs.items() if cost == best}
            fewest[id(node)] = best + (0 if node.is_intermediate or node.s.name != "clause" else 1)
        elif id(node) not in reached:
            reached.add(id(node))
            stack.append((node, True))
            stack.extend((child, False) for packed in node.children for child in (packed.left, packed.right)
                         if isinstance(child, SymbolNode))


class Clauses(lark.Transformer):
    """Parse tree -> a list of conjunctions, each a list of :class:`Clause`."""

    def start(self, conjunctions: list) -> list[list[Clause]]:
        return conjunctions

    def conj(self, clauses: list) -> list[Clause]:
        return clauses

    def _ambig(self, alternatives: list) -> object:
        # the reading with the fewest clauses ("put red and green in the bin" is one clause, not two), then the
        # longest exception ("all except red and blue" leaves out both), then the fewest clauses that relate a block to
        # itself ("red near green and blue and green away from blue": blue is near red), then the earlier clauses' lists the longest
        # ("a tower of red, green and blue and orange not near it": blue in the tower); between equals, the same one on
        # every run (the parser lists them in an order that follows string hashing)
        return min(alternatives, key=lambda reading: (reading_cost(reading), _self_related(reading), _lists_first(reading),
                                                      repr(reading)))

    # -- clauses ------------------------------------------------------------------------------------
    def act(self, items: list) -> Clause:
        negated = len(items) == 2
        return replace(items[-1], negated=negated)

    def act_except(self, items: list) -> Clause:
        return replace(excepting(items[-2], items[-1]), negated=len(items) == 3)

    def state(self, items: list) -> Clause:
        subjects, *rest = items
        return replace(rest[-1], subjects=subjects, negated=len(rest) == 2)

    def state_except(self, items: list) -> Clause:  # "all in the bin except yellow"
        return excepting(self.state(items[:-1]), items[-1])

    def ellipsis_state(self, items: list) -> Clause:
        return replace(items[-1], negated=len(items) == 2, elliptic=True)

    def ellipsis_refs(self, items: list) -> Clause:
        return Clause("", subjects=items[-1], negated=len(items) == 2, elliptic=True)

    def ellipsis_refs_negated(self, items: list) -> Clause:  # "..., blue should not"
        return Clause("", subjects=items[0], negated=True, elliptic=True)

    def ellipsis_refs_affirmed(self, items: list) -> Clause:  # "red is not in the bin and green is"
        return Clause("", subjects=items[0], elliptic=True, affirmed=True)

    def condition(self, items: list) -> Clause:
        return items[0]

    # -- actions ------------------------------------------------------------------------------------
    def put(self, items: list) -> Clause:  # "move red from the bin onto green": where it goes says where it came from
        return replace(items[-1], subjects=items[0])

    def release(self, items: list) -> Clause:
        refs = refs_in(items)
        return Clause("release", subjects=refs[0] if refs else ())  # "... and let go": the block before

    def out_bin(self, items: list) -> Clause:
        return Clause("out_bin", subjects=items[0])

    def off(self, items: list) -> Clause:
        refs = refs_in(items)
        return Clause("off", subjects=refs[0], objects=refs[1] if len(refs) > 1 else ())

    def hold(self, items: list) -> Clause:
        refs = refs_in(items)
        return Clause("hold", subjects=refs[0] if refs else ())

    def clean_all(self, _: list) -> Clause:
        return Clause("in_bin", subjects=(Ref("all"),))

    def clean_all_except(self, items: list) -> Clause:
        return Clause("in_bin", subjects=(Ref("all", excluded=items[-1]),))

    def clean(self, items: list) -> Clause:
        return Clause("in_bin", subjects=items[0])

    def off_table(self, items: list) -> Clause:
        """'take red off the table': into the bin, unless the sentence puts it somewhere else after."""
        return Clause("off_table", subjects=items[0])

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

    def stack_unsaid(self, items: list) -> Clause:
        """'stack red, green and blue', 'build a tower of red, green and blue': a tower, the first named at the
        bottom (the resolver refuses blocks not named one by one: they say nothing of the order)."""
        return Clause("tower", subjects=items[0] if items else ())

    def stack_any_order(self, items: list) -> Clause:
        """'stack red, green and blue in any order': one tower, its order left to the world when planned."""
        return Clause(ANY_ORDER_TOWER, subjects=items[0] if items else ())

    def separate_from(self, items: list) -> Clause:
        return Clause("away", subjects=items[0], objects=items[1])

    def keep(self, items: list) -> Clause:
        return Clause("keep", subjects=items[0])

    def swap(self, items: list) -> Clause:
        refs = refs_in(items)
        return Clause("swap", subjects=refs[0] if refs else (Ref("all"),))

    def swap_with(self, items: list) -> Clause:  # "swap red with green" ('with' reads as 'near')
        return Clause("swap", subjects=items[0] + items[1].objects)

    def unstack(self, items: list) -> Clause:  # "unstack onto the table": where unstacked blocks go anyway
        refs = [item for item in refs_in(items) if isinstance(item, tuple)]
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

    def both(self, _: list) -> Ref:
        return Ref("both")

    def other(self, _: list) -> Ref:
        return Ref("other")

    def the_other(self, _: list) -> Ref:
        return Ref("the_other")

    def it(self, _: list) -> Ref:
        return Ref("it")

    def them(self, _: list) -> Ref:
        return Ref("them")

    def tower(self, _: list) -> Ref:
        return Ref("tower")

    def top(self, _: list) -> Ref:
        return Ref("top")

    def base(self, _: list) -> Ref:
        return Ref("base")

    def whole(self, _: list) -> Ref:
        return Ref("whole")

    def upper(self, items: list) -> Ref:
        return Ref("upper", (str(items[0]),))

    def lower(self, items: list) -> Ref:
        return Ref("lower", (str(items[0]),))

    def held_block(self, _: list) -> Ref:
        return Ref("held")

    def binned_block(self, _: list) -> Ref:
        return Ref("binned")

    def level(self, items: list) -> Ref:
        return Ref("level", (str(items[0]),))


def excepting(clause: Clause, excluded: tuple[Ref, ...]) -> Clause:
    """``clause`` with ``excluded`` left out of its ``all``; refused where it names no ``all``."""
    if not any(ref.kind == "all" for ref in clause.subjects):
        raise LanguageError("'except' follows 'all' or 'every block': e.g. 'put all except red in the bin'")
    subjects = tuple(replace(ref, excluded=ref.excluded + excluded) if ref.kind == "all" else ref
                     for ref in clause.subjects)
    return replace(clause, subjects=subjects)


def refs_in(items: list) -> list:
    """The reference tuples (and clauses) among a rule's children, tokens left out."""
    return [i for i in items if not isinstance(i, lark.Token)]


LISTED_OBJECTS = ("near", "away")
"""The relations whose objects may be a list of blocks ('next to red and green')."""


def _self_related(node: object) -> int:
    """How many clauses name one block among both their subjects and their objects."""
    if isinstance(node, Clause):
        named = [{colour for ref in refs if ref.kind == "colours" for colour in ref.colours}
                 for refs in (node.subjects, node.objects)]
        return int(bool(named[0] & named[1]))
    if isinstance(node, (list, tuple)):
        return sum(map(_self_related, node))
    return 0


def _lists_first(node: object) -> tuple[int, ...]:
    """Minus each clause's number of blocks listed, in the order said: a block between two clauses joins the first
    ("orange far from purple and pink, and green away from red"). Its subjects, and its objects where a list of them
    can stand (near or away from several blocks; a block goes on one)."""
    if isinstance(node, Clause):
        return (-len(node.subjects) - (len(node.objects) if node.kind in LISTED_OBJECTS else 0),)
    if isinstance(node, (list, tuple)):
        return tuple(count for n in node for count in _lists_first(n))
    return ()


def reading_cost(node: object) -> tuple[int, int]:
    """How a reading ranks, lower first: its clauses, then minus the blocks its exceptions leave out."""
    if isinstance(node, Ref):
        clauses, excluded = reading_cost(node.excluded)
        return clauses, excluded - len(node.excluded)
    if isinstance(node, Clause):
        return 1, reading_cost((node.subjects, node.objects))[1]
    if isinstance(node, (list, tuple)):
        costs = [reading_cost(n) for n in node]
        return sum(c for c, _ in costs), sum(e for _, e in costs)
    return 0, 0
