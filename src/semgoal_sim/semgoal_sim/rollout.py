"""Running sub-goals and tasks in a world: goal checks, the expert's task scripts, episode loops."""

from __future__ import annotations

import itertools
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from semgoal_core.expert import WorldView, expert_action
from semgoal_core.settling import SETTLE_STEPS, Settling, at_rest, moving_blocks
from semgoal_core.tasks import get_task
from semgoal_core.vocabulary import Literal, SemanticLayout, SubGoal
from semgoal_sim.world import FetchWorld

SUBGOAL_STEPS = 60
"""Control steps the expert gets per sub-goal (2.4 s of sim time)."""


def satisfied(layout: SemanticLayout, vector: np.ndarray, literals: list[Literal]) -> bool:
    """Whether every literal holds in the semantic ``vector``."""
    return all(bool(vector[layout.index(lit)]) == lit.value for lit in literals)


def held_blocks(world: FetchWorld, vector: np.ndarray) -> list[str]:
    """The blocks ``holding`` is true of in the world's semantic ``vector``."""
    return [b for b in world.blocks if vector[world.layout.index(Literal("holding", (b,)))]]


def settled(world: FetchWorld, literals: list[Literal]) -> bool:
    """The literals hold in ``world`` now, with the world at rest for them (:mod:`semgoal_core.settling`)."""
    snapshot = world.snapshot()
    vector = world.semantic_vector(snapshot)
    return (satisfied(world.layout, vector, literals)
            and at_rest(literals, moving_blocks(world.blocks, snapshot.block_velocities), held_blocks(world, vector)))


def _close_clique(layout: SemanticLayout, vector: np.ndarray, view: WorldView, x: str,
                  partners: list[str]) -> tuple[str, ...]:
    """The largest set of ``partners`` that are pairwise close now (a single nearest one if none are)."""
    is_close = lambda a, b: bool(vector[layout.index(Literal("close", (a, b)))])  # noqa: E731
    for size in range(len(partners), 1, -1):
        for group in itertools.combinations(partners, size):
            if all(is_close(a, b) for a, b in itertools.combinations(group, 2)):
                return group
    return (min(partners, key=lambda p: np.linalg.norm(view.positions[p] - view.positions[x])),)


def resting_on(resting: dict[str, str], top: str) -> str:
    """The block ``top`` rests on, given ``resting``: block -> the block on it."""
    return next(below for below, above in resting.items() if above == top)


def expert_next_steps(goal: list[Literal], layout: SemanticLayout, vector: np.ndarray, view: WorldView) -> list[SubGoal]:
    """The expert's next one or two sub-goals toward ``goal`` from the current state (closed loop).

    Takes the first unsatisfied literal and returns the pick and the put that achieve it: a hand-
    written high level that re-decides after every move, so slips and disturbances are repaired.
    """
    holds = lambda lit: bool(vector[layout.index(lit)]) == lit.value  # noqa: E731
    blocks = list(view.positions)
    open_literals = [lit for lit in goal if not holds(lit) and lit.name != "holding"]
    if not open_literals:
        held = [lit.args[0] for lit in goal if lit.name == "holding" and not holds(lit)]
        if not held:
            return []
        other = next(b for b in blocks if b != held[0])
        return [SubGoal("put_on_table", (held[0],)) if view.bin else SubGoal("put_near", (held[0], other))]
    literal = open_literals[0]
    a = literal.args[0]
    if literal.name == "close" and literal.value:
        scores = {b: sum(holds(lit) for lit in goal if lit.name == "close" and b in lit.args) for b in literal.args}
        x = min(literal.args, key=lambda b: (scores[b], -blocks.index(b)))
        partners = [b for lit in goal if lit.name == "close" and lit.value and x in lit.args for b in lit.args if b != x]
        put = SubGoal("put_near", (x, *_close_clique(layout, vector, view, x, partners)))
    elif literal.name == "close":
        put = SubGoal("put_away", (a, literal.args[1]))
    elif literal.name == "above":  # what stands on a goes first, from the top of its pile down
        resting = {lit.args[1]: lit.args[0] for lit in layout.true_literals(vector) if lit.name == "above"}
        top = a
        while top in resting:
            top = resting[top]
        if top != a:
            put = SubGoal("put_away", (top, resting_on(resting, top)))
        else:
            put = SubGoal("put_on", (a, literal.args[1])) if literal.value else SubGoal("put_away", (a, literal.args[1]))
    else:  # in_bin
        put = SubGoal("put_in_bin", (a,)) if literal.value else SubGoal("put_on_table", (a,))
    picked = bool(vector[layout.index(Literal("holding", (put.block,)))])
    return [put] if picked else [SubGoal("pick", (put.block,)), put]


Controller = Callable[[SubGoal, FetchWorld], np.ndarray]
"""(sub-goal, world) -> action: the expert, or a trained policy."""


def expert_controller(subgoal: SubGoal, world: FetchWorld) -> np.ndarray:
    achieved = satisfied(world.layout, world.semantic_vector(), subgoal.literals())
    return expert_action(subgoal, world.view(), achieved)


def run_subgoal(world: FetchWorld, subgoal: SubGoal, controller: Controller = expert_controller,
                max_steps: int = SUBGOAL_STEPS, confirm_steps: int = SETTLE_STEPS) -> tuple[bool, int]:
    """Act until the sub-goal's literals held at rest over ``confirm_steps`` consecutive steps (checked after
    every step, the planner's rule) or ``max_steps`` ran out."""
    literals, settling = subgoal.literals(), Settling(confirm_steps)
    for step in range(1, max_steps + 1):
        world.step(controller(subgoal, world))
        if settling.update(settled(world, literals), step):
            return True, step
    return False, max_steps


def hold_until_settled(world: FetchWorld, literals: list[Literal], max_steps: int = 4 * SETTLE_STEPS) -> tuple[bool, int]:
    """Hold the arm still until ``literals`` held at rest over ``SETTLE_STEPS`` steps (what the executive
    does once a goal's literals hold) or ``max_steps`` ran out."""
    settling = Settling()
    for step in range(1, max_steps + 1):
        world.step(np.zeros(4))
        if settling.update(settled(world, literals), step):
            return True, step
    return False, max_steps


@dataclass(frozen=True)
class EpisodeResult:
    success: bool
    steps: int
    subgoals: int


def solve(world: FetchWorld, goal: list[Literal], controller: Controller = expert_controller,
          max_steps: int = SUBGOAL_STEPS, max_subgoals: int | None = None) -> EpisodeResult:
    """The expert's high level (:func:`expert_next_steps`) drives ``world`` to ``goal``, ``controller`` doing each
    sub-goal: success when the goal holds at rest with every block on the table; at most ``max_subgoals`` (three
    turns of the hand per block when None)."""
    max_subgoals = max_subgoals or 6 * len(world.blocks)
    steps = subgoals = 0
    while subgoals < max_subgoals and not satisfied(world.layout, world.semantic_vector(), goal):
        for subgoal in expert_next_steps(goal, world.layout, world.semantic_vector(), world.view()):
            steps += run_subgoal(world, subgoal, controller, max_steps)[1]
            subgoals += 1
    success, settle_steps = hold_until_settled(world, goal)  # and, as the executive asks, every block on the table
    return EpisodeResult(success and not world.fallen_blocks(), steps + settle_steps, subgoals)


def run_task(task_name: str, seed: int, controller: Controller = expert_controller,
             max_steps: int = SUBGOAL_STEPS, max_subgoals: int | None = None) -> EpisodeResult:
    """One episode of a task, the expert choosing sub-goals (:func:`solve`)."""
    task = get_task(task_name)
    world = FetchWorld(task.scene, task.n_blocks)
    positions, goal = task.initial_state(seed)
    world.reset(positions)
    return solve(world, goal, controller, max_steps, max_subgoals)
