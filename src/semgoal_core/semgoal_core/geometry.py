"""Table and bin geometry shared by the simulator, the scripted expert and the policy's derived features.

Where a block fits among others (:func:`clear_of`) and where it goes in the bin (:func:`bin_spot`) are
defined here, once: a learned actor's ``bin_target`` input (``semgoal_core.features``) and the expert's
puts read the same function, and neither defines it for the other.
"""

from __future__ import annotations

import numpy as np

from semgoal_core.vocabulary import BLOCK_HALF_SIZE, BinGeometry, Scene

TABLE_TOP = 0.4
"""z of the table top (m), as in the Fetch benchmark."""
TABLE_CENTER = (1.3, 0.75)
"""Centre of the table top in the world frame (m), as in the Fetch benchmark."""
TABLE_HALF_SIZE = (0.25, 0.35)
"""Half extent of the table top in x and y (m)."""
GRASP_OPENING = 0.08
"""Finger opening (m) used to straddle a 5 cm block when grasping it and releasing it onto another.
Opening no wider keeps the fingers (they open along y) off neighbouring blocks."""
MIN_CENTRE_DISTANCE = 0.058
"""Closest two block centres may be (m) for a block to be set down between others: 5 cm and some play."""
FINGER_HALF_WIDTH = 0.0135
"""Half a finger's width (m) across the fingers' axis (x), measured on the Fetch gripper."""
FINGER_OUTER_FACE = 0.0149
"""How far (m) a finger's outer face lies beyond half the opening along the fingers' axis (y)."""
FINGER_REACH_X = FINGER_HALF_WIDTH + BLOCK_HALF_SIZE + 0.004
FINGER_REACH_Y = FINGER_OUTER_FACE + GRASP_OPENING / 2 + BLOCK_HALF_SIZE + 0.004
"""A spot is clear of a block when the half-open fingers there miss it, with a margin."""


GRIP_BELOW_BODY = 0.02
"""The grip site sits about this far (m) below the gripper body, which the sim's workspace box holds."""


def grip_ceiling(scene: Scene) -> float:
    """The highest the grip site goes in ``scene`` (m): its ``reach_height`` above the table, less
    :data:`GRIP_BELOW_BODY`."""
    return TABLE_TOP + scene.reach_height - GRIP_BELOW_BODY


def table_edge(xy: np.ndarray) -> str:
    """The edge of the table a point beyond it (or nearest it) lies past, as the first robot sees the table: ``near``
    and ``far`` across x (it faces +x), ``left`` and ``right`` across y."""
    over = np.abs(np.asarray(xy[:2], dtype=float) - TABLE_CENTER) - TABLE_HALF_SIZE
    if over[0] >= over[1]:
        return "near" if xy[0] < TABLE_CENTER[0] else "far"
    return "left" if xy[1] > TABLE_CENTER[1] else "right"


def clear_of(candidates: np.ndarray, obstacles: list[np.ndarray], clearance: float = MIN_CENTRE_DISTANCE) -> np.ndarray:
    """Spots where a block fits and the fingers, opening there, touch no obstacle."""
    if not obstacles:
        return np.ones(len(candidates), dtype=bool)
    delta = np.abs(candidates[:, None, :] - np.array(obstacles)[None, :, :2])
    fingers_miss = (delta[..., 0] >= FINGER_REACH_X) | (delta[..., 1] >= FINGER_REACH_Y)
    return np.all(fingers_miss & (np.linalg.norm(delta, axis=2) >= clearance), axis=1)


def nearest(candidates: np.ndarray, ok: np.ndarray, to: np.ndarray) -> np.ndarray | None:
    """The ``ok`` candidate (M, 2) nearest ``to`` in the table plane; None when none is ok."""
    if not ok.any():
        return None
    options = candidates[ok]
    return options[np.argmin(np.linalg.norm(options - to[:2], axis=1))]


def bin_spot(bin_geometry: BinGeometry, obstacles: list[np.ndarray], near: np.ndarray) -> np.ndarray | None:
    """Where a block goes in the bin: the free slot nearest ``near``; when untidy puts left no slot free,
    the free floor spot nearest it (a gap may still be wide enough). None when the bin is full."""
    for spots in (bin_geometry.slots, bin_geometry.interior):  # the floor's grid (~800 spots) only where no slot is free
        candidates = spots()
        spot = nearest(candidates, clear_of(candidates, obstacles), near)
        if spot is not None:
            return spot
    return None
