"""The perception node's core, without ROS: a frame and the arm's own state in (and any other arm's hand), tracked
blocks and the semantic state (truth values, confidences, moving and fallen blocks) out.

What it reads of the world is the camera's frame and the robots' proprioception (grip sites, fingers);
which blocks the scene holds is the task's set-up, as an operator would say it. Block poses never come
from anywhere but the camera.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from semgoal_core.geometry import TABLE_TOP
from semgoal_core.layout import CONTROL_DT
from semgoal_core.settling import moving_blocks
from semgoal_core.vocabulary import BLOCK_COLOURS, LAYOUTS, SCENES, fallen_blocks
from semgoal_perception.estimator import BlockEstimator
from semgoal_perception.geometry import PinholeCamera
from semgoal_perception.semantics import SemanticEstimator
from semgoal_perception.tracker import BlockTracker, Hand, Track

OtherHand = tuple[np.ndarray, float]
"""Another arm's hand as a world state carries it: grip site (m) and finger opening (m)."""


@dataclass(frozen=True)
class ArmState:
    """The robot's own state at the frame's time (m, m/s): what its joint encoders and kinematics give."""

    grip_position: np.ndarray
    grip_velocity: np.ndarray
    finger_positions: np.ndarray
    finger_velocities: np.ndarray

    @property
    def opening(self) -> float:
        return float(np.sum(self.finger_positions))

    @property
    def hand(self) -> Hand:
        return Hand(self.grip_position, self.grip_velocity, self.opening)


@dataclass(frozen=True)
class Perception:
    """One frame's outcome, for the scene's blocks present (scene order)."""

    blocks: tuple[str, ...]
    tracks: tuple[Track, ...]
    positions: np.ndarray
    """(max_blocks, 3) in the scene's slot order; zeros for absent slots (what ``layout.observation`` takes)."""
    velocities: np.ndarray
    present: np.ndarray
    vector: np.ndarray
    confidence: np.ndarray
    moving: tuple[str, ...]
    fallen: list[str]


class Perceiver:
    """The estimator, and per episode a tracker and the scene's semantic estimator."""

    def __init__(self, estimator: BlockEstimator) -> None:
        self.estimator = estimator
        self.episode: tuple | None = None
        self.tracker: BlockTracker | None = None
        self.semantics: SemanticEstimator | None = None
        self.last_step = 0
        self.other_grips: list[np.ndarray] = []
        """The other arms' grip sites at the last frame: their velocities by difference (a world state has none)."""

    def start(self, scene: str, blocks: tuple[str, ...], episode: object) -> None:
        """A new episode (a reset): tracks start unseen."""
        colours = list(BLOCK_COLOURS)
        self.episode = (scene, blocks, episode)
        self.tracker = BlockTracker([colours.index(b) for b in blocks], bin_geometry=SCENES[scene].bin)
        self.semantics = SemanticEstimator(LAYOUTS[scene])
        self.last_step = 0
        self.other_grips = []

    def perceive(self, rgb: np.ndarray, depth: np.ndarray, camera: PinholeCamera, arm: ArmState,
                 scene: str, blocks: tuple[str, ...], episode: object, step: int,
                 other_hands: Sequence[OtherHand] = ()) -> Perception:
        """One frame at control step ``step``; ``other_hands``: the other arms' hands, a block in one follows it."""
        if self.episode != (scene, blocks, episode) or step < self.last_step:
            self.start(scene, blocks, episode)
        frames = max(1, step - self.last_step) if self.last_step else 1
        self.last_step = step
        found = self.estimator.detect(rgb, depth, camera)
        self.tracker.update(found, [arm.hand, *self._others(other_hands, frames)], frames)
        return self.read_out(scene, blocks, arm, other_hands)

    def _others(self, other_hands: Sequence[OtherHand], frames: int) -> list[Hand]:
        """The other arms' hands with their velocities from the grip sites of the frame before (at rest at the first)."""
        grips = [np.asarray(grip, dtype=float) for grip, _ in other_hands]
        before = self.other_grips if len(self.other_grips) == len(grips) else grips
        self.other_grips = grips
        dt = CONTROL_DT * frames
        return [Hand(grip, (grip - last) / dt, float(opening))
                for grip, last, (_, opening) in zip(grips, before, other_hands, strict=True)]

    def read_out(self, scene: str, blocks: tuple[str, ...], arm: ArmState,
                 other_hands: Sequence[OtherHand] = ()) -> Perception:
        layout = LAYOUTS[scene]
        positions, velocities, sigmas = self.tracker.arrays()
        slots = [layout.objects.index(b) for b in blocks]
        present = np.zeros(len(layout.objects), dtype=bool)
        present[slots] = True
        slot_positions = np.zeros((len(layout.objects), 3))
        slot_velocities = np.zeros((len(layout.objects), 3))
        slot_sigmas = np.full((len(layout.objects), 3), 1.0)
        slot_positions[slots], slot_velocities[slots], slot_sigmas[slots] = positions, velocities, sigmas
        vector, confidence = self.semantics.estimate(np.where(present[:, None], slot_positions, 0.0), slot_sigmas,
                                                     arm.grip_position, arm.opening, present, other_hands)
        known = np.isfinite(positions).all(axis=1)
        fallen = fallen_blocks([b for b, k in zip(blocks, known, strict=True) if k], positions[known], TABLE_TOP)
        return Perception(blocks, tuple(self.tracker.tracks[c] for c in self.tracker.colours),
                          np.nan_to_num(slot_positions), slot_velocities, present, vector, confidence,
                          moving_blocks(list(blocks), velocities), fallen)
