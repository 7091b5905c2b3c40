"""Task episodes in one process, for evaluation: the hierarchy and the two flat baselines.

The hierarchical episode composes the same cores the nodes wrap (no ROS): the planner node's
:class:`Executive`, the policy node's :class:`SubgoalController` and the sim node's :class:`FetchWorld`,
stepped as the graph steps them in lockstep: the executive sees every new semantic state and every
control step, and the policy follows the sub-goal decided on the step before (one step of decision
latency, :func:`~semgoal_core.lockstep.lockstep_subgoal`). So an in-process episode and
one through the graph (``./semgoal eval --via-ros``) follow the same rules.

Every agent gets the same start (the task's seeded sampler), the same step budget and the same success
test: the task's goal literals hold with the world at rest (:mod:`semgoal_core.settling`) over
``SETTLE_STEPS`` control steps. Each outcome also records the first step at which the literals held at
all, the first-step rule, so the two can be compared on the same episodes.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol

import numpy as np

from semgoal_bringup.experiments.training import make_env
from semgoal_core.arms import robot_names
from semgoal_core.geometry import table_edge
from semgoal_core.lockstep import lockstep_subgoal
from semgoal_core.names import PlanStatus, is_person
from semgoal_core.settling import Settling, held_blocks_asked, moving_blocks
from semgoal_core.tasks import TASK_STEP_BUDGET, Task, get_task
from semgoal_core.vocabulary import SubGoal
from semgoal_planner.executive import Executive, Observation
from semgoal_planner.semantic import SemanticPlanner
from semgoal_policy import actor as actor_io
from semgoal_policy.agents import get_agent
from semgoal_policy.controller import Idle, SubgoalController
from semgoal_sim.rollout import settled
from semgoal_sim.world import FetchWorld


@dataclass(frozen=True)
class Fall:
    """The first block that left the table in an episode: where, when, and during (or after) which robot steps."""

    block: str
    position: tuple[float, float]
    """Its centre (x, y, m) at the first control step it was seen off the table (below the table top): past the edge it
    went over, as far as it flew."""
    step: int
    during: tuple[str, ...]
    """Each robot step at work then, with its agent (``pick(blue) by robot``)."""
    after: tuple[str, ...] = ()
    """Where none was (a block falls for a few steps, and a step it knocked from may have ended or been dropped by a
    re-plan meanwhile): the robot steps last at work before."""

    def __str__(self) -> str:
        x, y = self.position
        when = (f", during {' and '.join(self.during)}" if self.during else
                f", after {' and '.join(self.after)}" if self.after else "")
        return (f"{self.block} went over the table's {table_edge(np.array(self.position))} edge at ({x:.2f}, {y:.2f}) "
                f"at control step {self.step}{when}")


def robot_steps_at_work(executive: Executive) -> tuple[tuple[str, SubGoal], ...]:
    """Each robot step at work now: its agent and its sub-goal (worded only where a block falls)."""
    return tuple((who, executive.steps[index].subgoal) for who, index in sorted(executive.working.items())
                 if not is_person(who))


def _worded(steps: tuple[tuple[str, SubGoal], ...]) -> tuple[str, ...]:
    return tuple(f"{subgoal} by {who}" for who, subgoal in steps)


@dataclass(frozen=True)
class Outcome:
    task: str
    seed: int
    success: bool
    steps: int
    replans: int = 0
    first_held: int | None = None
    """The first control step at which the goal's literals held, at rest or not (None: never)."""
    linger_holds: bool | None = None
    """After a success and ``linger`` more control steps of the idle arm: whether the goal still held at rest
    (None: not checked)."""
    fell_off: bool = False
    """A block ended the episode off the table."""
    overlap: int = 0
    """Control steps over which two agents worked at once (a scripted person or a second arm beside the robot)."""
    arm_contacts: int = 0
    """Physics substeps over which two robot arms touched."""
    fall: Fall | None = None
    """The first block that left the table, where the episode watched for one (the hierarchy in process)."""
    unmet: tuple[str, ...] = ()
    """The goal's literals that did not hold at the end of a missed episode (the hierarchy in process; for goals one
    after the other, the one that failed)."""

    @property
    def first_step_success(self) -> bool:
        """Success by the first-step rule: the literals held at some step, moving blocks or not."""
        return self.first_held is not None

    @property
    def why(self) -> str:
        """Why an episode is no success, in the at-rest rule's words."""
        if self.fell_off:
            return "a block ended off the table" + (f": {self.fall}" if self.fall else "")
        unmet = f"{', '.join(self.unmet)} did not hold at the end" if self.unmet else ""
        if self.first_held is not None:
            return f"the goal held at step {self.first_held}, but " + (unmet or "not at rest at the end")
        return f"the goal never held in {self.steps} control steps ({self.replans} re-plans)" + (f": {unmet}" if unmet else "")


def observe(world: FetchWorld) -> Observation:
    """The semantic state as the planner node receives it: present objects, every literal's value and
    the blocks that fell off the table."""
    snapshot = world.snapshot()
    vector = world.semantic_vector(snapshot)
    present = [name for name, here in zip(world.layout.objects, world.present, strict=True) if here]
    return Observation(tuple(present), world.layout.decode(vector), world.step_count,
                       tuple(world.fallen_blocks(snapshot)),
                       moving_blocks(world.blocks, snapshot.block_velocities))


class Person(Protocol):
    """Someone working beside the robot in an episode (:class:`~semgoal_bringup.experiments.together.ScriptedPerson`)."""

    def claim(self, executive: Executive) -> None: ...

    def act(self, executive: Executive, world: FetchWorld) -> None: ...


class HierarchicalAgent:
    """Planner executive + one scene's sub-goal actor, on the benchmark's tasks or on any goal."""

    def __init__(self, scene: str, actor_dir: Path, arms: int = 1, sleep: bool = True) -> None:
        self.scene = scene
        self.sleep = sleep
        """Blocks at rest sleep in its worlds (:func:`semgoal_sim.scene.build_model`)."""
        self.controllers = [SubgoalController(scene, actor_dir, arm=arm, shared=arms > 1) for arm in range(arms)]
        """One per arm, each driving the same actor in its arm's frame (:class:`semgoal_core.arms.ArmFrame`)."""
        self.controller = self.controllers[0]
        self.robots = robot_names(arms)
        self._worlds: dict[tuple[str, int], FetchWorld] = {}
        """One world per task (or family) and block count, kept between its episodes."""

    def run(self, task_name: str, seed: int, budget: int = TASK_STEP_BUDGET, linger: int = 0) -> Outcome:
        task = _scene_task(task_name, self.scene)
        return self.run_goal(task.initial_state(seed)[0], task.name, seed, budget, label=task.name, linger=linger)

    def run_goal(self, positions: np.ndarray, goal: str, seed: int, budget: int = TASK_STEP_BUDGET,
                 label: str = "", linger: int = 0) -> Outcome:
        """An episode from blocks at ``positions`` (the scene's first ``len(positions)`` objects) to ``goal`` (a
        task, literals or a sentence), as the planner node runs it; a goal the planner refuses fails at step 0."""
        return self.run_goals(positions, (goal,), seed, budget, label, linger)

    def run_goals(self, positions: np.ndarray, goals: Sequence[str], seed: int, budget: int = TASK_STEP_BUDGET,
                  label: str = "", linger: int = 0, person: Person | None = None, concurrent: bool = True,
                  on_step: Callable[[FetchWorld], None] | None = None) -> Outcome:
        """:meth:`run_goal` for goals one after the other, each from where the one before left the world and with
        ``budget`` steps of its own; the episode succeeds when every goal did. ``first_held``: of the last goal.
        ``linger``: after a success, this many control steps more of the arm with no goal, as the policy node runs
        it, then whether the last goal still holds at rest (``linger_holds``). ``person``: claims steps of each plan
        and does them in the world, while the arm makes room without a step of its own, as the policy node does;
        ``concurrent``: the executive lets them work at once (else in turns; the robot alone takes the same steps).
        With two arms each runs its own steps, and a step is done by whichever arm is free first. ``on_step``: called
        with the world after each control step (a camera recording it)."""
        key = (label, len(positions))
        if key not in self._worlds:
            self._worlds[key] = FetchWorld(self.scene, len(positions), len(self.robots), self.sleep)
        world = self._worlds[key]
        world.reset(positions)
        success, replans, first_held, executive, overlap, fall, recent = True, 0, None, None, 0, None, ()
        decided_before: dict[str, list | None] = {}  # a goal's first step follows the decision before it, as the
        for goal in goals:  # policy node does
            executive = Executive(SemanticPlanner(self.scene), concurrent=concurrent, robots=self.robots,
                                  reach=world.reach)
            executive.observe(observe(world))
            planned, _ = executive.set_goal(goal, step_budget=budget)
            if planned and person is not None:
                person.claim(executive)
            first_held = None
            while planned and executive.status == PlanStatus.EXECUTING:
                decided_now = {robot: (executive.active_for(robot).subgoal.literals() if executive.active_for(robot)
                                       else ([] if executive.settling else None)) for robot in self.robots}
                followed = [lockstep_subgoal(decided_before.get(robot), decided_now[robot]) for robot in self.robots]
                if all(literals is None for literals in followed) and person is None:
                    break  # a human step: nobody acts in an evaluation
                actions = []
                for arm, (controller, literals) in enumerate(zip(self.controllers, followed, strict=True)):
                    if literals is None:  # others work: the arm makes room
                        controller.set_subgoal([], Idle.MAKE_ROOM)
                    else:
                        controller.set_subgoal(literals, keep=held_blocks_asked(executive.goal))  # settling: retreat
                    actions.append(controller.act(world.observation(arm=arm), (seed, world.step_count)))
                world.step(np.array(actions))
                if on_step is not None:
                    on_step(world)
                if person is not None:
                    person.act(executive, world)
                overlap += len(executive.working) > 1
                decided_before = decided_now
                executive.tick(world.step_count)
                executive.observe(observe(world))
                at_work = robot_steps_at_work(executive)
                if fall is None and executive.observation.fallen:
                    block = executive.observation.fallen[0]
                    x, y = world.snapshot().block_positions[world.blocks.index(block), :2]
                    fall = Fall(block, (round(float(x), 3), round(float(y), 3)), world.step_count, _worded(at_work),
                                () if at_work else _worded(recent))
                recent = at_work or recent
                if first_held is None and executive.observation.holds(executive.goal):
                    first_held = world.step_count
            replans += executive.replans
            success = success and executive.status == "succeeded"
            if not success:
                break
        steps = world.step_count
        linger_holds = self._linger(world, executive.goal, seed, linger) if success and linger and executive else None
        unmet = () if success or executive is None else tuple(
            str(literal) for literal in executive.goal if not executive.observation.holds([literal]))
        return Outcome(label or " -> ".join(goals), seed, success, steps, replans, first_held, linger_holds,
                       bool(world.fallen_blocks()), overlap, world.arm_contacts, fall, unmet)

    def _linger(self, world: FetchWorld, goal: list, seed: int, steps: int) -> bool:
        """Run the arm with no step (what the policy node does once a goal is done: it retreats, keeping what the
        goal asks to hold) for ``steps`` control steps; whether ``goal`` then holds with the world at rest."""
        self.controller.set_subgoal([], keep=held_blocks_asked(goal))
        for _ in range(steps):
            world.step(self.controller.act(world.observation(), (seed, world.step_count)))
        return settled(world, goal)


class FlatAgent:
    """A flat baseline's exported actor (``flat-semantic`` or ``flat-continuous``) on whole tasks."""

    def __init__(self, agent: str, scene: str, actor_dir: Path) -> None:
        self.scene = scene
        self.actor = actor_io.load(actor_dir, scene)[0]
        self.env = make_env(agent, scene)

    def run(self, task_name: str, seed: int, budget: int = TASK_STEP_BUDGET) -> Outcome:
        task = _scene_task(task_name, self.scene)
        obs, _ = self.env.reset(seed=seed, options={"kind": task.name, "start_seed": seed})
        settling, first_held = Settling(), None
        for step in range(1, budget + 1):
            action = np.clip(self.actor.act(obs["observation"], obs["desired_goal"]), -1.0, 1.0)
            obs, _, _, _, info = self.env.step(action)
            if first_held is None and info["goal_holds"]:
                first_held = step
            if settling.update(info["is_success"], step):  # as the executive: only with every block on the table
                fell_off = self._fell_off()
                return Outcome(task.name, seed, not fell_off, step, first_held=first_held, fell_off=fell_off)
        return Outcome(task.name, seed, False, budget, first_held=first_held, fell_off=self._fell_off())

    def _fell_off(self) -> bool:
        return bool(self.env.world.fallen_blocks())


def _scene_task(task_name: str, scene: str) -> Task:
    task = get_task(task_name)
    if task.scene != scene:
        raise ValueError(f"task {task.name} is set in {task.scene}; this agent's actor is for {scene}")
    return task


def make_agent(agent: str, scene: str, actor_dir: Path | None = None, arms: int = 1,
               sleep: bool = True) -> HierarchicalAgent | FlatAgent:
    """The runner for ``agent`` on ``scene`` (the hierarchical one with ``arms`` arms, its blocks at rest sleeping
    unless ``sleep`` is False); ``actor_dir`` defaults to the shipped actor."""
    spec = get_agent(agent)  # KeyError with the valid names
    actor_dir = actor_dir or actor_io.models_dir() / spec.model_name(scene)
    if agent != "hierarchical":
        return FlatAgent(agent, scene, actor_dir)
    return HierarchicalAgent(scene, actor_dir, arms, sleep)
