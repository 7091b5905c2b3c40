"""The plan under execution: operator edits, the execution monitor and re-planning. No ROS here.

``observe`` takes every new semantic state, ``tick`` every control step. The goal, and the active step,
are achieved when their literals hold with the world at rest (:mod:`semgoal_core.settling`) over
``settle_steps`` control steps in a row. While the goal's literals hold but the world has not settled
yet, the plan is ``settling``: no step is active and the policy holds the arm still. A robot step that
stalls for ``stall_steps`` control steps, or a plan that the observed state contradicts for
``contradiction_steps`` in a row (a block moved by hand, a dropped block), is re-planned from the
observed state, at most ``max_replans`` times; then the goal fails with the reason. A step assigned to
a human is waited for (its literals observed at rest) up to ``human_steps`` control steps, then the goal
fails with that reason; a pick is never a person's step. Every edit is checked by
simulating the remaining steps from the observed state (see :meth:`SemanticPlanner.simulate`); a refused
edit leaves the plan exactly as it was.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field

from semgoal_core.names import FINISHED, UNDER_WAY, Assignee, PlanStatus, StepStatus
from semgoal_core.settling import SETTLE_STEPS, Settling, at_rest, held_blocks_asked
from semgoal_core.vocabulary import LAYOUTS, SCENES, SYMMETRIC_PREDICATES, Literal, SubGoal, VocabularyError, parse_literal, parse_subgoal
from semgoal_planner.goals import Goal, GoalError, read_goal
from semgoal_planner.semantic import PlanningError, SemanticPlanner, in_sequence

EDIT_OPS = ("insert", "remove", "move", "replace", "approve", "pause", "resume", "replan", "assign")


@dataclass
class PlanStep:
    subgoal: SubGoal
    status: str = StepStatus.PENDING
    """pending, active, done, failed or skipped."""
    assignee: str = Assignee.ROBOT
    edited: bool = False
    """A person's: inserted, replaced, moved or assigned by an edit. A plan repair keeps it while it can run."""


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

    def settled(self, literals: list[Literal]) -> bool:
        """The literals hold and the world is at rest for them (:func:`semgoal_core.settling.at_rest`)."""
        return self.holds(literals) and at_rest(literals, self.moving, self.held)

    def reached(self, literals: list[Literal]) -> bool:
        """The literals hold and the hand holds no block they do not ask for: what is left is to wait for rest."""
        return self.holds(literals) and not set(self.held) - held_blocks_asked(literals)

    @property
    def held(self) -> list[str]:
        return [lit.args[0] for lit in self.literals if lit.name == "holding" and lit.value]

    @property
    def true_literals(self) -> list[Literal]:
        return [lit for lit in self.literals if lit.value]


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

    goal: list[Literal] = field(default_factory=list)
    goal_text: str = ""
    steps: list[PlanStep] = field(default_factory=list)
    current: int = 0
    status: str = PlanStatus.EMPTY
    revision: int = 0
    replans: int = 0
    message: str = ""
    observation: Observation | None = None
    step_started: int = 0
    contradicted_since: int | None = None
    confirmation: Settling = field(init=False)
    """Counts the control steps over which the active step's literals held at rest."""
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

    def __post_init__(self) -> None:
        self.confirmation = Settling(self.settle_steps)
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
                "replans": self.replans, "message": self.message, "goal_steps": self.goal_steps,
                "step_budget": self.step_budget, "step_started": self.step_started, "last_tick": self.last_tick}

    def restore(self, snapshot: dict, message: str) -> None:
        """Take up a :meth:`snapshot` (of the same world): the active step is checked against the world again
        on the next observation, and its clocks start from there. Raises ValueError for a snapshot that does not
        fit this scene."""
        scene = SCENES[self.planner.scene]
        try:
            steps = [PlanStep(parse_subgoal(s["subgoal"], scene), StepStatus(s["status"]), Assignee(s["assignee"]),
                              bool(s.get("edited", False))) for s in snapshot["steps"]]
            goal = [parse_literal(text) for text in snapshot["goal"]]
            status = PlanStatus(snapshot["status"])
        except (KeyError, TypeError, ValueError) as error:
            raise ValueError(f"the journal's plan does not fit scene {scene.name}: {error}") from None
        self.goal, self.goal_text, self.steps, self.status = goal, str(snapshot["goal_text"]), steps, status
        for name in ("current", "replans", "goal_steps", "step_budget", "step_started", "last_tick"):
            setattr(self, name, int(snapshot[name]))
        self.revision = int(snapshot["revision"])
        if self.current < len(self.steps) and self.steps[self.current].status == StepStatus.ACTIVE:
            self.steps[self.current].status = StepStatus.PENDING  # re-activated once the world says it is not done
        self.confirmation.reset()
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
        confirming = self.confirmation.pending or self.goal_settling.pending
        if (changed or confirming) and self.status in UNDER_WAY:
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
        if self.status == PlanStatus.EXECUTING and (self.confirmation.pending or self.goal_settling.pending):
            self._advance()  # may finish the plan, re-plan, or fail the goal
        if self.status != PlanStatus.EXECUTING or self.current >= len(self.steps) or self.settling:
            return
        if self.contradicted_since is not None and step - self.contradicted_since >= self.contradiction_steps:
            self.replan("the observed state contradicts the plan")
        elif self.steps[self.current].assignee == Assignee.ROBOT and step - self.step_started > self.stall_steps:
            self.replan(f"step {self.current} {self.steps[self.current].subgoal} made no progress in "
                        f"{self.stall_steps} control steps")
        elif self.steps[self.current].assignee == Assignee.HUMAN and step - self.step_started > self.human_steps:
            self._finish(PlanStatus.FAILED, f"step {self.current} {self.steps[self.current].subgoal} was a person's and was "
                                   f"not done within {self.human_steps} control steps; assign it to the robot "
                                   "or send the goal again")

    @property
    def settling(self) -> bool:
        """The goal's literals hold and the plan waits for them to hold at rest: the arm holds still."""
        obs = self.observation
        return self.status == PlanStatus.EXECUTING and obs is not None and obs.reached(self.goal)

    @property
    def active(self) -> PlanStep | None:
        """The step the policy should execute now; None while paused, waiting, settling, done or on a human step."""
        if self.status != PlanStatus.EXECUTING or self.current >= len(self.steps) or self.settling:
            return None
        step = self.steps[self.current]
        return step if step.assignee == Assignee.ROBOT else None

    def orderings(self) -> list[tuple[int, ...]]:
        """For each step, the earlier steps it must follow (:meth:`SemanticPlanner.orderings`): what a person or a
        second agent may do at the same time. In sequence where the world's blocks are not known yet."""
        steps = [step.subgoal for step in self.steps]
        if self.observation is not None:
            try:
                return self.planner.orderings(self.observation.objects, self.goal, steps)
            except (PlanningError, KeyError, ValueError):  # what only shows the plan never stops the planner
                pass
        return in_sequence(len(steps))

    def _advance(self) -> None:
        obs = self.observation
        if obs is None or self.status in FINISHED:
            return
        if self.goal_settling.update(obs.settled(self.goal), obs.step, max(obs.step, self.last_tick)):
            for step in self.steps[self.current:]:
                step.status = StepStatus.DONE if obs.holds(step.subgoal.literals()) else StepStatus.SKIPPED
            self.current = len(self.steps)
            self._finish(PlanStatus.SUCCEEDED, f"goal {self.goal_text} holds at rest")
            return
        if self.settling:
            return
        while self.current < len(self.steps) and self._achieved(self.steps[self.current], obs):
            self.steps[self.current].status = StepStatus.DONE
            self._emit(f"step {self.current} {self.steps[self.current].subgoal} done")
            self.current += 1
            self.step_started, self.contradicted_since = obs.step, None
            self.revision += 1
        if self.current >= len(self.steps):
            self.replan("all steps are done but the goal does not hold")
        elif self.status == PlanStatus.EXECUTING and self.steps[self.current].status != StepStatus.ACTIVE:
            self.steps[self.current].status = StepStatus.ACTIVE
            self.step_started = obs.step
            self._emit(f"step {self.current} {self.steps[self.current].subgoal} started "
                       f"({self.steps[self.current].assignee})")
        self._check_reach()

    def _check_reach(self) -> None:
        """Fail at once when the active robot step needs a block that fell off the table: no re-plan can
        bring it back (a person can put it back and send the goal again), so the budget is not spent on it."""
        step, obs = self.active, self.observation
        if step is None or obs is None or not obs.fallen:
            return
        lost = [block for block in step.subgoal.args if block in obs.fallen]
        if lost:
            self._finish(PlanStatus.FAILED, f"{' and '.join(lost)} fell off the table, out of the arm's reach: step "
                                   f"{self.current} {step.subgoal} cannot be done")

    def _achieved(self, step: PlanStep, obs: Observation) -> bool:
        """The step's literals hold at rest, for ``settle_steps`` control steps in a row if the robot runs it
        (a grasp that only brushes the block, or a block let go in mid-air, does not count yet)."""
        holds = obs.settled(step.subgoal.literals())
        if holds and (step.assignee == Assignee.HUMAN or self.status != PlanStatus.EXECUTING):
            return True
        done = self.confirmation.update(holds, obs.step, max(obs.step, self.last_tick))
        if done:
            self.confirmation.reset()
        return done

    def _check_consistency(self) -> None:
        """The rest of the plan still runs from the observed state; a step whose literals already hold (still
        settling or being confirmed) is as good as done: the steps after it are checked from here."""
        obs = self.observation
        first = self.current
        if first < len(self.steps) and obs.holds(self.steps[first].subgoal.literals()):
            first += 1
        try:
            self._simulate([s.subgoal for s in self.steps[first:]])
            self.contradicted_since = None
        except PlanningError as error:
            if self.contradicted_since is None:
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
        if not by_operator and any(step.edited for step in self.steps[self.current:]):
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
        human = {s.subgoal for s in self.steps[self.current:] if s.assignee == Assignee.HUMAN}
        new = [PlanStep(s, assignee=Assignee.HUMAN if s in human else Assignee.ROBOT) for s in steps]
        return self._take_up(new, f"re-planned ({reason})", counted=not by_operator)

    def _repair(self, reason: str) -> tuple[bool, str]:
        obs, rest = self.observation, self.steps[self.current:]
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
        done = [s for s in self.steps[: self.current] if s.status == StepStatus.DONE]
        self._install(done + rest, message, keep=len(done))
        if paused:
            self.status = PlanStatus.PAUSED
        self._advance()
        return True, self.message

    def _install(self, steps: list[PlanStep], message: str, keep: int = 0) -> None:
        self.steps, self.current = steps, keep
        self.confirmation.reset()
        self.goal_settling.reset()
        self.status = PlanStatus.AWAITING_APPROVAL if self.require_approval else PlanStatus.EXECUTING
        self.contradicted_since = None
        self.step_started = self.observation.step if self.observation else 0
        self._changed(message)

    def _finish(self, status: str, message: str) -> None:
        self.status = status
        if status == PlanStatus.FAILED and self.current < len(self.steps):
            self.steps[self.current].status = StepStatus.FAILED
        self._changed(message)

    def _changed(self, message: str) -> None:
        self.revision += 1
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

        ``revision`` (non-zero) is the plan revision the operator saw: step numbers name other steps
        once a re-plan has rebuilt the plan, so an edit made against an older revision is refused."""
        op = op.strip().lower()
        if op not in EDIT_OPS:
            return False, f"unknown edit {op!r}; valid: {', '.join(EDIT_OPS)}"
        if self.status in FINISHED:
            return False, f"no plan to edit (plan is {self.status}); send a goal first"
        if revision and revision != self.revision:
            return False, (f"{op} refused: it was made against plan revision {revision}, and the plan is at "
                           f"revision {self.revision} now; look at it again (plan show)")
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
            self.step_started = self.observation.step
        self._changed(message or ("paused" if pause else "resumed"))
        if not pause:
            self._advance()
        return True, self.message

    def _edit_steps(self, op: str, index: int, to_index: int, action: str) -> tuple[bool, str]:
        steps = copy.deepcopy(self.steps)
        pending = range(self.current, len(steps))
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
                who = action.strip().lower()
                if who not in list(Assignee):
                    raise ValueError(f"assign takes {' or '.join(map(repr, map(str, Assignee)))}, got {action!r}")
                if who == Assignee.HUMAN and steps[index].subgoal.kind == "pick":
                    raise ValueError(f"step {index} {steps[index].subgoal} asks the robot's hand to hold a block, which "
                                     "a person cannot do for it: give the person the put after it")
                steps[index].assignee, steps[index].edited = Assignee(who), True
            self._simulate([s.subgoal for s in steps[self.current:]])
        except (ValueError, PlanningError) as error:
            return False, f"{op} refused: {error}"
        for i, step in enumerate(steps):
            if i >= self.current:
                step.status = StepStatus.PENDING
        self.steps = steps
        self._changed(f"{op} applied")
        self._advance()
        return True, self.message

    def _subgoal(self, action: str) -> SubGoal:
        try:
            return parse_subgoal(action, SCENES[self.planner.scene])
        except VocabularyError as error:
            raise ValueError(str(error)) from None

    def _range_text(self) -> str:
        return f"{self.current}..{len(self.steps) - 1}" if self.current < len(self.steps) else "none"

    def _simulate(self, steps: list[SubGoal]) -> None:
        obs = self.observation
        self.planner.simulate(obs.objects, obs.true_literals, self.goal, steps, first_index=self.current)
