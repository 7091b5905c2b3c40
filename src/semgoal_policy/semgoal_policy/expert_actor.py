"""The scripted expert as an actor: the teacher the learned actors imitate, behind the same interface.

A scene with no trained actor (the tabletop ran this way while its object-centric actor trained) still runs whole: the
planner, the predicates and the sim as they are, the policy node's safety rules as they are, the expert choosing
each command from the observation and the sub-goal's literals (``model_dir: expert``). It reads what an actor
reads, nothing more: the goal's literals give the sub-goal (:func:`semgoal_core.vocabulary.subgoal_of`) and the
observation the blocks, the grip and the fingers.
"""

from __future__ import annotations

import numpy as np

from semgoal_core import layout
from semgoal_core.expert import WorldView, expert_action
from semgoal_core.geometry import TABLE_TOP, grip_ceiling
from semgoal_core.vocabulary import LAYOUTS, SCENES, evaluate, subgoal_of

EXPERT = "expert"
"""The ``model_dir`` that names the scripted expert instead of an exported actor."""


class ExpertActor:
    """``act(observation, goal)`` -> the expert's command (``noise`` is ignored: the expert is deterministic)."""

    def __init__(self, scene: str) -> None:
        self.scene, self.layout = scene, LAYOUTS[scene]
        self.ceiling = grip_ceiling(SCENES[scene])

    def act(self, observation: np.ndarray, goal: np.ndarray, noise: np.ndarray | None = None) -> np.ndarray:
        """The command for one row, or one per row of a batch (as the learned actors take them)."""
        observation, goal = np.asarray(observation), np.asarray(goal)
        if observation.ndim == 2:
            return np.stack([self._act_one(o, g) for o, g in zip(observation, goal, strict=True)])
        return self._act_one(observation, goal)

    def _act_one(self, observation: np.ndarray, goal: np.ndarray) -> np.ndarray:
        size = self.layout.size
        subgoal = subgoal_of(self.layout.decode(goal[:size], goal[size:]))
        arm, blocks = layout.arm_state(observation), layout.block_slots(self.scene, observation)
        present = blocks["present"][:, 0] > 0.5
        grip, opening = arm["grip_position"].astype(np.float64), float(arm["finger_positions"].sum())
        positions = blocks["position"].astype(np.float64)
        view = WorldView({name: positions[i] for i, name in enumerate(self.layout.objects) if present[i]}, grip, opening,
                         SCENES[self.scene].bin, self.ceiling)
        vector = evaluate(self.layout, positions, grip, opening, TABLE_TOP, present)
        achieved = all(bool(vector[self.layout.index(literal)]) == literal.value for literal in subgoal.literals())
        return expert_action(subgoal, view, achieved).astype(np.float32)
