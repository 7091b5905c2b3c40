"""Planning over the semantic vocabulary: problems from semantic states, Plan2Goals, plan validation.

A scene's PDDL domain (``domains/<scene>.pddl``) has one action per sub-goal type; put near / put away
with two references are the ``*_both`` actions. Problems are built from the true literals of a semantic
state (close written in both orders; ``hand-empty`` when nothing is held) and goal literals.
Plan2Goals maps every planned action to a :class:`~semgoal_core.vocabulary.SubGoal`, whose literals
are what the policy is conditioned on.
"""

from __future__ import annotations

import functools
import itertools
from collections.abc import Collection
from dataclasses import dataclass
from pathlib import Path

from semgoal_core.settling import held_blocks_asked
from semgoal_core.vocabulary import Literal, SubGoal
from semgoal_ros.package_data import share_path
from strips_planner.deorder import deorder, transitive_reduction
from strips_planner.grounding import Operator, Task, ground
from strips_planner.pddl import Atom, Condition, Domain, Problem, parse_domain
from strips_planner.planner import PlanResult, solve_task


def domain_dir() -> Path:
    """The scenes' PDDL domains as installed: share/semgoal_planner/domains."""
    return share_path("semgoal_planner", "domains")
HAND_EMPTY = "hand-empty"
CLEAR, GROUNDED = "clear", "grounded"
"""Helpers of domains with towers, derived from ``above`` like ``hand-empty`` from ``holding``: no block on it; on
no block."""
SEARCH_SECONDS = 2.0
"""The time a search for a plan may take before the greedy search takes over (and as long again before the goal is
refused): a planner node answers within seconds, never stalls (a goal no plan reaches took minutes to prove so on the
tabletop with six blocks)."""
FALLBACK_SEARCH = "lazy"
"""The search that takes over from a shortest-plan search out of time: greedy, its plans longer but found fast."""
BRIDGE_STEPS = 4
"""Most steps a plan repair adds before a kept step (two turns of the hand); a step further away is dropped."""
ACTION_SUBGOALS: dict[str, tuple[str, int]] = {
    # PDDL action -> (sub-goal type, how many leading arguments the sub-goal keeps as its block and references)
    "pick": ("pick", 1),
    "pick_from": ("pick", 1),
    "put_near": ("put_near", 2),
    "put_near_both": ("put_near", 3),
    "put_away": ("put_away", 2),
    "put_away_both": ("put_away", 3),
    "put_on": ("put_on", 2),
    "put_on_table": ("put_on_table", 1),
    "put_in_bin": ("put_in_bin", 1),
}
KEEPS_APART = frozenset({"put_near"})
"""Actions whose arguments after the kept ones are blocks the moved block ends up not close to (the
three-block ``put_near(x, y, z)``: close to y, not to z): the sub-goal's ``apart``, sent to the actor where the
plan relies on it (:func:`_relied_upon`)."""


class PlanningError(ValueError):
    """No plan, or an invalid one; the message says why in the vocabulary's terms."""


def placed_twice(goal: list[Literal]) -> list[tuple[Literal, Literal, str]]:
    """The pairs of ``goal``'s literals that ask a block to be in two places at once: in the hand, in the bin or on
    one block (no two), with at most one block on it and none on a block held or in the bin. Every scene's actions
    keep these true, so no plan reaches such a goal, and a search would visit every state to prove it (minutes on the
    tabletop with six blocks). Each pair comes with the reason in words."""
    true = [lit for lit in goal if lit.value and lit.name in ("holding", "in_bin", "above")]
    pairs = []
    for first, second in itertools.combinations(true, 2):
        if first.args[0] == second.args[0]:
            pairs.append((first, second, "a block is in one place: in the hand, in the bin or on one block"))
        elif first.name == second.name == "above" and first.args[1] == second.args[1]:
            pairs.append((first, second, "one block at most stands on a block"))
        elif any(a.name == "above" and b.name in ("holding", "in_bin") and a.args[1] == b.args[0]
                 for a, b in ((first, second), (second, first))):
            pairs.append((first, second, "nothing stands on a block held or in the bin"))
    return pairs


@functools.cache
def load_domain(scene: str) -> Domain:
    path = domain_dir() / f"{scene}.pddl"
    if not path.exists():
        raise PlanningError(f"no PDDL domain for scene {scene!r} in {domain_dir()}")
    return parse_domain(path.read_text())


def plan2goal(op: Operator) -> SubGoal:
    """Plan2Goals for one action: ``(put_near_both red green blue)`` -> ``put_near(red,green,blue)``,
    ``(put_near red green blue)`` -> ``put_near(red,green,not blue)``."""
    kind, keep = ACTION_SUBGOALS[op.name]
    return SubGoal(kind, op.args[:keep], op.args[keep:] if op.name in KEEPS_APART else ())


def _operators_for(task: Task, step: SubGoal) -> list[Operator]:
    """The actions that achieve what ``step`` asks, those that promise least first: a step typed without the
    blocks to keep apart from (``put_away(red,green)`` in three_blocks) runs as an action that promises more."""
    asked = set(step.literals())
    promised = {op: plan2goal(op) for op in task.operators}
    matching = [op for op, goal in promised.items()
                if goal.kind == step.kind and goal.block == step.block and asked <= set(goal.literals())]
    return sorted(matching, key=lambda op: len(promised[op].literals()))


def _runs(task: Task, state: int, choices: list[list[Operator]]) -> bool:
    """Whether some choice of an action for each step (``choices``: each step's actions, a step may run as
    several, :func:`_operators_for`) runs them all from ``state`` and ends in the goal."""
    if not choices:
        return task.goal_reached(state) and not task.unsolvable_reason
    return any(op.applicable(state) and _runs(task, op.apply(state), choices[1:]) for op in choices[0])


def _relied_upon(task: Task, plan: list[Operator], index: int) -> SubGoal:
    """The sub-goal of ``plan[index]`` with the promises the rest of the plan and the goal rely on: a block to
    keep apart from (or put away from) stays only if a later step needs that or the goal asks it before a step
    sets it again. MC-3's ``put_near(a,b,c)`` keeps a from c only until c is put next to a, so the actor is
    asked for close(a,b) alone; a promise nobody relies on would only narrow where the block may go."""
    def relied(literal: Literal) -> bool:
        bits = _bits(task, literal)
        for op in plan[index + 1:]:
            if (op.pre if literal.value else op.pre_neg) & bits:
                return True
            if (op.add | op.delete) & bits:
                return False
        return bool((task.goal if literal.value else task.goal_neg) & bits)

    step = plan2goal(plan[index])
    apart = tuple(block for block in step.apart if relied(Literal("close", (step.block, block), False)))
    if step.kind != "put_away":
        return SubGoal(step.kind, step.args, apart)
    away = tuple(block for block in step.references if relied(Literal("close", (step.block, block), False)))
    return SubGoal(step.kind, (step.block, *(away or step.references)))


def _undoing(task: Task, made: Literal, broken: Literal) -> str:
    """The domain's reason ``made`` never comes true while ``broken`` holds: every action that makes it true
    undoes ``broken``, needs it false, or needs the free gripper that ``broken`` (a holding) takes; "" when
    some action does none of these (the conflict lies deeper)."""
    def sets(op: Operator, literal: Literal) -> bool:
        return bool((op.add if literal.value else op.delete) & _bits(task, literal))

    def needs_false(op: Operator) -> bool:
        return bool((op.pre_neg if broken.value else op.pre) & _bits(task, broken))

    free_gripper = _bits(task, Literal(HAND_EMPTY, ())) if broken.name == "holding" and broken.value else 0
    reasons = {}
    for op in task.operators:
        if sets(op, made):
            reasons[str(plan2goal(op))] = (f"makes {_phrase(broken.negated())}" if sets(op, broken.negated()) else
                                           f"needs {_phrase(broken.negated())}" if needs_false(op) else
                                           f"needs the free gripper that {broken} takes" if op.pre & free_gripper else "")
    if not reasons or not all(reasons.values()):
        return ""
    if len(reasons) == 1:
        (action, why), = reasons.items()
        return f"{action}, the only action that makes {_phrase(made)}, {why}"
    return f"every action that makes {_phrase(made)} ({', '.join(reasons)}) {' or '.join(dict.fromkeys(reasons.values()))}"


def _not_both(task: Task, first: Literal, second: Literal,
              known: str = "no action sequence of the scene's domain reaches both") -> str:
    """That ``first`` and ``second`` cannot hold together, with the domain's reason where its actions show it, else
    ``known``."""
    reasons = [why for made, broken in ((first, second), (second, first)) if (why := _undoing(task, made, broken))]
    return f"{first} and {second} cannot hold together: {'; '.join(reasons) or known}"


def in_sequence(count: int) -> list[tuple[int, ...]]:
    """The orderings of ``count`` steps done one after another: each after the one before."""
    return [(i - 1,) if i else () for i in range(count)]


def _turns(actions: list[Operator], hand: int) -> list[int]:
    """Each action's turn of the hand (from a pick to the step that lets go, ``hand`` the empty hand's bits),
    numbered from 0."""
    numbers, number = [], 0
    for op in actions:
        numbers.append(number)
        number += bool(op.add & hand)  # a step that lets go ends its turn
    return numbers


def _bins_first(task: Task, plan: list[Operator]) -> list[Operator]:
    """``plan`` with its turns of the hand that put a block in the bin first, as far as its orderings allow
    (:func:`strips_planner.deorder.deorder`), the rest in their order: a block picked beside a finished tower can
    knock it over, so Sort clears its blocks into the bin before it builds its tower. (Moving every other turn before
    the stacking ones too put blocks next to a tower's foot before it was built, and the stacking knocked them.) The
    hand is left out of the orderings (each turn begins and ends with it empty); an order that does not run (a turn
    begun or ended in the hand) leaves the plan as it was."""
    hand = _bits(task, Literal(HAND_EMPTY, ()))
    binning = sum(1 << index for index, atom in enumerate(task.facts) if atom.predicate == "in_bin")
    stacking = sum(1 << index for index, atom in enumerate(task.facts) if atom.predicate == "above")
    if not (binning and stacking and any(op.add & stacking for op in plan)):
        return plan
    turn, after = _turn_orderings(task, plan, hand)
    bins = {turn[i] for i, op in enumerate(plan) if op.add & binning}
    order: list[int] = []
    while len(order) < len(after):
        ready = [t for t in range(len(after)) if t not in order and after[t] <= set(order)]
        order.append(min(ready, key=lambda t: (t not in bins, t)))
    reordered = [op for t in order for op, of in zip(plan, turn, strict=True) if of == t]
    return reordered if _runs(task, task.init, [[op] for op in reordered]) else plan


def _turn_orderings(task: Task, actions: list[Operator], hand: int) -> tuple[list[int], list[set[int]]]:
    """Each action's turn of the hand (:func:`_turns`) and, per turn, the turns it must follow: where one of its
    steps relies on an effect of the other's or would undo one too early (:func:`strips_planner.deorder.deorder`,
    the hand left out: each agent has its own)."""
    turn = _turns(actions, hand)
    after: list[set[int]] = [set() for _ in range(turn[-1] + 1 if actions else 0)]
    for j, preds in enumerate(deorder(task, actions, ignore=hand)):
        after[turn[j]] |= {turn[i] for i in preds if turn[i] != turn[j]}
    return turn, after


def _bits(task: Task, literal: Literal) -> int:
    """The task's facts that ``literal``'s atom is (close in both orders), as a bit mask."""
    return sum(1 << task.facts.index(atom) for atom in _atoms(literal) if atom in task.facts)


def _phrase(literal: Literal) -> str:
    """``close(red,green) true`` / ``close(red,green) false``."""
    return f"{literal.name}({','.join(literal.args)}) {'true' if literal.value else 'false'}"


def _atoms(literal: Literal) -> list[Atom]:
    atom = Atom(literal.name, literal.args)
    return [atom, Atom(literal.name, literal.args[::-1])] if literal.name == "close" else [atom]


def _literal(atom: Atom, value: bool = True) -> Literal:
    return Literal(atom.predicate, atom.args, value)


AUTO_SEARCH = "auto"
SCENE_SEARCH = {"tabletop": "astar"}
"""Each scene's search where it is not breadth-first. Both find shortest plans; on the tabletop a tower of six took
breadth-first 270 ms and A* with LM-cut 3-5 ms."""


def scene_search(scene: str, search: str = AUTO_SEARCH) -> str:
    """``search``, or the scene's own (:data:`SCENE_SEARCH`, else breadth-first) for ``auto``."""
    return SCENE_SEARCH.get(scene, "bfs") if search == AUTO_SEARCH else search


@dataclass
class SemanticPlanner:
    """Plans for one scene from semantic states (the true literals and the objects present)."""

    scene: str
    search: str = AUTO_SEARCH
    """A search of ``strips_planner``, or ``auto``: the scene's own (:func:`scene_search`)."""
    heuristic: str | None = None
    seconds: float = SEARCH_SECONDS
    """How long the search may take before :data:`FALLBACK_SEARCH` takes over, for as long again."""

    def __post_init__(self) -> None:
        self.search = scene_search(self.scene, self.search)

    @property
    def domain(self) -> Domain:
        return load_domain(self.scene)

    def problem(self, objects: tuple[str, ...], state: list[Literal], goal: list[Literal]) -> Problem:
        init = {atom for lit in state if lit.value for atom in _atoms(lit)}
        if not any(lit.name == "holding" and lit.value for lit in state):
            init.add(Atom(HAND_EMPTY, ()))
        if CLEAR in self.domain.predicates:
            stacked = [lit.args for lit in state if lit.name == "above" and lit.value]
            held = {lit.args[0] for lit in state if lit.name == "holding" and lit.value}
            init |= {Atom(CLEAR, (block,)) for block in objects if all(below != block for _, below in stacked)}
            init |= {Atom(GROUNDED, (block,)) for block in objects
                     if block not in held and all(top != block for top, _ in stacked)}
        conditions = tuple(Condition(Atom(lit.name, lit.args), lit.value) for lit in goal)
        if not held_blocks_asked(goal):  # a goal is achieved at rest: no block left in the hand it does not ask for
            conditions += (Condition(Atom(HAND_EMPTY, ()), True),)
        problem = Problem(f"{self.scene}-now", self.domain.name, dict.fromkeys(objects, "block"), init, conditions)
        problem.minimise_cost = ":action-costs" in self.domain.requirements  # the tabletop's puts near and away
        return problem

    def task(self, objects: tuple[str, ...], state: list[Literal], goal: list[Literal]) -> Task:
        return ground(self.domain, self.problem(objects, state, goal))

    def plan(self, objects: tuple[str, ...], state: list[Literal], goal: list[Literal]) -> list[SubGoal]:
        """The sub-goals of a shortest plan (bfs) from ``state`` to ``goal``, each with the promises the rest relies
        on; PlanningError if none exists."""
        goal_text = " & ".join(map(str, goal))
        task = self.task(objects, state, goal)
        if twice := placed_twice(goal):
            raise PlanningError(f"no plan reaches {goal_text} from the current state: {_not_both(task, *twice[0])}")
        result = self.solve(task)
        if result.plan is None:
            why = result.reason if result.stats.timed_out else self.conflict(objects, state, goal) or result.reason
            raise PlanningError(f"no plan reaches {goal_text} from the current state: {why}")
        actions = _bins_first(task, list(result.plan))
        return [_relied_upon(task, actions, index) for index in range(len(actions))]

    def solve(self, task: Task) -> PlanResult:
        """The scene's search on ``task`` for :attr:`seconds`, then, where it ran out of time, the greedy
        :data:`FALLBACK_SEARCH` for as long again (a plan, not the shortest)."""
        result = solve_task(task, self.search, self.heuristic, self.seconds)
        if result.plan is None and result.stats.timed_out:
            greedy = solve_task(task, FALLBACK_SEARCH, None, self.seconds)
            if greedy.plan is not None or not greedy.stats.timed_out:
                return greedy
            greedy.reason = f"no plan found in {2 * self.seconds:g} s by a shortest-plan search and a greedy one"
            return greedy
        return result

    def conflict(self, objects: tuple[str, ...], state: list[Literal], goal: list[Literal]) -> str:
        """Why no plan reaches ``goal``, in its own literals: one no plan reaches alone, or the first pair
        that no plan reaches together ("" when every pair is reachable, or not found so in time: the conflict takes
        three or more)."""
        reaches = lambda literals: self.solve(self.task(objects, state, literals)).plan is not None  # noqa: E731
        for literal in goal:
            if not reaches([literal]):
                return f"{literal} cannot be reached in this scene"
        for first, second in itertools.combinations(goal, 2):
            if not reaches([first, second]):
                return _not_both(self.task(objects, state, []), first, second)
        return ""

    def simulate(self, objects: tuple[str, ...], state: list[Literal], goal: list[Literal],
                 steps: list[SubGoal], first_index: int | list[int] = 0, underway: Collection[int] = ()) -> None:
        """Check that ``steps`` run one after another from ``state`` and end in ``goal``; else PlanningError,
        naming a step by its index in the plan (``first_index`` for the first of ``steps``, or each one's), as
        `plan show` does. ``underway``: positions in ``steps`` of steps already making their effect (a block held
        over the one it goes on): they run without the preconditions they undo themselves (that block clear)."""
        task = self.task(objects, state, goal)
        choices = [_operators_for(task, step) for step in steps]
        for position in underway:
            choices[position] = [op._replace(pre=op.pre & ~op.delete) for op in choices[position]]
        if _runs(task, task.init, choices):
            return
        current = task.init  # no choice of actions runs the steps: say where the first choices fail
        numbers = range(first_index, first_index + len(steps)) if isinstance(first_index, int) else first_index
        for number, step, candidates in zip(numbers, steps, choices, strict=True):
            if not candidates:
                raise PlanningError(f"step {number} {step}: not an action of scene {self.scene} with these objects")
            runnable = next((op for op in candidates if op.applicable(current)), None)
            if runnable is None:
                missing = self._unmet(task, candidates[0], current)
                raise PlanningError(f"step {number} {step} cannot run: it needs {missing}, which does not hold by then")
            current = runnable.apply(current)
        if not task.goal_reached(current) or task.unsolvable_reason:
            unmet = ["an empty hand (the goal asks for no block held)" if c.atom.predicate == HAND_EMPTY
                     else str(_literal(c.atom, c.positive)) for c in self.problem(objects, state, goal).goal
                     if not self._holds(task, c, current)]
            raise PlanningError(f"the plan does not reach the goal: after the last step {', '.join(unmet)} "
                                f"{'does' if len(unmet) == 1 else 'do'} not hold")

    def repair(self, objects: tuple[str, ...], state: list[Literal], goal: list[Literal], steps: list[SubGoal],
               protected: frozenset[int] = frozenset()) -> tuple[list[int | SubGoal], list[tuple[int, str]]]:
        """Mend ``steps`` (the plan's rest) for ``state``: keep every step that can still run, in its order, plan
        only what is missing before a kept step (what it needs and no longer has) and after the last one (what the
        goal needs), then leave out each turn of the hand (a pick up to the step that lets go) the goal is reached
        without, unless it has a step of ``protected`` (a person's) whose literals do not hold yet. Returns the new
        rest, a kept step as its index in ``steps`` and a planned one as a sub-goal, and the steps dropped, each
        with why. PlanningError when the goal cannot be reached after the kept steps (re-plan from scratch then)."""
        task = self.task(objects, state, goal)
        current, rest, dropped = task.init, [], []
        for index, step in enumerate(steps):
            actions = _operators_for(task, step)
            if not actions:
                dropped.append((index, f"not an action of scene {self.scene} with these objects"))
                continue
            if all(self._holds_literal(task, literal, current) for literal in step.literals()):
                dropped.append((index, "its literals hold already"))
                continue
            runnable = next((op for op in actions if op.applicable(current)), None)
            bridge: list[Operator] = []
            if runnable is None:
                bridge = self._bridge(task, current, actions[0]) or []
                for op in bridge:
                    current = op.apply(current)
                runnable = actions[0] if actions[0].applicable(current) else None
            if runnable is None:
                dropped.append((index, f"it needs {self._unmet(task, actions[0], current)}, which no short plan brings about"))
                continue
            rest += [(plan2goal(op), op) for op in bridge] + [(index, runnable)]
            current = runnable.apply(current)
        tail = self.solve(Task(task.facts, current, task.goal, task.goal_neg, task.operators))
        if tail.plan is None or task.unsolvable_reason:
            raise PlanningError(f"the goal cannot be reached after the steps kept: {tail.reason or task.unsolvable_reason}")
        rest += [(plan2goal(op), op) for op in tail.plan]
        wanted = {i for i in protected if i < len(steps)
                  and not all(self._holds_literal(task, lit, task.init) for lit in steps[i].literals())}
        rest, unneeded = self._without_unneeded_turns(task, rest, wanted)
        return [item for item, _ in rest], dropped + [(i, "the goal is reached without its turn") for i in unneeded]

    @staticmethod
    def _without_unneeded_turns(task: Task, rest: list[tuple[int | SubGoal, Operator]], wanted: set[int]
                                ) -> tuple[list[tuple[int | SubGoal, Operator]], list[int]]:
        """``rest`` less each turn of the hand it reaches the goal without (first to last), but for turns with a
        ``wanted`` step; and the kept steps' indices so left out."""
        ids = _turns([op for _, op in rest], _bits(task, Literal(HAND_EMPTY, ())))
        turns = [[item for item, t in zip(rest, ids, strict=True) if t == number] for number in dict.fromkeys(ids)]
        unneeded: list[int] = []
        for candidate in list(turns):
            if any(isinstance(item, int) and item in wanted for item, _ in candidate):
                continue
            trial = [item for t in turns if t is not candidate for item in t]
            state = task.init
            for _, op in trial:
                if not op.applicable(state):
                    break
                state = op.apply(state)
            else:
                if task.goal_reached(state):
                    turns.remove(candidate)
                    unneeded += [item for item, _ in candidate if isinstance(item, int)]
        return [item for t in turns for item in t], unneeded

    def _bridge(self, task: Task, state: int, action: Operator) -> list[Operator] | None:
        """A shortest plan from ``state`` to where ``action`` runs, of at most :data:`BRIDGE_STEPS` steps; None if
        there is none."""
        result = self.solve(Task(task.facts, state, action.pre, action.pre_neg, task.operators))
        return result.plan if result.plan is not None and len(result.plan) <= BRIDGE_STEPS else None

    @staticmethod
    def _holds_literal(task: Task, literal: Literal, state: int) -> bool:
        bits = _bits(task, literal)
        return bool(state & bits) == literal.value if bits else not literal.value

    def orderings(self, objects: tuple[str, ...], goal: list[Literal], steps: list[SubGoal]) -> list[tuple[int, ...]]:
        """For each of ``steps``, the earlier steps it must follow. The plan is cut into turns of a hand, from a
        pick to the step that lets go; a turn follows another where one of its steps relies on an effect of the
        other's or would undo one too early (:func:`strips_planner.deorder.deorder`, the hand left out: each agent
        has its own). Within a turn the steps keep their order. So binning red and binning green are independent,
        while Swap-2's second block is picked only once the first is off it. Each step runs as the action that
        promises least of those it names; a step that names none follows the one before."""
        named = {block for literal in goal for block in literal.args} | {b for step in steps for b in step.args}
        task = self.task(tuple(dict.fromkeys((*objects, *sorted(named)))), [], goal)  # a world that lost a block too
        actions = [next(iter(_operators_for(task, step)), None) for step in steps]
        if None in actions:
            return in_sequence(len(steps))
        turn, turn_after = _turn_orderings(task, actions, _bits(task, Literal(HAND_EMPTY, ())))
        after: list[set[int]] = [{i - 1} if i and turn[i - 1] == turn[i] else set() for i in range(len(steps))]
        first = {t: turn.index(t) for t in set(turn)}
        last = {t: len(turn) - 1 - turn[::-1].index(t) for t in set(turn)}
        for t, before in enumerate(turn_after):  # a turn starts after the whole of each turn it follows
            after[first[t]] |= {last[u] for u in before}
        return transitive_reduction(after)

    @staticmethod
    def _holds(task: Task, condition: Condition, state: int) -> bool:
        true = condition.atom in task.facts and bool(state >> task.facts.index(condition.atom) & 1)
        return true == condition.positive

    @staticmethod
    def _unmet(task: Task, op: Operator, state: int) -> str:
        needed = [_literal(f) for i, f in enumerate(task.facts) if op.pre >> i & 1 and not state >> i & 1]
        needed += [_literal(f, False) for i, f in enumerate(task.facts) if op.pre_neg >> i & 1 and state >> i & 1]
        text = ["a free gripper" if lit.name == HAND_EMPTY else str(lit) for lit in needed]
        return " and ".join(text) or "a state the plan does not reach"
