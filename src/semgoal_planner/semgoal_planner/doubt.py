"""Not deciding on a state the source is unsure of: a semantic state from the camera carries a confidence per
literal; while a literal the plan relies on (the goal's, the active step's) is less sure than a threshold, the
planner keeps its decisions as they stand (the arm carries on with its step), for a bounded number of control
steps; then it takes the latest state as it is. A state from the simulator (no confidences) is always sure."""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

from semgoal_core.vocabulary import Literal


def unsure_literals(literals: Sequence[Literal], confidence: Sequence[float], relied_on: Iterable[Literal],
                    threshold: float) -> list[tuple[Literal, float]]:
    """The literals of the state (with their confidences) whose atoms the plan relies on and whose confidence is
    under ``threshold`` (a non-finite one counts as 0). ValueError when the confidences do not match the literals."""
    if not confidence:
        return []
    if len(confidence) != len(literals):
        raise ValueError(f"{len(confidence)} confidences for {len(literals)} literals")
    atoms = {(lit.name, lit.args) for lit in relied_on}
    found = []
    for literal, value in zip(literals, confidence, strict=True):
        sure = value if math.isfinite(value) else 0.0
        if (literal.name, literal.args) in atoms and sure < threshold:
            found.append((literal, sure))
    return found


class Doubt:
    """How long the planner has been holding its decisions for unsure literals, and whether it still may.

    The first state of a new world (another episode, or a step count that went back) is never held: the
    planner's decisions would otherwise rest on the world before the reset (a goal planned on it, a sub-goal
    stamped with its steps), and in lockstep the new world waits for a decision on it."""

    def __init__(self, threshold: float = 0.9, wait_steps: int = 25) -> None:
        self.threshold, self.wait_steps = threshold, wait_steps
        self.since: int | None = None
        self.world: tuple[int, int] | None = None
        """(episode, step) of the last state judged."""

    def holds(self, unsure: list[tuple[Literal, float]], step: int, episode: int = 0) -> bool:
        """Whether to keep the decisions as they stand on this state (of control ``step`` of world ``episode``)."""
        new_world = self.world is None or episode != self.world[0] or step < self.world[1]
        self.world = (episode, step)
        if not unsure or new_world:
            self.since = None
            return False
        if self.since is None:
            self.since = step
        return step - self.since < self.wait_steps
