"""Block tracks across frames: a small filter per block that smooths the voter's centres into positions
and velocities, and carries a block the camera does not see this frame.

Occlusion is normal: a block under the arm, in the hand or below another block keeps its track. Unseen,
a block in a hand follows that hand's grip site (the arms' kinematics; with two arms, either); any other stays
where it was, presumed still, its uncertainty growing each frame. After :data:`LOST_FRAMES` unseen frames it is
reported lost, with its last estimate, never dropped.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from enum import IntEnum
from typing import NamedTuple

import numpy as np

from semgoal_core.layout import CONTROL_DT
from semgoal_core.vocabulary import THRESHOLDS
from semgoal_perception.estimator import Detection

ALPHA, BETA = 0.6, 0.12
"""Alpha-beta filter gains (a steady-state Kalman filter of a constant-velocity block): measured voter
noise (about 1 mm per frame) leaves a velocity noise of a few mm/s, well under the rest threshold."""
SIGMA_GROWTH = 0.002
"""Growth of an unseen free block's standard deviation per frame (m)."""
SIGMA_HELD = 0.004
"""Standard deviation of a block carried unseen in the hand (m): the fingers hold it, but it can slip."""
SIGMA_MAX = 0.05
LOST_FRAMES = 75
"""Unseen this many frames in a row (3 s at 25 Hz) and a block is lost (its last estimate still kept)."""


class TrackStatus(IntEnum):
    """What the camera knows of a block now (the wire values of ``BlockEstimate.status``)."""

    VISIBLE = 0
    OCCLUDED = 1
    HELD = 2
    """Unseen in the closed hand: it follows the grip site."""
    LOST = 3
    NEVER_SEEN = 4


class Hand(NamedTuple):
    """One arm's hand as its kinematics give it: grip site (m), its velocity (m/s), finger opening (m)."""

    position: np.ndarray
    velocity: np.ndarray
    opening: float


@dataclass
class Track:
    position: np.ndarray = field(default_factory=lambda: np.full(3, np.nan))
    velocity: np.ndarray = field(default_factory=lambda: np.zeros(3))
    sigma: np.ndarray = field(default_factory=lambda: np.full(3, SIGMA_MAX))
    status: TrackStatus = TrackStatus.NEVER_SEEN
    unseen: int = 0
    pixels: int = 0
    grip_offset: np.ndarray | None = None
    """Block centre minus grip site while it is in a closed hand; None when it is not."""
    hand: int | None = None
    """Which hand of the frame's ``hands`` holds it (0: the own arm's); None when none does."""


def in_hand(position: np.ndarray, grip: np.ndarray, opening: float) -> bool:
    """The geometry of ``holding`` for one block (the thresholds of :mod:`semgoal_core.vocabulary`)."""
    rel = position - grip
    t = THRESHOLDS
    return bool(t.holding_opening_min <= opening <= t.holding_opening_max
                and np.linalg.norm(rel[:2]) < t.holding_xy and abs(rel[2]) < t.holding_z)


class BlockTracker:
    """Tracks of the blocks of one scene (by colour index), updated once per frame."""

    def __init__(self, colours: list[int], dt: float = CONTROL_DT) -> None:
        self.colours = list(colours)
        self.dt = dt
        self.tracks = {colour: Track() for colour in self.colours}

    def update(self, found: list[Detection], hands: Sequence[Hand], frames: int = 1) -> dict[int, Track]:
        """Fold one frame's detections in; ``hands``: every arm's hand, the own arm's first; ``frames`` control
        steps since the last update."""
        dt = self.dt * frames
        seen = {d.colour: d for d in found if d.colour in self.tracks}
        for colour, track in self.tracks.items():
            detection = seen.get(colour)
            if detection is not None:
                self._measure(track, detection, dt)
            else:
                self._predict(track, hands, frames)
            holder = None if track.status == TrackStatus.NEVER_SEEN else next(
                (i for i, hand in enumerate(hands) if in_hand(track.position, hand.position, hand.opening)), None)
            if holder is None:
                track.grip_offset, track.hand = None, None
            elif track.grip_offset is None or track.hand != holder:
                track.grip_offset, track.hand = track.position - hands[holder].position, holder
        return self.tracks

    def _measure(self, track: Track, detection: Detection, dt: float) -> None:
        if track.status in (TrackStatus.NEVER_SEEN, TrackStatus.LOST):
            track.position, track.velocity = detection.centre.copy(), np.zeros(3)
        else:
            predicted = track.position + track.velocity * dt
            residual = detection.centre - predicted
            track.position = predicted + ALPHA * residual
            track.velocity = track.velocity + BETA / dt * residual
        track.sigma = detection.sigma.copy()
        track.status, track.unseen, track.pixels = TrackStatus.VISIBLE, 0, detection.pixels

    def _predict(self, track: Track, hands: Sequence[Hand], frames: int) -> None:
        if track.status == TrackStatus.NEVER_SEEN:
            return
        track.unseen += frames
        track.pixels = 0
        if track.hand is not None and track.hand < len(hands):
            hand = hands[track.hand]
            track.position = hand.position + track.grip_offset
            track.velocity = np.asarray(hand.velocity, dtype=float).copy()
            track.sigma = np.maximum(track.sigma, SIGMA_HELD)
            track.status = TrackStatus.HELD
            return
        track.velocity = np.zeros(3)
        track.sigma = np.minimum(track.sigma + SIGMA_GROWTH * frames, SIGMA_MAX)
        track.status = TrackStatus.LOST if track.unseen >= LOST_FRAMES else TrackStatus.OCCLUDED

    def reset(self, colours: list[int]) -> None:
        """A new episode (or scene): every track starts unseen."""
        self.colours = list(colours)
        self.tracks = {colour: Track() for colour in self.colours}

    def arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Positions, velocities and standard deviations, (N, 3) each, in ``colours`` order."""
        tracks = [self.tracks[c] for c in self.colours]
        return (np.array([t.position for t in tracks]), np.array([t.velocity for t in tracks]),
                np.array([t.sigma for t in tracks]))
