"""Goal requests: a task name (``DC-3``), a conjunction of literals (``in_bin(red) & not close(red,green)``)
or a plain-English sentence (``put the red block in the bin``, :mod:`semgoal_planner.english`).

Parsing checks every literal against the scene's vocabulary and the objects present, and refuses
contradictions, so a planner only ever sees goals it can state.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from semgoal_core.consistency import ContradictionError, check_consistent
from semgoal_core.tasks import TASKS, Task, get_task, goal_form, goal_in_state, split_literals
from semgoal_core.vocabulary import LAYOUTS, Literal, VocabularyError, parse_literal
from semgoal_planner.english import (
    KEEP,
    MAX_GOAL_CHARS,
    ON_PREFIX,
    STACK,
    SWAP,
    TOWER_ALL,
    TOWER_BASE,
    TOWER_REST,
    TOWER_TOP,
    UNDER_PREFIX,
    LanguageError,
    parse_english,
)
from semgoal_planner.english.resolver import (
    ALL_BUT_PREFIX,
    HELD,
    IN_BIN_BLOCK,
    TOP_PREFIX,
    TOWER_MIDDLE,
    is_tower_place,
    stacks_in_order,
)


class GoalError(ValueError):
    """A goal that cannot be stated in the scene: the message says what is wrong and what is valid."""


@dataclass(frozen=True)
class Goal:
    """A goal read once, where it entered: a task (whose literals come from the world's state when it is
    planned: Swap-2 swaps whatever stack there is) or literals (typed, or what a sentence became), with the
    words it was given in, for display."""

    said: str
    literals: tuple[Literal, ...] = ()
    task: str = ""

    def instantiate(self, scene: str, objects: tuple[str, ...], state: list[Literal]) -> list[Literal]:
        """The literals to plan for in a world of ``scene`` with ``objects`` present, now in ``state``: a task's
        goal in that state, or the literals once every block they name is present, a block named by what it stands
        on or under placed (:func:`relative`), towers whose order is left open ordered (:func:`stacked`), 'the tower'
        placed (:func:`the_tower`), swaps made (:func:`swapped`), 'every block but ...' listed (:func:`every_block_but`) and
        blocks kept where they are (:func:`kept`). Nothing is parsed."""
        if self.task:
            return task_goal(self.task, scene, objects, state)
        layout = LAYOUTS[scene]
        try:
            placed = swapped(the_tower(stacked(relative(self.literals, state), state), state, objects), state)
            placed = every_block_but(placed, objects)
            goal = [layout.validate(literal, objects) for literal in kept(placed, state, scene, objects)]
            check_consistent(goal)
        except (VocabularyError, ContradictionError) as error:
            raise GoalError(str(error)) from None
        return list(dict.fromkeys(goal))


def read_goal(text: str, scene: str, objects: tuple[str, ...]) -> Goal:
    """The goal ``text`` says in a world of ``scene`` with ``objects`` present: a task, literals, or else a
    sentence. The one place a typed goal is parsed."""
    if len(text) > MAX_GOAL_CHARS:
        raise GoalError(f"the goal is {len(text)} characters long; at most {MAX_GOAL_CHARS} are read")
    form = goal_form(text)
    if form == "task":
        return Goal(text.strip(), task=scene_task(text, scene).name)
    if form == "text":
        try:
            return Goal(text.strip(), tuple(parse_english(text, scene, objects)))
        except LanguageError as error:
            raise GoalError(f"{error} (or give a task, {', '.join(TASKS)}, or literals such as in_bin(red))") from None
    try:
        literals = [parse_literal(part) for part in split_literals(text)]
    except (ValueError, VocabularyError) as error:
        raise GoalError(str(error)) from None
    return typed_goal(literals, scene, objects, text.strip())


def typed_goal(literals: Sequence[Literal], scene: str, objects: tuple[str, ...], said: str = "") -> Goal:
    """A goal of literals already read: each checked against the scene's vocabulary and ``objects``, the whole
    against contradictions, repeats dropped."""
    layout = LAYOUTS[scene]
    try:
        goal = [layout.validate(literal, objects) for literal in literals]
        check_consistent(goal)
    except (VocabularyError, ContradictionError) as error:
        raise GoalError(str(error)) from None
    if not goal:
        raise GoalError(f"an empty goal: give a task ({', '.join(TASKS)}), literals or a sentence")
    goal = list(dict.fromkeys(goal))
    return Goal(said or " & ".join(map(str, goal)), tuple(goal))


def parse_goal(text: str, scene: str, objects: tuple[str, ...], state: list[Literal]) -> list[Literal]:
    """The goal literals for ``text`` in a world of ``scene`` with ``objects`` present, now in ``state``."""
    return read_goal(text, scene, objects).instantiate(scene, objects, state)


def relative(literals: Sequence[Literal], state: Sequence[Literal]) -> list[Literal]:
    """``literals`` with each block named by where it stands placed in ``state``: ``block_on_red`` becomes the block
    on red, ``block_under_green`` the block green is on, ``block_held`` the block in the hand, ``block_in_bin`` the one
    block in the bin (also where a group leaves it out: ``all_but_block_held``). GoalError where none is, or several
    are."""
    on = {lit.args[1]: lit.args[0] for lit in state if lit.name == "above" and lit.value}  # block -> the one on it
    under = {upper: below for below, upper in on.items()}
    held = [lit.args[0] for lit in state if lit.name == "holding" and lit.value]
    binned = [lit.args[0] for lit in state if lit.name == "in_bin" and lit.value]

    def placed(arg: str) -> str:
        if arg == HELD:
            if not held:
                raise GoalError("the hand holds no block now: name the block instead")
            return held[0]
        if arg == IN_BIN_BLOCK:
            if len(binned) != 1:
                raise GoalError(f"{'no block is' if not binned else f'{len(binned)} blocks are'} in the bin now"
                                f"{' (' + ', '.join(binned) + ')' if binned else ''}: name the block instead")
            return binned[0]
        if arg.startswith(ON_PREFIX):
            block = arg.removeprefix(ON_PREFIX)
            if block not in on:
                raise GoalError(f"no block stands on {block} now: name the block instead")
            return on[block]
        if arg.startswith(UNDER_PREFIX):
            block = arg.removeprefix(UNDER_PREFIX)
            if block not in under:
                raise GoalError(f"{block} stands on no block now: name the block instead")
            return under[block]
        return arg

    made = [Literal(lit.name, tuple(_through_group(arg, placed) for arg in lit.args), lit.value) for lit in literals]
    itself = next((lit for lit in made if lit.value and len(set(lit.args)) < len(lit.args)), None)
    if itself:
        raise GoalError(f"{itself.args[0]} would be {itself.name} itself: the block named by where it is now is "
                        f"{itself.args[0]}, so name another block")
    return [lit for lit in made if len(set(lit.args)) == len(lit.args)]  # "... on the table": not on itself


def stacked(literals: Sequence[Literal], state: Sequence[Literal]) -> list[Literal]:
    """``literals`` with each ``stack(a,b,...)`` made one tower in ``state``: what stands of it on the table kept at
    the bottom, the goal's own 'x on y' kept (:func:`~semgoal_planner.english.resolver.stacks_in_order`)."""
    if not any(literal.name == STACK for literal in literals):
        return list(literals)
    away = {lit.args[0] for lit in state if lit.name in ("in_bin", "holding") and lit.value}
    standing = [t for t in _towers([lit for lit in state if lit.name == "above" and lit.value]) if t[0] not in away]
    return stacks_in_order(literals, standing)


def the_tower(literals: Sequence[Literal], state: Sequence[Literal], objects: Sequence[str]) -> list[Literal]:
    """``literals`` with 'the tower' placed: the one tower the goal itself builds ("a tower of red and green, then
    yellow next to the tower"), else the one standing in ``state`` (two or more blocks one on another, the blocks the
    goal moves to it set aside). :data:`TOWER_TOP` becomes its top block, and each further block put on the tower goes
    on the one put there before it; :data:`TOWER_BASE` its bottom block; :data:`TOWER_ALL` each of its blocks;
    :data:`TOWER_REST` each of ``objects`` not in it. GoalError where no tower stands, or several do."""
    said = {arg.removeprefix(ALL_BUT_PREFIX) for literal in literals for arg in literal.args}  # a group's too
    if not any(map(is_tower_place, said)):
        return list(literals)
    moved = {lit.args[0] for lit in literals if is_tower_place(lit.args[-1]) and not is_tower_place(lit.args[0])}
    built = _towers([lit for lit in literals if lit.name == "above" and lit.value and not is_tower_place(lit.args[-1])])
    if len(built) == 1:
        tower = kept = built[0]
    else:
        towers = _towers([lit for lit in state if lit.name == "above" and lit.value])
        standing = [t for t in towers if sum(b not in moved for b in t) >= 2] or towers  # not a moved block's own
        if not standing:
            raise GoalError("no tower stands now (no block is on another): name the block instead of 'the tower'")
        if len(standing) > 1:
            tops = [[b for b in t if b not in moved][-1] for t in standing]
            said = (f"say which block, e.g. 'put {sorted(moved)[0]} on {tops[0]}'" if moved else
                    f"name the blocks instead of 'the tower' (the first is {', '.join(standing[0])}, from the bottom)")
            raise GoalError(f"{len(standing)} towers stand now (topped by {', '.join(tops)}): {said}")
        tower = _swapped_in(standing[0], literals)
        kept = [b for b in tower if b not in moved] or tower
    placed = []
    if Literal(SWAP, (TOWER_ALL,)) in literals:  # the tower reversed: each block under the one it was on, and 'the
        placed = [Literal("above", pair) for pair in itertools.pairwise(tower)]  # tower' after it is the new one
        literals = [lit for lit in literals if not (lit.name == "above" and set(lit.args) <= set(tower))]  # as built
        tower, kept = tower[::-1], kept[::-1]
    place = {TOWER_TOP: kept[-1], TOWER_BASE: tower[0],
             **{arg: _counted(arg, tower) for arg in said
                if is_tower_place(arg) and arg not in (TOWER_TOP, TOWER_BASE, TOWER_ALL, TOWER_REST)}}
    named = {lit.args[0] for lit in literals if TOWER_REST not in lit.args}  # "... and the rest": not these
    each_of = {TOWER_ALL: tower, TOWER_REST: [o for o in objects if o not in tower and o not in named]}
    for literal in (each for lit in literals if lit != Literal(SWAP, (TOWER_ALL,)) for each in _each_of(lit, each_of)):
        args = tuple(_through_group(arg, lambda said: place.get(said, said)) for arg in literal.args)
        if len(set(args)) < len(args):  # "put the top block on the table", "... and the others next to it": not
            continue  # on or by itself
        placed.append(Literal(literal.name, args, literal.value))
        if literal.name == "above" and literal.value and literal.args[-1] == TOWER_TOP:  # the next block put on
            place[TOWER_TOP] = literal.args[0]  # the tower goes on this one
    return placed


def _through_group(arg: str, place: Callable[[str], str]) -> str:
    """``arg`` as ``place`` places it, also where a group leaves it out (``all_but_tower_top``: all but the top)."""
    if arg.startswith(ALL_BUT_PREFIX):
        return ALL_BUT_PREFIX + place(arg.removeprefix(ALL_BUT_PREFIX))
    return place(arg)


def every_block_but(literals: Sequence[Literal], objects: Sequence[str]) -> list[Literal]:
    """``literals`` with each group ``all_but_B`` (:data:`ALL_BUT_PREFIX`, its stand-in placed by now) made one literal
    for each block of ``objects`` but ``B`` and the literal's other blocks."""
    made = []
    for literal in literals:
        group = next((arg for arg in literal.args if arg.startswith(ALL_BUT_PREFIX)), None)
        left_out = group and group.removeprefix(ALL_BUT_PREFIX)
        made += _each_of(literal, {group: [b for b in objects if b != left_out]} if group else {})
    return made


def _swapped_in(tower: list[str], literals: Sequence[Literal]) -> list[str]:
    """``tower`` (bottom first) as the goal's swaps of two of its blocks leave it: 'swap red and green, then put blue
    on the tower' puts blue on the block that ends on top."""
    tower = list(tower)
    for literal in literals:
        if literal.name == SWAP and set(literal.args) <= set(tower):
            i, j = (tower.index(block) for block in literal.args)
            tower[i], tower[j] = tower[j], tower[i]
    return tower


def _counted(place: str, tower: Sequence[str]) -> str:
    """The block of ``tower`` (bottom first) a counted place names: :data:`TOWER_MIDDLE`, ``tower_top_K``,
    ``tower_bottom_K``. GoalError where the tower has no such block."""
    if place == TOWER_MIDDLE:
        if len(tower) % 2 == 0:
            raise GoalError(f"the tower has {len(tower)} blocks ({', '.join(tower)}, from the bottom), so no middle one: "
                            "name the block instead")
        return tower[len(tower) // 2]
    k = int(place.rsplit("_", 1)[1])
    if k > len(tower):
        raise GoalError(f"the tower has {len(tower)} blocks ({', '.join(tower)}, from the bottom), not {k}: name the "
                        "block instead")
    return tower[-k] if place.startswith(TOP_PREFIX) else tower[k - 1]


def _each_of(literal: Literal, groups: dict[str, list[str]]) -> list[Literal]:
    """``literal`` once for each block of the group it names (:data:`TOWER_ALL`: the whole tower; :data:`TOWER_REST`:
    the blocks not in it), else itself."""
    group = next((arg for arg in literal.args if arg in groups), None)
    if group is None:
        return [literal]
    return [Literal(literal.name, tuple(block if arg == group else arg for arg in literal.args), literal.value)
            for block in groups[group] if block not in literal.args]  # "all but the tower next to blue": not blue


def _towers(above: Sequence[Literal]) -> list[list[str]]:
    """The towers that ``above`` literals make, each bottom block first, in the order their bottoms appear."""
    under = {lit.args[0]: lit.args[1] for lit in above}  # block -> what it is on
    upper = {below: block for block, below in under.items()}
    towers = []
    for bottom in [b for b in dict.fromkeys(under.values()) if b not in under]:
        chain = [bottom]
        while chain[-1] in upper and upper[chain[-1]] not in chain:
            chain.append(upper[chain[-1]])
        towers.append(chain)
    return towers


def swapped(literals: Sequence[Literal], state: Sequence[Literal]) -> list[Literal]:
    """``literals`` with each ``swap(a,b)`` made what the two blocks trading places means in ``state``: the one on the
    other goes under it (and onto what the other stood on), or the one in the bin comes out as the other goes in.
    GoalError where they have no places to trade (neither on the other, both in the bin or both out)."""
    true = set(state)
    made: list[Literal] = []
    for literal in literals:
        if literal.name != SWAP:
            made.append(literal)
            continue
        a, b = literal.args
        on = next(((top, below) for top, below in ((a, b), (b, a)) if Literal("above", (top, below)) in true), None)
        binned = [block for block in (a, b) if Literal("in_bin", (block,)) in true]
        if on:
            made += [Literal("above", on[::-1]), Literal("above", on, False)]
            support = next((lit.args[1] for lit in state if lit.name == "above" and lit.value and lit.args[0] == on[1]),
                           None)
            if support:  # in a tower: the upper block takes the lower one's place on what it stood on
                made.append(Literal("above", (on[0], support)))
        elif len(binned) == 1:
            outside = b if binned == [a] else a
            made += [Literal("in_bin", (outside,)), Literal("in_bin", (binned[0],), False)]
        else:
            where = "in the bin" if binned else "out of the bin"
            raise GoalError(f"{a} and {b} have no places to trade now: neither is on the other, and both are {where}")
    return made


def kept(literals: Sequence[Literal], state: Sequence[Literal], scene: str, objects: Sequence[str]) -> list[Literal]:
    """``literals`` with each ``keep(a)`` made a's place in ``state``: in the bin or not, in the hand or not, on which
    block (the scene's predicates with ``a`` first). Closeness is not kept: another block may still be put next to
    it. A block the goal itself places (names first) is not kept, and an atom the goal states is left to it."""
    rest = [literal for literal in literals if literal.name != KEEP]
    placed = {literal.args[0] for literal in rest}
    stated = {(literal.name, literal.args) for literal in rest}
    predicates = LAYOUTS[scene].scene.predicates
    true = set(state)
    for block in dict.fromkeys(lit.args[0] for lit in literals if lit.name == KEEP and lit.args[0] not in placed):
        atoms = [("in_bin", (block,)), ("holding", (block,)), *(("above", (block, o)) for o in objects if o != block)]
        rest += [Literal(name, args, Literal(name, args) in true) for name, args in atoms
                 if name in predicates and (name, args) not in stated]
    return rest


def scene_task(name: str, scene: str) -> Task:
    """The task ``name``, refused unless it runs in ``scene``."""
    task = get_task(name)
    if task.scene != scene:
        raise GoalError(f"task {task.name} runs in scene {task.scene}, but this world is {scene}")
    return task


def task_goal(name: str, scene: str, objects: tuple[str, ...], state: list[Literal]) -> list[Literal]:
    task = scene_task(name, scene)
    if tuple(objects) != task.blocks:
        raise GoalError(f"task {task.name} needs blocks {', '.join(task.blocks)}; this world has {', '.join(objects)}")
    try:
        return goal_in_state(task, state)
    except ValueError as error:
        raise GoalError(str(error)) from None
