"""Actor inputs derived from the observation alone, appended to it for actors trained on them. No MuJoCo.

An exported actor names the derived features it was trained on (``layout.describe``); the training env
and the policy's controller compute them with :func:`augment` from the same observation vector, so the
sim's observation, the flat baselines and older actors stay as they are.

``bin_target`` (desk cleanup): where the block between the fingers goes in the bin, relative to the grip
(x, y; zeros when no spot is free): the free slot nearest the grip, else the nearest free floor spot, as the scripted
expert chooses it (:func:`semgoal_core.geometry.bin_spot`). In a scene without a bin, an actor trained with one is
shown its training scene's (:func:`shown_bin`): the object-centric actor trained on the tabletop, shown zeros on the
paper's two and three blocks (a bin spot right under the grip, which it never saw), carried blocks it was to put near
others about for hundreds of steps. Desk actors were weak at DC-4's
last put, three blocks binned: they hovered over the middle of the bin instead of the free end, though
the free spot is a function of the block positions they see.

``subject_offset`` (any scene): where the block(s) the sub-goal names are, relative to the grip (x, y, z;
the mean over the blocks named by the goal's mask, zeros when it names none). The observation holds every
block's offset, and the actor has to pick out the one the goal's one-hot mask points at; this hands it
over. HER keeps it valid: a relabelled goal carries the episode's mask, so it names the same blocks.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from semgoal_core.geometry import bin_spot
from semgoal_core.layout import ARM_SIZE, BLOCK_SIZE, BLOCK_SLICE, observation_size
from semgoal_core.vocabulary import LAYOUTS, SCENES, THRESHOLDS, BinGeometry

PRESENT, POSITION, RELATIVE = (BLOCK_SLICE["present"].start, BLOCK_SLICE["position"],
                              BLOCK_SLICE["relative_position"])


def _blocks(scene: str, observation: np.ndarray) -> np.ndarray:
    """(max blocks, BLOCK_SIZE): the observation's block slots."""
    return observation[ARM_SIZE:observation_size(scene)].reshape(-1, BLOCK_SIZE)


def shown_bin(scene: str, trained_scene: str) -> BinGeometry | None:
    """The bin :func:`bin_target` reads in ``scene`` for an actor trained on ``trained_scene``: the scene's own, else
    the training scene's (None when neither has one)."""
    return SCENES[scene].bin or SCENES[trained_scene].bin


def bin_target(scene: str, observation: np.ndarray, goal: np.ndarray | None = None,
               bin_geometry: BinGeometry | None = None) -> np.ndarray:
    """(2,) float32: the bin spot for the block between the fingers minus the grip position (x, y); ``bin_geometry``:
    the bin to read (default: the scene's own; zeros without one)."""
    bin_geometry = bin_geometry or SCENES[scene].bin
    if bin_geometry is None:
        return np.zeros(2, dtype=np.float32)
    grip = observation[0:3]
    blocks = _blocks(scene, observation)
    blocks = blocks[blocks[:, PRESENT] > 0.5]
    relative = blocks[:, RELATIVE]
    between_fingers = ((np.linalg.norm(relative[:, :2], axis=1) < THRESHOLDS.holding_xy)
                       & (np.abs(relative[:, 2]) < THRESHOLDS.holding_z))
    spot = bin_spot(bin_geometry, list(blocks[~between_fingers, POSITION]), grip[:2])
    return np.zeros(2, dtype=np.float32) if spot is None else (spot - grip[:2]).astype(np.float32)


def _naming(scene: str) -> np.ndarray:
    """(semantic atoms, blocks): 1 where an atom names the block (close(red,green) names both)."""
    objects = SCENES[scene].objects
    naming = np.zeros((LAYOUTS[scene].size, len(objects)), np.float32)
    for row, (_, args) in enumerate(LAYOUTS[scene].atoms):
        for arg in args:
            naming[row, objects.index(arg)] = 1.0
    return naming


_NAMING = {scene: _naming(scene) for scene in SCENES}


def subject_offset(scene: str, observation: np.ndarray, goal: np.ndarray | None,
                   bin_geometry: BinGeometry | None = None) -> np.ndarray:
    """(3,) float32: the grip-relative position of the blocks the goal's mask names (weighted by how many
    masked atoms name each, absent blocks left out); zeros without a goal or a named block present. (No bin read.)"""
    if goal is None:
        return np.zeros(3, np.float32)
    naming = _NAMING[scene]
    blocks = _blocks(scene, observation)
    weights = (goal[naming.shape[0]:] @ naming) * (blocks[:, PRESENT] > 0.5)
    total = weights.sum()
    return np.zeros(3, np.float32) if total == 0 else (weights @ blocks[:, RELATIVE] / total).astype(np.float32)


DerivedFeature = Callable[[str, np.ndarray, np.ndarray | None, BinGeometry | None], np.ndarray]
DERIVED_FEATURES: dict[str, tuple[int, DerivedFeature]] = {"bin_target": (2, bin_target),
                                                           "subject_offset": (3, subject_offset)}
"""Name -> (width, function of scene, observation, semantic goal and the bin shown)."""
FEATURE_VERSIONS: dict[str, int] = {"bin_target": 1, "subject_offset": 1}
"""Name -> version of what the feature computes. An exported actor records the versions it was trained on
and loading refuses another (``semgoal_policy.actor``): bump a version whenever a change here, or in what a
feature calls (``semgoal_core.geometry.bin_spot``), changes its values; ``tests/unit/core/test_features.py``
holds golden values that fail until it is bumped."""


def widths(names: Sequence[str]) -> dict[str, int]:
    """Name -> width for ``names``, as :func:`semgoal_core.layout.describe` records them."""
    return {name: DERIVED_FEATURES[name][0] for name in names}


def width(names: Sequence[str]) -> int:
    """How many entries ``names`` append to the observation."""
    return sum(widths(names).values())


def augment(scene: str, observation: np.ndarray, names: Sequence[str], goal: np.ndarray | None = None,
            bin_geometry: BinGeometry | None = None) -> np.ndarray:
    """The observation with the derived features ``names`` appended (itself when there are none);
    ``goal``: the semantic goal the actor is conditioned on (target, mask); ``bin_geometry``: the bin shown
    (:func:`shown_bin`; default: the scene's own)."""
    if not names:
        return observation
    extra = [DERIVED_FEATURES[name][1](scene, observation, goal, bin_geometry) for name in names]
    return np.concatenate([observation, *extra]).astype(np.float32)


def check(names: Sequence[str]) -> tuple[str, ...]:
    """``names`` as a tuple; ValueError for an unknown feature."""
    for name in names:
        if name not in DERIVED_FEATURES:
            raise ValueError(f"unknown derived feature {name!r}; valid: {', '.join(DERIVED_FEATURES)}")
    return tuple(names)
