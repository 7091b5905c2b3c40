"""Pass 1 of reading a sentence: lower-case, phrases and synonyms to one canonical word each, fillers
dropped, counted references ('the two blocks') spelled out; an unknown word is refused, named."""

from __future__ import annotations

import re
from collections.abc import Sequence

from semgoal_core.vocabulary import BLOCK_COLOURS, LAYOUTS

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
    (r"(at|on) the (bottom|base|foot)|at first|first|to start with|to start|bottom up|from the bottom( up)?", ""),
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

class LanguageError(ValueError):
    """A sentence that cannot be read as a goal of the scene: the message names the word or the problem."""

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
    words = _tower_in_order(_joined([w for w in text.split() if w not in FILLERS]))
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


def _tower_in_order(words: list[str]) -> list[str]:
    """'stack red then green then blue': the blocks of a tower named in order, not clauses after one another."""
    joined = []
    for i, word in enumerate(words):
        in_tower = (word == "then" and 0 < i < len(words) - 1 and words[i + 1] in BLOCK_COLOURS
                    and _listing_after_stack(words[:i]))
        joined.append("and" if in_tower else word)
    return joined


def _listing_after_stack(words: list[str]) -> bool:
    """Whether ``words`` end in 'stack' and a list of colours only."""
    for word in reversed(words):
        if word == "stack":
            return True
        if word not in BLOCK_COLOURS and word not in ("and", "then"):
            return False
    return False


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
