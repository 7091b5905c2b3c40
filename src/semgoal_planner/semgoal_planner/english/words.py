"""Pass 1 of reading a sentence: lower-case, phrases and synonyms to one canonical word each, fillers
dropped, counted references ('the two blocks') spelled out; an unknown word is refused, named."""

from __future__ import annotations

import functools
import itertools
import re
import unicodedata
from collections.abc import Sequence

from semgoal_core.vocabulary import BLOCK_COLOURS, LAYOUTS

TOP_DOWN = "topdown"
SENTENCE_END = "then and"
"""What a full stop between sentences, or a semicolon, reads as until the lists are read: a clause ends there (to every
rule that looks for 'then' before it or 'and' after it), and no list of blocks, joined by one word at a time, runs
across it; then a 'then'."""
"""The mark 'from top to bottom' leaves: the tower's blocks are named from the top (:func:`_top_down`)."""
DIRECTION = "direction"
"""What 'to the left of', 'behind' leave: a direction, which no predicate states (refused in :func:`normalise`)."""
ANY_ORDER = "anyorder"
"""What 'in any order' leaves: nothing for blocks put each in its place; after 'stack', a tower left open."""
AFFIRMED = "affirmed"
"""What a verb ending an ellipsis leaves ('red is not in the bin and green is'): the relation holds for it."""
IN_PLACE = "inplace"
"""What 'stays', 'remains where it is' leave after the blocks they keep: the end of a clause that keeps them."""
INTO_A_TOWER = "intoatower"
"""What 'in a tower' leaves where no blocks are named in order: nothing after 'stack', else a tower with no order
(refused in :func:`normalise`)."""
UNORDERED_TOWER = ("say which blocks to stack and, if it matters, in which order: e.g. 'stack red on green', 'build a "
                   "tower of red, green and blue' (from the bottom up), 'stack everything' (in any order)")
"""Why a tower is refused whose blocks the goal does not say."""
BUT_LEAVE = "butleave"
"""What 'but leave', 'but keep' leave: an exception after an 'all' or a clean-up, else a block kept (:func:`_kept_besides`)."""
UNDER_A_TOWER = "underatower"
"""What 'under the tower', 'at the bottom of the tower' leave: a block slid under a standing tower, which means building
the tower again on it (refused in :func:`normalise`, saying how to name the new tower)."""
TOP_MARK, BASE_MARK = "towertop", "towerbase"
"""The marks 'with blue on top' and 'with red at the bottom' leave before the block they name
(:func:`_tower_end_named`)."""
_COLOUR = "|".join(BLOCK_COLOURS)
_LISTED = rf"(the )?({_COLOUR})(( and| ,|,) (the )?({_COLOUR}))*"
"""Blocks named in a list ('red, green and the blue')."""
MAX_GOAL_CHARS = 2_000
"""Longest sentence read (characters): an operator's goal is a line; longer input is refused at once."""
MAX_GOAL_WORDS = 100
"""Most words read (after phrases became canonical words): the parser's time grows with the cube of a sentence's
length where its 'and's may join blocks or clauses (a hundred words: at most 0.4 s)."""

_NOT_A_LIST = rf"(?!( and)?( then)? (the )?({_COLOUR})( block| cube| one)?( and\b| then\b|$))"
"""Not followed by a block ('red at the bottom, then green': a tower's list, not a block put under a tower)."""
_LISTED_INTO_A_TOWER = (rf"((put|place|set|arrange|lay|move|get|stack|pile|sort) )?(the )?"
                        rf"(?P<listed>(?P<base>{_COLOUR})(( and| then)? ({_COLOUR}))+)"
                        r"( blocks| cubes)? (in|into|as|to) (a|one|another|a second|a separate) (single )?(tower|stack|pile)")
"""Blocks named into a tower, whatever the verb ('put red, green and blue in a tower'): stacked in the order named; where
the tower goes, its bottom block goes."""

_NOT_AFTER_A_PUT = "".join(rf"(?<!\b{verb} )" for verb in ("put", "place", "move", "stack", "set", "drop", "lay"))
"""Not right after a verb that puts a block somewhere: there 'the block on red' is a block put on red."""

NUMBERS = {"two": 2, "three": 3, "four": 4, "five": 5, "six": 6, "seven": 7, "eight": 8}
_ORDINALS = {"second": 2, "third": 3, "fourth": 4, "fifth": 5, "sixth": 6, "seventh": 7}
"""A block's place counted in a tower ('the second block from the top'), the end itself being 'the top block'."""

_SHADES = {"purple": r"violet|lilac|lavender", "cyan": r"turquoise|teal|aqua(marine)?|(light|sky) blue", "yellow": r"gold(en)?",
           "red": r"scarlet|crimson", "green": r"lime|emerald", "blue": r"navy( blue)?|(dark|royal) blue"}
"""Other names of the blocks' colours, each for the one colour of the eight it can only mean."""

_NO_PLACE_AFTER = (rf"(?!(\s+(the\s+)?({_COLOUR})(\s+(block|cube|one))?(\s+(and|or|nor))?)+\s+(in|into|inside|on|onto|to|"
                   r"near|next|beside|by|close|away|far|apart|together|off|out|from|under|atop|upon|over|toward|towards|back|"
                   r"beneath|below|underneath|between|against|alongside)\b)")
"""After 'don't move': no place follows the blocks ('don't move red into the bin' is not 'keep red')."""
_DENIED = r"(don'?t|do not|never|please don'?t|must not|mustn'?t|should not|shouldn'?t|may not|cannot|can'?t|avoid)"
"""The words that deny the verb after them."""
PHRASES: tuple[tuple[str, str], ...] = (
    # phrases before the words they contain; the order matters
    *((shades, colour) for colour, shades in _SHADES.items()),  # "the violet block": purple
    (r"on-?top", "on top"),  # "ontop of green", "on-top of green"
    (rf"(?P<place>(near|next to|beside|close to|by|against|adjacent to) (the )?({_COLOUR})( block| cube| one)?) (and )?"
     r"(touching|so (that )?(they|it) (touch|touches))( (it|each other|one another|them))?(?= *$| and| then)",
     r"\g<place>"),  # "put red near green, touching": the closeness said again
    (r"over(?= (to|next to|near|beside|by|close to|into|onto)\b)", ""),  # "carry red over to green", "bring it over next to
    # blue": the place after it
    (r"side-by-side", "side by side"),
    (rf"(?P<noun>blocks?|cubes?|ones?|everything) (that|which) (are|is) not(?= (the )?({_COLOUR})\b)|(?P<noun2>blocks?|"
     rf"cubes?|ones?|everything) (that|which) (aren't|isn't)(?= (the )?({_COLOUR})\b)", r"\g<noun>\g<noun2> other than"),
    # "every block that is not red", "the blocks that aren't red or green", "everything that is not blue": the others
    (rf"non-?(?P<colour>{_COLOUR}) (?P<noun>blocks|cubes|ones)", r"\g<noun> other than \g<colour>"),  # "the non-red blocks"
    (rf"other than (?P<first>(the )?({_COLOUR})) (n?or|and not)(?= (the )?({_COLOUR})\b)", r"other than \g<first> and"),  # "the
    # blocks that are not red or green": neither
    (r"(get |have )?(the )?(desk|table|tabletop|workspace) (cleared|cleaned|tidied|emptied)( up| off)?", "clear the table"),
    # "I need the desk cleared"
    (r"(?P<verb>get rid of|dispose of|clear away|throw away|put away|bin|discard) (?P<all>(all|every|each|everything)"
     r"( of)?( the)?( blocks| cubes| block| cube| ones)?) (that (is|are) )?(on|from) (the )?(desk|table|tabletop|workspace)",
     r"\g<verb> \g<all>"),  # "get rid of all the cubes on the desk": those in the bin are there already
    (r"remove (?P<all>(all|every|each|everything)( of)?( the)?( blocks| cubes| block| cube| ones)?) (that (is|are) )?on (the )?"
     r"(desk|table|tabletop|workspace)", r"remove \g<all> from the table"),  # "remove all the blocks on the table"
    (rf"(?P<below>{_COLOUR})(?P<noun> block| cube)? (?P<end>at the (bottom|base)|first|goes first)(?P<joint>( and| then)+) "
     rf"(?P<above>(the )?({_COLOUR})( block| cube)?) (?P<on>on top of|on|onto|above|atop) it",
     r"\g<above> \g<on> \g<below>"),  # "red at the bottom, green on it": green on red
    (rf"(without|and not|but not)( ever)? (moving|move|disturbing|disturb|shifting|shift|pushing|push|sliding|slide|"
     rf"nudging|nudge){_NO_PLACE_AFTER}", "and keep"),  # "put orange in the bin without moving red": red kept ('not move
    # red' alone would read 'not put red down': held)
    (rf"without (get|carry|bring){_NO_PLACE_AFTER}", "and don't pick up"),  # "... without carrying red" (gerunds are
    (rf"without (throw|toss)(?! away| out){_NO_PLACE_AFTER}", "and don't throw away"),  # read as verbs by now)
    (rf"{_DENIED} (move|disturb|shift|push|slide|nudge|budge){_NO_PLACE_AFTER}|(don'?t|do not|never|please don'?t) touch"
     rf"{_NO_PLACE_AFTER}", "keep"),  # "don't move red": red's place as the world has it when planned (alone, it is
    # refused as asking for no change); 'red should not touch green' is apart
    (rf"(?<!to )get(?= (the )?({_COLOUR})\b){_NO_PLACE_AFTER}", "pick up"),  # "get red and put it on green": get it in
    # hand ('get red into the bin' puts it there)
    (rf"(?P<neg>{_DENIED}) (get|carry|bring){_NO_PLACE_AFTER}", r"\g<neg> pick up"),  # "don't carry red": not in the
    # hand ('carry red to the bin' puts it there)
    (rf"(?P<neg>{_DENIED}) (throw|toss|chuck|dump)(?! away| out){_NO_PLACE_AFTER}", r"\g<neg> throw away"),  # "don't
    # throw red": not into the bin
    (r"(?<!but )(leave|keep)( the| your| that| this) (tower|stack|pile)(?! of)( alone| standing| intact| untouched| in place| as it "
     r"is| where it is| up)?", "keep the_whole"),  # "leave the tower as it is": its blocks kept
    (r"stop (holding|carrying|gripping|grasping)", "release"),
    (r"(assemble|erect|raise|put together|set up|compose|put up)(?= (a|an|one|the|your) ((\d|two|three|four|five|six)[- ]"
     r"(block|cube|storey|story|level)s?[- ])?(tall |high |big |single )?(tower|stack|pile)\b)", "build"),  # "erect a tower of ..."
    (rf"(?P<block>(the )?({_COLOUR}))( block| cube| one)?'s? (top|upper side|top face)", r"the top of \g<block>"),  # "put red on
    # green's top"
    (rf"^(?P<place>(on top of|on|onto|atop|in|into|inside|next to|near|beside|close to|away from) (the )?({_COLOUR}|bin|box|"
     rf"basket)( block| cube| one)?)( and)? (?P<verb>put|place|stack|set|drop) (?P<what>(the )?({_COLOUR})( block| cube| "
     r"one)?)(?= and\b| then\b|$)", r"\g<verb> \g<what> \g<place>"),  # "on top of green put red": the place said first
    (rf"let (?P<what>(the )?({_COLOUR})( block| cube| one)?|it|them) (fall|drop|go)(?= (in|into|on|onto|next|near|beside|"
     r"by)\b)", r"put \g<what>"),  # "let red fall into the bin"
    (rf"(?P<verb>pick|lift|grab|raise) (?P<what>(the )?({_COLOUR})( block| cube| one)?|it) (up )?(off|from) (of )?the "
     r"(table|desk)", r"\g<verb> \g<what> up"),  # "pick red off the table": into the hand
    (r"(?P<verb>take|get|pull|lift|fish) out (?P<what>(?!of\b)[^,;]+?)(?= (of|from) (the )?(bin|box|basket|trash)\b|$| "
     r"and\b| then\b)", r"\g<verb> \g<what> out"),  # "take out every block except blue"
    (r"(in|into|inside) it(?=( too| as well| also)?( and\b| then\b|$))", "in the bin"),  # "empty the bin but keep blue
    # in it": no block holds one
    (r"out of it(?=( too| as well| also)?( and\b| then\b|$))", "out of the bin"),  # "... but keep green out of it"
    (r"along with|as well as", "and"),  # "red along with green in the bin"
    (r"the lower (?P<noun>block|cube|one)", r"the bottom \g<noun>"),  # "put the lower block in the bin": the tower's
    (r"the upper (?P<noun>block|cube|one)", r"the top \g<noun>"),
    (rf"(?:(?<=^)|(?<=\band )|(?<=\bthen ))(holding|held|in hand)(?= (the )?({_COLOUR})\b)", "hold"),  # "holding red", as
    # the predicate reads
    (r"(?P<moved>(the )?(bottom|lowest)( block| cube| one)) (on top|at the top|to the top)( of (the )?(tower|stack|pile|other( "
     r"block| cube| one)?))?", r"\g<moved> on the tower"),  # "put the bottom block on top"
    (rf"(?P<head>(swap|switch|exchange|trade)( the places of)? (the )?({_COLOUR})( block| cube)?( and| with) (the )?({_COLOUR})"
     r"( block| cube)?) (in|within|inside|of|on) (the|this|that|your) (tower|stack|pile)", r"\g<head>"),  # "swap red and
    # green in the tower": they trade places, wherever they are
    (r"(?P<head>(swap|switch|exchange|reverse|flip|invert)\b[^,;]*?) so (that )?(the )?(bottom|lower|lowest|top|upper)( one|"
     r" block| cube)? (is|ends up|goes|sits|comes|will be)( on| at the)? (top|bottom)", r"\g<head>"),  # "swap the blocks
    # so the bottom one is on top": what swapping does
    (r"(a (little|bit|touch)|slightly|somewhat|much|even|a lot)(?= (closer|nearer|further|farther)\b)", ""),  # "a little
    # closer to green": closeness has no degrees here
    (r"(closer|nearer)( together| to each other| to one another)?(?= and\b| then\b|$)", "together"),  # "move 2 blocks
    # closer"
    (r"(further|farther) (apart|away)( from each other| from one another)?(?= and\b| then\b|$)", "apart"),
    (r"(further|farther|much|well|far)(?= (away|apart) from\b)", ""),  # "move red further away from green"
    (r"(further|farther) from", "away from"),  # "move red further from green"
    (r"the (tower|stack|pile)'s (top|topmost|uppermost|highest|bottom|lowest|base)", r"the \2 block of the tower"),
    (r"hold (on to|onto)", "hold"),  # before 'on to' is read as 'on'
    (r"(every|each)( single)? one of", "all of"),
    (r"(every|each|all( of)?( the)?) (block|cube)s? (of|in|from) (the|that|this|your) (tower|stack|pile)", "the whole tower"),  #
    # "put every block of the tower on the table"  # "put every one of the blocks in the bin"
    (rf"(?P<lower>(the )?({_COLOUR}))( block| cube| one)? (should |must |will )?(be )?(supports?|supporting|bears?|bearing)"
     rf"(?= (the )?({_COLOUR})\b)", r"\g<lower> under"),  # "green supports red": red on green
    (rf"(?P<lower>(the )?({_COLOUR}))( block| cube| one)? (should |must |will )?(have|has) (?P<upper>(the )?({_COLOUR}))"
     r"( block| cube| one)? (on it|on top( of it)?|stacked on it)", r"\g<upper> on \g<lower>"),  # "green should have red on
    # it"
    (r"(?P<head>(not|\w*n't|never)( \w+){0,2}? (touching|touch|touches|near|next to|close to|beside|by)) either"
     r"(?= and\b| then\b|$)", r"\g<head> both"),  # "blue not touching either": neither of the two said before
    (r"(?P<held>(the )?bin (should |must |will |has to |needs to |is to |to )?(contains?|holds?|has|have|gets?) [^;]*?) and "
     r"(nothing else|no other (blocks?|cubes?|ones?))", r"\g<held> only"),  # "the bin should hold red and nothing else"
    (r"(and )?(when|once|after) (that|this|it) (is|has been) (done|finished|complete|completed|over)", "then"),  # "put blue
    # in the bin, and when that's done, put red on green"
    (r"(and )?(that is (it|all)|nothing (else|more)|(and |when |once )?(we are |you are |we're |you're |are )?(done|finished))"
     r"(?= and\b| then\b|$)", ""),  #
    # "red on green and that's it": the goal ends there
    (r"^((the|your|my|our) )?(goal|task|objective|aim|job|mission)( here| for you)?( is| will be)?( (to|that)( have| get| make"
     r"| achieve)?)?(?= )", ""),  # "the goal is to have red on green", "Task: stack red on green"
    (r"as (fast|quickly|soon|carefully|gently|slowly) as (you can|possible|you like)|take your time( and)?|no rush|no hurry"
     r"|hurry( up)?", ""),  # how, not where
    (r"(?P<verb>build|make|construct|create|stack|assemble) me", r"\g<verb>"),  # "build me a tower"
    (r"(there (should|must|will) be |leave |make sure (that )?there (is|are) )?no (towers?|stacks?|piles?)( (left|standing|"
     r"remaining|at all))?", "unstack all"),  # "there should be no tower"
    (rf"(?P<block>{_COLOUR})( block| cube| one)? (is|should be|must be|will be) the only (block|cube|one)(?= (in|on|near|next|"
     r"held)\b)", r"only \g<block>"),  # "red is the only block in the bin"
    (rf"(?P<refs>(the )?({_COLOUR})((,| and|,? then)? (the )?({_COLOUR}))+)( blocks| cubes)? (tower|stack|pile)(?= and\b| then\b|$)",
     r"stack \g<refs>"),  # "red green blue tower, others in bin"
    (r"(and )?(which|who|that) (stays?|remains?|(is|are) (left|kept|staying|remaining))( on the (desk|table)| where (it|they) "
     r"(is|are)| put| there| behind| out)?(?= and\b| then\b|$)", ""),  # "everything in the bin, except yellow which stays"
    (r"(form|make|create|build) (a|one) (group|cluster|bunch|huddle) (with|of|from|out of|using)", "group"),  # "form a group
    # with red and blue"
    (r"only (?P<verb>leave|keep|put|place|move|drop|throw|toss|set|bring|get)(?= (the )?(" + _COLOUR + r")\b)",
     r"\g<verb> only"),  # "only leave yellow on the desk", "only put blue in the bin"
    (rf"fill (up )?(the )?bin( up)? (with|using) (?P<what>{_LISTED}( blocks?| cubes?)?|everything|all( of)?( the)? (blocks|cubes))",
     r"put \g<what> in the bin"),  # "fill the bin with red and green"
    (r"wait( a (moment|second|bit|while|sec|minute))?(?! (for|until)\b)", ""),
    (rf"((make|have|let) )?(?P<refs>{_LISTED}|them|the two( blocks| cubes)?|both( blocks| cubes)?)( should| must| will| can| "
     r"need to| have to)? (swap|trade|switch|exchange|"
     r"change) (places|positions|spots)( with each other| with one another)?|(put|move|place) (each|both|the two) (blocks? |cubes? )?"
     r"(where|in the place of|in place of) the other( one| block| cube)?( is| was)?", r"swap \g<refs>"),  # "make red and green
    # swap places", "put each block where the other one is"  # "put red in the bin, wait, then ..."
    (r"(is it|would it be|will it be|could it be) possible( for you)? to|(i|we) (was|were|am|are) (hoping|wondering)( if| "
     r"whether| that)?( you)?( could| can| would| might| will)?|^(you|we)( really)? (should|must|need to|have to|will|can|could|"
     r"ought to|are to)|^you( really)?(?= (shouldn'?t|should not|must not|mustn'?t|may not|cannot|can'?t|don'?t|do not|"
     r"never)\b)", ""),  # "is it possible to put red on green", "you should put red in the bin"
    (r"(?<=\bwhile )(you|we)( (should|must|will|can))?(?= (put|place|move|stack|pick|take|drop|set|get|bring|hold|grab|"
     r"throw|toss|lift|remove|build|make|carry)\b)", ""),  # "... while you put red in the bin"
    (rf"^(can|could|may|should|shall) (?P<refs>{_LISTED})( block| cube| one)? (go|be put|be placed|sit|be)(?= (in|into|on|onto|"
     r"next|near|beside|by|away|far|out|off)\b)", r"\g<refs>"),  # "can red go on green?"
    (r"(i|we) (do not|don'?t) want( you to)?( have| put| see| leave)?", "do not put"),  # "I don't want red on green"
    (r"(?P<neg>(don'?t|do not|never|not) (put|place|move|leave|have|keep|stack|set|drop)) (any|a single|a) (block|cube|one)s?",
     r"\g<neg> all"),  # "I don't want any block in the bin": none there
    (r"(?P<verb>put|place|move|leave|have|keep|stack|set|drop) no (block|cube|one)s?", r"do not \g<verb> all"),  # "put no
    # blocks in the bin": none there
    (rf"replace (?P<old>{_LISTED})( block| cube| one)? with (?P<new>{_LISTED})( block| cube| one)? (?P<place>(in|into|inside|"
     r"on|onto|on top of|next to|near|beside|by) [^,;.]+?)(?= *$|[,;.]| and\b| then\b)",
     r"put \g<new> \g<place> instead of \g<old>"),  # "replace red with green in the bin": green there, red not
    (r"(the )?(gripper|hand|robot|arm|fingers) (should |must |will |has to |needs to |is to )?(hold|holds|have|has|grip|grips|"
     r"grasp|grasps|carry|carries)(?= (the )?(" + _COLOUR + r")\b)", "hold"),  # "the gripper should
    # hold red"
    (r"(i|we)( would|'d) (rather|prefer to|like to) have|(i|we)( would|'d)? prefer( to have)?|(it )?(would|will) be (nice|"
     r"good|great) to have|(what|all) (i|we) (want|need|would like|'d like) is", ""),  # "I'd rather have red in the bin"
    (rf"(and )?as (does|do|is|are|should|will|must)(?= (the )?({_COLOUR})\b)", "and"),  # "red goes in the bin, as does green"
    (rf"((then|and) )?(do |does )?(the )?same (for|with|to) (?P<refs>(the )?({_COLOUR}))( block| cube| one)?(?= *($|[;.,]|"
     rf"then\b|but\b|and\b(?! (the )?({_COLOUR})\b)))|(and )?so (does|do|should|must|will) (?P<so>(the )?({_COLOUR}))",
     rf"and \g<refs>\g<so> {AFFIRMED}"),  # "put red next to green; same for blue", "... and so does blue": blue in red's
    # stead, next to green (not next to red); a list after 'the same for' stays a list of the clause before
    (r"((then|and) )?(do )?(the )?same (for|with|to)", "and"),  # "put red in the bin; same for the others"
    (rf"(?P<refs>(the )?({_COLOUR})( block| cube| one)?) (bin|trash|basket)(?= and\b| then\b|$)", r"\g<refs> in the bin"),  #
    # "Red: bin."
    (r"out of contact with", "away from"), (r"in contact with", "next to"),  # "keep red out of contact with green"
    (r"in contact(?= and\b| then\b|$)", "together"),  # "red and green in contact"
    (rf"(?<=\band )that(?= (the )?({_COLOUR})\b)", ""),  # "ensure that red sits on green and that blue ..."
    (r"the (last|final|next) (thing|step)( (to do|you do|for you to do|i want))?( is| should be| will be)( to)?", "then"),
    (r"the first (thing|step)( (to do|you do|for you to do|i want))?( is| should be| will be)( to)?", ""),  # "the first
    # thing to do is put blue in the bin; the last thing is to put yellow on red"
    (r"at all times|all the time|always|forever|for good|permanently|no matter what|whatever happens|in any case|regardless|"
     r"eventually|(by|at) the end( of (it|the (task|episode|run|day)))?|(when|once) (you are|you're|you've|you have) (done|"
     r"finished)", ""),  # the goal's state is the one it ends in
    (r"^(ok(ay)?|alright|all right|u+m+|u+h+|e+r+m*|so|well|hey|hi|hello|right|now then|good|great|cool|actually|sorry)( and| then)?"
     r"(?= )", ""),  # "ok robot, now put green in the bin": a word to start with
    (r"(?:(?<=bin)|(?<=table)|(?<=desk)) next(?= and\b| then\b|$)", ""),  # "the yellow block goes in the bin next"
    (rf"(?P<place>next to|near|beside|close to|away from|far from|on top of|onto|on) (?P<said>(the )?({_COLOUR})( block| cube| "
     rf"one)?)(( and| but)+| *,)* not (?P<other>(the )?({_COLOUR}))( block| cube| one)?( *,)?( and| or| nor)( not)? "
     rf"(?P<third>(the )?({_COLOUR}))( block| cube| one)?(?= *($|[;.,]|then\b|but\b|and\b(?! +not\b)))",
     r"\g<place> \g<said> and not \g<place> \g<other> and not \g<place> \g<third>"),  # "... next to green, not blue or yellow"
    (rf"(?P<place>next to|near|beside|close to|away from|far from|on top of|onto|on) (?P<said>(the )?({_COLOUR})( block| cube| "
     rf"one)?)(( and| but)+| *,)* not (?P<other>(the )?({_COLOUR}))( block| cube| one)?(?= *($|[;.,]|then\b|but\b|"
     r"and\b(?! +not\b)))", r"\g<place> \g<said> and not \g<place> \g<other>"),  # "put red next to green, not blue":
    # not next to blue, the block said in the place's stead (the subject stays; 'instead of' contrasts the subject)
    (r"avoid|refrain from|^(instead of|rather than)", "do not"),  # "avoid stacking red on green", "instead of putting red
    # in the bin, put it on green"
    (r"(,? )?(instead of|rather than)", "and not"),  # "put red in the bin rather than green": as ', not green'
    (rf"(?P<verb>put|place|move|set|lay|stack|drop|throw|toss|get|bring|take) (?P<said>{_LISTED}) (and |but )*not "
     rf"(?P<other>{_LISTED}) (and )?(?P<place>(in|into|inside|on|onto|upon|atop|near|next to|beside|close to|by|away from|"
     r"far from|out of|off)\b.*?)(?= and\b| then\b|$)", r"\g<verb> \g<said> \g<place> and not \g<other>"),  # "put red, not
    # green, in the bin": the place said after both
    (r"((away|far|apart) from|(not|\w*n't|never)(?P<between>( \w+){0,3}?) (near|next to|close to|beside|by|touching|touch"
     r"|touches)) (anything( else)?|any( other)? (block|cube|one)s?|any of the others|another (block|cube|one)|every(thing|"
     r" other (block|cube|one)))(?! else\b)", r"\g<between> away"),  # "red should not be near anything": away from
    # every other block, named before or not
    (r"(in|into) a (row|line)", "together"),  # "put the blocks in a row": each next to the next
    (r"(clear|clean|empty|rid)( off| up)? (the )?(table|desk|tabletop|workspace|surface) of", "clean"),  # "clear the desk of
    # all blocks except yellow"
    (rf"(?P<block>\b({_COLOUR})( block| cube| one)?)( (should|must|has to|needs to|will|can))? (leave|leaves|exit|exits|"
     r"comes? out of) (the )?(bin|box|basket|trash|bucket)\b", r"\g<block> out of the bin"),  # "red must leave the bin"
    (r"(?P<whole>(clear|clean|empty|tidy)( off| up)? (the )?(table|desk|tabletop|workspace|surface)) (into|in|to) (the )?"
     r"(bin|basket|box|trash|bucket)", r"\g<whole>"),  # "empty the desk into the bin"
    (rf"if (?P<refs>(the )?({_COLOUR})( block| cube| one)?) (is not|isn't|is n't) (?P<place>(in|on|onto|next to|near|beside|"
     r"by|away from|out of) [^,]+?),? (then )?(put|move|place|get) it there", r"put \g<refs> \g<place>"),  # "if red isn't in
    # the bin, put it there": the goal says so
    (r"(unless|if|in case) (it|they|that|this) (is|are|isn't|aren't|is not|are not) (not )?(already|yet) (there|so|done|in place"
     r"|in (the )?(bin|box|basket|trash))", ""),  # "put purple in the bin unless it is already there": the goal says so
    (r"(?P<join>and|then) (build |make )?(another|a second|a separate|one more)( tower| stack| pile| one)? (of|with|from|using"
     r"|out of)", r"\g<join> stack"),  # "a tower of red and green and another of blue and yellow"
    (r"(put|place|set|stack) one( block| cube| of them)? (on|onto|on top of|atop) the other( block| cube| one)?",
     "stack both"),  # of two blocks: a tower in either order
    (r"(?:(?<=^)|(?<=\band )|(?<=\bthen )|(?<=\bbut )|(?<=\bwhile )|(?<=\bwhereas )|(?<=\bsure )|(?<=\bsure that )|"
     r"(?<=\bensure )|(?<=\bensure that ))"
     rf"(?P<who>(the )?({_COLOUR})( block| cube| one)?((,? and|,) (the )?({_COLOUR})( block| cube| one)?)*|the rest|the others|"
     r"all the others|all (of )?the other (blocks|cubes|ones)|everything else|every other (block|cube|one)|the other (blocks"
     r"|cubes|ones|two|three)|(all )?(the )?remaining (blocks|cubes|ones)) (should |must |will |can |may )?(stays?|remains?"
     r"|(is|are|be) left)( (where|as) (it|they) (is|are|was|were|stands?)| put| in place| there| alone| untouched| unmoved"
     r"| as is)?(?= and\b| then\b| but\b| while\b|$)", rf"keep \g<who> {IN_PLACE}"),  # "put red in the bin, green stays": where
    # it is ("red and green stay, the rest go in the bin": the mark ends the clause, not "keep ... in the bin")
    (rf"(?:(?<=\band )|(?<=\bbut ))(?P<refs>{_LISTED})( blocks?| cubes?| ones?)? (is|are|does|do|should|must|will|can|has|have)( to)?( be)?"
     r"(?= and\b| then\b|$)", rf"\g<refs> {AFFIRMED}"),  # "red is not in the bin and green is": green is in it
    (r"any (longer|more)", ""),
    (r"(on|onto|to) the (very )?top of", "on top of"),  # "put orange on the top of the tower"
    (r"off (of )?(the )?top of", "off"),
    (r"from (on )?(the )?top of|from (on|atop|upon)(?= (the )?(" + _COLOUR + r")\b)", "from"),  # "move
    # green from on top of red onto blue"  # "take red off the top of green"
    (r"(to|in|on|onto|into|at) (an? |some )?(empty|free|clear|open|clean)( spot| place| space| area| part)( (on|of) the (table|"
     r"desk))?", "on the table"),  # "move red to an empty spot": out of the hand and the bin, on no block
    (r"(?P<verb>move|put|take|bring|return|place|get) (all )?(the |all the )?(blocks|cubes|ones) ((that|which) (are|is) )?"
     r"(in|inside|from) the (bin|box|basket|trash|container) (back )?(to|on|onto|out on|out onto) the (table|desk)",
     "take all out of the bin"),  # "move the blocks that are in the bin back to the table"
    (r"(?P<verb>move|put|place|throw|toss|drop|get|bring|take) (every|each|all( of)?( the)?|the) (blocks?|cubes?)( (that|which)"
     r" (is|are))? (on|from|lying on|sitting on) the (table|desk)(?= (in|into|to) (the )?(bin|box|basket|trash))",
     r"\g<verb> all"),  # "put all the blocks on the desk into the bin": every block there
    (r"(the )?(loose|free|unstacked|scattered|spare) (blocks|cubes|ones)", "all except the_whole"),  # "the loose
    # blocks": those in no tower
    (r"(store|stow)( away)?", "clean"),  # "store the green block": in the bin
    (r"space (?P<what>them|it|everything|all( the)?( blocks| cubes)?|the (blocks|cubes)) out", r"separate \g<what>"),
    (r"(?P<noun>tower|stack|pile)( of)? (using|with|from|out of|made of|made up of|made from|consisting of|composed of)"
     rf"(?= (the )?({_COLOUR})\b)(?! (the )?({_COLOUR})( block| cube| one)? (on (the )?top|(at|on) the (top|bottom|base|foot)|as "
     r"the (top|bottom|base)|uppermost|highest|lowest)\b)", r"\g<noun> of"),  # "a tower of height three using red, green
    # and blue", not "a tower with red at the bottom" (that names its end)
    (rf"((build|make|form|create|construct) )?(a |the |one )?(tower|stack|pile) (with|where|in which|such that|so that)"
     rf"(?= (the )?({_COLOUR})( block| cube| one)?( is| sits| goes)? (on top of|on|atop|above) (the )?({_COLOUR})\b)",
     "stack"),  # "a tower with yellow on top of orange on top of red"
    (r"(while|whilst) (still )?holding", f"{SENTENCE_END} hold"),  # "put red in the bin while holding green"
    (r"while|whilst|meanwhile", SENTENCE_END),  # "hold orange while red sits on green": a clause of its own
    (rf"(?P<refs>{_LISTED})( blocks| cubes)?( should| must| are| is| will| can)?( not| never)( be)? (stacked|piled|put|placed|"
     r"set)( up)? (on|onto|upon|atop|on top of) (each other|one another)", r"do not stack \g<refs>"),  # "red and green should
    # not be stacked on each other": neither on the other
    (r"(?P<verb>put|place|set|stack|pile|move) (?P<refs>all( of)?( the)?( blocks| cubes)?|the (blocks|cubes)|everything|them|"
     r"every (block|cube)) (on|onto|upon|atop|on top of) (each other|one another|another) *,? *(with )?(?P<end>(the )?("
     + _COLOUR + r")( block| cube)? (on top|at the (top|bottom|base)))", r"stack \g<refs> with \g<end>"),
    (r"(?P<verb>put|place|set|stack|pile|move) (?P<refs>all( of)?( the)?( blocks| cubes)?|the (blocks|cubes)|everything|them|"
     r"every (block|cube)) (on|onto|upon|atop|on top of) (each other|one another|another)", rf"stack \g<refs> {ANY_ORDER}"),
    # "put all blocks on top of each other": one tower of them (in the order left open, where no end is said)
    (rf"unstack (?P<upper>(the )?({_COLOUR}))( block| cube)? from( the top of)? (?P<lower>(the )?({_COLOUR}))", r"unstack "
     r"\g<upper> off \g<lower>"),  # "unstack red from green"
    (r"(?P<verb>stack|pile) (?P<what>it all|them all|everything|all( of)?( the)?( blocks| cubes)?|them) up", r"\g<verb> "
     r"\g<what>"),  # "stack it all up"
    (r"\bit all\b", "all"),
    (rf"(?P<verb>(put|place|set|stack|pile|move) )?(?P<refs>{_LISTED})( blocks| cubes)?(( should| must| will| can)? be)?"
     rf"( stacked| piled| placed| put| set)?( up)? (on|onto|upon|atop|on top of) (each other|one another)",
     rf"stack \g<refs> {ANY_ORDER}"),  # "put red and green on top of each other": one on the other, either way
    (rf"(?P<refs>{_LISTED})( blocks| cubes)?( should| must| are| is| will| can)?"
     r"( not| never)( be)? (stacked|piled)( up)?", r"unstack \g<refs>"),  # "red and green should not be stacked": neither
    # on a block
    (rf"(?P<verb>put|place|move|stack|pile|drop|throw|toss|set|lay|arrange) ((the |all (of )?the |all |every |each )?(blocks"
     rf"|cubes|block|cube)|them|these|those) (?P<place>([^,:;]*? )?)in ((the|this|that) )?(following )?order:? "
     rf"(?P<listed>(the )?({_COLOUR})((,| ,)? (and |then )?(the )?({_COLOUR}))+)", r"\g<verb> \g<listed> \g<place>"),
    # "put the blocks in the bin in the order red, green, blue": the blocks listed
    (rf"(?P<verb>stack|pile|build a tower of|build a stack of) (them all|all of them|all( the)?( blocks| cubes)?|everything)"
     rf"(?= (the )?({_COLOUR})\b)", r"\g<verb>"),  # "stack them all: red first, then green": the blocks listed
    (rf"(?P<block>{_COLOUR})( block| cube| one)? (is |should be |must be |be )?not (on|on top of|stacked on) (anything|any"
     r"( other)? (block|cube|one)s?|another( block| cube| one)?|any of the others)", r"take \g<block> off"),  # "blue is
    # not on anything": on no block
    (rf"(?P<place>next to|near|beside|close to|by) (the )?(?P<block>{_COLOUR})( block| cube| one)? (on|onto) (the )?"
     r"(table|desk)", r"\g<place> \g<block> and on the table"),  # "green next to red on the table": both
    (rf"(nothing|none of the (blocks|cubes)|no (other )?(block|cube)s?)( else)? (but|except( for)?|other than|besides|apart "
     rf"from|aside from|save for)(?= (the )?({_COLOUR})\b)", "only"),  # "nothing but red should be on the table"
    (r"(make sure |ensure )?(that )?(none of the (blocks|cubes)|no (other )?(block|cube)s?|nothing|no one)( else)?( should| must"
     r"| may| can| is| are| will)?( be| stay| remain| sit| sits| rest| rests)?( stacked| piled| left| put| placed)? (on|on top "
     rf"of|onto|atop|upon) (the )?(?P<block>{_COLOUR})( block| cube| one)?\b", r"take all off \g<block>"),  # "nothing
    # should be on red": no block on it
    (rf"clear (off )?(the )?top of (the )?(?P<block>{_COLOUR})( block| cube| one)?\b", r"take all off \g<block>"),
    (r"(none of the (blocks|cubes)|no (block|cube)s?|nothing)( should| must| may| can| is| are| will)?( be| stay| remain)?"
     r" (stacked|piled|on (top of )?(another|any other|each other|one another|other)( blocks?| cubes?| ones?)?)",
     "unstack"),  # "none of the blocks should be stacked", "no block on top of another"
    (r"(don'?t|do not|never|please don'?t) (knock|tear|topple|take)( over| down)?( the| your| that| this)? (tower|stack|pile)"
     r"( over| down)?", "keep the_whole"),  # "don't knock the tower over": the same, for the tower's blocks
    (r"(drop|release|let go of|put down|set down) (the )?(block|cube|one|what|whatever)( that)? (you are|you're|"
     r"you have|is|it is) (holding|carrying|gripping|in (your|the) (hand|gripper))(?! (in|into|inside|on|onto|atop|upon|next|"
     r"near|beside|close|by|away|far|to)\b)", "release all"),  # not "drop what you are holding in the bin": the_held
    (rf"(?P<base>(at|on) the (bottom|base|foot)) and (the )?(?P<top>{_COLOUR})( block| cube| one)? (on (the )?top|at the top|"
     r"as the top)", r"\g<base> and with \g<top> on top"),  # "with red at the bottom and purple at the top"
    (rf"(?P<top>on (the )?top|at the top|as the top) and (the )?(?P<base>{_COLOUR})( block| cube| one)? ((at|on) the (bottom|"
     r"base|foot)|as the (bottom|base))", r"\g<top> and with \g<base> at the bottom"),  # "... and red at the bottom"
    (rf"(and )?with (the )?(?P<top>{_COLOUR})( block| cube| one)? (on (the )?top|at the top|as the top|"
     r"uppermost|highest)(?! of\b)", rf"{TOP_MARK} \g<top>"),  # "a tower of red and green with blue on top"
    (rf"(and )?with (the )?(?P<base>{_COLOUR})( block| cube| one)? ((at|on) the (bottom|base|foot)|"
     r"as the (bottom|base)|lowest)(?! of\b)", rf"{BASE_MARK} \g<base>"),
    (r"(spread|lay|put|take|break)( the| your| that| this)? (tower|stack|pile) (out|down|apart)( on the (table|desk))?|"
     r"(unstack|dismantle|disassemble|take apart|break up|break down|tear down|undo)( the| your| that| this)? (tower|stack|"
     r"pile)s?|(unstack|dismantle|disassemble|take apart|break up|break down|tear down|knock over|knock down) (all|every|both)"
     r"( of)?( the)? (towers|stacks|piles)|"
     r"take( the| your| that| this)? (tower|stack|pile)s? apart|dismantle|disassemble", "unstack"),
    (r"(take|pull|break) (?P<what>it|them) (apart|down)", r"unstack \g<what>"),  # "... then take it apart"  # blocks on the table
    (r"((that|which) (are|is) )?(except( for)?|but( for| leave| keep| spare| skip| not)?|other than|apart from|besides|"
     r"save for|not( part of)?|(that|which) (aren't|isn't)( part of)?) "
     r"(the (blocks|cubes|ones)|those|what('s| is))?( (that|which) (are|is|stand|make up|form))? ?"
     r"((in|of|on|forming|making up) )?(the|that|this|your) (tower|stack|pile)"
     r"(?! of)", "except the_whole"),  # "put every block except those in the tower in the bin": the others, when planned
    (r"the (whole|entire|complete) (tower|stack|pile|thing)|all( of)? the (blocks|cubes) (of|in) the (tower|stack|pile)|"
     r"the (tower|stack|pile)'?s (blocks|cubes)", "the_whole"),  # "put the whole tower in the bin": each of its blocks
    (r"(switch|swap|change|reverse|flip) (which|the) (block|cube|one)( that)? (is|sits|goes|lies) (on top|at the top|on the "
     r"bottom|at the bottom|underneath|below)", "swap the_whole"),  # "switch which block is on top": the tower reversed
    (r"(reverse|invert|flip( over)?|turn over|turn upside down|swap|switch|exchange)( the order of)?( the (blocks|cubes) "
     r"(of|in))? (the|that|this|your) (tower|stack|pile)('?s (blocks|cubes))?( upside down| over| around)?|turn (the|that|"
     r"this|your) (tower|stack|pile) (upside down|over)|(reverse|invert|swap|switch|flip|change) the order of (all )?(the )?(blocks|cubes)"
     r"|(re)?(build|make|stack|arrange|put) (the|that|this|your) (tower|stack|pile|blocks|cubes)( again)? (in|into) (the )?"
     r"(reverse|reversed|opposite|inverse) order( again)?|(re)?(stack|put|place|arrange|build|turn|flip) (them|it|all|(the|that|"
     r"this|your) (tower|stack|pile|blocks|cubes))( again)? (the )?other way (a)?round",
     "swap the_whole"),  # "reverse the tower": its blocks'
    # order turned over, the top one at the bottom (placed when planned)
    (r"(?P<verb>put|place|move|bring|carry|transfer|shift|drop|throw|toss|chuck|dump|discard|clean) (the|that|this|your) "
     r"(tower|stack|pile)(?! of)", r"\g<verb> the_whole"),  # "put the tower in the bin": what is moved is each block
    (rf"(the (block|cube|one)( (that|which))?( is|'s| sits| lies| stands| rests)|whatever( is|'s| sits| lies)?|what( is|'s|"
     rf" sits| lies)) "
     rf"(on top of|on|atop|upon|above|stacked on) (the )?(?P<below>{_COLOUR})( block| cube| one)?|"
     rf"{_NOT_AFTER_A_PUT}the (block|cube|one) (on top of|on|atop|upon|above) (the )?(?P<below2>{_COLOUR})( block| cube| one)?"
     rf"|(?P<verb>put|place|move|stack|set|drop|lay) the (block|cube|one) (on top of|on|atop|upon|above) (the )?"
     rf"(?P<below3>{_COLOUR})( block| cube| one)?(?= (in|into|on|onto|next|near|beside|by|close|away|far|out|off)\b)",
     r"\g<verb> the_upper \g<below>\g<below2>\g<below3>"),  # "the block on red": the one standing on it when planned; after
    # "put" only where a place follows ("put the block on red in the bin"), as "put the block on red" puts it there
    (rf"(the (block|cube|one)( (that|which))?|whatever|what(?= is|'s| sits| lies| stands))( is|'s| sits| lies| stands)? (under|"
     rf"underneath|below|beneath|supporting) "
     rf"(the )?(?P<above>{_COLOUR})( block| cube| one)?|the (block|cube|one)( that| which)? (the )?(?P<upper>{_COLOUR})"
     r"( block| cube| one)? (is|sits|stands|lies|rests) on", r"the_lower \g<above>\g<upper>"),  # "the block under green"
    (r"(whatever|what|the (block|cube|one|thing)( that| which)?) (you are|you're|you have|you've got|the robot is|the robot"
     r" has|the hand is|the gripper is|is)( currently| now| still)? (holding|carrying|gripping|grasping|got|in (your|the|its) "
     r"(hand|gripper))|the (block|cube|one) (in|inside) (your|the|its) (hand|gripper)|the held (block|cube|one)|what you "
     r"(hold|have|carry)|the (block|cube|one) (that|which) (is|'s) (held|being held|in (your|the|its) (hand|gripper))",
     "the_held"),  # "put whatever you are holding in the bin": the block held when planned
    (r"the (binned|trashed) (block|cube|one)", "the block that is in the bin"),  # "put the binned block on red"
    (r"the (block|cube|one) (that|which) (is|'s) (in|inside) the (bin|box|basket|trash|container)|the (block|cube|one) (in|"
     r"inside) the (bin|box|basket|trash|container)(?= (out|on|onto|next|near|beside|by|away|back|to)\b)|the (block|cube|one)"
     r"(?= (out of|from) the (bin|box|basket|trash|container)\b)", "the_binned"),  # "take the block that is in the bin
    # out", "put the block in the bin on the table": the one there when planned
    *((rf"the ({word}|{k}(st|nd|rd|th))[- ](block |cube |one )?(from|counting from)[- ](the[- ])?(?P<end>top|bottom)"
       r"( block| cube| one)?( of (the|that|this|your) (tower|stack|pile))?", rf"the_\g<end>{k}")
      for word, k in _ORDINALS.items()),  # "the second block from the top", "the second-from-top block": when planned
    *((rf"the (block|cube|one) ({word}|{k}(st|nd|rd|th)) from the (?P<end>top|bottom)( of (the|that|this|your) (tower|"
       r"stack|pile))?", rf"the_\g<end>{k}") for word, k in _ORDINALS.items()),  # "the block second from the top"
    *((rf"the ({word}|{k}(st|nd|rd|th))[- ]{side}( block| cube| one)?( (of|in) (the|that|this|your) (tower|stack|pile))?",
       f"the_{end}{k}") for word, k in _ORDINALS.items()
      for side, end in (("(highest|topmost|uppermost)", "top"), ("(lowest|bottommost)", "bottom"))),  # "the second
    # highest block"
    (r"(take|lift|pull) off(?= the\b)", "remove"),  # "take off the top three blocks"
    *((rf"the {end} {word} (blocks|cubes)( (of|in) (the|that|this|your) (tower|stack|pile))?",
       " and ".join([*(f"the_{end}{i}" for i in range(k, 1, -1)), "the_top" if end == "top" else "the_base"]))
      for word, k in NUMBERS.items() for end in ("top", "bottom")),  # "the top two blocks": the top one and the one
    # under it
    (r"the (middle|central) (block|cube|one)( (of|in) (the|that|this|your) (tower|stack|pile))?|the (block|cube|one) in the "
     r"middle( of (the|that|this|your) (tower|stack|pile))?", "the_middle"),
    (r"the (top|topmost|uppermost|highest) (block|cube|one)( (of|in) (the|that|this|your) (tower|stack|pile))?|"
     rf"the (block|cube|one) (on|at) (the )?top( of (the|that|this|your) (tower|stack|pile))?(?! of (the )?({_COLOUR}))",
     "the_top"),
    (r"the (bottom|lowest|base) (block|cube|one)( (of|in) (the|that|this|your) (tower|stack|pile))?|"
     r"the (block|cube|one) (at|on) the (bottom|base|foot)( of (the|that|this|your) (tower|stack|pile))?",
     "the_base"),  # "put the top block in the bin": the tower's ends, placed when planned
    (rf"(put|place|set|stack) (?P<what>(the )?({_COLOUR})( block| cube| one)?) (at|on) the (bottom|base|foot)"
     rf"(?=( and)?( then)? (the )?({_COLOUR})( block| cube| one)?( and\b| then\b|$))", r"stack \g<what>"),  # "put red at the
    # bottom, then green, then blue": a tower listed from the bottom
    (rf"(?P<verb>put|place|move|set|stack|get) (?P<what>(the )?({_COLOUR})( block| cube| one)?) (at|to|on|onto) the (very )?"
     r"top( of (the|that|this|your) (tower|stack|pile))?(?= and\b| then\b|$)" + _NOT_A_LIST, r"\g<verb> \g<what> on the_tower"),
    (rf"(?P<verb>put|place|move|set|stack|get) (?P<what>(the )?({_COLOUR})( block| cube| one)?) (at|to|on|onto) the "
     r"(bottom|base|foot)( of (the|that|this|your) (tower|stack|pile))?(?= and\b| then\b|$)" + _NOT_A_LIST,
     rf"\g<verb> \g<what> {UNDER_A_TOWER}"),
    # "put red at the top": on the tower; "put yellow at the bottom": under it
    (r"((at|to|on|in) the (bottom|base|foot) of|under|underneath|beneath|below)( the| that| this| your) (tower|stack|"
     r"pile)(?! of)", UNDER_A_TOWER),  # "put red at the bottom of the tower"
    (r"add (?P<what>[^,;]+?) (to|onto|on top of) (the|that|this|your) (tower|stack|pile)(?! of)",
     r"put \g<what> on the_tower"),  # "add blue to the tower": on top of it
    (r"(?P<place>on top of|on to|onto|upon|atop|on|next to|near|beside|close to|away from|far from|by|touching|touch|touches)"
     r"( the| that| this| your) (tower|stack|pile)(?! of)", r"\g<place> the_tower"),  # "put orange on the tower": the one standing then
    (rf"with (?P<what>(the )?({_COLOUR})( block| cube| one)?) (?P<place>beside|next to|near|close to|by|away from|far from) "
     r"(?P<it>it|them|the (tower|stack|pile))", r"and put \g<what> \g<place> \g<it>"),  # "a tower of red and green, with
    # blue beside it"
    (r"with(?= (the )?(" + _COLOUR + r")( block| cube| one)? (apart|away|isolated|separated|far|alone|"
     r"by itself|on its own|in|out|held)\b)", "and"),  # "red and green side by side, with blue apart"
    (r"(thanks|thank you)( (very|so) much| a lot| in advance)?|if you (don'?t|do not) mind|(would|do) you mind|if (it is|it's"
     r"|that is|that's) (ok|okay|alright|all right|possible|not too much trouble)|if (possible|you can|you could|you would|you"
     r" please)|when(ever)? you (can|get a chance|have (a moment|time|a minute|a second|a sec))|at your (earliest )?convenience"
     r"|as soon as (you can|possible)|(i|we)( would|'d) appreciate( it)? if|it would be (great|nice|good|ideal) if|(that |it )?"
     r"(would|will) be (great|nice|good|perfect|ideal|lovely|fine|appreciated|helpful)|for me|for us|kindly|try to|attempt to"
     r"|(we|i) (need|want|would like|'d like)( you)?( to)?( see)?|we( would|'d) like( you)?( to)?( see)?|^ *(how|what) about",
     ""),  # politeness: no goal in it ("I want to see red on green", "how about red on green")
    (r"^(hmm+|hm+|um+|uh+|erm?|ah|oh|yes|yeah|yep|well|(no|nope)(?= and))( and)?|(i|we) (think|guess|believe|suppose|"
     r"reckon|feel)( that)?|maybe|perhaps|(help|assist) (me|us)( to)?", ""),  # "hmm, ...", "no, put green in the bin
    # instead", "I think red should go in the bin", "could you help me put ..."
    (r"(make sure|make certain|make it so|ensure|see to it|check|verify)( that| to)?( you)?|i( would|'d) like( you)?( to)?|"
     r"i want( you)?( to)?|"
     r"i need( you)?( to)?|sort( out)?( all)?( the| your)? (blocks|cubes)|"
     r"(can|could|would|will) you( please)?|let'?s|go ahead and|where (it|they) (is|are)|as (it|they) (is|are)|as is|"
     r"^ *why (don'?t|do not) (you|we)|^ *why not", ""),
    (r"in (any|whatever|no particular|either|random) order|the order (does not|doesn't) matter", ANY_ORDER),
    (r"in ((that|this|the same|the given|the listed|the named|the following) )?order(?! to\b)|(starting|beginning) with(?= (the )?"
     rf"({_COLOUR})\b)", ""),  # "stack red, green and blue in that order", "put everything in the bin, starting with red"
    (r"(in|into) (a|one|the same) (group|cluster|bunch|huddle|heap|clump)", "together"),  # "red and green in a group"
    (r"right away|straight away|at once|as soon as (you can|possible)|asap|one (by|after) (one|another|the other)|"
     r"one at a time|(each )?in turn|(block|cube|piece|one) by (block|cube|piece|one)|one (block|cube|piece) at a time|"
     r"flat(?= (on|upon)\b)", ""),  # how soon, or in what turns, says nothing of where the blocks end
    (r"((needs?|has|have|ought|got|is going|are going|wants?) )?to ((all|both) )?(be|end up|stay|remain|sit)|(ends?|ending|"
     r"winds?) up|"
     r"(needs?|has|have|ought|got|is going|are going|wants?) to (go|get|move)(?= (in|into|inside|on|onto|next|near|beside|"
     r"by|away|far|out|off|back)\b)", ""),  # "red needs to go in the bin"
    (r"nothing else|no other (blocks?|cubes?|ones?)|none of the others", "other not"),  # "nothing else should be in the
    # bin": the blocks not named
    (r"somewhere else|elsewhere|some ?place else|out of (the|its|my|your|our) way", "away"),  # "red beside green, blue
    # somewhere else", "move red out of the way": away from the others
    (r"(everything|everyone|all|anything|any block|each block|every block)( else)|else", "other"),  # "everything else"
    (r"(in|into|as) (a|an|the shape of an?) (triangle|circle|square|ring|cross|pyramid|diamond|l[- ]shape|t[- ]shape|star|"
     r"rectangle|zig-?zag|v[- ]shape)|(form|make|build|create) an? (triangle|circle|square|ring|cross|pyramid|diamond|star)|"
     r"(in|into|at|to) (a|the) (corner|edge|side)( of the (table|desk))?|(in|into|at|to) the (middle|center|centre) of the "
     r"(table|desk)", DIRECTION),  # shapes and
    # places on the table
    (r"(back )?((to|in|into|at) (the )?(spot|place|position|location) )?where (it|they) (was|were|used to be|came from|"
     r"started|stood|lay)", DIRECTION),  # "put red back where it was": a place the goal cannot name
    (rf"((to|in|into|at) (the )?(spot|place|position|location) )?where (the )?({_COLOUR})( block| cube| one)? (is|was|sits|sat|"
     rf"stands|stood|lies|lay|used to be)( before| now)?|from (left|right) to (left|right)|(on |at |to )?(the )?opposite "
     r"(sides|ends|corners|edges)( of the (table|desk))?", DIRECTION),  # "put red where green was": a place on the table
    (r"(to|on|at) the (left|right)( hand)?( side)?( of)?|(left|right) of|in front of|behind|in back of|"
     r"(north|south|east|west) of|(in|at|to|near|by|on|into) the (far |near )?((edge|corner|center|centre)( of the (table|desk|"
     r"tabletop))?|(middle|side|end|front|back) of the (table|desk|tabletop))", DIRECTION),
    (r"the other (two|three)|all (of )?(the )?others|all (of )?the other (blocks|cubes|ones)|every other (block|cube|one)",
     "other"),
    (r"as well as|as well|along with|plus", "and"),
    (rf"(all|every|each|both)( of)?( the)? (?P<colour>{_COLOUR}) (blocks|cubes|ones)", r"\g<colour>"),  # "all red blocks":
    # the one red block
    (rf"(and )?so (does|do|is|are|should|must|will|has|have)(?= (the )?({_COLOUR})\b)", "and"),  # "... and so does green"
    (r"(knock|tear|topple|take)( over| down)?( the| your)? (tower|stack|pile)( over| down)?|"
     r"(knock|topple)( over| down)?", "unstack"),  # "knock the tower over", "knock it over"
    (_LISTED_INTO_A_TOWER + rf" and(?= (the )?({_COLOUR})\b)", r"stack \g<listed> and put"),  # "red and green in a
    # tower and blue in the bin": blue a clause of its own, not the tower's third block
    (_LISTED_INTO_A_TOWER + r"(?= and\b|$)", r"stack \g<listed> then"),  # "red, green and blue in a tower, the rest ..."
    (_LISTED_INTO_A_TOWER, r"stack \g<listed> and put \g<base>"),  # "... in a tower next to yellow": its bottom block
    (rf"(?P<verb>stack|build a tower of|build a stack of) (the )?(?P<listed>(?P<base>{_COLOUR})(( and| then)? ({_COLOUR}))+)"
     r"( blocks| cubes)? (?P<place>next to|near|beside|close to|by|away from|far from|(in|into|out of)(?= (the )?bin\b)|"
     rf"(on|onto)(?= (the )?table\b)|(on|onto|on top of)(?= (the )?({_COLOUR}|the_tower)\b))",
     r"\g<verb> \g<listed> and put \g<base> \g<place>"),
    # "stack red, green and blue next to yellow", "in the bin", "on the table", "on yellow": the tower, so its bottom
    # block, goes there
    (r"(in|into|as|to) (a|one) (single )?(tower|stack|pile)", INTO_A_TOWER),  # "stack all blocks into one tower"
    (r"((build|make|form|create) |^)(two|three|2|3|a couple of|several|some) (towers|stacks|piles)", ""),  # then each said
    (r"(take|remove|get|lift|move|put) (everything|all( the)?( blocks| cubes)?|them all|every block|each block) (off|from|"
     r"down from) "
     r"(the|that|this|your) (tower|stack|pile)", "unstack"),
    (r"(off( of)?|(down )?from)( the| that| this| your) (tower|stack|pile)(?! of)", "off"),  # "take red off the tower"
    (rf"^(?P<order>(from )?(the )?(top (down )?to (the )?bottom|bottom (up )?to (the )?top|top down|bottom up))(?= (the )?"
     rf"({_COLOUR})\b)", r"stack \g<order>"),  # "from bottom to top: red, green, blue": a tower, in that order
    (r"(from )?(the )?top (down )?to (the )?bottom|from the top( down)?|top down", TOP_DOWN),
    (r"(from )?(the )?bottom (up )?to (the )?top", ""),
    (r"(build|make|form|create|stack|pile)( up)?( them( all)?| everything| all( the)?( blocks| cubes)?)?( in(to)?)? (one|a "
     r"single|one single|a big|one big|a tall|one tall|a single big|one single big|one large|a large) (tower|stack|pile)"
     r"(?! (with|of|from|out of|using|made)\b)|(build|make|form|create|stack)( up)? (the|a|one) (tallest|highest|biggest|"
     r"largest) (tower|stack|pile)( (that )?(you can|possible|there can be))?|(build|make|form|create) (a|one) (tower|stack|"
     r"pile) as (high|tall|big|large) as (possible|you can)", "stack all"),  # "make one big tower": of every block
    (r"(?P<verb>stack|pile)( up)? (?P<what>everything|them( all)?|all( of)?( the)?( blocks| cubes)?|the (blocks|cubes))"
     r"( up)?( (on|onto) (the )?(table|desk))?(?! (on|onto|next|near|beside|by|in|into|away)\b)", r"stack \g<what>"),
    # "pile everything up", "stack all blocks on the table": one tower (on the table, where a tower stands)
    (r"(build|make|form|create)( a| the| one)? (tower|stack|pile)( with| of| from| out of| using)?|tower", "stack"),
    (r"(at|on) the (bottom|base|foot)|first of all|first off|to begin with|for starters|at first|first|to start with|to start|"
     r"bottom up|(from )?(the )?bottom (up )?to (the )?top|from the bottom( up)?", ""),
    (r"(leave|let) (?P<what>[^,;]+?) (alone|be)\b", r"keep \g<what>"),  # "leave red alone": as 'keep red where it is'
    (r"by (itself|themselves)|on (its|their) own|(all )?alone|lonely|solitary", "apart"),  # "red with green, blue alone"
    (r"(near|next to|close to|beside|by|touching|touch) (neither|none)( of them| of those| of the others)?(?= *(and\b|then\b|$))",
     "away from the others"),  # "red and green together, and blue near neither"
    (r"and then|after that|afterwards|after this|once done|when done|followed by|so that|so|such that|;", "then"),
    (r"don'?t|do not|never|no longer|isn'?t|aren'?t|is not|are not|should not|shouldn'?t|must not|mustn'?t|"
     r"doesn'?t|does not|won'?t|cannot|can'?t|can not|may not|might not|not", "not"),
    (rf"(all|every|everything|each)( the| of the)?( blocks?| cubes?| ones?)? but( not)?(?= (the )?({_COLOUR}|blocks?|cubes?|"
     r"ones?|two|three|four|five|six|seven|\d|the_\w+)\b)", "all except"),  # "all but red", "all but the top block"
    # (the_top: said by where it is), not "keep everything, but move red"
    (r"((keep|leave|with)( the| an| your)? )?(holding nothing|hold nothing|hand empty|gripper empty|"
     r"empty[- ]handed|(empty|open)( your| the)? (hand|gripper|fingers))|(the|your|its) (hand|gripper)( should| must| will| "
     r"is)?( be| stay| remain)? (empty|free)|(nothing|no (block|cube)s?) (should |must |will |is |are )?(be )?(in (the|your|its) (hand|"
     r"gripper)|held)|(do not|don'?t|never|not) (hold|carry|grip|grasp)( on to| onto)? anything", "and release all"),  # "the
    # hand should be empty", "don't hold anything"
    (r"(empty|clear|clean)( off| up)? (the )?(desk|table|tabletop|workspace)|((clear|clean|take|get|move|remove) )?(everything|"
     r"all( the)?( blocks| cubes)?) (off|from) (of )?(the )?(desk|table|tabletop|workspace)|(make sure )?(that )?(no|none of the) "
     r"(block|blocks|cube|cubes)( should| must| will)?( be| is| are| remains?| stays?| left)* (on|upon) (the )?(table|desk|"
     r"tabletop)|(make sure )?(that )?nothing( should| must| will)?( be| is| remains?| stays?| left)* on (the )?(table|desk|"
     r"tabletop)", "clean the table"),  # "empty the desk", "no block should be left on the table"
    (r"(nothing|none( of them| of the (blocks|cubes))?|no (two )?(blocks?|cubes?|ones?))( should| must| may| can| is| are| will)?"
     r"( be)? (touch|touches|touching|near|next to|close to|beside|by|in contact with) (anything|any other( block| cube| one)?|"
     r"another( block| cube| one)?|each other|one another)", "all apart"),  # "nothing should touch anything"
    (r"nothing|none( of them| of the (blocks|cubes))?|no (two )?(blocks?|cubes?|ones?)", "all not"),
    (r"(but |and )?not (be |being )?(stacked|piled)( up)?( on (top of )?(each other|one another|the other))?(?! (on|onto|upon|"
     r"atop|on top of) )", "and unstack them"),  # "put the blocks side by side but not stacked"
    (r"without (stack|put (one|it|them) on (top of )?(the other|each other|one another|another))( them| it)?",
     "and unstack them"),  # "put red near green without stacking them": neither on the other (gerunds read as verbs)
    (r"by(?= (put|pick|take|move|place|stack|throw|toss|drop|bring|carry|clean|clear|separate|group|remove|lift|"
     r"grab|unstack|build|make|empty|get)\b)", "and"),  # "clean up the desk by putting all the blocks in the bin"
    (rf"((?:all|everything|every (?:block|cube|one)|each (?:block|cube|one)|all (?:the )?(?:blocks|cubes)) (?:of (?:them|the "
     rf"(?:blocks|cubes)) )?)without(?= (the )?({_COLOUR})\b)", r"\1except"),  # "stack everything without red"
    (r"without", "and not"),  # "put red near green without touching blue"
    (r"(?<!the )(?<!and )(?<!then )(rests?|resting)(?= (on|upon|atop|onto|in|inside|into|next|near|beside|close|by)\b)",
     ""),  # "green rests on red"; not "the rest", nor "red on green and rest in the bin"
    (r"(stacked|piled|placed|positioned|moved|located|lying|sitting|standing)(?= (on|upon|atop|onto|in|inside|into|"
     r"next|near|beside|close|away|far|out|off)\b)", ""),  # "I'd like green stacked on red"
    (r"\b(be|been|is|are|gets?|got) (put|set|dropped|thrown|tossed|carried|brought|laid)(?= (on|upon|atop|onto|in|inside|"
     r"into|next|near|beside|close|away|far|out|off)\b)", ""),  # "red should be put in the bin", "red gets put on green"
    (rf"(?P<said>(({_COLOUR})|(?P<many>blocks|cubes|objects|ones|they|them|these|those))( (must|should|will|would|can|"
     r"could|need to|have to|are|were))?) (all|(?(many)(?!)|both))(?= (be|are|stay|sit|apart|together|in|on|near|next|away|"
     r"separated|touching|touch)\b)", r"\g<said>"),  # "red, green and blue must all be apart", "the blocks should all be apart"
    (r"(from|off)( of)? (the )?(desk|table)(?= (in|into|to|onto|on|next|near|beside|close|away)\b)", ""),  # "move
    # the blocks from the desk into the bin": where they go
    (r"not (near|next to|close to|by|beside|touching) (anything|any( other)? (block|cube|one))", "away"),  # "not
    # near anything": away from every other block
    (r"(on|onto|to) (the )?(table|desk)(?= (next to|near|beside|close to|by|away from|far from|apart from)\b)",
     r"\g<0> and"),  # "put red on the table next to green": both
    (rf"fill (up )?(the )?(bin|basket|box|trash|bucket)( up)? with (?P<what>(the )?({_COLOUR})(( and|,)? (the )?"
     rf"({_COLOUR}))*)", r"put \g<what> in the bin"),  # "fill the bin with red and blue"
    (r"what(ever)? (is|remains) left|what(ever)? remains", "the rest"),  # "... and whatever is left in the bin"
    (r"(is|are|be|stays?|gets?) left(?= (on|in|off|out|near|next|by|beside)\b)", ""),  # "no block is left on the desk"
    *((rf"(the )?bin (should |must |will |has to |needs to |is to |to )?(contains?|holds?|has|have|gets?) "
       rf"(?P<what>everything|all( of)?( the)? (blocks|cubes)|(only |just )?(the )?({_COLOUR})( block| cube| one)?"
       rf"( and( the)? ({_COLOUR})( block| cube| one)?)*)( in (it|the bin)| inside( it)?)?{only}",
       rf"{said}\g<what> in the bin") for only, said in ((r" only\b", "only "), ("", ""))),  # "the bin should contain red",
    # "I want the bin to contain red and blue only", "the bin has red in it"
    (rf"(the )?(desk|table|tabletop) (should |must |will |is to |has to )?(only (have|hold)|(have|hold) only) (?P<what>(the )?"
     rf"({_COLOUR})( block| cube| one)?( and( the)? ({_COLOUR})( block| cube| one)?)*)( on it)?",
     r"keep only \g<what> on the table"),  # "the desk should only have yellow on it"
    (rf"(the )?(blocks|cubes|objects)(?= (the )?({_COLOUR})\b)", ""),  # "stack the blocks red, green, blue": those named
    (rf"(?P<first>{_COLOUR})(?= ({_COLOUR})\b)", r"\g<first> and"),  # "tower red green blue": a list said bare
    (r"((all|both|each)( of)? )?the (blocks|cubes|objects)", "all"),
    (r"(and )?(except for|except|other than|save for|excluding|with the exception of)", "except"),  # "clear the desk,
    # except for red"
    (r"but(?=( (and|or|the|" + _COLOUR + r"|block|cube|one))+( then\b|$))", "except"),  # "... but blue"
    (r"but (leave|keep|spare|skip)(?=( (and|or|the|" + _COLOUR + r"|block|blocks|cube|cubes|one))+"
     r"( then\b|$))", BUT_LEAVE),  # "clean the table but leave red and yellow"
    (r"but", "and"),
    (r"in (the|your|its|my|the robot's) (hand|gripper|grip|fingers)|in hand|in the air|held|holding|grasped", "held"),
    (r"together with|(right |up |flush )?against", "near"),  # "push red up against blue"
    (r"(?P<verb>separate|split( up)?|part) (?P<what>[^,;]+?) from (each other|one another)", r"\g<verb> \g<what>"),  # "separate
    # all blocks from each other"
    (r"together(?= (in|into|inside) )", ""),  # "put red and green together in the bin": both there
    (r"close together|near each other|close to each other|next to each other|beside each other|side by side|"
     r"together|neighbou?rs|(touch|touches|touching|adjacent)( each other| one another)?(?= (and|then)\b|$)",
     "together"),
    (r"(far from|away from|apart from) (each other|one another|every other( block| cube| one)?|each of the others)",
     "apart"),
    (r"apart from", "away"),
    (r"far apart|apart|separated|isolated", "apart"),
    (rf"line (?P<what>them|all|it|(the )?({_COLOUR})( and (the )?({_COLOUR}))*) up", r"group \g<what>"),  # "line the blocks up"
    (r"line up|line|arrange in a row", "group"),  # "line up red, green and blue"
    (r"(re-?)?arrange", "put"),  # "arrange red and green side by side", "rearrange the blocks so red is on blue"
    (rf"from (the )?(?P<from>{_COLOUR})( block| cube| one)? to(?= (the )?({_COLOUR})\b)", r"from \g<from> on"),  # "move
    # red from green to blue": off one block, onto the other
    (r"in(?=( (too|as well|also))?( (and|then)\b| *$))", "in the bin"),  # "put everything else in", "... and red in too"
    (r"over to", "to"),
    (r"in to(?= (the )?(bin|box|basket|trash|bucket)\b)", "into"),  # "put red in to the bin"
    (r"(?P<swap>\b(swap|switch|exchange|trade|reverse|invert|flip)\b[^;]*?\bon) (the )?top(?! of)",
     r"\g<swap> the_tower"),  # "swap red and green and put blue on top": on the tower as the swap leaves it, not on
    # a block the sentence does not name
    (r"on (the )?top(?! of)", "on other"),  # "put red on top": on the other block
    (r"on top of|on to|onto|upon|atop|on|above|over", "on"),
    (r"in the middle (and )?(of|between)|midway between|next to|close to|near to|adjacent to|beside|besides|alongside|nearby|"
     r"by the side of|right by|near|with|towards|toward|up to|in between|between|touch|touches|touching|neighbou?ring|neighbou?r (of|to)|"
     rf"closer to|closer|by(?= (the )?({_COLOUR}|it|them|other|all|the_tower|the_top|the_base)\b)", "near"),  # "put red
    # by green"
    (r"finally|lastly|next|at the end|in the end|secondly|thirdly|fourthly|fifthly|subsequently", "then"),
    (r"far away from|away from|far from|apart from|distant from|clear of", "away"),
    (r"far away|far off|well away", "away"),  # "move blue far away": from every other block
    (r"out of|outside of|outside|out from", "out"),
    (r"into|inside of|inside|within|in", "in"),
    (r"underneath|beneath|below|under", "under"),
    (r"off of|off", "off"),
    (r"close", "together"),
    (r"far", "apart"),
    (r"pick up|pickup|pick-up|pick|(grab|get|take|catch) hold of|grab|grasp|grip|lift up|lift|hold on to|hold onto|hold up|"
     r"hold|seize|raise|(hand|give|pass)( it| them)? (me|over|to me)", "pick"),  # "hand me red": held out in the gripper
    (r"let go of|let go|release|set down|put down|lay down|drop off", "release"),
    (r"clean up|clean|tidy up|tidy|clear up|clear off|clear away|clear|(throw|toss|chuck|put) away|dump|"
     r"discard|dispose of|get rid of|fill up|fill", "clean"),
    (r"empty out|empty", "empty"),
    (r"spread out|spread apart|spread|split up|split|scatter|pull apart|separate|space out|isolate|single out",
     "separate"),
    (r"put together|bring together|push together|gather|group|cluster|bunch up|bunch|collect|pair up|pair", "group"),
    (r"take down|unstack", "unstack"),
    (r"(swap|switch|exchange|trade|change|reverse)( around| over)?( the)? (positions|places|spots|locations) of|"
     r"swap( around| over)?|switch( around)?|exchange|trade places of|change places of", "swap"),
    (r"(swap|switch|change|reverse|invert|flip) the order( of (the )?(stacked )?(blocks|cubes|tower|stack|pile))?(?! of)",
     "swap the_whole"),  # "swap the order", as the paper's Swap-2 says it: the tower standing turned over
    (r"(reverse|invert|flip( over)?|turn (over|upside down)) it|turn it (over|upside down)", "swap the_whole"),  # "build a
    # tower of red and green, then reverse it"
    (rf"(reverse|invert|flip)( the order of)?(?= (them|both|the two|(the )?({_COLOUR}))\b)", "swap"),  # "reverse red and
    # green": two blocks swapped
    (r"unload(?= (the )?(bin|box|basket|trash|bucket)\b)", "empty"),  # "unload the bin"
    (r"un-?bin (?P<what>[^,;]+?)(?= *(and\b|then\b|$))", r"take \g<what> out of the bin"),  # "unbin green and red"
    (r"pull|retrieve|fetch|extract|fish|dig|unload", "take"),
    (r"place|set|move|bring|get|carry|throw|toss|stick|position|transfer|shift|drop|slide|push|stow|store|deposit|"
     r"return|lay|add|load|put|relocate|nudge|chuck|pop|insert|plop|perch|balance|cent(er|re)|reposition", "put"),
    (rf"^rest(?= (the )?({_COLOUR})\b)|lower(?= (the )?({_COLOUR})\b)", "put"),  # "rest red on green", "lower red onto
    # green"; not "the rest", "the lower block"
    (r"(pile|stack|heap) up|pile|stack|heap", "stack"),
    (r"sort( out)?", "put"),  # "sort red and green into the bin"
    (r"remove|take away", "remove"),
    (r"keep|leave|have|let", "keep"),
    (r"binned|trashed", "in the bin"),  # "the rest binned", "red should be binned"
    (r"all (of )?(the )?other (blocks|cubes|ones)|all (of )?the others|(the )?left ?overs?( blocks| cubes)?|(the )?left ?over "
     r"(blocks|cubes|ones)|the rest of (all|them|these|those|the (blocks|cubes))|any (remaining|other|left ?over)( blocks| cubes|"
     r" ones)?", "the rest"),  # "bin the leftovers", "the rest of the blocks", "any remaining blocks"
    (r"(?P<verb>move|touch|disturb|shift|bump) anything(?! else\b)", r"\g<verb> all"),  # "don't move anything (except red)"
    (r"anything(?= (except|but|other than|apart from|besides|save)\b)", "all"),  # "put anything except red in the bin"
    (r"(each|all|every one) of (them|those|these)(?![^,;.]*\b(except|but|apart|other than|besides|save|excluding)\b)(?= (be|"
     r"are|stay|sit|apart|together|in|into|on|onto|near|next|away|separated|touching)\b)", "them"),  # "pick up red and green
    # and put each of them in the bin": the blocks named before, as 'them' and 'them all' (every block, said first)
    (r"everything|every|each|all of them|all of|all|the (whole )?lot", "all"),
    (r"the (other|remaining) (block|cube|one)|the one (left|remaining)|the (block|cube) (left|remaining)", "the_other"),
    # one block, said in the singular: refused where it could be more than one
    (r"the others|others|the other|other|the rest|rest|remaining ones|remaining|another|any other", "other"),
    (r"(they|them|those|these)(?P<modal> (must|should|will|would|can|could|need to|have to|are|were))? both|both of (them|those|"
     r"these)", r"both\g<modal>"),  # "put them both in the bin", "they should both be ...":
    # the two named before, refused where that is unclear
    (r"(it|them|those|these) all|all of (it|them)", "all"),  # "put it all in the bin"
    (r"those|these|they|them", "them"),
    (r"(the|a|an|this|that) (block|cube|one)|this|that|it", "it"),
    (r"((trash|waste|garbage|rubbish|recycling|storage|dust) ?)?(basket|box|container|tray|trash can|trash|bucket|crate|bin|"
     r"(?:(?<=\bthe )|(?<=\ba )|(?<=\bthis )|(?<=\bthat )|(?<=\byour )|(?<=\bin )|(?<=\binto ))can|receptacle)|garbage|rubbish|"
     r"recycling", "bin"),  # "the can", not "blue can go on red"
    (r"(can|could|may|might)(?= (go|be|sit|stand|rest|stay|end|get|fit|lie)\b)", ""),  # "so that blue can go on red"
    (r"tabletop|table top|table|desk|workspace|surface", "table"),
)
"""(regular expression over whole words, canonical word): applied in order."""

FILLERS = frozenset({
    "please", "pls", "plz", "respectively", "likewise", "similarly", "instead", "the", "a", "an", "of", "robot", "now",
    "again", "back", "also",
    "too", "just", "some", "your",
    "my", "our", "its", "their", "block", "blocks", "cube", "cubes", "one", "ones", "piece", "pieces", "object",
    "objects", "thing", "things", "is", "are", "be", "been", "being", "should", "must", "will", "shall", "stay", "stays",
    "remain", "remains", "end", "ends", "there", "here", "sure", "make", "go", "goes", "belong", "belongs",
    "first", "firstly", "last", "start", "begin", "alone", "untouched", "sit", "sits", "sitting", "lie", "lies", "lying",
    "stand", "stands", "standing", "somewhere", "anywhere", "quickly", "carefully", "slowly", "gently", "softly",
    "immediately", "right", "straight", "anymore", "still", "finish", "were", "was",
})
"""Words that carry nothing for the goal."""

CANONICAL = frozenset({
    "and", "then", "not", "on", "near", "away", "out", "in", "under", "off", "pick", "release", "clean",
    "empty", "separate", "group", "unstack", "put", "stack", "remove", "keep", "held", "together", "apart",
    "all", "except", "other", "the_other", "them", "it", "bin", "table", "to", "from", "up", "down", "take", "both", "only",
    "the_tower", "the_top", "the_base", "the_whole", "the_upper", "the_lower", "the_held", "the_binned", "the_middle", "swap",
    ANY_ORDER,
    IN_PLACE, AFFIRMED,
    *(f"the_{end}{k}" for end in ("top", "bottom") for k in range(2, 9)),
})
"""The words the grammar reads (besides the colours)."""

UNDECIDED = frozenset({"or", "either", "nor", "whichever", "if", "unless", "when", "whenever", "maybe", "perhaps"})
"""Words that make a goal a choice or a condition, which a goal (one state to reach) cannot be: refused by name."""


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


_CONDITION_WORDS = frozenset({"in", "to", "out", "from", "near", "away", "on", "under", "off", "down", "together", "apart",
                              "held"})
"""The words a place or state starts with in the grammar (``dest``, ``condition``)."""


_TAKES_AFTER_A_LIST = {"stack": frozenset(),
                       "remove": frozenset({"from", "out", "off", "from bin", "out bin", "from table", "off table"}),
                       "pick": frozenset({"up", "off", "from", "out", "held", "from bin", "out bin", "from table",
                                          "off table"}),
                       "separate": frozenset({"apart", "out", "from", "away"}), "group": frozenset({"together", "near"}),
                       "clean": frozenset({"in bin"}), "swap": frozenset(), "unstack": frozenset({"down", "on table"}),
                       "empty": frozenset({"out", "out bin"}), "release": frozenset(), "bin": frozenset()}
"""Verbs that take a bare list of blocks, with the place words each takes after it, and "bin" or "table" after them where
that is meant (the grammar's ``action``; 'stack' none: a tower going somewhere was rewritten above). Another place after the
list would split it: all but the last block to the verb, the last to the place."""
_SPLIT_LIST = ("'{verb} {listed} {place} ...' would {verb} all but the last block and put the last one {place} ...: give "
               "it a verb of its own (e.g. '{verb} red and green and put blue in the bin')")
_SPLIT_TOWER = ("a tower of {listed} cannot be '{place}' as a whole: say where its bottom block goes (e.g. 'stack red, "
                "green and blue next to yellow') or give the last block a verb of its own ('stack red and green and put "
                "blue in the bin')")


def _refuse_a_list_split(words: list[str]) -> None:
    """'stack red, green and blue apart', 'separate red, green and blue in the bin': a list of blocks after a verb,
    then a place the verb does not take, is refused (read, it would split the list, see :data:`_TAKES_AFTER_A_LIST`)."""
    for start in (i for i, word in enumerate(words) if word in _TAKES_AFTER_A_LIST):
        end, named = start + 1, 0
        while end < len(words) and words[end] in BLOCK_COLOURS:
            named += 1
            end += 2 if end + 2 < len(words) and words[end + 1] == "and" and words[end + 2] in BLOCK_COLOURS else 1
        place = words[end] if end < len(words) else ""
        said = f"{place} {words[end + 1]}" if words[end + 1:end + 2] in (["bin"], ["table"]) else place
        if named >= 2 and place in _CONDITION_WORDS and said not in _TAKES_AFTER_A_LIST[words[start]]:
            listed = ", ".join(w for w in words[start + 1:end] if w != "and")
            message = _SPLIT_TOWER if words[start] == "stack" else _SPLIT_LIST
            raise LanguageError(message.format(verb=words[start], listed=listed, place=place))


def _sentences_in_turn(words: list[str]) -> list[str]:
    """Each :data:`SENTENCE_END` made a 'then', once no list of blocks can run across it."""
    return _joined(words, sentence_ends=False)


def _place_after_a_list(words: list[str]) -> list[str]:
    """'put red, then green, into the bin', 'first red, then green, into the bin': the place after a 'put' (or at the
    start) and its blocks, set off by a comma, is theirs (not another place for the last of them, which has none)."""
    words = list(words)
    for i in range(len(words) - 2, 0, -1):
        if words[i] != "and" or words[i + 1] not in _PLACE_WORDS:
            continue
        start = i
        while start > 0 and words[start - 1] in (*BLOCK_COLOURS, "and", "then"):
            start -= 1
        if (start == 0 or words[start - 1] == "put") and any(w in BLOCK_COLOURS for w in words[start:i]):
            del words[i]
    return words


def _stacked_into_a_tower(words: list[str]) -> list[str]:
    """'stack all blocks into one tower', 'put them all in a single stack', '... and the rest in a tower': the blocks
    named before the mark stacked, their verb (or, with none of their own, a 'stack' put before them) saying it."""
    words = list(words)
    while INTO_A_TOWER in words:
        at = words.index(INTO_A_TOWER)
        start = at
        while start > 0 and words[start - 1] in _NAMING:
            start -= 1
        if start > 0 and words[start - 1] in _PLACE_WORDS and "and" in words[start:at]:  # "put red on green and the
            start += words[start:at].index("and")  # others in a tower": green is where red goes, not in the tower
        while start < at and words[start] == "and":  # the clause's joiner, not its blocks'
            start += 1
        verb = words[start - 1] if start > 0 else "then"
        if start == at or verb not in ("stack", "put", "and", "then"):
            raise LanguageError(UNORDERED_TOWER)
        if verb == "put":
            words[start - 1] = "stack"
        elif verb != "stack":
            words.insert(start, "stack")
            at += 1
        del words[at]
    return words


_PLACE_WORDS = frozenset({"on", "near", "in", "away", "under", "off", "to", "from", "out"})
"""Words after which a block is where another goes, not one a tower's mark may take."""
_NAMING = frozenset({"all", "except", "only", "other", "the_other", "them", "it", "both", "and", *BLOCK_COLOURS})
"""The words that name blocks, which a tower's mark may follow."""


def _order_left_open(words: list[str]) -> list[str]:
    """'in any order' said of a tower ('stack red, green and blue in any order'): the mark moved to just after the
    'stack' it follows (or, said first, precedes), which the grammar reads as a tower left open; of anything else ('put
    the blocks in the bin in any order'), dropped: it says where, not when."""
    at = words.index(ANY_ORDER)
    rest = [w for w in words if w != ANY_ORDER]
    stacks = [i for i, w in enumerate(rest) if w == "stack"]
    before = [i for i in stacks if i < at]
    if not stacks:
        return rest
    verb = before[-1] if before else stacks[0]
    return [*rest[:verb + 1], ANY_ORDER, *rest[verb + 1:]]


_TYPOGRAPHY = str.maketrans({"\u2018": "'", "\u2019": "'", "\u201b": "'", "\u00b4": "'", "`": "'", "\u201c": '"',
                             "\u201d": '"', "\u201e": '"', "\u2014": " - ", "\u2013": " - ", "\u2015": " - ", "\u2026": ".",
                             "\u00a0": " ", "+": " and ", "\u2192": " to "})
"""What word processors and phones put for plain characters ('Don\u2019t', \u201cred\u201d, a dash between clauses)."""


def _plain(text: str) -> str:
    """``text`` in plain characters, without emoji and other symbols that say nothing of where a block goes."""
    text = re.sub(r"\s*[-=]+>\s*", " to ", text.translate(_TYPOGRAPHY))  # "red -> bin"
    text = re.sub(rf"\b(?P<block>(?:{_COLOUR})(?: block| cube)?)\s+-+\s+(?=(?:in|into|on|onto|next|near|beside|by|away|out|"
                  r"off|under)\b)", r"\g<block> ", text)  # "red - in the bin": as 'red: in the bin'
    text = re.sub(r"\s+-+\s+", ", ", text)  # "put red in the bin - green too"
    return "".join(c for c in text if unicodedata.category(c) not in ("So", "Sk", "Cf", "Cs", "Co"))


def _punctuation_read(mark: re.Match) -> str:
    """A colon says nothing; a semicolon, or a full stop between sentences, ends a clause (:data:`SENTENCE_END`: 'pick
    up red. Blue on yellow.' is not 'pick up red and blue'); a comma (or a mark at the end) is 'and'."""
    if mark[0] == ":":
        return " "
    if mark[0] == ";" or (set(mark[0]) & set(".!") and mark.end() < len(mark.string)):
        return f" {SENTENCE_END} "
    return " and "


def normalise(text: str, scene: str, blocks: Sequence[str]) -> list[str]:
    """The canonical words of ``text``; raises :class:`LanguageError` naming a word it does not know (with the
    ``blocks`` present, by colour, and goals the scene can state)."""
    if len(text) > MAX_GOAL_CHARS:
        raise LanguageError(f"the goal is {len(text)} characters long; at most {MAX_GOAL_CHARS} are read")
    said = _plain(text).lower()
    text = _NUMBERED.sub(" ; ", re.sub(r"\s*\n\s*", "\n", said))  # "1. put red in the bin 2. put green in the bin",
    # one step a line: steps in turn
    text = re.sub(r"[()\[\]\"]", " ", text)
    text = _STACKED_SO.sub(_stacked_with_ends, text)  # "stack the blocks so that red is at the bottom": with red there
    text = _JOINED_COLOURS.sub(lambda m: f"{m['colour']} {'and' if m['mark'] == '-' else 'or'} ", text)  # "red-green"
    text = _TOWERS_OF_A_SIZE.sub(_towers_of_a_size, text)  # "two towers of three: red, green, blue and yellow, ..."
    text = _GERUND.sub(lambda m: _GERUNDS[m[0]], text)  # "after picking up red"
    text = _in_time_order(_said_after(text))  # before the punctuation they read goes
    text = " " + re.sub(r"[,.!?:;]+", _punctuation_read, text.strip()) + " "
    text = re.sub(r"\bboth\b(?= (the )?(" + _COLOUR + r")\b)", " ", text)  # "both (the) red and green"
    text = _LEFT_OUT_EITHER.sub(r"\g<head> \g<first> and \g<second>", text)  # "all but not red or green": neither
    text = _EXCEPTION_AFTER_ALL.sub(_as_exception, text)  # "everything in the bin apart from green"
    text = _OTHERS_COUNTED.sub(lambda match: _others_counted(match, blocks), text)  # "the other four"
    text = _COUNTED.sub(lambda match: _all_counted(match, blocks), text)  # "the two blocks", "all three"
    text = _BLOCKS_AFTER_A_VERB.sub(lambda match: _verb_on_all(match, blocks), text)  # "move blocks apart"
    text = _MADE_BOTH_ENDS.sub(lambda m: f" {m['first']} at the {_END_SAID[m['first_end']]} and {m['second']} at the "
                               f"{_END_SAID[m['second_end']]} ", text)  # "make red the top block and green the bottom"
    text = _MADE_AN_END.sub(lambda m: f" put {m['made'] or m['said']} at the {_END_SAID[m['end']]} ", text)  # "make red
    # the top block", "green should be at the bottom"
    if len(blocks) == 2:  # of two blocks: "put red at the bottom", the other on it (where no other end is said); "build
        # a tower with red at the bottom", of both
        if len(re.findall(r"\b(?:top|bottom|base|foot)\b", text)) == 1:
            text = _END_OF_TWO.sub(lambda m: f"{m['verb']} {m['what']} {'on top' if m['end'] == 'top' else 'under the other block'}",
                                   text)
        text = _BASE_OF_TWO.sub(r"\g<noun> of all with ", text)
    text = _TOWER_WITHOUT.sub(_tower_of_all_but, text)  # "a tower of four without red"
    text = _TOWER_SIZE.sub(lambda size: _tower_sized(size, blocks), text)  # "a 3-block tower", "a tower of three
    # blocks with red at the bottom"
    text = _RESPECTIVELY.sub(_respectively, text)  # "red and blue on green and yellow respectively"
    text = _RELATIVE_ON.sub(r"\g<block> and \g<block> ", text)  # "blue on green which is on red"
    text = _tower_by_positions(text)  # "red on top, green in the middle, blue at the bottom"
    if _SEVERAL_TOWERS.search(text):  # "two towers, one of red and green and one of blue and yellow"
        text = _EACH_TOWER.sub(" stack ", text)
    text = _NOT_EITHER_OF.sub(lambda m: f"{m['head']} {'other' if m['others'] else 'both'}", text)
    if one := _ONE_NOT_NAMED.search(text):
        raise LanguageError(f"'{one['said'].strip()}' leaves open which block: name it by colour ({', '.join(blocks)})")
    if some := _SOME_OF.search(text):  # after 'three of the blocks: red, green and blue' is read
        raise LanguageError(f"'{some[0]}' leaves open which: name the blocks by colour ({', '.join(blocks)})")
    if _A_QUESTION.match(said):
        raise LanguageError(f"{said.strip()!r} is a question, not a goal: a goal says how the world should end, e.g. "
                            f"{examples(scene, blocks)}; what holds now is on /semgoal/semantic_state (the console shows it)")
    if order := _AN_ORDER.match(said):
        raise LanguageError(f"'{order['order']}' is an order to the robot, not a goal (the state the world should end in): "
                            f"pause, resume or re-plan with './semgoal plan pause|resume|replan', start again with the "
                            f"sim's reset_world service; a goal says where the blocks go, e.g. {examples(scene, blocks)}")
    if (taken_back := _CORRECTION.search(said)) and re.search(r"\w", said[:taken_back.start()]):
        raise LanguageError(f"'{taken_back[0]}' takes back what was said before it: say the goal once, as the world "
                            f"should end, e.g. {examples(scene, blocks)}")
    if held := _HELD_OVER.search(text):
        raise LanguageError(f"'{held[0].strip()}': where the hand is is none of scene {scene}'s predicates ("
                            f"{', '.join(LAYOUTS[scene].scene.predicates)}); holding says only which block is in the hand: "
                            f"say 'hold {held['block']}' or where the block should go, e.g. {examples(scene, blocks)}")
    text = _KEPT_EITHER.sub(r"\g<head> \g<first> and \g<second>", text)  # "without moving red or green": both kept
    text = _NOT_ONE_OR_OTHER.sub(r"\g<verb> neither \g<first> nor \g<second>", text)  # "don't put red or green in the bin"
    text = _KEPT_FROM.sub(r" \g<blocks> not ", text)  # "stop red from touching green"
    text = _NEITHER_PLACE.sub(r"not \g<place> \g<first> or \g<second>", text)  # "neither near green nor near blue"
    text = _NEITHER.sub(lambda m: f" {m['first']} and {m['second']} not {'held' if m['verb'] in _HOLDING_VERBS else ''} ",
                        text)  # "neither red nor green should be in the bin", "hold neither red nor green"
    text = _NOT_EITHER.sub(r"\g<head> \g<first> and \g<second>", text)  # "not near red or green": near neither
    if "close" not in LAYOUTS[scene].scene.predicates:  # "put red in the bin without touching green": not moving it
        text = re.sub(r"\bwithout (touching|bumping( into)?|hitting|knocking( into)?)\b", "without moving", text)
    if "in_bin" in LAYOUTS[scene].scene.predicates:
        text = _THROWN.sub(r"\g<verb>\g<what> away", text)  # "grab red and toss it"
        text = _THROWN_AWAY.sub(lambda m: f" clean {m['what'] or m['out'] or ''} ", text)  # "throw everything away
        # except red", "throw red out": into the bin
    text = re.sub(r"&+", " and ", text)
    text = re.sub(r"\b(it|that|there|here|what)'s\b", r"\1 is", text)
    text = re.sub(r"\b(they|we|you)'re\b", r"\1 are", text)
    for pattern, canonical in PHRASES:
        text = re.sub(rf"(?<![\w'])(?:{pattern})(?![\w'])", f" {canonical} ", " ".join(text.split()))
    if re.search(r"\breplace\b", text):  # the phrases read 'replace red with green' where a place follows
        raise LanguageError("'replace ... with ...' needs the place the new block goes, e.g. 'replace red with green in the "
                            "bin' (green there, red not), or say both blocks' places")
    words = [w for w in text.split() if w not in FILLERS]
    words = _beside_the_bin(words)
    for rewrite in (_place_after_a_list, _joined, _kept_besides, _tower_end_named, _listing_in_order, _chained_on,
                    _top_down, _top_named_last):  # word-level readings, in order
        words = rewrite(words)
    _refuse_a_list_split(words)
    words = _sentences_in_turn(words)
    words = _stacked_into_a_tower(words)
    if ANY_ORDER in words:
        words = _order_left_open(words)
    if UNDER_A_TOWER in words:
        raise LanguageError("a block goes under a standing tower only by building the tower again on it: name the new "
                            "tower's blocks from the bottom up, e.g. 'build a tower of red, green and blue'")
    if DIRECTION in words:
        raise LanguageError(f"directions and places on the table (left of, behind, the corner, a triangle) are not among scene "
                            f"{scene}'s predicates ({', '.join(LAYOUTS[scene].scene.predicates)}): say e.g. "
                            f"{examples(scene, blocks)}")
    unknown = [w for w in words if w not in CANONICAL and w not in BLOCK_COLOURS]
    if choice := next((w for w in unknown if w in UNDECIDED), None):
        raise LanguageError(f"'{choice}' leaves the goal open: a goal is the one state the world ends in, so say it "
                            f"plainly, e.g. {examples(scene, blocks)}")
    if count := next((w for w in unknown if w.isdigit() or w in NUMBERS), None):
        raise LanguageError(f"'{count}' blocks, but which? a goal names its blocks by colour ({', '.join(blocks)}), "
                            f"e.g. {examples(scene, blocks)}")
    if unknown:  # a word the reader knows nowhere before one it knows only in other phrases ('build' without a tower)
        unknown.sort(key=lambda word: word in _known_words())
        raise LanguageError(f"unknown word {unknown[0]!r}{_did_you_mean(unknown[0])}: goals name blocks by colour "
                            f"({', '.join(blocks)}) and say where they go, e.g. {examples(scene, blocks)}")
    if len(words) > MAX_GOAL_WORDS:
        raise LanguageError(f"the goal reads as {len(words)} words; at most {MAX_GOAL_WORDS} are parsed: give it as "
                            "several goals, one after the other")
    while words and words[0] in ("and", "then"):
        words.pop(0)
    while words and words[-1] in ("and", "then"):
        words.pop()
    if not words:
        if _SEVERAL_TOWERS.search(said):  # "make two towers": each tower's blocks left unsaid
            raise LanguageError("say which blocks each tower has: e.g. 'a tower of red and green and another of blue "
                                "and yellow'")
        raise LanguageError(f"the goal says nothing to do: e.g. {examples(scene, blocks)}")
    return words


LISTING_VERBS = frozenset({"stack", "put", "clean", "take", "remove", "bin", "group", "separate"})
"""Verbs whose blocks may be named in order ('put red, then blue, then green in the bin'): one action on all of them.
Not 'pick' ('pick up red, then green' ends with green in the hand)."""


def _did_you_mean(word: str) -> str:
    """' (did you mean 'green'?)' for a word a letter or two away from one the reader knows (two letters swapped, one
    letter wrong), else ''."""
    import difflib

    known = _known_words()
    if len(word) <= 2:
        return ""
    swapped = {word[:i] + word[i + 1] + word[i] + word[i + 2:] for i in range(len(word) - 1)}  # 'teh', 'bni'
    close = {w for w in known if w in swapped or (len(w) == len(word) and sum(map(str.__ne__, w, word)) == 1)}  # 'bim'
    close |= set(difflib.get_close_matches(word, known, n=2, cutoff=0.75))
    close.discard(word)
    if not close:
        return ""
    best = max(sorted(close), key=lambda w: (difflib.SequenceMatcher(None, word, w).ratio(), w in CANONICAL or w in BLOCK_COLOURS))
    return f" (did you mean {best!r}?)"


@functools.cache
def _known_words() -> tuple[str, ...]:
    """Every word the reader takes: colours, canonical words, fillers and the words of its phrases."""
    phrased = {word for pattern, _ in PHRASES for word in re.findall(r"[a-z]{3,}", re.sub(r"\\[a-zA-Z]", " ", pattern))}
    marks = {TOP_DOWN, DIRECTION, ANY_ORDER, IN_PLACE, INTO_A_TOWER, BUT_LEAVE, UNDER_A_TOWER, TOP_MARK, BASE_MARK, AFFIRMED}
    said = (set(BLOCK_COLOURS) | CANONICAL | FILLERS | phrased) - marks  # the reader's own marks are no words anyone says
    return tuple(sorted(word for word in said if "_" not in word))


def _listing_in_order(words: list[str]) -> list[str]:
    """'stack red then green then blue', 'put red, then blue, then green in the bin': the blocks of one action named
    in order (a tower's from the bottom), not clauses after one another ('a tower of red and green; blue and yellow in
    the bin': a 'then' before two blocks starts a clause)."""
    joined = []
    for i, word in enumerate(words):
        listed = (word == "then" and 0 < i < len(words) - 1 and words[i + 1] in BLOCK_COLOURS
                  and not (words[i + 2:i + 3] == ["and"] and words[i + 3:i + 4] and words[i + 3] in BLOCK_COLOURS)
                  and (_listing_after_verb(words[:i]) or _bare_list(words[:i])))
        joined.append("and" if listed else word)
    return joined


def _bare_list(words: list[str]) -> bool:
    """Whether ``words`` are blocks only, with no verb or place ('red then green in the bin': one list)."""
    return all(word in BLOCK_COLOURS or word == "and" for word in words)


def _top_named_last(words: list[str]) -> list[str]:
    """'a tower: green at the bottom, then blue, then red on top': the last of a tower's blocks named in order is its
    top, not a block on some other one ('on top' alone reads 'on the other block')."""
    kept, i = [], 0
    while i < len(words):
        if words[i:i + 2] == ["on", "other"] and (i + 2 == len(words) or words[i + 2] in ("and", "then")):
            start = _listing_start(words, i)
            if start > 0 and words[start - 1] == "stack" and sum(w in BLOCK_COLOURS for w in words[start:i]) >= 2:
                i += 2
                continue
        kept.append(words[i])
        i += 1
    return kept


def _tower_end_named(words: list[str]) -> list[str]:
    """'a tower of red, green and blue with blue on top', '... with red at the bottom': the tower's list read from the
    end it names (reversed where that end is its first block), and a block not in the list put on top (or under it)."""
    while marks := [i for i, word in enumerate(words[:-1]) if word in (TOP_MARK, BASE_MARK) and words[i + 1] in BLOCK_COLOURS]:
        mark = marks[0]
        top, named = words[mark] == TOP_MARK, words[mark + 1]
        after = words[mark + 2:]
        if (not top and after[:1] == ["and"] and after[1:2] and after[1] in BLOCK_COLOURS and after[2:4] == ["on", "other"]
                and after[4:5] in ([], ["and"], ["then"])):  # "with red at the bottom and blue on top"
            after = [TOP_MARK, after[1], *after[4:]]
        before = words[:mark]
        while before and before[-1] == "and":  # "red and green, with blue on top"
            before.pop()
        start = _listing_start(before, len(before))
        colours = [w for w in before[start:] if w in BLOCK_COLOURS]
        end = "top" if top else "bottom"
        said = f"with {named} {'on top' if top else 'at the bottom'}"
        if chain := _chain_ends(before):  # "put red on green with blue on top"
            upper, lower, blocks = chain
            if named == (upper if top else lower):
                words = [*before, *after]
            elif named not in blocks:
                words = [*before, "and", *((named, "on", upper) if top else (lower, "on", named)), *after]
            else:
                raise LanguageError(f"{named} is in the tower said, not at its {end}: '{said}' names the {end}")
            continue
        if before[-1:] == ["stack"]:  # "a tower with red on top" (on the other block), "with red at the bottom, then ..."
            words = [*before, named, *(("on", "other") if top else ()), *after]
            continue
        if before[-3:] in (["put", "all", INTO_A_TOWER], ["stack", "all", INTO_A_TOWER]):  # "put all the blocks in one
            before = [*before[:-3], "stack", "all"]  # tower with purple on top"
        if before[-2:] == ["stack", "them"] and not set(before) & set(BLOCK_COLOURS):  # "stack them with green at the
            before = [*before[:-1], "all"]  # bottom", no block named before: every block
        if before[-2:] == ["stack", "all"]:  # "stack all the blocks with purple on top": the others under it, any order
            words = [*before, "and", *_end_pinned(words[mark], named)]
            if after[:1] == [BASE_MARK if top else TOP_MARK] and after[1:2] and after[1] in BLOCK_COLOURS:  # "... and
                words, after = [*words, "and", *_end_pinned(after[0], after[1])], after[2:]  # purple at the top"
            words += after
            continue
        if start == 0 or before[start - 1] != "stack" or not colours:
            others = " and ".join([c for c in BLOCK_COLOURS if c != named][:2])
            raise LanguageError(f"'{said}' names the {end} of a tower listed after 'stack': e.g. 'build a tower of "
                                f"{others} {said}'")
        if named not in colours:
            listing = [*colours, named] if top else [named, *colours]
        elif named == (colours[-1] if top else colours[0]):
            listing = colours
        elif named == (colours[0] if top else colours[-1]):
            listing = colours[::-1]
        else:
            raise LanguageError(f"{named} is named inside the tower's list and at its {end}: name the tower's blocks "
                                f"from the bottom up, e.g. 'build a tower of {', '.join(colours)}'")
        words = [*before[:start], *" and ".join(listing).split(), *after]
    return words


def _end_pinned(mark: str, block: str) -> list[str]:
    """A tower's end said of a tower whose order is left open: nothing on its top block, its bottom one on the table
    (:func:`~semgoal_planner.english.resolver.stack_order` then builds the tower between them)."""
    return ["take", "all", "off", block] if mark == TOP_MARK else ["put", block, "on", "table"]


def _chain_ends(words: list[str]) -> tuple[str, str, set[str]] | None:
    """The top block, the bottom block and all the blocks of the tower that ``words`` end in ('put red on green and
    green on blue': red, blue), or None where they do not end in blocks put on blocks."""
    start = len(words)
    while start > 0 and (words[start - 1] in BLOCK_COLOURS or words[start - 1] in ("on", "and")):
        start -= 1
    clause = words[start:]
    pairs = [(clause[i - 1], clause[i + 1]) for i, word in enumerate(clause) if word == "on"
             and 0 < i < len(clause) - 1 and clause[i - 1] in BLOCK_COLOURS and clause[i + 1] in BLOCK_COLOURS]
    if not pairs or start == 0 or words[start - 1] not in ("put", "stack"):
        return None
    tops, bottoms = {a for a, _ in pairs}, {b for _, b in pairs}
    top, bottom = tops - bottoms, bottoms - tops
    return (top.pop(), bottom.pop(), tops | bottoms) if len(top) == len(bottom) == 1 else None


def _chained_on(words: list[str]) -> list[str]:
    """'blue on green on red': each block on the next, 'blue on green and green on red' (and so for 'under')."""
    chained = list(words[:2])
    for i in range(2, len(words)):
        if (words[i] in ("on", "under") and words[i - 1] in BLOCK_COLOURS and words[i - 2] == words[i]
                and i + 1 < len(words) and words[i + 1] in BLOCK_COLOURS):
            chained += ["and", words[i - 1]]
        chained.append(words[i])
    return chained


def _top_down(words: list[str]) -> list[str]:
    """'stack red, green and blue from top to bottom': the tower's colours reversed, so the first is at the bottom
    as everywhere else; the mark may stand before or after the list that follows 'stack'."""
    while TOP_DOWN in words:
        mark = words.index(TOP_DOWN)
        words = words[:mark] + words[mark + 1:]
        start = _listing_start(words, mark)
        ahead = mark
        while ahead < len(words) and words[ahead] == "and":  # "from the top down, build a tower of ..."
            ahead += 1
        if (start == 0 or words[start - 1] != "stack") and ahead < len(words) and words[ahead] == "stack":
            start = ahead + 1
        elif start == 0 or words[start - 1] != "stack":
            raise LanguageError("'from top to bottom' orders a tower's blocks: say 'stack red, green and blue from "
                                "top to bottom'")
        end = start
        while end < len(words) and (words[end] in BLOCK_COLOURS or words[end] in ("and", "then")):
            end += 1
        listing = words[start:end]
        colours = iter([w for w in listing if w in BLOCK_COLOURS][::-1])
        words[start:end] = [next(colours) if w in BLOCK_COLOURS else w for w in listing]
    return words


def _listing_after_verb(words: list[str]) -> bool:
    """Whether ``words`` end in one of :data:`LISTING_VERBS` and a list of colours only."""
    start = _listing_start(words, len(words))
    return start > 0 and words[start - 1] in LISTING_VERBS


def _listing_start(words: list[str], end: int) -> int:
    """Where the run of colours and connectives ('red and green then blue') that ends before ``end`` begins."""
    start = end
    while start > 0 and (words[start - 1] in BLOCK_COLOURS or words[start - 1] in ("and", "then")):
        start -= 1
    return start


_JOINED_COLOURS = re.compile(rf"\b(?P<colour>{_COLOUR}) *(?P<mark>[-/]) *(?=(?:{_COLOUR})\b)")
"""Colours joined by hyphens ('a red-green-blue tower': a list of blocks) or slashes ('red/green': one or the other,
refused as a choice)."""
_COUNTED = re.compile(r"\b(?:(?:all|both)(?: of)?(?: the)? (?P<all>" + "|".join(NUMBERS) + r"|[2-8])(?: blocks| cubes| ones)?"
                      r"|the (?P<the>" + "|".join(NUMBERS) + r"|[2-8]) (?:blocks|cubes|ones))\b")
"""A count of blocks meant as all of them: 'all three blocks', 'both of the two', 'the two blocks'."""
_BLOCKS_AFTER_A_VERB = re.compile(r"^\s*(?:(?P<verb>move|put|place|bring|get|push|pull|swap|switch|exchange|stack|separate|gather|"
                                  r"group|arrange|spread|set|lay) )?(?:(?P<count>" + "|".join(NUMBERS) + r"|[2-8]) )?(?:stacked "
                                  r"|scattered |loose )?(?:blocks|cubes)\b")
"""A goal's first words naming the blocks bare, with or without their count ('move blocks apart', 'Move 2 blocks
closer', 'swap 2 stacked blocks', as the paper names its tasks): all of them."""


def _all_counted(match: re.Match, blocks: Sequence[str]) -> str:
    """'all' where the count is the number of blocks present, else the refusal names the blocks there are."""
    said = match["all"] or match["the"]
    if not _counts_all(said, blocks):
        raise LanguageError(f"{match[0]!r} speaks of {said} blocks, but this world has {len(blocks)} "
                            f"({', '.join(blocks)}): name the blocks by colour")
    return " all "


def _counts_all(said: str, blocks: Sequence[str]) -> bool:
    return (NUMBERS[said] if said in NUMBERS else int(said)) == len(blocks)


def _verb_on_all(match: re.Match, blocks: Sequence[str]) -> str:
    """'move blocks apart', 'Move 2 blocks closer': the verb on all the blocks; a count of fewer than there are is
    left as said (and refused later as leaving open which)."""
    if match["count"] and not _counts_all(match["count"], blocks):
        return match[0]
    return f" {match['verb'] or ''} all "


_EXCEPTION_AFTER_ALL = re.compile(
    r"\b((?:all|every|everything|each)\b.*?) (?:apart from|aside from|besides|but for)"
    r"(?=(?: (?:and|or|the|block|blocks|cube|cubes|one|ones|" + _COLOUR + r"))+"
    r"(?P<after> *$|(?: (?:should|must|shall|will|can|need to|needs to|have to|has to))?(?: (?:be|go|goes|stay|stays|are|is"
    r"|belong|belongs|end up|ends up))? (?:in|into|inside|on|onto|to|near|next|beside|close|off|under|away|far)\b))")
"""'apart from', 'besides' after 'all' and before the blocks: an exception, not a place, where the words between or
after say where the blocks go ('put everything apart from blue in the bin', 'bin all besides red'); in 'keep
every block apart from green' it is the place."""
_SIZE = r"(?:\d+|" + "|".join(NUMBERS) + r")"
_OTHERS_COUNTED = re.compile(rf"\b(?:the +)?(?:other|remaining) +(?P<count>{_SIZE})(?: +(?:blocks|cubes|ones))?\b|\bthe +"
                             rf"(?P<count2>{_SIZE}) +(?:others|other +(?:blocks|cubes|ones)|remaining(?: +(?:blocks|cubes|ones))?|"
                             r"(?:blocks |cubes |ones )?left(?: over)?)\b")
"""'the other four', 'the remaining two blocks', 'the three others': the blocks the rest of the goal does not name."""


def _named_elsewhere(match: re.Match, blocks: Sequence[str]) -> set[str]:
    """The blocks the goal names outside ``match``: what 'the other four' or 'a tower of five' leaves out."""
    return set(re.findall(rf"\b(?:{_COLOUR})\b", f"{match.string[:match.start()]} {match.string[match.end():]}")) & set(blocks)


def _others_counted(match: re.Match, blocks: Sequence[str]) -> str:
    """'the rest', where the count is what the blocks named elsewhere in the goal leave; else refused, with that count."""
    said = match["count"] or match["count2"]
    count = NUMBERS.get(said) or int(said)
    named = _named_elsewhere(match, blocks)
    if named and count == len(blocks) - len(named):
        return " the rest "
    raise LanguageError(f"{match[0].strip()!r}: the goal names {len(named)} of the {len(blocks)} blocks "
                        f"({', '.join(blocks)}), which leaves {len(blocks) - len(named)}: say which {count} by colour")


_END_SAID = {"top": "top", "highest": "top", "uppermost": "top", "topmost": "top", "bottom": "bottom", "lowest": "bottom",
             "bottommost": "bottom", "base": "bottom", "foot": "bottom"}
_BLOCK_SAID = rf"(?:the )?(?:{_COLOUR})(?: block| cube| one)?"
_LEFT_OUT_EITHER = re.compile(rf"\b(?P<head>except(?: for)?|but not|without|excluding|other than|apart from|besides|save "
                              rf"for) +(?P<first>{_BLOCK_SAID}(?: +(?:and +)?{_BLOCK_SAID})*) +(?:or|nor) +(?P<second>{_BLOCK_SAID})\b")
"""'everything except red or green', 'a tower, but not with red or green': the 'or' under the exception leaves out both."""
_AN_END = (rf"the (?:very )?(?P<{{end}}>{'|'.join(_END_SAID)})(?: (?:block|cube|one))?(?: of (?:the|that|this|your) "
           r"(?:tower|stack|pile))?")
"""A tower's end said ('the very top block of the tower'), its group named by ``end`` (``str.format``)."""
_MADE_AN_END = re.compile(rf"(?:\b(?:make|let|have) (?P<made>{_BLOCK_SAID}) (?:be )?|^ *(?P<said>{_BLOCK_SAID}) (?:(?:should|must|"
                          r"needs to|has to|will|shall) )?(?:be|go|goes|end up|ends up|sit|sits|is) (?:at |on )?)"
                          + _AN_END.format(end="end") + r"(?= *$| and\b| then\b)")
"""'make red the top block', 'green should be at the bottom': the block put at that end (of the tower standing)."""
_AN_END_SAID = rf"(?P<{{block}}>{_BLOCK_SAID}) (?:be )?" + _AN_END
_MADE_BOTH_ENDS = re.compile(r"\b(?:make|let|have) " + _AN_END_SAID.format(block="first", end="first_end") + r" *,? *(?:and )?"
                             r"(?:(?:make|let|have) )?" + _AN_END_SAID.format(block="second", end="second_end")
                             + r"(?= *$| and\b| then\b)")
"""'make red the top block and green the bottom': both blocks' places in the tower, read as 'red at the top and green at
the bottom'."""
_END_OF_TWO = re.compile(rf"(?P<verb>put|place|move|set|stack|get) (?P<what>{_BLOCK_SAID}) (?:at|to|on|onto) the (?:very )?"
                         r"(?P<end>top|bottom|base|foot)(?: of (?:the|that|this|your) (?:tower|stack|pile))?(?= *$| and\b| then\b)")
"""'put red at the bottom' where two blocks are all there is: the other on it ('at the top': on the other)."""
_BASE_OF_TWO = re.compile(rf"\b(?P<noun>tower|stack|pile) with (?={_BLOCK_SAID} (?:at|on) the (?:bottom|base|foot)\b)")
"""'a tower with red at the bottom' where two blocks are all there is: a tower of both."""
_TOWER_SIZE = re.compile(rf"\b(?:(?P<size>{_SIZE})[- ](?:block|cube|storey|story|level)s?[- ]"
                         r"(?:high |tall )?(?P<noun>tower|stack|pile)|(?P<noun2>tower|stack|pile) +(?:and +)?(?:(?:that|which)"
                         rf" (?:is|are) )?(?:(?P<of>of) (?:height |size )?(?P<size2>{_SIZE})(?: blocks| cubes)?"
                         rf"|(?P<size3>{_SIZE})(?: blocks| cubes)? (?:high|tall)(?: +and(?= +(?:of|with|from|using"
                         r"|out of)\b))?))\b")
"""A tower's size said with its blocks ('a 3-block tower', 'a tower of three: ...', 'a tower that is three blocks
tall with ...'), or without them where the size is every block there is ('a tower of six blocks' of six)."""


_TOWER_WITHOUT = re.compile(rf"\b(?P<tower>(?:tower|stack|pile)(?: of {_SIZE}(?: blocks| cubes)?)?) +(?:and +)?(?:without|"
                            rf"but not with|excluding|except(?: for)?|other than|apart from|leaving out|not using) +(?P<left_out>"
                            rf"{_BLOCK_SAID}(?: +(?:and|or|nor) +{_BLOCK_SAID})*)")
"""'a tower (of four) without red', 'a tower, but not with red or green': a tower of all the blocks but those (an 'or'
under the 'not' leaves out both)."""


def _tower_of_all_but(match: re.Match) -> str:
    left_out = re.sub(r"\b(?:or|nor)\b", "and", match["left_out"])
    return f"{match['tower']} of all except {left_out}"


_OF_ALL_BUT = re.compile(r" *(?:from|using|out of|of|with) +(?:all|every|everything|each)\b(?P<but>.*?)(?=\bthen\b|$)")
"""'... tower of four from everything but red', after the tower's size: the blocks left out follow."""


def _tower_sized(size: re.Match, blocks: Sequence[str]) -> str:
    """A tower said with its size, as the tower: 'of' kept for the blocks that follow ('a tower of three: red, green and
    blue'), not before its blocks' places ('a tower of three blocks with red at the bottom, ...'). Where its blocks are
    not listed in its clause, nor all said by their places, the tower is of every block if that is as many, of the
    blocks the rest of the goal does not name if that is ('put orange in the bin and build a tower of five', of six),
    and is refused if neither."""
    said = size["size"] or size["size2"] or size["size3"]
    count = NUMBERS.get(said) or int(said)
    before, rest = size.string[:size.start()], size.string[size.end():]
    places_follow = re.match(r" *with\b", rest)
    colours = rf"\b(?:{_COLOUR})\b"
    noun = size["noun"] or size["noun2"]
    if of_all := _OF_ALL_BUT.match(rest):
        left_out = set(re.findall(colours, re.split(rf"\band(?! +(?:the +)?{colours})\b", of_all["but"])[0])) & set(blocks)
        if count != len(blocks) - len(left_out):
            raise LanguageError(f"{size[0].strip()!r} of all but {', '.join(sorted(left_out)) or 'none'} would be a "
                                f"tower of {len(blocks) - len(left_out)}: say which {count} blocks ({', '.join(blocks)})")
        return f" {noun} "
    listed_after = re.search(colours, re.split(rf"\b(?:with|then|and(?! +(?:the +)?{colours}))\b", rest)[0])
    listed_before = re.search(colours, re.split(r"\b(?:then|and)\b", before)[-1])  # 'stack red, green and blue into ...'
    first, *more = re.split(r"\bthen\b", rest)  # '... with red at the bottom, then green, then blue': its order
    in_order = itertools.takewhile(bool, (re.match(rf" *{_BLOCK_SAID} *(?:and\b|$)", clause) for clause in more))
    placed = places_follow and len(set(re.findall(colours, " ".join((first, *(m[0] for m in in_order)))))) == count
    if not listed_after and not listed_before and not placed:
        named_elsewhere = _named_elsewhere(size, blocks)
        if count == len(blocks):
            return f" {noun} of all "
        if named_elsewhere and count == len(blocks) - len(named_elsewhere):
            return f" {noun} of the rest "
        raise LanguageError(f"{size[0]!r}: say which {count} blocks, e.g. 'build a tower of "
                            f"{', '.join(blocks[:count]) or 'red, green and blue'}' (this world has {len(blocks)}: "
                            f"{', '.join(blocks)})")
    return f" {noun} {size['of'] or '' if listed_after else ''} "


_LIST_SAID = (rf"(?:the +)?(?:{_COLOUR})(?: +(?:block|cube))?(?: +(?:and +)?(?:the +)?(?:{_COLOUR})(?: +(?:block|cube))?)+"
              r"(?: +blocks| +cubes)?")
_RESPECTIVELY = re.compile(rf"(?P<movers>{_LIST_SAID}) +(?P<place>on top of|onto|on|next to|near|beside|close to|by|away "
                           rf"from) +(?P<places>{_LIST_SAID})(?: +and)? +respectively\b")
"""'put red and blue on green and yellow respectively': each block of the first list by the one of the second."""


def _respectively(match: re.Match) -> str:
    movers, places = (re.findall(rf"\b(?:{_COLOUR})\b", match[group]) for group in ("movers", "places"))
    if len(movers) != len(places):
        raise LanguageError(f"'respectively' pairs {len(movers)} blocks with {len(places)}: name as many of each")
    return " and ".join(f"{mover} {match['place']} {place}" for mover, place in zip(movers, places, strict=True))


_RELATIVE_ON = re.compile(r"\b(?P<block>" + _COLOUR + r")(?: +block| +cube| +one)?(?: +and)? +"
                          r"(?:which|that) +(?:(?:(?:should|must|will|shall) +)?"
                          r"(?:is|be|sits?|stands?|rests?|lies|lie|goes|go|ends? +up) +)?(?=(?:on|upon|atop|onto)\b)")
"""'green which is on red': a block that a relative clause places, read as 'green and green on red'."""
_ONE_NOT_NAMED = re.compile(r"^(?!.*(?:\b(?:not|never|no|nothing|without|nor)\b|n't\b))(?:.*\s)?(?P<said>(?:another|any|some|one "
                            r"more|an?)(?: other)? (?:block|cube))\b(?! tower)")
"""'put another block on the tower', 'move any block next to red': one block the goal does not name (refused; where the
sentence denies, 'not on another block' is every other block)."""
_SOME_OF = re.compile(r"(?<!every )(?<!each )\b(?:one|any|some|a few|several|a couple|either|half|most|many|two|three|four|five|six|seven|"
                      r"\d) of (?:the |these |those |your )?(?:blocks|cubes|them|ones)\b|\b(?:all|everything|every (?:block|cube)) (?:of )?"
                      r"(?:the |them )?(?:blocks |cubes )?(?:but|except(?: for)?|save|apart from) (?:one|two|three|four|five|six|\d)"
                      r"\b(?! of\b)")
"""'one of the blocks', 'some of them', 'all of them except one': blocks the goal does not say (refused)."""
_SUGGESTED = r"\s+(?:(?:don'?t|do not) (?:you|we)|not)\b"
"""After 'why': 'why don't you put red in the bin?', 'why not bin red': a goal suggested, not a question."""
_A_QUESTION = re.compile(r"^\W*(?:(?:is|are|does|do|did|was|were|has|have)\b(?!\s+(?:you|it possible)\b).*\?\W*$|(?:where|which|"
                         rf"what|how|why|who|when)\b(?!.*\b(?:you|i|we)\b.*\b(?:want|like|need)\b)(?!{_SUGGESTED}).*\?\W*$|"
                         rf"(?:where|which|how many|why)\b(?!{_SUGGESTED}))")
"""'is red in the bin?', 'where is red?': asking about the world, not saying how it should end (refused)."""
_AN_ORDER = re.compile(r"^\W*(?:please\W+)?(?P<order>stop|cancel|abort|halt|pause|resume|continue|reset|restart|undo|redo|"
                       r"never ?mind|help|quit|exit|start over)\W*(?:please|now|it|that|everything)?\W*$")
"""'stop', 'undo', 'help': an order about the run, not a state to reach (refused with where those orders go)."""
_CORRECTION = re.compile(r"\b(?:no,? wait|wait,? no|no,? sorry|sorry|scratch that|i mean|on second thought|or rather|correction|"
                         r"actually|make that)\b")
"""'put red in the bin, no wait, green': words that take back what came before them (refused after a word)."""
_HELD_OVER = re.compile(rf"\b(?:hold|carry|dangle)\s+(?:up\s+)?(?P<block>{_BLOCK_SAID}|it|them)\s+(?:up\s+)?(?:above|"
                        r"over|high above|up over)\s+(?!(?:to|into|onto|next|near|beside|by|close)\b)(?P<place>[\w ]+?)"
                        r"(?=,|\.|;|\band\b|\bthen\b|$)")
"""'hold blue above the bin', 'pick up red and hold it over green': a place in the air, which no predicate says
(refused)."""
_HOLDING_VERBS = ("hold", "carry", "grab", "pick up", "lift")
_PLACING_VERBS = ("put", "place", "move", "set", "stack", "drop", "throw", "toss", "get", "bring", "lay")
"""The verbs a 'neither ... nor' or a denied 'or' may follow: those that put a block somewhere, or into the hand."""
_KEPT_EITHER = re.compile(r"\b(?P<head>(?:don't|dont|do not|never)\s+(?:move|touch|disturb|shift)|(?:without|and not|but not)\s+"
                          rf"(?:moving|move|disturbing|disturb|shifting|shift))\s+(?P<first>{_BLOCK_SAID}(?:\s+(?:and\s+)?"
                          rf"{_BLOCK_SAID})*)\s+(?:or|nor)\s+(?P<second>{_BLOCK_SAID})(?!\s+(?:in|into|inside|on|onto|to|near|"
                          r"next|beside|by|close|away|off|out|from|under)\b)")
"""'without moving red or green', 'don't touch red or green': both kept where they are (the 'or' under a 'not'), as
long as no place follows ('don't move red or green into the bin' is :data:`_NOT_ONE_OR_OTHER`'s)."""
_NOT_ONE_OR_OTHER = re.compile(r"\b(?:don't|dont|do not|never|not)\s+(?P<verb>" + "|".join(_PLACING_VERBS + _HOLDING_VERBS)
                               + rf")\s+(?P<first>{_BLOCK_SAID}(?: and {_BLOCK_SAID})*) or (?P<second>{_BLOCK_SAID})")
"""'don't put red or green in the bin': neither (the 'or' under a 'not')."""
_KEPT_FROM = re.compile(rf"\b(?:stop|prevent|keep)\s+(?P<blocks>{_BLOCK_SAID}(?:,? and {_BLOCK_SAID})*)\s+from\s+"
                        r"(?:being |going |getting |ending up )?")
"""'stop red from touching green', 'prevent red from being in the bin': red, not."""
_NEITHER = re.compile(r"\b(?:(?P<verb>" + "|".join(_PLACING_VERBS + _HOLDING_VERBS) + r") )?"
                      rf"neither (?P<first>{_BLOCK_SAID}(?: and {_BLOCK_SAID})*) nor (?P<second>{_BLOCK_SAID})"
                      r"(?: (?:should|must|will|can|may|is|are)(?: be)?| be)?\b")
"""'neither red nor green (should be) in the bin', 'put neither red nor green in the bin': both, not."""
_NOT_EITHER_OF = re.compile(r"(?P<head>(?:\bnot|n't|\bnever)(?: \w+){0,3}?) either(?: of (?:them|the two|those|these)(?: blocks|"
                            r" cubes)?| one| of (?P<others>the others|the other (?:two|blocks|cubes|ones)))?\b")
"""'blue should not touch either of them': neither, so both; 'not on either of the others': on none of them (before
'either of' is refused as leaving open which)."""
_NEITHER_PLACE = re.compile(r"\bneither (?P<place>near|next to|close to|beside|by|touching|on|on top of|above) "
                            rf"(?P<first>{_BLOCK_SAID}) nor (?:(?:be )?(?P=place) )?(?P<second>{_BLOCK_SAID})")
"""'red should be neither near green nor near blue': near neither (then read by :data:`_NOT_EITHER`)."""
_NOT_EITHER = re.compile(r"\b(?P<head>(?:not|n't|never|nor) (?:be )?(?:near|next to|close to|beside|by|touch|touches|"
                         r"touching|in contact with|on|on top of|above)|(?:away|far|apart) from) "
                         rf"(?P<first>{_BLOCK_SAID}) or (?P<second>{_BLOCK_SAID})\b")
"""'blue must not be near red or green', 'away from red or green': from both (a denied 'or' is an 'and' of denials)."""
_POSITION = re.compile(rf"\b(?P<block>{_COLOUR})(?: block| cube| one)?(?: (?:is|goes|sits|stays|"
                       r"should be|must be|will be))? (?P<where>on top|at the top|on the top|in the middle|in between|"
                       r"at the bottom|on the bottom|at the base|top|middle|bottom|base(?= and| then| *$))\b(?: of (?:it|that|"
                       r"them)\b)?")
"""A block's place in a tower: 'red on top', 'green in the middle', 'blue at the bottom' ('red on top of it' after
another block's place), or said bare: 'red bottom, green middle, blue top'."""
_WITH = re.compile(r"\bwith (?:the )?$")
_A_TOWER_WITH = re.compile(r"\b(?:tower|stack|pile) +with (?:the )?$")
"""A tower named by its blocks' places alone ('a stack with blue at the bottom, ...'), no list of blocks before."""
_ALL_IN_A_TOWER_WITH = re.compile(r"\b(?:all|every|everything|each)\b[^,;.]*\b(?:tower|stack|pile) +with (?:the )?$")
"""Every block put in the tower whose places follow ('all the blocks in one tower with red at the bottom and ...')."""
_BETWEEN_PLACES = re.compile(rf"(?: |and|then|with|(?:{_COLOUR})(?: block| cube| one)?)*")
"""What may stand between two blocks' places in a tower said in a run: joining words, and blocks named bare."""
_LEVELS = {"on top": 2, "at the top": 2, "on the top": 2, "in the middle": 1, "in between": 1, "at the bottom": 0,
           "on the bottom": 0, "at the base": 0, "top": 2, "middle": 1, "bottom": 0, "base": 0}


def _tower_by_positions(text: str) -> str:
    """Two or more blocks' places in a tower said one after another ('red on top, green in the middle, blue at the
    bottom', any order) as the tower from the bottom up ('stack blue and green and red'); blocks named bare between its
    two ends go between them in the order said ('yellow on top, then orange, then purple at the bottom')."""
    runs: list[list[re.Match]] = []
    bare: list[list[str]] = []  # each run's blocks named between its places, without one
    for match in _POSITION.finditer(text):
        gap = text[runs[-1][-1].end():match.start()] if runs else ""
        if runs and _BETWEEN_PLACES.fullmatch(gap) and (not re.search(_COLOUR, gap) or not bare[-1]):
            runs[-1].append(match)
            bare[-1] += re.findall(rf"\b(?:{_COLOUR})\b", gap)
        else:
            runs.append([match])
            bare.append([])
    for run, between in reversed([(r, b) for r, b in zip(runs, bare, strict=True) if len(r) >= 2]):
        before = text[:run[0].start()]
        if with_ := _WITH.search(before):
            if not _A_TOWER_WITH.search(before) or _ALL_IN_A_TOWER_WITH.search(before):
                continue  # "a tower of red and green with blue on top", "all the blocks in a tower with red at the
                # bottom and blue on top": the tower's ends, read later
            before = before[:with_.start()]  # "a stack with blue on the bottom, green in the middle and red on top"
        levels = [(_LEVELS[m["where"]], m["block"]) for m in run]
        if between:
            if len(run) != 2 or {level for level, _ in levels} != {0, 2}:
                raise LanguageError("a tower's blocks named between its top and its bottom go in the order said: name "
                                    "its top and bottom blocks around them, e.g. 'red on top, then green, then blue at "
                                    "the bottom'")
            said = [levels[0][1], *between, levels[1][1]]
            levels = list(enumerate(said[::-1] if levels[0][0] == 2 else said))
        if len({level for level, _ in levels}) < len(levels):
            raise LanguageError("two blocks are said to be at one place in the tower: name its blocks from the bottom "
                                "up, e.g. 'build a tower of red, green and blue'")
        tower = " and ".join(block for _, block in sorted(levels))
        before = re.sub(r"\b(?:put|place|set|arrange|position)\s*$", "", before)  # "put red on top and green at the bottom"
        before = re.sub(r"\b(tower|stack|pile) (where|in which|such that|so that) *$", r"\1 ", before)  # "a tower where red
        # is at the bottom and ..."
        said = "" if re.search(r"\b(?:tower|stack|pile)(?: and| of)? *$", before) else "stack "  # "a tower (of three): red
        # on top, ..."
        text = f"{before} {said}{tower} {text[run[-1].end():]}"
    return text


_NUMBERED = re.compile(r"(?:^|(?<=\s))(?:\d+[.)]|[a-h]\)|step \d+:?|(?:second|third|fourth|fifth|secondly|thirdly|next),)(?=\s)"
                       r"|\n(?:[-*\u2022\u00b7]\s)?|^[-*\u2022\u00b7]\s")
"""A step's number, letter, bullet or ordinal before it ('1.', '2)', 'b)', '- ', 'step 3', 'second,'), or a line of
its own: the steps come in turn."""
_GERUNDS = {"picking": "pick", "putting": "put", "placing": "place", "taking": "take", "moving": "move",
            "stacking": "stack", "unstacking": "unstack", "removing": "remove", "building": "build", "lifting": "lift",
            "grabbing": "grab", "dropping": "drop", "throwing": "throw", "tossing": "toss", "bringing": "bring",
            "leaving": "leave", "keeping": "keep", "releasing": "release", "clearing": "clear",
            "cleaning": "clean", "separating": "separate", "grouping": "group", "gathering": "gather",
            "setting": "set", "getting": "get", "emptying": "empty", "making": "make", "binning": "bin",
            "discarding": "discard"}
_GERUND = re.compile(rf"\b(?:{'|'.join(_GERUNDS)})\b")
"""'after picking up red': the verb as in a command ('holding' is left as it is: 'keep holding green')."""
_BLOCKS_ONLY = re.compile(rf"(?:\s|,|\b(?:and|the|block|blocks|cube|cubes|one|{_COLOUR})\b)+")
_LEADING_WHEN = re.compile(r"^\s*(?P<when>after|before|once|when)\s+(?:you(?:'re|'ve|\s+are|\s+have)?\s+(?:(?:done|finished)"
                           r"\s+(?:with\s+)?)?|i\s+)?(?P<first>[^,;]+?)"
                           r"\s*,\s*(?:then\s+)?(?P<rest>.+)$")
_FIRST_SAID_LAST = re.compile(r"^(?P<main>.+?)\s*,?\s+(?:but|and)\s+(?:first(?:ly)?|before that|beforehand)\s*,?\s+(?P<first>.+)$"
                              r"|^(?P<main2>.+?)\s*,?\s+(?:but|and)\s+(?P<first2>.+?)\s+(?:first|beforehand|before that)\s*$")
"""'B, but first A', 'B, and A first': A said last, done first."""
_TRAILING_WHEN = re.compile(r"^(?P<main>.+?)(?<!\bone)(?:\s*,?\s+(?:but\s+)?(?:only|just))?\s+(?P<when>after|before|(?:but\s+)?"
                            r"not\s+until)\s+(?:you\s+(?:have\s+)?|i\s+)?"
                            r"(?P<other>(?!that\b|this\b|which\b).+)$")


_SAID_AFTER = re.compile(r"\b(?P<verb>stack|pile|(?:re-?)?arrange|order|place|put|position|set|build|make|assemble|organi[sz]e)"
                         r"( up)? (all )?(of )?(the |these |those )?((two|three|four|five|six|seven|eight|\d) )?"
                         r"(blocks|cubes|them|everything)( up)?(?P<tower> (in|into) (a|one|a single) (tower|stack|pile))?"
                         r"\s*(?P<then>:|,? (so that|such that|so|in such a way that|like this|as follows|this way)\b)")
"""'stack the blocks so that yellow is on blue, ...', 'place all the blocks in one tower: red, green, ...': all the blocks
said first, what becomes of them after."""


_COUNTED_THEN_NAMED = re.compile(r"\b(?P<verb>put|place|move|throw|toss|drop|stack|take|bring|get|load) (?:(the )?(any )?"
                                 r"(two|three|four|five|six|seven|eight|\d) (of the )?(blocks|cubes)|(these|those)( two| three| four| "
                                 r"five| six| \d)?( blocks| cubes)?|them|the "
                                 r"following( blocks| cubes)?) (?P<where>(in|into|on|onto|next|near|beside|by|close|away|"
                                 r"far|out|off|to|inside)\b[^:;]*?)\s*:\s*(?P<named>[^.;]+)")
"""'put two blocks in the bin: red and green', 'put these in the bin: red, green': the blocks named after the colon,
where the count was."""


_BINNED_THEN_NAMED = re.compile(r"\b(?P<verb>bin|discard|dump|trash|throw (?:away|out)|toss(?: out)?|get rid of|clear away|"
                                r"remove) (?:all )?(?:of )?(?:(?:the |these |those )?(?:(?:two|three|four|five|six|seven|eight|\d) )?"
                                r"(?:blocks|cubes)|them|(?:these|those)(?: (?:two|three|four|five|six|seven|eight|\d))?|the following"
                                r"(?: blocks| cubes)?)(?: in (?:\w+ )?order)?\s*:\s*(?P<named>[^.;]+)")
"""'bin them in order: red, green, blue': a verb that says where, its blocks named after the colon."""


_PLACE_THEN_NAMED = re.compile(r"^\s*(?P<where>(?:in|into|inside|onto|on top of|on|next to|near|away from) (?:the )?\w+)(?: please)?"
                               r"\s*:\s*(?P<named>[^.;:]+)$")
"""'into the bin: red, green': the place said first, the blocks after the colon."""


def _said_after(text: str) -> str:
    """What becomes of 'the blocks' said after them: after a colon, a tower's ('stack' kept before its list), else the
    clauses that follow alone; blocks counted, then named after a colon, as named."""
    def said(match: re.Match) -> str:
        towered = match["tower"] or match["verb"] in ("stack", "pile", "build", "assemble")
        return " stack " if towered and match["then"] == ":" else " "
    text = _COUNTED_THEN_NAMED.sub(lambda m: f"{m['verb']} {m['named']} {m['where']}", text)
    text = _BINNED_THEN_NAMED.sub(r"\g<verb> \g<named>", text)
    text = _PLACE_THEN_NAMED.sub(lambda m: f"put {m['named']} {m['where']}", text)
    return _SAID_AFTER.sub(said, text)


def _in_time_order(text: str) -> str:
    """'after A, B', 'B after A', 'A before B', 'before B, A' as 'A then B' (later clauses override earlier ones). 'B
    after green' names only a block: the verb is B's, said again after it ('B then green'); for a goal's end state
    the order of two clauses that do not clash does not matter."""
    if match := _FIRST_SAID_LAST.match(text):  # "put green on red, but first pick up red"
        return f"{match['first'] or match['first2']} ; {match['main'] or match['main2']}"
    if match := _LEADING_WHEN.match(text):
        first, rest = match["first"], match["rest"]
        return f"{rest} ; {first}" if match["when"] == "before" else f"{first} ; {rest}"
    if match := _TRAILING_WHEN.match(text):
        main, other = match["main"], match["other"]
        if match["when"] == "before" or _BLOCKS_ONLY.fullmatch(other):
            return f"{main} ; {other}"
        return f"{other} ; {main}"
    return text


_TOWERS_OF_A_SIZE = re.compile(rf"\b(?P<count>two|three|2|3) (?P<noun>towers|stacks|piles) of (?P<size>{_SIZE})(?: blocks| cubes)?"
                               rf"(?: each)?\s*[:,]?\s*(?P<listed>(?:the )?(?:{_COLOUR})(?:(?: block| cube)?(?:\s*,\s*|\s+and\s+|"
                               rf"\s+)(?:and )?(?:the )?(?:{_COLOUR}))+)")
"""'two towers of three: red, green, blue and yellow, orange, purple': the blocks listed in turn, each tower from the
bottom up."""


def _towers_of_a_size(match: re.Match) -> str:
    """Each tower said as 'one of ...' (:data:`_EACH_TOWER`), the list cut in the towers' size; refused where the list
    does not fill them."""
    count, size = (NUMBERS.get(match[key]) or int(match[key]) for key in ("count", "size"))
    listed = re.findall(rf"\b(?:{_COLOUR})\b", match["listed"])
    if len(listed) != count * size:
        raise LanguageError(f"'{match[0].strip()}': {count} {match['noun']} of {size} take {count * size} blocks, "
                            f"{len(listed)} are listed: name each tower's blocks, e.g. 'two towers, one of red and "
                            "green and one of blue and yellow'")
    towers = [" and ".join(listed[i:i + size]) for i in range(0, count * size, size)]
    return f"{count} {match['noun']}, " + " and ".join(f"one of {tower}" for tower in towers)


_SEVERAL_TOWERS = re.compile(r"\b(two|three|2|3|a couple of|several|some) (towers|stacks|piles)\b")
_EACH_TOWER = re.compile(r"\b(one|the other|another|the (first|second|third|last))( tower| stack| pile)? (of|with|from)\b")
"""Each of several towers said as 'one of red and green', 'the other of blue and yellow': a tower of those blocks."""
_AN_END_REACHED = (rf"(?:the )?(?P<colour>{_COLOUR})(?: block| cube| one)? +(?:(?:is|ends up|sits|stands|goes|should be|will be|"
                   r"gets|lies) +)?(?:at|on) +(?:the )?(?:very )?(?P<end>top|bottom|base)\b(?! +of\b)")
_STACKED_SO = re.compile(rf"\b(?P<head>(?:stack|pile|tower)\b[^.;]*?) *(?: so that| so| such that| in such a way that| making sure"
                         rf"(?: that)?|,) +(?P<ends>{_AN_END_REACHED}(?: *,? *and +{_AN_END_REACHED.replace('?P<', '?P<second_')})?)")
"""'stack the blocks so that red is at the bottom (and blue is at the top)', 'a tower of every block, red on top': as 'with
red at the bottom', the tower's ends."""


def _stacked_with_ends(match: re.Match) -> str:
    ends = [(match["colour"], match["end"]), (match["second_colour"], match["second_end"])]
    return f"{match['head']} with " + " and ".join(f"{colour} at the {end}" for colour, end in ends if colour)


_THROWN_AWAY = re.compile(r"\b(?:throw|toss|chuck|clear)\b(?P<what>(?: +[\w']+){1,12}?) +away\b(?! +from)|"
                          r"\b(?:throw|toss|chuck)\b(?P<out>(?: +[\w']+){1,12}?) +out\b(?! +(?:of|from))|"
                          r"\b(?:throw|toss|chuck) +out\b(?! +(?:of|from))")
"""'throw everything away', 'toss the red block away': where there is a bin, into it (as 'throw away red')."""
_THROWN = re.compile(rf"\b(?P<verb>throw|toss|chuck)(?P<what>(?:(?: +and| +or|,)* +(?:the )?(?:{_COLOUR})(?: block| cube| one)?)+| it|"
                     r" them| everything| all(?: (?:of )?the (?:blocks|cubes))?)(?= *(?:$|[;.]|(?:,| and\b)(?! *(?:and )?(?:the )?"
                     rf"(?:{_COLOUR})\b)| then\b| except\b| but\b| apart from\b| other than\b| besides\b| save for\b))")
"""'toss red', 'grab red and throw it': thrown with no place said, where there is a bin, away into it ('don't throw red'
keeps it out)."""
_PLACE = re.compile(r"\b(in|into|inside|on|onto|to|near|next|beside|close|out|off|up|held|holding|away|far)\b")
_PLACING_VERB = re.compile(r"\b(?:(?:bin|stack|clear|clean|tidy|dump|discard|throw|toss|remove)(?: up| away| out)?|(?:tower|stack"
                           r"|pile) (?:of|using|with|from|out of))$")
"""A verb that says where the blocks after it go ('bin everything besides red', 'clean up all apart from green', 'a tower
using every block apart from yellow')."""


def _as_exception(match: re.Match) -> str:
    said, before = match[1], match.string[:match.start()].strip()
    place = match["after"].strip() or _PLACE.search(said) or _PLACING_VERB.search(before)
    return f"{said} except" if place else match[0]


def _beside_the_bin(words: list[str]) -> list[str]:
    """'keep red away from the bin' as out of it; 'next to the bin' refused: no predicate says a block is beside it."""
    for at, (word, then) in enumerate(itertools.pairwise(words)):
        if then == "bin" and word == "near":
            raise LanguageError("no predicate says a block is next to the bin, only whether it is in it: say 'in the "
                                "bin', or 'out of the bin'")
        if then == "bin" and word == "away":
            words = [*words[:at], "out", *words[at + 1:]]
    return words


def _kept_besides(words: list[str]) -> list[str]:
    """'clean the table but leave red' takes red out of the clean-up; 'put red on green but leave blue (alone)', with no
    'all' or clean-up before it in the clause, keeps blue where it is."""
    kept: list[str] = []
    start = 0
    for word in words:
        if word == BUT_LEAVE:
            kept += ["except"] if {"all", "clean"} & set(kept[start:]) else ["and", "keep"]
            continue
        if word == "then":
            start = len(kept) + 1
        kept.append(word)
    return kept


def _joined(words: list[str], sentence_ends: bool = True) -> list[str]:
    """Runs of connectives as one ("red, and green" -> "red and green"; "and, then" -> "then"), and a group said twice
    once ("together in a group"); ``sentence_ends``: each :data:`SENTENCE_END` kept as it is, for now."""
    joined: list[str] = []
    for word in words:
        if (joined and word in ("and", "then") and joined[-1] in ("and", "then")
                and not (sentence_ends and [joined[-1], word] == SENTENCE_END.split())):
            joined[-1] = "then" if "then" in (word, joined[-1]) else "and"
        elif joined and word in ("together", "apart") and joined[-1] == word:
            continue
        else:
            joined.append(word)
    return joined
