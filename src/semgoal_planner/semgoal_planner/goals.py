"""Goal requests: a task name (``DC-3``), a conjunction of literals (``in_bin(red) & not close(red,green)``)
or a plain-English sentence (``put the red block in the bin``, :mod:`semgoal_planner.english`).

Parsing checks every literal against the scene's vocabulary and the objects present, and refuses
contradictions, so a planner only ever sees goals it can state.
"""

from __future__ import annotations

import re

from semgoal_core.consistency import ContradictionError, check_consistent
from semgoal_core.tasks import TASKS, Task, get_task, goal_form, goal_in_state
from semgoal_core.vocabulary import LAYOUTS, Literal, VocabularyError, parse_literal
from semgoal_planner.english import MAX_GOAL_CHARS, LanguageError, parse_english

_SEPARATORS = re.compile(r"\s*(?:&&?|∧|\band\b|,(?![^()]*\)))\s*", re.IGNORECASE)


class GoalError(ValueError):
    """A goal that cannot be stated in the scene: the message says what is wrong and what is valid."""


def split_literals(text: str) -> list[str]:
    """``a(x) & not b(x,y), c(y)`` -> the literal texts (commas inside parentheses are arguments)."""
    parts = [p.strip() for p in _SEPARATORS.split(text.strip())]
    if not text.strip() or any(not p for p in parts):
        raise GoalError(f"cannot read goal {text!r}: expected a task ({', '.join(TASKS)}) or literals joined by '&'")
    return parts


def parse_goal(text: str, scene: str, objects: tuple[str, ...], state: list[Literal]) -> list[Literal]:
    """The goal literals for ``text`` in a world of ``scene`` with ``objects`` present, now in ``state``:
    a task, literals, or else a sentence."""
    if len(text) > MAX_GOAL_CHARS:
        raise GoalError(f"the goal is {len(text)} characters long; at most {MAX_GOAL_CHARS} are read")
    form = goal_form(text)
    if form == "task":
        return task_goal(text, scene, objects, state)
    if form == "text":
        try:
            return parse_english(text, scene, objects)
        except LanguageError as error:
            raise GoalError(f"{error} (or give a task, {', '.join(TASKS)}, or literals such as in_bin(red))") from None
    layout = LAYOUTS[scene]
    try:
        goal = [layout.validate(parse_literal(part), objects) for part in split_literals(text)]
        check_consistent(goal)
    except (VocabularyError, ContradictionError) as error:
        raise GoalError(str(error)) from None
    return list(dict.fromkeys(goal))


def check_goal_text(text: str, scene: str) -> None:
    """Refuse a goal that no world of ``scene`` could state (a task of another scene, an unknown predicate
    or block, a wrong arity, a contradiction) before any state is known; the blocks present are checked
    once one is."""
    if goal_form(text) == "task":
        scene_task(text, scene)
    else:
        parse_goal(text, scene, LAYOUTS[scene].objects, [])


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
