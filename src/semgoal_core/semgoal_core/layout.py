"""The observation and goal layouts, defined once for training, evaluation and the nodes. No MuJoCo.

Observation (float32), after the Fetch benchmark's: the arm, then one fixed-size slot per block of the
scene (absent blocks of a smaller desk-cleanup variant are zeros with ``present`` = 0):

    arm:   grip position (3), grip velocity x dt (3), finger positions (2), finger velocities x dt (2)
    block: present (1), position (3), position relative to the grip (3), linear velocity x dt (3)

Goal: ``concat(target, mask)`` over the scene's semantic vector: mask 1 where a literal constrains the
entry, target its value, zero elsewhere. The achieved goal is ``concat(semantic vector x mask, mask)``
(:func:`achieved_goal`), so HER relabels by copying an achieved goal into the desired one: the mask
travels along and a relabelled goal looks like one the planner sends (zeros outside the mask).
"""

from __future__ import annotations

import numpy as np

from semgoal_core.vocabulary import LAYOUTS, SCENES

CONTROL_DT = 0.04
"""Seconds per control step (20 substeps of 0.002 s); velocities are scaled by it, as in Fetch."""
MAX_DISPLACEMENT = 0.05
"""End-effector displacement (m) per control step for an action of 1 (Fetch benchmark)."""
ARM_FEATURES = (("grip_position", 3), ("grip_velocity", 3), ("finger_positions", 2), ("finger_velocities", 2))
BLOCK_FEATURES = (("present", 1), ("position", 3), ("relative_position", 3), ("velocity", 3))
ARM_SIZE = sum(size for _, size in ARM_FEATURES)
BLOCK_SIZE = sum(size for _, size in BLOCK_FEATURES)


def _slices(features: tuple[tuple[str, int], ...]) -> dict[str, slice]:
    starts = np.cumsum([0, *(size for _, size in features)])
    return {name: slice(int(start), int(start) + size) for (name, size), start in zip(features, starts, strict=False)}


BLOCK_SLICE = _slices(BLOCK_FEATURES)
"""Feature name -> its columns in a block slot, e.g. ``blocks[:, BLOCK_SLICE["relative_position"]]``."""
ARM_SLICE = _slices(ARM_FEATURES)
"""Feature name -> its entries in the observation's arm part."""


def observation_size(scene: str) -> int:
    return ARM_SIZE + BLOCK_SIZE * SCENES[scene].max_blocks


GOAL_KINDS = ("semantic", "positions")
"""Semantic goals (target + mask over the predicate vector) or, for the flat-continuous baseline, the
block centres of a goal configuration (one (x, y, z) slot per block of the scene, absent ones zero)."""


def goal_size(scene: str, goal: str = "semantic") -> int:
    if goal not in GOAL_KINDS:
        raise ValueError(f"unknown goal kind {goal!r}; valid: {', '.join(GOAL_KINDS)}")
    return 2 * LAYOUTS[scene].size if goal == "semantic" else 3 * SCENES[scene].max_blocks


def describe(scene: str, goal: str = "semantic", derived: dict[str, int] | None = None) -> dict:
    """The layout as data: stored next to exported actors and checked when they are loaded. ``derived``:
    name -> width of the features an actor gets appended to the observation (``semgoal_core.features``);
    recorded only when there are some, as older actors have none."""
    described = {
        "scene": scene,
        "observation_size": observation_size(scene),
        "arm_features": [list(f) for f in ARM_FEATURES],
        "block_features": [list(f) for f in BLOCK_FEATURES],
        "blocks": list(SCENES[scene].objects),
        "semantic_atoms": [f"{name}({','.join(args)})" for name, args in LAYOUTS[scene].atoms],
        "goal": goal,
        "goal_size": goal_size(scene, goal),
    }
    if derived:
        described["derived_features"] = [[name, width] for name, width in derived.items()]
    return described


def observation(
    scene: str,
    grip_position: np.ndarray,
    grip_velocity: np.ndarray,
    finger_positions: np.ndarray,
    finger_velocities: np.ndarray,
    block_positions: np.ndarray,
    block_velocities: np.ndarray,
) -> np.ndarray:
    """The observation vector. ``block_positions`` / ``block_velocities`` (n, 3) hold the blocks present,
    in scene order (n may be below the scene's maximum)."""
    slots = SCENES[scene].max_blocks
    obs = np.zeros(ARM_SIZE + BLOCK_SIZE * slots, dtype=np.float32)
    obs[0:3] = grip_position
    obs[3:6] = np.asarray(grip_velocity) * CONTROL_DT
    obs[6:8] = finger_positions
    obs[8:10] = np.asarray(finger_velocities) * CONTROL_DT
    blocks = obs[ARM_SIZE:].reshape(slots, BLOCK_SIZE)
    count = len(block_positions)
    blocks[:count, BLOCK_SLICE["present"]] = 1.0
    blocks[:count, BLOCK_SLICE["position"]] = block_positions
    blocks[:count, BLOCK_SLICE["relative_position"]] = np.asarray(block_positions) - np.asarray(grip_position)
    blocks[:count, BLOCK_SLICE["velocity"]] = np.asarray(block_velocities)[:, :3] * CONTROL_DT
    return obs


def arm_state(observation: np.ndarray) -> dict[str, np.ndarray]:
    """The arm's features of an observation by name (:data:`ARM_FEATURES`; velocities as stored, x dt)."""
    return {name: observation[s] for name, s in ARM_SLICE.items()}


def block_slots(scene: str, observation: np.ndarray) -> dict[str, np.ndarray]:
    """The block slots of an observation by feature name, each (max_blocks, width) (:data:`BLOCK_FEATURES`)."""
    blocks = np.asarray(observation)[ARM_SIZE:observation_size(scene)].reshape(-1, BLOCK_SIZE)
    return {name: blocks[:, s] for name, s in BLOCK_SLICE.items()}


def achieved_goal(semantic_vector: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """The achieved goal of a state for an episode's ``mask``: the constrained entries of the semantic vector."""
    mask = np.asarray(mask, dtype=np.float32)
    return np.concatenate([np.asarray(semantic_vector, dtype=np.float32) * mask, mask])


def goal_reward(achieved_goal: np.ndarray, desired_goal: np.ndarray) -> np.ndarray:
    """Sparse semantic reward, vectorised over leading axes: 1 where every masked entry matches, else 0.

    The mask is read from ``desired_goal``; no hand-written dense term (paper, "Training the low-level
    policy").
    """
    n = desired_goal.shape[-1] // 2
    target, mask = desired_goal[..., :n], desired_goal[..., n:]
    mismatch = (np.abs(achieved_goal[..., :n] - target) > 0.5) & (mask > 0.5)
    return (~mismatch.any(axis=-1)).astype(np.float32)


def position_reward(achieved_goal: np.ndarray, desired_goal: np.ndarray) -> np.ndarray:
    """Dense reward of the flat-continuous baseline (paper, "Baselines"): minus the summed distance (m)
    between the block centres and their goal centres, vectorised over leading axes. Absent blocks are
    zero in both and add nothing."""
    slots = achieved_goal.reshape(*achieved_goal.shape[:-1], -1, 3) - desired_goal.reshape(*desired_goal.shape[:-1], -1, 3)
    return -np.linalg.norm(slots, axis=-1).sum(axis=-1).astype(np.float32)
