"""The plan under execution: operator edits, the execution monitor and re-planning. No ROS here.

``observe`` takes every new semantic state, ``tick`` every control step. The goal, and the active step,
are achieved when their literals hold with the world at rest (:mod:`semgoal_core.settling`) over
``settle_steps`` control steps in a row. While the goal's literals hold but the world has not settled
yet, the plan is ``settling``: no step is active and the policy holds the arm still. A robot step that
stalls for ``stall_steps`` control steps, or a plan that the observed state contradicts for
``contradiction_steps`` in a row (a block moved by hand, a dropped block), is re-planned from the
observed state, at most ``max_replans`` times; then the goal fails with the reason. A step assigned to
a human is waited for (its literals observed at rest) up to ``human_steps`` control steps, then the goal
fails with that reason. A person's pick is their own hand's, which no predicate observes: it is done as it starts,
and the turn's put is confirmed by what it puts where (``claim`` gives a person a whole turn; ``assign`` a put the
robot's hand hands over). Every edit is checked by simulating the remaining steps from the observed state (see
:meth:`SemanticPlanner.simulate`); a refused edit leaves the plan exactly as it was.

``concurrent`` (the default): every agent (the robot arms, each person) works at once on its first ready step, one
whose predecessors (:meth:`Executive.orderings`) are done, while two agents never work on the same block and an
agent's hand takes one turn at a time; a person's drop into the bin is refused while an arm puts into it
(:meth:`Executive.region_holder`), and two arms share it, kept apart by the sim's guard. In turns, one step is active
at a time, in plan order.
"""

from __future__ import annotations

import contextlib
import copy
from collections.abc import Callable
from dataclasses import dataclass, field

from semgoal_core.names import FINISHED, UNDER_WAY, Assignee, PlanStatus, StepStatus, agent, is_person
from semgoal_core.settling import SETTLE_STEPS, Settling, at_rest, held_blocks_asked
from semgoal_core.vocabulary import (
    LAYOUTS,
    ONE_AGENT_REGIONS,
    SCENES,
    SYMMETRIC_PREDICATES,
    Literal,
    SubGoal,
    VocabularyError,
    parse_literal,
    parse_subgoal,
)
from semgoal_planner.goals import Goal, GoalError, read_goal
from semgoal_planner.semantic import PlanningError, SemanticPlanner, in_sequence

EDIT_OPS = ("insert", "remove", "move", "replace", "approve", "pause", "resume", "replan", "assign", "claim")
OVER = (StepStatus.DONE, StepStatus.SKIPPED)


@dataclass
class PlanStep:
    subgoal: SubGoal
    status: str = StepStatus.PENDING
    """pending, active, done, failed or skipped."""
    assignee: str = Assignee.ROBOT
    edited: bool = False
    """A person's: inserted, replaced, moved or assigned by an edit. A plan repair keeps it while it can run."""
    started: int = 0
    """The control step it became active (its stall and person clocks)."""
    confirmation: Settling = field(default_factory=Settling, compare=False, repr=False)
    """Counts the control steps over which a robot step's literals held at rest."""


@dataclass
class Observation:
    objects: tuple[str, ...]
    literals: list[Literal]
    """Every literal of the scene with its truth value now."""
    step: int
    fallen: tuple[str, ...] = ()
    """Blocks that fell off the table: no robot step can move them again."""
    moving: tuple[str, ...] = ()
    """Blocks not at rest (:func:`semgoal_core.settling.moving_blocks`)."""

    def holds(self, literals: list[Literal]) -> bool:
        """Whether every one of ``literals`` has its value now (a symmetric predicate's in either argument order:
        a step's ``close(blue,green)`` is the state's ``close(green,blue)``)."""
        values = {(lit.name, lit.args): lit.value for lit in self.literals}
        values |= {(lit.name, lit.args[::-1]): lit.value for lit in self.literals if lit.name in SYMMETRIC_PREDICATES}
        return all(values.get((lit.name, lit.args), False) == lit.value for lit in literals)

    def settled(self, literals: list[Literal], blocks: tuple[str, ...] | None = None) -> bool:
        """The literals hold and the world is at rest for them (:func:`semgoal_core.settling.at_rest`); ``blocks``:
        only these need be at rest (a step while other agents work on others)."""
        moving, held = self.moving, self.held
        if blocks is not None:
            moving, held = set(moving) & set(blocks), set(held) & set(blocks)
        return self.holds(literals) and at_rest(literals, moving, held)

    def reached(self, literals: list[Literal]) -> bool:
        """The literals hold and the hand holds no block they do not ask for: what is left is to wait for rest."""
        return self.holds(literals) and not set(self.held) - held_blocks_asked(literals)

    @property
    def held(self) -> list[str]:
        return [lit.args[0] for lit in self.literals if lit.name == "holding" and lit.value]

    @property
    def true_literals(self) -> list[Literal]:
        return [lit for lit in self.literals if lit.value]


def blocks_of(subgoal: SubGoal) -> tuple[str, ...]:
    """The blocks a step works on: the one it moves, its references, those it keeps apart from."""
    return (*subgoal.args, *subgoal.apart)


def turns_of(steps: list[PlanStep]) -> list[int]:
    """Each step's turn of a hand, numbered from 0: from a pick to the step that lets go."""
    numbers, number = [], 0
    for step in steps:
        numbers.append(number)
        number += step.subgoal.kind != "pick"
    return numbers


def open_turns(steps: list[PlanStep], turns: list[int]) -> dict[int, list[int]]:
    """The turns begun and not over, each with its steps' indices: a hand holds its block, or a person carries it."""
    members: dict[int, list[int]] = {}
    for index, turn in enumerate(turns):
        members.setdefault(turn, []).append(index)
    return {turn: indices for turn, indices in members.items()
            if steps[indices[0]].status in (StepStatus.DONE, StepStatus.ACTIVE) and steps[indices[-1]].status not in OVER}


def _making_its_effect(step: PlanStep, obs: Observation) -> bool:
    """An active step whose literals to make true hold already, before the rest does (a block held over the one it
    goes on is above it while the hand still holds it): what it undoes of its own preconditions is its doing."""
    made = [literal for literal in step.subgoal.literals() if literal.value]
    return step.status == StepStatus.ACTIVE and bool(made) and obs.holds(made)


def rest_of(steps: list[PlanStep], obs: Observation) -> list[int]:
    """The indices of the steps left, in the order one hand would run them from ``obs``: not done, less active ones
    whose literals hold, with the pick of a turn a person carries (their hand, which no predicate observes); the
    turns a robot's hand holds (its pick done, or holding) come first, so two arms' blocks in hand are put down first."""
    turns = turns_of(steps)
    begun = open_turns(steps, turns)
    picked = {turn: steps[busy[0]].assignee for turn, busy in begun.items() if steps[busy[0]].subgoal.kind == "pick"
              and (steps[busy[0]].status == StepStatus.DONE or obs.holds(steps[busy[0]].subgoal.literals()))}
    rest = [i for i, step in enumerate(steps) if step.status not in OVER
            and not (step.status == StepStatus.ACTIVE and obs.holds(step.subgoal.literals()))]
    rest += [begun[turn][0] for turn, who in picked.items() if is_person(who) and any(turns[i] == turn for i in rest)]
    return sorted(rest, key=lambda i: (is_person(picked.get(turns[i], Assignee.HUMAN)), i))


@dataclass
class Executive:
    planner: SemanticPlanner
    stall_steps: int = 150
    """Control steps a robot step may take before it is re-planned (the policy needs about 20 to 40)."""
    human_steps: int = 3000
    """Control steps a person's step may take (2 min at 25 Hz) before the goal fails with that reason."""
    contradiction_steps: int = 10
    """Control steps the observed state must contradict the plan before a re-plan (debounces releases)."""
    max_replans: int = 10
    """Re-plans before the goal fails; the step budget bounds an episode anyway. More than 10 gained nothing on
    the desk tasks' validation starts (``docs/history.md``)."""
    settle_steps: int = SETTLE_STEPS
    """The goal, and a robot step, are achieved once their literals held at rest over this many consecutive
    control steps."""
    require_approval: bool = False
    """New plans (and re-plans) wait for an operator's approve before they execute."""
    concurrent: bool = True
    """Every agent works on its first ready step at once; else one step at a time, in plan order (in turns). The robot
    alone takes the same steps either way."""
    robots: tuple[str, ...] = (Assignee.ROBOT,)
    """The robot arms (:func:`semgoal_core.arms.robot_names`). A step of ``robot`` goes to the first free arm of those
    that reach its block (:attr:`reach`), which then takes its whole turn; one of ``robot:2`` waits for that arm."""
    reach: Callable[[str], tuple[str, ...]] | None = None
    """block -> the arms that may take a step on it: the hand it is in, else the nearer first (where the world says
    where blocks and hands are); None: every arm, in :attr:`robots`' order."""

    goal: list[Literal] = field(default_factory=list)
    goal_text: str = ""
    steps: list[PlanStep] = field(default_factory=list)
    current: int = 0
    status: str = PlanStatus.EMPTY
    revision: int = 0
    steps_revision: int = 0
    """The revision at which the steps last changed (a plan, a re-plan, an edit): an edit made against an earlier one
    names steps that may be others now; one made since, while steps were done, names the same steps."""
    replans: int = 0
    message: str = ""
    observation: Observation | None = None
    contradicted_since: int | None = None
    consistency: tuple[tuple, PlanningError | None] | None = field(default=None, repr=False, compare=False)
    """The last consistency check: what it depended on (state, steps, goal) and the contradiction it found, so a
    control step that changed none of them does not ground and run the plan again."""
    goal_settling: Settling = field(init=False)
    """Counts the control steps over which the goal's literals held at rest."""
    last_tick: int = 0
    """The latest control step seen by :meth:`tick`: world states reach the planner before the semantic
    states the predicates derive from them, so confirmation counts up to here."""
    goal_steps: int = 0
    """The world's control steps since the goal was set, summed tick by tick while it is under way: a world reset
    to step 0 under it (or a planner restart) neither loses nor double-counts any."""
    step_budget: int = 0
    """Control steps (``goal_steps``) the goal may take before it fails (0: no limit)."""
    events: list[str] = field(default_factory=list)
    """Readable log lines since the last :meth:`drain_events` (the node logs them)."""
    blind: str = ""
    """Why the plan is paused for want of a trustworthy state (:meth:`pause_blind`); "" when it is not."""

    _orderings: tuple[tuple, list[tuple[int, ...]]] = field(default=((), []), init=False, repr=False)
    """The plan's orderings and what they were worked out for (its steps and objects)."""

    def __post_init__(self) -> None:
        self.goal_settling = Settling(self.settle_steps)

    # -- goals ---------------------------------------------------------------------------------------
    def set_goal(self, goal: Goal | str, step_budget: int = 0) -> tuple[bool, str]:
        """Plan for a goal from the observed state; on failure the previous plan stays. The goal fails
        once ``step_budget`` control steps (0: no limit) are spent without it holding.

        ``goal`` is read where it entered (:func:`~semgoal_planner.goals.read_goal`; the planner node reads its
        requests); text is read here, for callers in this process, against the world observed."""
        obs = self.observation
        scene = self.planner.scene
        try:
            if isinstance(goal, str):
                goal = read_goal(goal, scene, obs.objects if obs else LAYOUTS[scene].objects)
            if obs is None:
                return False, "no semantic state observed yet: start the sim and predicates nodes first"
            literals = goal.instantiate(scene, obs.objects, obs.true_literals)
            steps = self.planner.plan(obs.objects, obs.true_literals, literals)
        except (GoalError, PlanningError) as error:
            return False, str(error)
        self.goal, self.goal_text = literals, " & ".join(map(str, literals))
        self.replans, self.goal_steps, self.step_budget = 0, 0, max(0, step_budget)
        meaning = "" if goal.said == self.goal_text else f" (the goal: {self.goal_text})"
        self._install([PlanStep(s) for s in steps], f"planned {len(steps)} step(s) for {goal.said}{meaning}")
        self._advance()
        return True, self.message

    def cancel(self, reason: str = "cancelled by the operator") -> None:
        if self.status in UNDER_WAY:
            self._finish(PlanStatus.FAILED, reason)

    # -- the journal ---------------------------------------------------------------------------------
    def snapshot(self) -> dict:
        """What a planner started again needs to carry on (:mod:`semgoal_planner.journal`), as plain data."""
        return {"goal": [str(lit) for lit in self.goal], "goal_text": self.goal_text,
                "steps": [{"subgoal": str(s.subgoal), "status": str(s.status), "assignee": str(s.assignee),
                           "edited": s.edited} for s in self.steps],
                "current": self.current, "status": str(self.status), "revision": self.revision,
                "steps_revision": self.steps_revision,
                "replans": self.replans, "message": self.message, "goal_steps": self.goal_steps,
                "step_budget": self.step_budget, "last_tick": self.last_tick}

    def restore(self, snapshot: dict, message: str) -> None:
        """Take up a :meth:`snapshot` (of the same world): the active steps are checked against the world again
        on the next observation, and their clocks start from the last control step the snapshot saw. Raises
        ValueError for a snapshot that does not fit this scene."""
        scene = SCENES[self.planner.scene]
        try:
            steps = [PlanStep(parse_subgoal(s["subgoal"], scene), StepStatus(s["status"]), agent(s["assignee"]),
                              bool(s.get("edited", False))) for s in snapshot["steps"]]
            goal = [parse_literal(text) for text in snapshot["goal"]]
            status = PlanStatus(snapshot["status"])
        except (KeyError, TypeError, ValueError) as error:
            raise ValueError(f"the journal's plan does not fit scene {scene.name}: {error}") from None
        self.goal, self.goal_text, self.steps, self.status = goal, str(snapshot["goal_text"]), steps, status
        for name in ("current", "replans", "goal_steps", "step_budget", "last_tick"):
            setattr(self, name, int(snapshot[name]))
        self.revision = int(snapshot["revision"])
        self.steps_revision = int(snapshot.get("steps_revision", self.revision))
        for step in self.steps:  # an active step's clocks start again from here, its confirmation too
            step.started, step.confirmation = self.last_tick, Settling(self.settle_steps)
        self.goal_settling.reset()
        self.contradicted_since = None
        self.message = message
        self._emit(message)

    def continue_revisions(self, revision: int) -> None:
        """Number the next plan after ``revision`` (a journal that was not taken up): an edit made on an old
        plan's numbers then never applies to a new plan."""
        self.revision = max(self.revision, revision)

    # -- monitoring ----------------------------------------------------------------------------------
    def observe(self, observation: Observation) -> None:
        changed = (self.observation is None or observation.literals != self.observation.literals
                   or observation.fallen != self.observation.fallen or observation.moving != self.observation.moving)
        reset = self.observation is not None and observation.objects != self.observation.objects
        self.observation = observation
        if reset and self.status in UNDER_WAY:  # a world reset to other blocks: the plan names blocks gone
            self._finish(PlanStatus.FAILED, f"the world now has {', '.join(observation.objects)}: the goal {self.goal_text} "
                                   "was for another world; send it again")
            return
        if (changed or self._confirming) and self.status in UNDER_WAY:
            self._advance()
            if self.status == PlanStatus.EXECUTING:
                self._check_consistency()
        if (self.step_budget and self.status in UNDER_WAY
                and self.goal_steps >= self.step_budget):
            self._finish(PlanStatus.FAILED, f"the goal did not hold within its budget of {self.step_budget} control steps")

    def tick(self, step: int) -> None:
        """A control step happened (from the world state stream): the goal's step count, stall and contradiction
        clocks. A step before the last is a world reset to step 0: its steps count from there."""
        if self.status in UNDER_WAY:
            self.goal_steps += step - self.last_tick if step >= self.last_tick else step
        self.last_tick = step
        if self.observation is not None:
            self.observation.step = max(self.observation.step, step)
        if self.status == PlanStatus.EXECUTING and self._confirming:
            self._advance()  # may finish the plan, re-plan, or fail the goal
        if self.status != PlanStatus.EXECUTING or self.current >= len(self.steps) or self.settling:
            return
        if self.contradicted_since is not None and step - self.contradicted_since >= self.contradiction_steps:
            self.replan("the observed state contradicts the plan")
            return
        for index in self.working.values():
            active = self.steps[index]
            if not is_person(active.assignee) and step - active.started > self.stall_steps:
                self.replan(f"step {index} {active.subgoal} made no progress in {self.stall_steps} control steps")
                return
            if is_person(active.assignee) and step - active.started > self.human_steps:
                whose = "a person's" if active.assignee == Assignee.HUMAN else f"{active.assignee}'s"
                self._finish(PlanStatus.FAILED, f"step {index} {active.subgoal} was {whose} and was not done within "
                                       f"{self.human_steps} control steps; assign it to the robot or send the goal "
                                       "again")
                return

    @property
    def _confirming(self) -> bool:
        return self.goal_settling.pending or any(step.confirmation.pending for step in self.steps)

    @property
    def settling(self) -> bool:
        """The goal's literals hold and the plan waits for them to hold at rest: the arm holds still."""
        obs = self.observation
        return self.status == PlanStatus.EXECUTING and obs is not None and obs.reached(self.goal)

    @property
    def working(self) -> dict[str, int]:
        """Each agent at work now, and the index of its active step."""
        return {step.assignee: index for index, step in enumerate(self.steps) if step.status == StepStatus.ACTIVE}

    @property
    def active(self) -> PlanStep | None:
        """The step the first arm's policy should execute now: :meth:`active_for`."""
        return self.active_for(Assignee.ROBOT)

    def active_for(self, robot: str) -> PlanStep | None:
        """The step ``robot``'s policy should execute now; None while paused, waiting, settling, done or on a
        person's step."""
        index = self.working.get(robot)
        if self.status != PlanStatus.EXECUTING or index is None or self.settling:
            return None
        return self.steps[index]

    def region_holder(self, region: str) -> tuple[str, int] | None:
        """The agent at ``region`` (``bin``) now, with its step's index: the robot's active step that puts there; a
        person's drop there waits for it. None while no robot is."""
        return next(((who, index) for who, index in self.working.items()
                     if not is_person(who) and ONE_AGENT_REGIONS.get(self.steps[index].subgoal.kind) == region), None)

    def orderings(self) -> list[tuple[int, ...]]:
        """For each step, the earlier steps it must follow (:meth:`SemanticPlanner.orderings`): what a person or a
        second agent may do at the same time. In sequence where the world's blocks are not known yet."""
        steps = [step.subgoal for step in self.steps]
        objects = self.observation.objects if self.observation is not None else None
        key = (objects, tuple(steps), tuple(self.goal))
        if self._orderings[0] != key:
            orderings = in_sequence(len(steps))
            with contextlib.suppress(PlanningError, KeyError, ValueError):  # an ordering never stops the planner
                orderings = self.planner.orderings(objects, self.goal, steps) if objects is not None else orderings
            self._orderings = (key, orderings)
        return self._orderings[1]

    def _advance(self) -> None:
        obs = self.observation
        if obs is None or self.status in FINISHED:
            return
        if self.goal_settling.update(obs.settled(self.goal), obs.step, max(obs.step, self.last_tick)):
            for step in self.steps:
                if step.status not in OVER:
                    step.status = StepStatus.DONE if obs.holds(step.subgoal.literals()) else StepStatus.SKIPPED
            self.current = len(self.steps)
            if obs.fallen:  # what is done stays done: a goal holds only with every block on the table
                self._finish(PlanStatus.FAILED, f"goal {self.goal_text} holds at rest, but {' and '.join(obs.fallen)} "
                                                f"fell off the table: put it back and send the goal again")
            else:
                self._finish(PlanStatus.SUCCEEDED, f"goal {self.goal_text} holds at rest")
            return
        if self.settling:
            return
        while True:
            candidates = list(self.working.values())
            if self.status != PlanStatus.EXECUTING and self.current < len(self.steps):
                candidates.append(self.current)  # paused or awaiting approval: the world may do the next step
            finished = [index for index in candidates if self._achieved(self.steps[index], obs)]
            for index in finished:
                self.steps[index].status = StepStatus.DONE
                self._emit(f"step {index} {self.steps[index].subgoal} done")
                self.contradicted_since = None
                self.revision += 1
            self.current = next((i for i, s in enumerate(self.steps) if s.status not in OVER), len(self.steps))
            started = self._start_ready() if self.status == PlanStatus.EXECUTING else False
            if not finished and not started:
                break
        if self.current >= len(self.steps):
            self.replan("all steps are done but the goal does not hold")
        self._check_reach()

    def _start_ready(self) -> bool:
        """Start the first ready step (its predecessors over) whose agent is free and that waits for nothing
        (:meth:`_waits`); a person's pick is done as it starts. Whether one started: called until none does."""
        obs, turns, working = self.observation, turns_of(self.steps), self.working
        begun = open_turns(self.steps, turns)
        after = self.orderings() if self.concurrent else in_sequence(len(self.steps))
        ready = [i for i, step in enumerate(self.steps)
                 if step.status == StepStatus.PENDING and all(self.steps[j].status in OVER for j in after[i])]
        # an agent's steps it is the first choice for before those it is a second choice for (the nearer arm's)
        choices = sorted((rank, i, who) for i in ready for rank, who in enumerate(self._doers(i, turns, begun)))
        free = ((i, who) for _, i, who in choices
                if who not in working and not self._waits(i, who, turns, begun, working))
        index, who = next(free, (None, None))
        if index is None:
            return False
        step, generic = self.steps[index], self.steps[index].assignee
        if who != generic:  # a robot's step taken by another arm than the first: that arm's whole turn
            for i, turn in enumerate(turns):
                if turn == turns[index] and self.steps[i].status not in OVER and self.steps[i].assignee == generic:
                    self.steps[i].assignee = who
        step.status, step.started = StepStatus.ACTIVE, obs.step
        step.confirmation = Settling(self.settle_steps)
        if is_person(step.assignee) and step.subgoal.kind == "pick":
            step.status = StepStatus.DONE
            self._emit(f"step {index} {step.subgoal}: {step.assignee} takes {step.subgoal.block} up themselves")
        else:
            self._emit(f"step {index} {step.subgoal} started ({step.assignee})")
        return True

    def _doers(self, index: int, turns: list[int], begun: dict[int, list[int]]) -> tuple[str, ...]:
        """Who may do step ``index``: its agent; for a robot's step with several arms, those :attr:`reach` names for its
        block (the hand it is in, else the nearer first: after a re-plan the done picks of two hands interleave, so
        the plan's turns no longer say whose hand a block is in); else the arm that holds its turn once begun."""
        step = self.steps[index]
        if step.assignee != Assignee.ROBOT:
            return (step.assignee,)
        if self.reach and len(self.robots) > 1:
            return self.reach(step.subgoal.block)
        if turns[index] in begun:
            return (self.steps[begun[turns[index]][0]].assignee,)
        return self.robots

    def _waits(self, index: int, who: str, turns: list[int], begun: dict[int, list[int]], working: dict[str, int]) -> str:
        """Why the ready step ``index`` may not start yet for agent ``who`` ("" when it may): another agent works on
        one of its blocks, or has one in hand, or its hand is in another turn (``begun``: :func:`open_turns`)."""
        step = self.steps[index]
        for other, busy in begun.items():
            hand = self.steps[busy[0]].assignee
            if turns[index] != other and step.subgoal.kind == "pick" and hand == who:
                return f"{hand}'s hand is busy with step {busy[0]}"
            carried = self.steps[busy[0]].subgoal.block
            if turns[index] != other and hand != who and carried in blocks_of(step.subgoal):
                return f"{hand} has {carried} in hand"
        for worker, busy in working.items():
            if set(blocks_of(self.steps[busy].subgoal)) & set(blocks_of(step.subgoal)):
                return f"{worker} works on a block of it"
        return ""

    def _check_reach(self) -> None:
        """Fail at once when the active robot step needs a block that fell off the table: no re-plan can
        bring it back (a person can put it back and send the goal again), so the budget is not spent on it."""
        obs = self.observation
        if obs is None or not obs.fallen:
            return
        for robot in self.robots:
            step = self.active_for(robot)
            lost = [block for block in step.subgoal.args if block in obs.fallen] if step else []
            if lost:
                self._finish(PlanStatus.FAILED, f"{' and '.join(lost)} fell off the table, out of the arm's reach: "
                                       f"step {self.working[robot]} {step.subgoal} cannot be done")
                return

    def _achieved(self, step: PlanStep, obs: Observation) -> bool:
        """The step's literals hold at rest, for ``settle_steps`` control steps in a row if the robot runs it
        (a grasp that only brushes the block, or a block let go in mid-air, does not count yet)."""
        # the world at large is not at rest while someone else works in it, or while another arm holds its block
        others = len(self.working) > 1 or len(self.robots) > 1
        holds = obs.settled(step.subgoal.literals(), blocks_of(step.subgoal) if others else None)
        if holds and (is_person(step.assignee) or self.status != PlanStatus.EXECUTING):
            return True
        return step.confirmation.update(holds, obs.step, max(obs.step, self.last_tick))

    def _check_consistency(self) -> None:
        """The rest of the plan still runs from the observed state; a step whose literals already hold (still
        settling or being confirmed) is as good as done: the steps after it are checked from here."""
        obs = self.observation
        depends_on = (obs.objects, tuple(obs.literals), tuple(self.goal),
                      tuple((step.subgoal, step.status, step.assignee) for step in self.steps))
        if self.consistency is None or self.consistency[0] != depends_on:
            try:
                self._simulate(self.steps)
                self.consistency = (depends_on, None)
            except PlanningError as error:
                self.consistency = (depends_on, error)
        error = self.consistency[1]
        if error is None:
            self.contradicted_since = None
        elif self.contradicted_since is None:
            self.contradicted_since = obs.step
            self._emit(f"observed state contradicts the plan ({error}); re-planning unless it clears "
                       f"within {self.contradiction_steps} steps")

    # -- re-planning ---------------------------------------------------------------------------------
    def replan(self, reason: str, by_operator: bool = False) -> tuple[bool, str]:
        """Where a person edited the plan's rest, mend it for the observed state (:meth:`SemanticPlanner.repair`:
        what still runs is kept, the person's steps, assignments and order with it, and only what is missing is
        planned); else, where the repair cannot reach the goal, or the operator asks for it, plan again from
        scratch: the robot's own steps are best planned anew, the shortest plan from where the world is. The
        monitor's re-plans spend ``max_replans``; an operator's re-plan spends none of it, and a paused plan stays
        paused."""
        obs = self.observation
        if self.status in FINISHED or obs is None:
            return False, "nothing to re-plan: no goal is being executed"
        if not by_operator and self.replans >= self.max_replans:
            self._finish(PlanStatus.FAILED, f"{reason}; gave up after {self.replans} re-plans")
            return False, self.message
        if not by_operator and any(step.edited for step in self._undone()):
            try:
                return self._repair(reason)
            except PlanningError as error:
                reason = f"{reason}; from scratch, as the repair could not: {error}"
        try:
            steps = self.planner.plan(obs.objects, obs.true_literals, self.goal)
        except PlanningError as error:
            if by_operator:  # the plan stays as it was
                return False, f"re-planning failed: {error}"
            self._finish(PlanStatus.FAILED, f"{reason}; re-planning failed: {error}")
            return False, self.message
        # a step the operator gave a person stays theirs when the new plan has it too
        people = {s.subgoal: s.assignee for s in self._undone() if is_person(s.assignee)}
        new = [PlanStep(s, assignee=people.get(s, Assignee.ROBOT)) for s in steps]
        return self._take_up(new, f"re-planned ({reason})", counted=not by_operator)

    def _repair(self, reason: str) -> tuple[bool, str]:
        obs, rest = self.observation, self._undone()
        mended, dropped = self.planner.repair(obs.objects, obs.true_literals, self.goal, [s.subgoal for s in rest],
                                              frozenset(i for i, step in enumerate(rest) if step.edited))
        kept = [rest[item] for item in mended if isinstance(item, int)]
        for step in kept:
            step.status = StepStatus.PENDING
        new = [rest[item] if isinstance(item, int) else PlanStep(item) for item in mended]
        dropped_text = "; ".join(f"dropped {rest[i].subgoal} ({why})" for i, why in sorted(dropped))
        message = (f"repaired ({reason}): kept {len(kept)} of {len(rest)} steps, planned {len(new) - len(kept)}"
                   + (f"; {dropped_text}" if dropped_text else ""))
        return self._take_up(new, message, counted=True)

    def _take_up(self, rest: list[PlanStep], message: str, counted: bool) -> tuple[bool, str]:
        """Follow the done steps with ``rest`` (a re-plan, ``counted`` against ``max_replans``, or a repair); a
        paused plan stays paused."""
        self.replans += counted
        paused = self.status == PlanStatus.PAUSED
        done = [s for s in self.steps if s.status == StepStatus.DONE]
        self._install(done + rest, message, keep=len(done))
        if paused:
            self.status = PlanStatus.PAUSED
        self._advance()
        return True, self.message

    def _install(self, steps: list[PlanStep], message: str, keep: int = 0) -> None:
        self.steps, self.current = steps, keep
        self.goal_settling.reset()
        self.status = PlanStatus.AWAITING_APPROVAL if self.require_approval else PlanStatus.EXECUTING
        self.contradicted_since = None
        self._changed(message, steps=True)

    def _finish(self, status: str, message: str) -> None:
        self.status = status
        if status == PlanStatus.FAILED:
            failed = list(self.working.values()) or ([self.current] if self.current < len(self.steps) else [])
            for index in failed:
                self.steps[index].status = StepStatus.FAILED
        self._changed(message)

    def _changed(self, message: str, steps: bool = False) -> None:
        """A new revision of the plan (``steps``: its steps changed, not only their progress)."""
        self.revision += 1
        if steps:
            self.steps_revision = self.revision
        self.message = message
        self._emit(message)

    def _emit(self, line: str) -> None:
        self.events.append(line)

    def drain_events(self) -> list[str]:
        events, self.events = self.events, []
        return events

    # -- operator edits ------------------------------------------------------------------------------
    def edit(self, op: str, index: int = 0, to_index: int = 0, action: str = "", revision: int = 0) -> tuple[bool, str]:
        """Apply one operator edit; refuse it (plan unchanged) with the reason when it is invalid.

        ``revision`` (non-zero) is the plan revision the operator saw: step numbers name other steps once a re-plan
        or an edit has changed the steps, so an edit made against a revision before that is refused. Steps done
        since change no step's number: a person's claim is not refused because the robot finished a step."""
        op = op.strip().lower()
        if op not in EDIT_OPS:
            return False, f"unknown edit {op!r}; valid: {', '.join(EDIT_OPS)}"
        if self.status in FINISHED:
            return False, f"no plan to edit (plan is {self.status}); send a goal first"
        if revision and not self.steps_revision <= revision <= self.revision:
            return False, (f"{op} refused: it was made against plan revision {revision}, and the plan's steps are "
                           f"those of revision {self.steps_revision} on (now {self.revision}); look at it again "
                           "(plan show)")
        if op == "approve":
            if self.status != PlanStatus.AWAITING_APPROVAL:
                return False, f"nothing to approve: the plan is {self.status}"
            self.status = PlanStatus.EXECUTING
            self._changed("plan approved")
            self._advance()
            return True, self.message
        if op in ("pause", "resume"):
            return self._pause(op == "pause")
        if op == "replan":
            return self.replan("asked by the operator", by_operator=True)
        return self._edit_steps(op, index, to_index, action)

    def pause_blind(self, reason: str) -> None:
        """Pause an executing plan while the state it would act on cannot be trusted (``reason``: no camera
        frame, say); :meth:`resume_sighted` carries on. A plan paused by the operator, or not executing, is
        left as it is."""
        if self.status == PlanStatus.EXECUTING and not self.blind:
            self.blind = reason
            self._pause(True, f"paused: {reason}")

    def resume_sighted(self) -> None:
        """A trustworthy state again: resume the plan :meth:`pause_blind` paused."""
        if self.blind:
            self.blind = ""
            if self.status == PlanStatus.PAUSED:
                self._pause(False, "resumed: the state can be trusted again")

    def _pause(self, pause: bool, message: str = "") -> tuple[bool, str]:
        if pause and self.status != PlanStatus.EXECUTING:
            return False, f"cannot pause: the plan is {self.status}"
        if not pause and self.status != PlanStatus.PAUSED:
            return False, f"cannot resume: the plan is {self.status}"
        if not pause and self.blind and not message:
            return False, f"cannot resume: {self.blind}; the plan resumes by itself once the state can be trusted"
        self.status = PlanStatus.PAUSED if pause else PlanStatus.EXECUTING
        if not pause and self.observation:
            for index in self.working.values():
                self.steps[index].started = self.observation.step
        self._changed(message or ("paused" if pause else "resumed"))
        if not pause:
            self._advance()
        return True, self.message

    def _edit_steps(self, op: str, index: int, to_index: int, action: str) -> tuple[bool, str]:
        steps = copy.deepcopy(self.steps)
        doers = {id(new): old.assignee for new, old in zip(steps, self.steps, strict=True)}
        pending = [i for i in range(self.current, len(steps)) if steps[i].status not in OVER]
        try:
            if op == "insert":
                if not self.current <= index <= len(steps):
                    raise ValueError(f"insert position {index} is outside {self.current}..{len(steps)} (done steps stay)")
                steps.insert(index, PlanStep(self._subgoal(action), edited=True))
            elif index not in pending:
                raise ValueError(f"step {index} is not a pending step (pending: {self._range_text()})")
            elif op == "remove":
                del steps[index]
            elif op == "move":
                if to_index not in pending:
                    raise ValueError(f"target position {to_index} is not a pending position ({self._range_text()})")
                steps.insert(to_index, steps.pop(index))
                steps[to_index].edited = True
            elif op == "replace":
                steps[index] = PlanStep(self._subgoal(action), assignee=steps[index].assignee, edited=True)
            elif op == "assign":
                who = agent(action)
                if not is_person(who) and who != Assignee.ROBOT and who not in self.robots:
                    raise ValueError(f"there is no {who} at this table: the arms are {', '.join(self.robots)}")
                if is_person(who) and steps[index].subgoal.kind == "pick":
                    raise ValueError(f"step {index} {steps[index].subgoal} asks the robot's hand to hold a block, which "
                                     "a person cannot do for it: give the person the put after it, or let them claim "
                                     "the step to do its whole turn with their own hands")
                steps[index].assignee, steps[index].edited = who, True
            elif op == "claim":
                self._claim(steps, index, agent(action or Assignee.HUMAN))
            self._simulate(steps)
        except (ValueError, PlanningError) as error:
            return False, f"{op} refused: {error}"
        self.steps = steps
        after = self.orderings() if self.concurrent else in_sequence(len(steps))
        for i, step in enumerate(steps):  # a step whose agent or predecessors changed is started anew
            if step.status == StepStatus.ACTIVE and (doers.get(id(step)) != step.assignee
                                                     or any(steps[j].status not in OVER for j in after[i])):
                step.status = StepStatus.PENDING
        self._changed(f"{op} applied", steps=True)
        self._advance()
        return True, self.message

    @staticmethod
    def _claim(steps: list[PlanStep], index: int, who: str) -> None:
        """Give ``who`` every step of ``index``'s turn not begun yet (a person's pick is their own hand's); ValueError
        when another agent is at one of them."""
        turns = turns_of(steps)
        turn = [i for i, t in enumerate(turns) if t == turns[index]]
        busy = [i for i in turn if steps[i].status == StepStatus.ACTIVE and steps[i].assignee != who]
        if busy:
            raise ValueError(f"step {busy[0]} {steps[busy[0]].subgoal} of that turn is {steps[busy[0]].assignee}'s "
                             "under way")
        for i in turn:
            if steps[i].status not in OVER:
                steps[i].assignee, steps[i].edited = who, True

    def _subgoal(self, action: str) -> SubGoal:
        try:
            return parse_subgoal(action, SCENES[self.planner.scene])
        except VocabularyError as error:
            raise ValueError(str(error)) from None

    def _range_text(self) -> str:
        return f"{self.current}..{len(self.steps) - 1}" if self.current < len(self.steps) else "none"

    def _simulate(self, steps: list[PlanStep]) -> None:
        """Check that ``steps`` (a plan, its done steps with it) run on from the observed state to the goal."""
        obs = self.observation
        rest = rest_of(steps, obs)
        self.planner.simulate(obs.objects, obs.true_literals, self.goal, [steps[i].subgoal for i in rest], rest,
                              [k for k, i in enumerate(rest) if _making_its_effect(steps[i], obs)])

    def _undone(self) -> list[PlanStep]:
        return [step for step in self.steps if step.status not in OVER]
